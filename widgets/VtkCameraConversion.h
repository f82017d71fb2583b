#pragma once
// Conversion between the analysis camera (contour::Camera) and a vtkCamera.
#include "camera/Camera.h"

class vtkCamera;

namespace contour {

// Sets position, focal point, view up, vertical view angle and projection.
// The viewport is not part of a vtkCamera: the view keeps its own aspect.
void applyCameraToVtk(const Camera& camera, vtkCamera* vtk);

// The vtkCamera as an analysis camera with the given viewport.
Camera cameraFromVtk(vtkCamera* vtk, const Viewport& viewport);

// True when both cameras show the same view (same projection, eye, viewing
// direction, up and field of view, up to a relative tolerance); the target
// may differ along the viewing direction and the viewports may differ.
bool sameView(const Camera& a, const Camera& b, double tolerance = 1e-6);

} // namespace contour
