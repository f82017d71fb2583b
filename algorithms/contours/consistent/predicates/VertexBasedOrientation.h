#pragma once
// Vertex-Based Orientation and contour consistency (Bénard 2014 §4,
// Definitions 1-3).
#include "camera/Facing.h"
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <cstdint>

namespace contour::consistent {

enum class Vbo : std::int8_t { Back = -1, Undefined = 0, Front = 1 };

// Definition 1: F for FFF, CFF, CCF; B for BBB, CBB, CCB; undefined for CCC,
// CFB, FBB, FFB (any permutation).
Vbo vertexBasedOrientation(VertexLabel a, VertexLabel b, VertexLabel c);

// Definition 2: a face is contour-consistent iff its VBO is defined and
// equals its geometric facing (the exact predicate triangleFacing()).
bool isConsistent(Vbo vbo, Facing facing);

// Definition 3: a CC edge is degenerate iff its two adjacent triangles have
// the same VBO (two CCF or two CCB triangles). An edge with an undefined VBO
// on either side is not called degenerate here: its face is already counted
// as inconsistent. Boundary edges (one face) are never degenerate.
bool isDegenerateEdge(VertexLabel a, VertexLabel b, Vbo left, Vbo right);

} // namespace contour::consistent
