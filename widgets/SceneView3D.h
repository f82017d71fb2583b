#pragma once
// The 3D view of a snapshot: the working mesh with faces coloured by facing
// (sceneColors::kFrontFace / kBackFace, kUnclassifiedFace before the facing
// phase), the curves drawn on top as thick lines, and the analysis camera's
// frustum when this view's own camera differs from it.
#include "SceneColors.h"
#include "VtkOpenGLWidget.h"
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <memory>
#include <optional>
#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

class vtkPolyData;

namespace contour {

class SceneView3D : public VtkOpenGLWidget {
    Q_OBJECT

public:
    explicit SceneView3D(QWidget* parent = nullptr);
    ~SceneView3D() override;

    // Shows the snapshot's mesh, facing and curves. The mesh geometry is only
    // converted again when the snapshot's mesh changes.
    void setSnapshot(const Snapshot& snapshot);
    void clearScene();
    bool hasMesh() const { return static_cast<bool>(mesh_); }
    // Whether the faces are currently coloured from a facing field.
    bool showsFacing() const { return showsFacing_; }
    int curveCount() const { return curveCount_; }
    // Triangles in the VTK data shown for the mesh (0 when none).
    long long displayedFaceCount() const;

    // The camera the method runs with; drawn as a frustum when it differs
    // from this view's camera.
    void setAnalysisCamera(const Camera& camera);
    const std::optional<Camera>& analysisCamera() const { return analysisCamera_; }

    // Sets this view's VTK camera from an analysis camera.
    void setViewCamera(const Camera& camera);
    // This view's VTK camera as an analysis camera whose viewport is the
    // view's size in device pixels ("set analysis camera from this view").
    Camera viewCamera() const;
    // Rotates this view's camera about its focal point (degrees), as a
    // trackball drag does.
    void orbit(double azimuthDegrees, double elevationDegrees);

    // True when the frustum is drawn (decided before each render).
    bool isFrustumVisible() const;
    // True when this view's camera shows the analysis camera's view.
    bool viewMatchesAnalysisCamera() const;

signals:
    // The frustum appeared or disappeared (the view left or joined the
    // analysis camera).
    void viewMatchChanged(bool matches);

protected:
    void beforeRender() override;

private:
    void updateFrustum();

    vtkNew<vtkPolyDataMapper> meshMapper_;
    vtkNew<vtkActor> meshActor_;
    vtkNew<vtkLookupTable> facingColors_;
    vtkNew<vtkPolyDataMapper> curveMapper_;
    vtkNew<vtkActor> curveActor_;
    vtkNew<vtkLookupTable> curveColors_;
    vtkNew<vtkPolyDataMapper> frustumMapper_;
    vtkNew<vtkActor> frustumActor_;

    std::shared_ptr<const TriangleMesh> mesh_;
    vtkSmartPointer<vtkPolyData> meshData_;
    std::shared_ptr<const std::vector<Polyline>> curves_;
    std::optional<Camera> analysisCamera_;
    bool showsFacing_ = false;
    int curveCount_ = 0;
    bool lastMatch_ = true;
};

} // namespace contour
