#include "HighlightLayer.h"

#include "VtkStyle.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

HighlightLayer::HighlightLayer() {
    mapper_->ScalarVisibilityOff();
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    actor_->SetMapper(mapper_);
    vtkProperty* property = actor_->GetProperty();
    vtkStyle::setColor(property, sceneColors::kSelection);
    property->SetLineWidth(static_cast<float>(sceneColors::kSelectionLineWidth));
    property->SetPointSize(static_cast<float>(sceneColors::kSelectionPointSize));
    property->RenderPointsAsSpheresOn();
    property->LightingOff();
    actor_->VisibilityOff();
    actor_->PickableOff();
}

std::vector<SceneLayer::Prop> HighlightLayer::props() const {
    return {{actor_, true}};
}

void HighlightLayer::update(const Snapshot& snapshot) {
    snapshot_ = snapshot;
    rebuild();
}

void HighlightLayer::setSelection(const Selection& selection) {
    selection_ = selection;
    rebuild();
}

void HighlightLayer::rebuild() {
    data_ = nullptr;
    const TriangleMesh* mesh = snapshot_.mesh.get();
    if (mesh && selectionExists(snapshot_, selection_)) {
        auto points = vtkSmartPointer<vtkPoints>::New();
        auto lines = vtkSmartPointer<vtkCellArray>::New();
        auto verts = vtkSmartPointer<vtkCellArray>::New();
        const auto addPoint = [&](const Vec3& p) {
            return points->InsertNextPoint(p.x(), p.y(), p.z());
        };
        switch (selection_.kind) {
        case SelectionKind::Face: {
            const Triangle& t = mesh->triangle(selection_.id);
            const std::array<vtkIdType, 4> ids{addPoint(mesh->position(t[0])),
                                               addPoint(mesh->position(t[1])),
                                               addPoint(mesh->position(t[2])), 0};
            lines->InsertNextCell(4, ids.data());
            break;
        }
        case SelectionKind::Vertex: {
            const vtkIdType id = addPoint(mesh->position(selection_.id));
            verts->InsertNextCell(1, &id);
            break;
        }
        case SelectionKind::Edge: {
            const Index h = mesh->edgeHalfedge(selection_.id);
            const std::array<vtkIdType, 2> ids{addPoint(mesh->position(mesh->from(h))),
                                               addPoint(mesh->position(mesh->to(h)))};
            lines->InsertNextCell(2, ids.data());
            break;
        }
        case SelectionKind::Chain: {
            const ViewChain& chain =
                snapshot_.viewGraph->chains[static_cast<size_t>(selection_.id)];
            std::vector<vtkIdType> ids;
            for (const Vec3& p : chain.points)
                ids.push_back(addPoint(p));
            if (ids.size() >= 2)
                lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
            else if (ids.size() == 1)
                verts->InsertNextCell(1, ids.data());
            break;
        }
        case SelectionKind::None:
            break;
        }
        if (points->GetNumberOfPoints() > 0) {
            data_ = vtkSmartPointer<vtkPolyData>::New();
            data_->SetPoints(points);
            data_->SetLines(lines);
            data_->SetVerts(verts);
        }
    }
    mapper_->SetInputData(data_ ? data_.Get() : vtkSmartPointer<vtkPolyData>::New().Get());
    applyVisibility();
}

void HighlightLayer::applyVisibility() {
    actor_->SetVisibility(isVisible() && data_);
}

} // namespace contour
