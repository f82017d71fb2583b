#include "SceneView3D.h"

#include "SnapshotToVtk.h"
#include "VtkCameraConversion.h"

#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

namespace {

void setTableColor(vtkLookupTable* table, vtkIdType index, const SceneColor& color) {
    table->SetTableValue(index, color.r, color.g, color.b, 1.0);
}

void setColor(vtkProperty* property, const SceneColor& color) {
    property->SetColor(color.r, color.g, color.b);
}

} // namespace

SceneView3D::SceneView3D(QWidget* parent) : VtkOpenGLWidget(parent) {
    vtkRenderer* ren = renderer();
    ren->GradientBackgroundOn();
    ren->SetBackground(sceneColors::kBackgroundBottom.r, sceneColors::kBackgroundBottom.g,
                       sceneColors::kBackgroundBottom.b);
    ren->SetBackground2(sceneColors::kBackgroundTop.r, sceneColors::kBackgroundTop.g,
                        sceneColors::kBackgroundTop.b);
    ren->SetBackgroundAlpha(1.0);

    // Lines (the curves) are pulled towards the viewer and polygons pushed
    // away, so curves lying on the surface are not z-fought.
    vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();

    // Facing -1, 0, +1 map to table entries 0, 1, 2.
    facingColors_->SetNumberOfTableValues(3);
    facingColors_->SetTableRange(-1.0, 1.0);
    facingColors_->Build();
    setTableColor(facingColors_, 0, sceneColors::kBackFace);
    setTableColor(facingColors_, 1, sceneColors::kEdgeOnFace);
    setTableColor(facingColors_, 2, sceneColors::kFrontFace);
    meshMapper_->SetLookupTable(facingColors_);
    meshMapper_->SetScalarModeToUseCellData();
    meshMapper_->SetColorModeToMapScalars();
    meshMapper_->UseLookupTableScalarRangeOn();
    meshMapper_->ScalarVisibilityOff();
    meshMapper_->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0);
    meshActor_->SetMapper(meshMapper_);
    vtkProperty* meshProperty = meshActor_->GetProperty();
    setColor(meshProperty, sceneColors::kUnclassifiedFace);
    // No specular highlight: shading then only scales a face's colour, so its
    // hue tells front from back everywhere.
    meshProperty->SetAmbient(0.3);
    meshProperty->SetDiffuse(0.7);
    meshProperty->SetSpecular(0.0);
    meshActor_->VisibilityOff();
    ren->AddActor(meshActor_);

    // CurveType 0 contour, 1 boundary, 2 surface intersection.
    curveColors_->SetNumberOfTableValues(3);
    curveColors_->SetTableRange(0.0, 2.0);
    curveColors_->Build();
    setTableColor(curveColors_, 0, sceneColors::kContour3D);
    setTableColor(curveColors_, 1, sceneColors::kBoundary);
    setTableColor(curveColors_, 2, sceneColors::kIntersection);
    curveMapper_->SetLookupTable(curveColors_);
    curveMapper_->SetScalarModeToUseCellData();
    curveMapper_->SetColorModeToMapScalars();
    curveMapper_->UseLookupTableScalarRangeOn();
    curveMapper_->ScalarVisibilityOn();
    curveMapper_->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
    curveActor_->SetMapper(curveMapper_);
    curveActor_->GetProperty()->SetLineWidth(4.0f);
    curveActor_->GetProperty()->LightingOff();
    curveActor_->VisibilityOff();
    ren->AddActor(curveActor_);

    frustumActor_->SetMapper(frustumMapper_);
    setColor(frustumActor_->GetProperty(), sceneColors::kFrustum);
    frustumActor_->GetProperty()->SetLineWidth(1.5f);
    frustumActor_->GetProperty()->LightingOff();
    frustumActor_->VisibilityOff();
    frustumActor_->PickableOff();
    ren->AddActor(frustumActor_);
}

SceneView3D::~SceneView3D() = default;

