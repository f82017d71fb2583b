#include "CageLayer.h"

#include "SnapshotToVtk.h"
#include "VtkStyle.h"

#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

CageLayer::CageLayer() {
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    actor_->SetMapper(mapper_);
    vtkStyle::setColor(actor_->GetProperty(), sceneColors::kControlCage);
    actor_->GetProperty()->SetLineWidth(1.0f);
    actor_->GetProperty()->LightingOff();
    actor_->VisibilityOff();
    actor_->PickableOff();
}

std::vector<SceneLayer::Prop> CageLayer::props() const {
    return {{actor_, false}};
}

void CageLayer::update(const Snapshot& snapshot) {
    if (snapshot.cage != cage_) {
        cage_ = snapshot.cage;
        mapper_->SetInputData(cage_ ? cageToPolyData(*cage_) : vtkSmartPointer<vtkPolyData>::New());
    }
    applyVisibility();
}

void CageLayer::setShown(bool show) {
    show_ = show;
    applyVisibility();
}

long long CageLayer::edgesShown() const {
    vtkPolyData* cage = mapper_->GetInput();
    return actor_->GetVisibility() && cage ? cage->GetNumberOfLines() : 0;
}

vtkPolyData* CageLayer::cageData() const {
    return cage_ ? mapper_->GetInput() : nullptr;
}

void CageLayer::applyVisibility() {
    actor_->SetVisibility(isVisible() && show_ && cage_);
}

} // namespace contour
