#pragma once
// The control cage (Snapshot::cage, the polygon mesh a smooth surface is
// built from) as a near-black wireframe; off until asked for.
#include "SceneLayer.h"

#include <memory>
#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

class vtkPolyData;

namespace contour {

class CageLayer : public SceneLayer {
public:
    CageLayer();

    std::vector<Prop> props() const override;
    // Converts the cage only when the snapshot's cage changes.
    void update(const Snapshot& snapshot) override;

    void setShown(bool show);
    bool isShown() const { return show_; }
    // Cage edges drawn (0 while hidden or without a cage).
    long long edgesShown() const;
    vtkPolyData* cageData() const;

protected:
    void applyVisibility() override;

private:
    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
    std::shared_ptr<const PolygonMesh> cage_;
    bool show_ = false;
};

} // namespace contour
