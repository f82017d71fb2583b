#pragma once
// A triangle mesh of the Powell-Sabin spline for drawing and for the fields
// a researcher inspects: each quadratic patch split uniformly into k^2
// triangles, welded along patch and macro-patch boundaries by their exact
// position in the layout (not by distance), so the result is one manifold
// mesh with the layout's topology. Points are mapped by `toWorld` (the
// inverse of the view's projective transform).
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/PowellSabinSpline.h"

#include <functional>
#include <vector>

namespace contour::powell_sabin {

struct SplineTessellation {
    TriangleMesh mesh;
    std::vector<Vec3> normals;     // per vertex, unit, world (zero-length at cones)
    std::vector<int> patch;        // per triangle: the patch 12 f + l
    std::vector<int> macroPatch;   // per triangle: the layout face f
    std::vector<int> patchEdge;    // per edge: 0 inside a patch, 1 patch, 2 macro-patch, 3 cut
    std::vector<Vec3> barycentric; // per vertex: in its macro-patch (layout face)
    std::vector<Index> vertexMacroPatch; // per vertex: a layout face it lies in
    // Per triangle, per corner: barycentric coordinates in the triangle's own
    // macro-patch (a welded vertex has other ones in its other macro-patches).
    std::vector<std::array<Vec3, 3>> cornerBarycentric;
    // Per vertex: a patch it lies in and its barycentric coordinates there,
    // where evaluateTessellationPoints evaluates it.
    std::vector<Index> vertexPatch;
    std::vector<Vec3> vertexPatchBarycentric;
};

// `level` = k >= 1 subdivisions per patch side. `toWorld` maps a spline
// point and its two uv derivatives to world coordinates (null: identity).
struct SplineToWorld {
    std::function<Vec3(const Vec3&)> point;
    std::function<Eigen::Matrix3d(const Vec3&)> jacobian;
};
// The triangle of tessellateSpline(..., level) that holds the point at
// barycentric coordinates `barycentric` of patch `patch` (its order: level^2
// triangles per patch, row by row, each row's up and down triangles
// alternating).
Index tessellationTriangle(Index patch, const Vec3& barycentric, int level);

SplineTessellation tessellateSpline(const PowellSabinSpline& spline, const ConeLayout& layout,
                                    int level, const SplineToWorld& toWorld = {});

// The tessellation of another spline on the same layout (the next view's
// fit) keeps the connectivity and labels of `previous`, which
// tessellateSpline made for that layout: the welding by layout position is
// view-independent, so a new view evaluates only the positions and unit
// normals of the vertices (in parallel). Throws std::invalid_argument when
// the spline has other patches than `previous` was made for.
struct TessellationPoints {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
};
TessellationPoints evaluateTessellationPoints(const SplineTessellation& previous,
                                              const PowellSabinSpline& spline,
                                              const SplineToWorld& toWorld = {});

} // namespace contour::powell_sabin
