#include "CurveLayer.h"

#include "SnapshotToVtk.h"
#include "VtkStyle.h"

#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

CurveLayer::CurveLayer() {
    using vtkStyle::setTableColor;
    // CurveType 0 contour, 1 boundary, 2 surface intersection.
    colors_->SetNumberOfTableValues(3);
    colors_->SetTableRange(0.0, 2.0);
    colors_->Build();
    setTableColor(colors_, 0, sceneColors::kContour3D);
    setTableColor(colors_, 1, sceneColors::kBoundary);
    setTableColor(colors_, 2, sceneColors::kIntersection);
    colorsOverField_->SetNumberOfTableValues(3);
    colorsOverField_->SetTableRange(0.0, 2.0);
    colorsOverField_->Build();
    setTableColor(colorsOverField_, 0, sceneColors::kContourOverField);
    setTableColor(colorsOverField_, 1, sceneColors::kBoundary);
    setTableColor(colorsOverField_, 2, sceneColors::kIntersection);
    mapper_->SetLookupTable(colors_);
    mapper_->SetScalarModeToUseCellData();
    mapper_->SetColorModeToMapScalars();
    mapper_->UseLookupTableScalarRangeOn();
    mapper_->ScalarVisibilityOn();
    // Lines pulled towards the viewer (the mesh's polygons are pushed away).
    mapper_->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    actor_->SetMapper(mapper_);
    actor_->GetProperty()->SetLineWidth(4.0f);
    actor_->GetProperty()->LightingOff();
    actor_->VisibilityOff();
}

std::vector<SceneLayer::Prop> CurveLayer::props() const {
    return {{actor_, false}};
}

void CurveLayer::update(const Snapshot& snapshot) {
    hasMesh_ = static_cast<bool>(snapshot.mesh);
    hasViewGraph_ = hasMesh_ && snapshot.viewGraph;
    const std::shared_ptr<const std::vector<Polyline>> curves =
        hasMesh_ ? snapshot.curves : nullptr;
    if (curves != curves_) {
        curves_ = curves;
        static const std::vector<Polyline> none;
        const std::vector<Polyline>& lines = curves_ ? *curves_ : none;
        mapper_->SetInputData(curvesToPolyData(lines));
        curveCount_ = static_cast<int>(lines.size());
    }
    applyVisibility();
}

void CurveLayer::setOverScalarField(bool over) {
    mapper_->SetLookupTable(over ? colorsOverField_.Get() : colors_.Get());
}

vtkPolyData* CurveLayer::curveData() const {
    return mapper_->GetInput();
}

void CurveLayer::applyVisibility() {
    actor_->SetVisibility(isVisible() && hasMesh_ && curveCount_ > 0 && !hasViewGraph_);
}

} // namespace contour
