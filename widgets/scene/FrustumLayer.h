#pragma once
// The analysis camera's viewing frustum as light grey lines, drawn only when
// the camera that looks at the scene differs from the analysis camera (from
// inside the frustum there is nothing to see of it).
#include "SceneLayer.h"
#include "camera/Camera.h"

#include <memory>
#include <optional>
#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

class vtkPolyData;

namespace contour {

class FrustumLayer : public SceneLayer {
public:
    FrustumLayer();

    std::vector<Prop> props() const override;
    // The mesh sets how deep an orthographic box reaches.
    void update(const Snapshot& snapshot) override;

    void setAnalysisCamera(const Camera& camera);
    const std::optional<Camera>& analysisCamera() const { return camera_; }
    // The camera looking at the scene; the frustum is drawn when it differs.
    void setViewCamera(const Camera& view);
    // Whether the frustum would be drawn for `view`.
    bool isShownFor(const Camera& view) const;
    vtkPolyData* frustumData() const;

protected:
    void applyVisibility() override;

private:
    void rebuild();

    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
    std::optional<Camera> camera_;
    std::shared_ptr<const TriangleMesh> mesh_;
    bool viewDiffers_ = false;
};

} // namespace contour
