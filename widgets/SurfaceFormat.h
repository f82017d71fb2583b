#pragma once
// The OpenGL surface format the VTK views need (docs/dev/debian-traps.md): a 3.2 core
// profile context. Call before the QApplication is created, in the app and in
// every test that shows a VTK view.
namespace contour {

void setDefaultSurfaceFormat();

} // namespace contour
