#pragma once
// The snapshot's raw curves (Snapshot::curves) as thick unlit lines over the
// mesh: contours red (black over a scalar field, whose map has red in it),
// boundaries green, surface intersections magenta. A snapshot with a view
// graph draws its chains instead (ViewGraphLayer), so this layer is then
// hidden.
#include "SceneLayer.h"

#include <memory>
#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

namespace contour {

class CurveLayer : public SceneLayer {
public:
    CurveLayer();

    std::vector<Prop> props() const override;
    void update(const Snapshot& snapshot) override;

    // Contours in sceneColors::kContourOverField instead of kContour3D.
    void setOverScalarField(bool over);
    int curveCount() const { return curveCount_; }
    vtkPolyData* curveData() const;

protected:
    void applyVisibility() override;

private:
    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
    vtkNew<vtkLookupTable> colors_;
    vtkNew<vtkLookupTable> colorsOverField_;
    std::shared_ptr<const std::vector<Polyline>> curves_;
    int curveCount_ = 0;
    bool hasMesh_ = false;
    bool hasViewGraph_ = false;
};

} // namespace contour
