#pragma once
// Triangulating one planar-ish polygon of a cage (n >= 5 corners; quads and
// triangles are handled by PolygonMesh::triangulate directly).
#include "core/Types.h"

#include <array>
#include <span>
#include <vector>

namespace contour {

// Ear clipping in the polygon's best-fit plane (Newell normal), with exact
// 2D orientation predicates: every triangle keeps the polygon's winding, so a
// non-convex polygon gives no folded or overlapping triangles (a fan from
// corner 0 does). Falls back to the fan when the projected polygon is not
// simple. Written by hand: the libraries we use triangulate whole meshes or
// need a constrained triangulation set-up, which a single cage face does not
// warrant.
std::vector<std::array<Index, 3>> triangulatePolygon(std::span<const Vec3> positions,
                                                     std::span<const Index> polygon);

} // namespace contour
