#pragma once
// The 3D view of a snapshot: the working mesh coloured by facing
// (sceneColors::kFrontFace / kBackFace, kUnclassifiedFace before the facing
// phase) or by a signed scalar field of the snapshot (g, radial, Gaussian or
// mean curvature: DivergingColorMap.h, with a scalar bar), the curves drawn
// on top as thick lines, and the analysis camera's frustum when this view's
// own camera differs from it.
#include "DivergingColorMap.h"
#include "SceneColors.h"
#include "VtkOpenGLWidget.h"
#include "camera/Camera.h"
#include "pipeline/FieldNames.h"
#include "pipeline/Snapshot.h"

#include <QRect>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>

class vtkPolyData;

namespace contour {

class SceneView3D : public VtkOpenGLWidget {
    Q_OBJECT

public:
    explicit SceneView3D(QWidget* parent = nullptr);
    ~SceneView3D() override;

    // Shows the snapshot's mesh, its colouring (colorField()) and curves. The
    // mesh geometry is only converted again when the snapshot's mesh changes.
    // A tessellated smooth surface is shaded with its exact normals, a plain
    // triangle mesh with flat faces.
    void setSnapshot(const Snapshot& snapshot);
    void clearScene();
    bool hasMesh() const { return static_cast<bool>(mesh_); }
    // The snapshot shown (empty after clearScene()).
    const Snapshot& snapshot() const { return snapshot_; }
    // Whether the faces are currently coloured from a facing field.
    bool showsFacing() const { return showsFacing_; }

    // What to colour the mesh by: fields::kFacing (front/back) or the name of
    // a scalar field (scalarFieldNames in SnapshotToVtk.h). The choice is kept
    // across snapshots; a snapshot without that field is shown by facing
    // (displayedColorField()), and the field is shown again as soon as a
    // snapshot has it (stepping back to the input and forward again, or a
    // re-run after a parameter change, keeps the choice).
    void setColorField(const std::string& field);
    const std::string& colorField() const { return colorField_; }
    // fields::kFacing or the scalar field actually shown.
    const std::string& displayedColorField() const { return displayedField_; }
    // The scalar fields of the current snapshot, in selector order.
    const std::vector<std::string>& scalarFields() const { return scalarFields_; }
    bool showsScalarField() const { return displayedField_ != fields::kFacing; }
    // The range of the diverging map of the shown scalar field.
    const SymmetricRange& scalarRange() const { return scalarRange_; }
    bool isScalarBarVisible() const;
    std::string scalarBarTitle() const;
    // The scalar bar's box (bar, labels and title) in the grabbed image's
    // device pixels, top-left origin; empty when the bar is hidden.
    QRect scalarBarRect() const;
    int curveCount() const { return curveCount_; }
    // Whether the mesh is shaded with the smooth surface's normals.
    bool hasSmoothShading() const { return static_cast<bool>(shownNormals_); }
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
    // The list of scalar fields or the displayed colouring changed.
    void colorFieldsChanged();
    // The frustum appeared or disappeared (the view left or joined the
    // analysis camera).
    void viewMatchChanged(bool matches);

protected:
    void beforeRender() override;

private:
    void updateFrustum();
    // Applies colorField_ to the current snapshot's mesh.
    void updateColoring();

    vtkNew<vtkPolyDataMapper> meshMapper_;
    vtkNew<vtkActor> meshActor_;
    vtkNew<vtkLookupTable> facingColors_;
    vtkNew<vtkPolyDataMapper> curveMapper_;
    vtkNew<vtkActor> curveActor_;
    vtkNew<vtkLookupTable> curveColors_;
    vtkNew<vtkLookupTable> curveColorsOverField_;
    vtkNew<vtkLookupTable> fieldColors_;
    vtkNew<vtkScalarBarActor> scalarBar_;
    vtkNew<vtkPolyDataMapper> frustumMapper_;
    vtkNew<vtkActor> frustumActor_;

    std::shared_ptr<const TriangleMesh> mesh_;
    Snapshot snapshot_;
    std::string colorField_ = fields::kFacing;
    std::string displayedField_ = fields::kFacing;
    std::vector<std::string> scalarFields_;
    // The field whose values are in meshData_ (to skip converting it again).
    std::shared_ptr<const Field> shownFieldValues_;
    std::string shownArrayName_;
    // The smooth surface's normals in meshData_, if any.
    std::shared_ptr<const Field> shownNormals_;
    SymmetricRange scalarRange_;
    vtkSmartPointer<vtkPolyData> meshData_;
    std::shared_ptr<const std::vector<Polyline>> curves_;
    std::optional<Camera> analysisCamera_;
    bool showsFacing_ = false;
    int curveCount_ = 0;
    bool lastMatch_ = true;
};

} // namespace contour
