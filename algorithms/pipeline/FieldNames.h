#pragma once
// Names of the fields that phases publish in a Snapshot. Views and exporters
// look fields up by these names, so a new method only has to publish them.
namespace contour::fields {

// Face, int: +1 front-facing, -1 back-facing, 0 edge-on (exact predicate).
inline constexpr const char* kFacing = "facing";
// Vertex, Vec3: unit vertex normals used by the facing function.
inline constexpr const char* kVertexNormal = "vertex_normal";
// Vertex, double: g = (c - p) · n, > 0 front-facing (Facing.h).
inline constexpr const char* kG = "g";
// Edge, int: 0 not a contour, 1 convex contour edge, 2 concave contour edge.
inline constexpr const char* kContourEdge = "contour_edge";
// Edge, int: 1 on a boundary edge.
inline constexpr const char* kBoundaryEdge = "boundary_edge";
// Face, int: 1 if the face carries an interpolated contour segment.
inline constexpr const char* kContourFace = "contour_face";
// Edge, double: parameter t of the zero crossing of g along the edge's
// stored half-edge, or NaN when g does not change sign on it.
inline constexpr const char* kZeroCrossing = "zero_crossing";

} // namespace contour::fields
