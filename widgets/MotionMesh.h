#pragma once
// A lighter copy of a large mesh for the 3D view to draw while the camera
// moves (level of detail, as ParaView does): under Mesa's software renderer
// a 100k-face mesh costs most of an orbit frame in vertex processing alone
// (README, bench_workbench). The copy is decimated with VTK's quadric
// decimation and each of its triangles remembers the original face nearest
// to its centre, so that the view can give it that face's colour (facing,
// VBO, a scalar field, the radial tint) and the moving picture keeps its
// meaning. Pure VTK data work on objects it creates itself: safe to run on a
// worker thread; no algorithm of the project runs here.
#include "mesh/TriangleMesh.h"

#include <vector>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace contour {

struct MotionMesh {
    // Points and triangles (no attributes); null when the build failed.
    vtkSmartPointer<vtkPolyData> data;
    // Point normals of `data` averaged over its triangles, for a view that
    // shades the full mesh smoothly (null when not computed).
    vtkSmartPointer<vtkDataArray> normals;
    // Per triangle of `data`: the face of the source mesh nearest to its
    // centre, whose colour it takes.
    std::vector<Index> sourceFaces;
    // Wall time the build took (decimation, normals and the face map).
    double seconds = 0.0;
};

// Decimates `mesh` to about `targetFaces` triangles (quadric decimation,
// Garland & Heckbert, as vtkQuadricDecimation implements it) and maps every
// triangle to its nearest source face. A mesh with no more than `targetFaces`
// faces is returned as it is (identity map).
MotionMesh buildMotionMesh(const TriangleMesh& mesh, Index targetFaces);

} // namespace contour
