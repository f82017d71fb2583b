#include "FrustumLayer.h"

#include "SnapshotToVtk.h"
#include "VtkCameraConversion.h"
#include "VtkStyle.h"

#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

FrustumLayer::FrustumLayer() {
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    actor_->SetMapper(mapper_);
    vtkStyle::setColor(actor_->GetProperty(), sceneColors::kFrustum);
    actor_->GetProperty()->SetLineWidth(1.5f);
    actor_->GetProperty()->LightingOff();
    actor_->VisibilityOff();
    actor_->PickableOff();
}

std::vector<SceneLayer::Prop> FrustumLayer::props() const {
    return {{actor_, false}};
}

void FrustumLayer::update(const Snapshot& snapshot) {
    if (snapshot.mesh != mesh_) {
        mesh_ = snapshot.mesh;
        if (mesh_)
            rebuild();
    }
    applyVisibility();
}

void FrustumLayer::setAnalysisCamera(const Camera& camera) {
    camera_ = camera;
    rebuild();
    applyVisibility();
}

void FrustumLayer::rebuild() {
    if (!camera_)
        return;
    // The image rectangle through the target; orthographic boxes reach to the
    // far side of the mesh.
    double depth = (camera_->target - camera_->eye).norm();
    if (camera_->isOrthographic() && mesh_)
        depth += 0.5 * mesh_->boundingBox().diagonal();
    mapper_->SetInputData(frustumToPolyData(*camera_, depth));
}

bool FrustumLayer::isShownFor(const Camera& view) const {
    return isVisible() && mesh_ && camera_ && !sameView(view, *camera_);
}

void FrustumLayer::setViewCamera(const Camera& view) {
    viewDiffers_ = camera_ && !sameView(view, *camera_);
    applyVisibility();
}

vtkPolyData* FrustumLayer::frustumData() const {
    return mapper_->GetInput();
}

void FrustumLayer::applyVisibility() {
    actor_->SetVisibility(isVisible() && mesh_ && camera_ && viewDiffers_);
}

} // namespace contour
