#pragma once
// The dense ground truth of the smooth contour (reference/DenseGroundTruth.h)
// in the 3D view, when the application hands one: its loops as thin teal
// polylines on the surface (depth-tested and pulled towards the viewer like
// the curves, so the hidden parts show when orbiting), its cusps as small
// teal dots. It is not part of a snapshot: setGroundTruth() sets it, and
// update() only notes whether the snapshot has a mesh to draw it on.
#include "SceneLayer.h"
#include "reference/DenseGroundTruth.h"

#include <memory>
#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

class vtkPolyData;

namespace contour {

class GroundTruthLayer : public SceneLayer {
public:
    GroundTruthLayer();

    std::vector<Prop> props() const override;
    void update(const Snapshot& snapshot) override;

    // Null clears it.
    void setGroundTruth(std::shared_ptr<const GroundTruth> truth);
    bool hasGroundTruth() const { return static_cast<bool>(truth_); }
    // Loops and cusps drawn now (0 while hidden or without a ground truth).
    long long loopsShown() const;
    long long cuspsShown() const;
    // Their VTK data (null without a ground truth).
    vtkPolyData* loopData() const;
    vtkPolyData* cuspData() const;

protected:
    void applyVisibility() override;

private:
    vtkNew<vtkPolyDataMapper> loopMapper_;
    vtkNew<vtkActor> loops_;
    vtkNew<vtkPolyDataMapper> cuspMapper_;
    vtkNew<vtkActor> cusps_;
    std::shared_ptr<const GroundTruth> truth_;
    bool hasMesh_ = false;
};

} // namespace contour
