#include "GroundTruthLayer.h"

#include "SnapshotToVtk.h"
#include "VtkStyle.h"

#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

GroundTruthLayer::GroundTruthLayer() {
    loopMapper_->ScalarVisibilityOff();
    // As the curves: lines pulled towards the viewer, points a little more.
    loopMapper_->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
    loopMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    loops_->SetMapper(loopMapper_);
    vtkStyle::setColor(loops_->GetProperty(), sceneColors::kGroundTruth);
    loops_->GetProperty()->SetLineWidth(static_cast<float>(sceneColors::kGroundTruthLineWidth3D));
    loops_->GetProperty()->LightingOff();
    loops_->VisibilityOff();
    loops_->PickableOff();
    cuspMapper_->ScalarVisibilityOff();
    cuspMapper_->SetRelativeCoincidentTopologyPointOffsetParameter(-120.0);
    cuspMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    cusps_->SetMapper(cuspMapper_);
    vtkStyle::setColor(cusps_->GetProperty(), sceneColors::kGroundTruth);
    cusps_->GetProperty()->SetPointSize(static_cast<float>(sceneColors::kGroundTruthCuspSize3D));
    cusps_->GetProperty()->RenderPointsAsSpheresOn();
    cusps_->GetProperty()->LightingOff();
    cusps_->VisibilityOff();
    cusps_->PickableOff();
}

std::vector<SceneLayer::Prop> GroundTruthLayer::props() const {
    return {{loops_, false}, {cusps_, false}};
}

void GroundTruthLayer::update(const Snapshot& snapshot) {
    hasMesh_ = static_cast<bool>(snapshot.mesh);
    applyVisibility();
}

void GroundTruthLayer::setGroundTruth(std::shared_ptr<const GroundTruth> truth) {
    if (truth != truth_) {
        truth_ = std::move(truth);
        loopMapper_->SetInputData(truth_ ? groundTruthLoopsToPolyData(*truth_)
                                         : vtkSmartPointer<vtkPolyData>::New());
        cuspMapper_->SetInputData(truth_ ? groundTruthCuspsToPolyData(*truth_)
                                         : vtkSmartPointer<vtkPolyData>::New());
    }
    applyVisibility();
}

long long GroundTruthLayer::loopsShown() const {
    return loops_->GetVisibility() ? loopMapper_->GetInput()->GetNumberOfLines() : 0;
}

long long GroundTruthLayer::cuspsShown() const {
    return cusps_->GetVisibility() ? cuspMapper_->GetInput()->GetNumberOfVerts() : 0;
}

vtkPolyData* GroundTruthLayer::loopData() const {
    return truth_ ? loopMapper_->GetInput() : nullptr;
}

vtkPolyData* GroundTruthLayer::cuspData() const {
    return truth_ ? cuspMapper_->GetInput() : nullptr;
}

void GroundTruthLayer::applyVisibility() {
    const bool shown = isVisible() && hasMesh_ && truth_;
    loops_->SetVisibility(shown);
    cusps_->SetVisibility(shown && !truth_->cusps.empty());
}

} // namespace contour
