#pragma once
// Fold tests for the local edits of Bénard 2014 §6.3-§6.4 ("creates no
// fold"). A fold is a triangle that turns over against the
// surface it replaces, either in parameter space (the preimage map M -> P
// stops being bijective, Bénard 2014 §4) or in 3D (vertices sit at their limit
// positions f(u), so a split or flip can turn a face over even when its
// preimages do not: Fig. 17). Every test answers "would this edit fold?"
// before the mesh is changed.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <array>

namespace contour::consistent {

// Barycentric coordinates (relative to a, b, c) of the orthogonal projection
// of x onto the plane of triangle a-b-c; NaN when the triangle is degenerate.
Vec3 projectedBarycentrics(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x);

// Fig. 17: inserting x inside face a-b-c (1 -> 3 split) folds the mesh iff
// the projection of x onto the face's plane falls outside the face, i.e. the
// new triangle opposite corner i turns over exactly when coordinate i <= 0.
bool insertionFolds(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x);

// True when triangle a-b-c (normal (b-a) x (c-a)) points against
// `reference` or is degenerate.
bool turnsOver(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& reference);

// Unnormalized (area-weighted) normal of a face of the mesh.
Vec3 faceNormal(const ConsistentMesh& m, Index f);

// Would flipping edge a-b (faces a-b-c and b-a-d become a-d-c and b-c-d, as
// ConsistentMesh::flipEdge) fold the mesh?
//   space3d: a new face points against the sum of the two old faces'
//     normals, i.e. the quad a-d-b-c is not convex seen along its mean
//     normal (the new diagonal leaves the quad);
//   parameterSpace: a new face is not counter-clockwise in every common
//     chart, or has no common chart (appendix B);
//   impossible: a-b is a boundary edge or c-d already is an edge.
struct FlipFold {
    bool space3d = false;
    bool parameterSpace = false;
    bool impossible = false;
    bool folds() const { return space3d || parameterSpace || impossible; }
};
FlipFold flipFolds(const ConsistentMesh& m, Index a, Index b);
inline bool flipWouldFold(const ConsistentMesh& m, Index a, Index b) {
    return flipFolds(m, a, b).folds();
}

// The triangle (corner preimages) is counter-clockwise in every common chart.
bool keepsParameterOrientation(const ConsistentMesh& m, const std::array<Preimage, 3>& corners);

// Appendix B along a whole new edge, not only at its midpoint: the segment
// between two preimages interpolates at 9 interior points (near a domain
// corner it can cross a third domain face, where interpolation, and the
// later root search on the edge, fails).
bool edgeInterpolates(const ConsistentMesh& m, const Preimage& a, const Preimage& b);

// Splitting edge a-b at preimage p keeps every new face unfolded in
// parameter space with a common chart, and every new edge interpolable
// (appendix B; the mesh's post-conditions). The 3D half is the caller's.
bool splitKeepsCharts(const ConsistentMesh& m, Index a, Index b, const Preimage& p);
// Its second half alone: every new face is counter-clockwise in every
// common chart of its corners (has one), whether or not its edges
// interpolate everywhere.
bool splitKeepsParameterOrientation(const ConsistentMesh& m, Index a, Index b, const Preimage& p);

// Would moving vertex v to `position` turn one of its faces over in 3D (a
// face's new normal against its current one)? The parameter-space half is
// shiftKeepsParameterOrientation() (Shiftability.h).
bool moveFolds3d(const ConsistentMesh& m, Index v, const Vec3& position);

// A face whose normal points against the limit normals n(u) of all three of
// its vertices: turned over against the smooth surface (a diagnostic count,
// not a post-condition: coarse faces may legitimately lean far).
bool againstSurfaceNormals(const ConsistentMesh& m, Index f);

} // namespace contour::consistent
