#pragma once
// Conversion of a Snapshot's parts to VTK data for the 3D view. Pure data
// conversion: no rendering and no algorithm runs here.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <vector>
#include <vtkSmartPointer.h>

class vtkIntArray;
class vtkPolyData;

namespace contour {

// Name of the cell array holding fields::kFacing on the mesh polydata, and of
// the cell array holding the CurveType of each curve.
inline constexpr const char* kVtkFacingArray = "facing";
inline constexpr const char* kVtkCurveTypeArray = "curve_type";

// The triangle mesh as polydata (points and triangles, no attributes).
vtkSmartPointer<vtkPolyData> meshToPolyData(const TriangleMesh& mesh);

// The face field fields::kFacing of `snapshot` as a cell array named
// kVtkFacingArray (+1 front, -1 back, 0 edge-on), or null when the snapshot
// has no facing field yet or it does not match the mesh.
vtkSmartPointer<vtkIntArray> facingToCellArray(const Snapshot& snapshot);

// The curves as polylines (a closed curve repeats its first point) with the
// cell array kVtkCurveTypeArray holding static_cast<int>(CurveType).
vtkSmartPointer<vtkPolyData> curvesToPolyData(const std::vector<Polyline>& curves);

// The camera's viewing frustum as lines: perspective, a pyramid from the eye
// to the image rectangle at `depth`; orthographic, a box from the eye plane
// to `depth`.
vtkSmartPointer<vtkPolyData> frustumToPolyData(const Camera& camera, double depth);

} // namespace contour
