#include "ViewGraphLayer.h"

#include "SnapshotToVtk.h"
#include "VtkStyle.h"

#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

namespace {

// The name of the RGB colour arrays of the chains and nodes.
constexpr const char* kViewGraphColorArray = "view_graph_colors";
// Line widths of visible, hidden and simplified chains (ChainState order).
constexpr std::array<float, 3> kChainWidths{4.0f, 2.5f, 1.5f};
constexpr float kNodeDotSize = 12.0f;

} // namespace

ViewGraphLayer::ViewGraphLayer() {
    // Chains depth-tested and pulled towards the viewer like the curves;
    // colours per cell (chains) or per point (nodes), set by recolour().
    for (size_t i = 0; i < chains_.size(); ++i) {
        Part& part = chains_[i];
        part.mapper->SetScalarModeToUseCellData();
        part.mapper->SetColorModeToDirectScalars();
        part.mapper->ScalarVisibilityOn();
        part.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
        part.mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
        part.actor->SetMapper(part.mapper);
        part.actor->GetProperty()->SetLineWidth(kChainWidths[i]);
        part.actor->GetProperty()->LightingOff();
        part.actor->VisibilityOff();
        part.actor->PickableOff();
    }
    for (Part& part : nodes_) {
        part.mapper->SetScalarModeToUsePointData();
        part.mapper->SetColorModeToDirectScalars();
        part.mapper->ScalarVisibilityOn();
        part.mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
        part.actor->SetMapper(part.mapper);
        part.actor->GetProperty()->SetPointSize(kNodeDotSize);
        part.actor->GetProperty()->RenderPointsAsSpheresOn();
        part.actor->GetProperty()->LightingOff();
        part.actor->VisibilityOff();
        part.actor->PickableOff();
    }
    // Nodes on hidden chains only: with those chains, pulled in front of the
    // surface they lie on.
    nodes_[1].mapper->SetRelativeCoincidentTopologyPointOffsetParameter(-120.0);
}

std::vector<SceneLayer::Prop> ViewGraphLayer::props() const {
    return {{chains_[0].actor, false},
            {chains_[1].actor, false},
            {chains_[2].actor, false},
            {nodes_[1].actor, false},
            {nodes_[0].actor, true}};
}

void ViewGraphLayer::update(const Snapshot& snapshot) {
    const std::shared_ptr<const ViewGraph> graph = snapshot.mesh ? snapshot.viewGraph : nullptr;
    if (graph != graph_) {
        graph_ = graph;
        const auto setData = [](Part& part, vtkSmartPointer<vtkPolyData> poly) {
            part.data = std::move(poly);
            part.mapper->SetInputData(part.data ? part.data.Get()
                                                : vtkSmartPointer<vtkPolyData>::New().Get());
        };
        for (size_t i = 0; i < chains_.size(); ++i)
            setData(chains_[i],
                    graph_ ? viewChainsToPolyData(*graph_, static_cast<ChainState>(i)) : nullptr);
        for (size_t hidden = 0; hidden < nodes_.size(); ++hidden)
            setData(nodes_[hidden], graph_ ? viewNodesToPolyData(*graph_, hidden != 0) : nullptr);
    }
    recolour();
    applyVisibility();
}

void ViewGraphLayer::recolour() {
    if (!graph_)
        return;
    using vtkStyle::insertColor;
    const SceneColor& visible =
        overScalarField_ ? sceneColors::kContourOverField : sceneColors::kContour3D;
    for (size_t i = 0; i < chains_.size(); ++i) {
        vtkPolyData* chains = chains_[i].data;
        if (!chains)
            continue;
        const auto state = static_cast<ChainState>(i);
        auto* indices =
            vtkIntArray::SafeDownCast(chains->GetCellData()->GetArray(kVtkChainIndexArray));
        auto* qis = vtkIntArray::SafeDownCast(chains->GetCellData()->GetArray(kVtkChainQiArray));
        auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
        colors->SetName(kViewGraphColorArray);
        colors->SetNumberOfComponents(3);
        for (vtkIdType c = 0; c < chains->GetNumberOfLines(); ++c) {
            if (state == ChainState::Simplified)
                insertColor(colors, viewGraphColors::kSimplified3D);
            else if (coloring_ == ChainColoring::ByChain)
                insertColor(colors, chainColor(indices->GetValue(c)),
                            state == ChainState::Hidden ? viewGraphColors::kHiddenDarken : 1.0);
            else
                insertColor(colors, qiColor(qis->GetValue(c), visible));
        }
        chains->GetCellData()->AddArray(colors);
        chains->GetCellData()->SetActiveScalars(kViewGraphColorArray);
        chains->Modified();
    }
    for (const Part& part : nodes_) {
        vtkPolyData* nodes = part.data;
        if (!nodes)
            continue;
        auto* types = vtkIntArray::SafeDownCast(nodes->GetPointData()->GetArray(kVtkNodeTypeArray));
        auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
        colors->SetName(kViewGraphColorArray);
        colors->SetNumberOfComponents(3);
        for (vtkIdType n = 0; n < nodes->GetNumberOfPoints(); ++n)
            insertColor(colors, nodeStyle(static_cast<ViewNodeType>(types->GetValue(n))).color);
        nodes->GetPointData()->AddArray(colors);
        nodes->GetPointData()->SetActiveScalars(kViewGraphColorArray);
        nodes->Modified();
    }
}

void ViewGraphLayer::applyVisibility() {
    for (size_t i = 0; i < chains_.size(); ++i)
        chains_[i].actor->SetVisibility(chainsShown(static_cast<ChainState>(i)) > 0);
    for (size_t hidden = 0; hidden < nodes_.size(); ++hidden) {
        const Part& part = nodes_[hidden];
        part.actor->SetVisibility(isVisible() && graph_ && part.data && showNodes_ &&
                                  (!hidden || showHidden_));
    }
}

long long ViewGraphLayer::chainsShown(ChainState state) const {
    const Part& part = chains_[static_cast<size_t>(state)];
    if (!isVisible() || !graph_ || !part.data)
        return 0;
    if ((state == ChainState::Hidden && !showHidden_) ||
        (state == ChainState::Simplified && !showSimplified_))
        return 0;
    return part.data->GetNumberOfLines();
}

long long ViewGraphLayer::nodesShown() const {
    long long shown = 0;
    for (const Part& part : nodes_)
        if (part.actor->GetVisibility())
            shown += part.data->GetNumberOfVerts();
    return shown;
}

vtkPolyData* ViewGraphLayer::chainData(ChainState state) const {
    return chains_[static_cast<size_t>(state)].data;
}

vtkPolyData* ViewGraphLayer::nodeData(bool hidden) const {
    return nodes_[hidden ? 1 : 0].data;
}

void ViewGraphLayer::setShowHiddenCurves(bool show) {
    showHidden_ = show;
    applyVisibility();
}

void ViewGraphLayer::setShowSimplifiedCurves(bool show) {
    showSimplified_ = show;
    applyVisibility();
}

void ViewGraphLayer::setShowNodes(bool show) {
    showNodes_ = show;
    applyVisibility();
}

void ViewGraphLayer::setChainColoring(ChainColoring coloring) {
    coloring_ = coloring;
    recolour();
}

void ViewGraphLayer::setOverScalarField(bool over) {
    if (over == overScalarField_)
        return;
    overScalarField_ = over;
    recolour();
}

} // namespace contour