void SceneView3D::setSnapshot(const Snapshot& snapshot) {
    if (!snapshot.mesh) {
        clearScene();
        return;
    }
    if (snapshot.mesh != mesh_) {
        mesh_ = snapshot.mesh;
        meshData_ = meshToPolyData(*mesh_);
        meshMapper_->SetInputData(meshData_);
        meshActor_->VisibilityOn();
        updateFrustum();
    }
    if (vtkSmartPointer<vtkIntArray> facing = facingToCellArray(snapshot)) {
        meshData_->GetCellData()->SetScalars(facing);
        meshMapper_->ScalarVisibilityOn();
        showsFacing_ = true;
    } else {
        meshData_->GetCellData()->RemoveArray(kVtkFacingArray);
        meshMapper_->ScalarVisibilityOff();
        showsFacing_ = false;
    }
    meshData_->Modified();

    if (snapshot.curves != curves_) {
        curves_ = snapshot.curves;
        static const std::vector<Polyline> none;
        const std::vector<Polyline>& curves = curves_ ? *curves_ : none;
        curveMapper_->SetInputData(curvesToPolyData(curves));
        curveCount_ = static_cast<int>(curves.size());
        curveActor_->SetVisibility(curveCount_ > 0);
    }
    requestRender();
}

long long SceneView3D::displayedFaceCount() const {
    return meshData_ && meshActor_->GetVisibility() ? meshData_->GetNumberOfPolys() : 0;
}

void SceneView3D::clearScene() {
    mesh_.reset();
    meshData_ = nullptr;
    curves_.reset();
    curveCount_ = 0;
    showsFacing_ = false;
    meshActor_->VisibilityOff();
    curveActor_->VisibilityOff();
    frustumActor_->VisibilityOff();
    requestRender();
}

void SceneView3D::setAnalysisCamera(const Camera& camera) {
    analysisCamera_ = camera;
    updateFrustum();
    requestRender();
}

void SceneView3D::updateFrustum() {
    if (!analysisCamera_)
        return;
    const Camera& camera = *analysisCamera_;
    // The image rectangle through the target; orthographic boxes reach to the
    // far side of the mesh.
    double depth = (camera.target - camera.eye).norm();
    if (camera.isOrthographic() && mesh_)
        depth += 0.5 * mesh_->boundingBox().diagonal();
    frustumMapper_->SetInputData(frustumToPolyData(camera, depth));
}

void SceneView3D::setViewCamera(const Camera& camera) {
    applyCameraToVtk(camera, renderer()->GetActiveCamera());
    renderer()->ResetCameraClippingRange();
    requestRender();
}

Camera SceneView3D::viewCamera() const {
    const double ratio = devicePixelRatioF();
    Viewport viewport{std::max(1, static_cast<int>(width() * ratio)),
                      std::max(1, static_cast<int>(height() * ratio))};
    return cameraFromVtk(renderer()->GetActiveCamera(), viewport);
}

void SceneView3D::orbit(double azimuthDegrees, double elevationDegrees) {
    vtkCamera* camera = renderer()->GetActiveCamera();
    camera->Azimuth(azimuthDegrees);
    camera->Elevation(elevationDegrees);
    camera->OrthogonalizeViewUp();
    renderer()->ResetCameraClippingRange();
    requestRender();
}

bool SceneView3D::viewMatchesAnalysisCamera() const {
    return !analysisCamera_ || sameView(viewCamera(), *analysisCamera_);
}

bool SceneView3D::isFrustumVisible() const {
    return mesh_ && analysisCamera_ && !viewMatchesAnalysisCamera();
}

void SceneView3D::beforeRender() {
    const bool visible = isFrustumVisible();
    frustumActor_->SetVisibility(visible);
    renderer()->ResetCameraClippingRange();
    const bool matches = viewMatchesAnalysisCamera();
    if (matches != lastMatch_) {
        lastMatch_ = matches;
        // Queued: listeners must not re-enter the paint.
        QMetaObject::invokeMethod(
            this, [this, matches] { emit viewMatchChanged(matches); }, Qt::QueuedConnection);
    }
}

} // namespace contour
