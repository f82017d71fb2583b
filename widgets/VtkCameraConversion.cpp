#include "VtkCameraConversion.h"

#include <algorithm>
#include <cmath>
#include <vtkCamera.h>

namespace contour {

void applyCameraToVtk(const Camera& camera, vtkCamera* vtk) {
    vtk->SetPosition(camera.eye.data());
    vtk->SetFocalPoint(camera.target.data());
    const Vec3 up = camera.trueUp();
    vtk->SetViewUp(up.data());
    vtk->SetViewAngle(camera.fovYDegrees);
    vtk->SetParallelProjection(camera.isOrthographic());
    vtk->SetParallelScale(0.5 * camera.orthoHeight);
    vtk->OrthogonalizeViewUp();
}

Camera cameraFromVtk(vtkCamera* vtk, const Viewport& viewport) {
    Camera camera;
    camera.projection =
        vtk->GetParallelProjection() ? Projection::Orthographic : Projection::Perspective;
    const double* p = vtk->GetPosition();
    const double* f = vtk->GetFocalPoint();
    const double* u = vtk->GetViewUp();
    camera.eye = Vec3(p[0], p[1], p[2]);
    camera.target = Vec3(f[0], f[1], f[2]);
    camera.up = Vec3(u[0], u[1], u[2]).normalized();
    camera.fovYDegrees = vtk->GetViewAngle();
    camera.orthoHeight = 2.0 * vtk->GetParallelScale();
    camera.viewport = viewport;
    return camera;
}

bool sameView(const Camera& a, const Camera& b, double tolerance) {
    if (a.projection != b.projection)
        return false;
    const double scale = std::max({1e-12, (a.target - a.eye).norm(), (b.target - b.eye).norm()});
    if ((a.eye - b.eye).norm() > tolerance * scale)
        return false;
    if ((a.forward() - b.forward()).norm() > tolerance ||
        (a.trueUp() - b.trueUp()).norm() > tolerance)
        return false;
    if (a.isOrthographic())
        return std::abs(a.orthoHeight - b.orthoHeight) <= tolerance * scale;
    return std::abs(a.fovYDegrees - b.fovYDegrees) <= tolerance * 180.0;
}

} // namespace contour
