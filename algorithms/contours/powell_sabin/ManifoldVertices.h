#pragma once
// The check that every vertex of a triangle mesh is manifold: rotating
// around it from vertexHalfedge() visits every corner at it. Where two fans
// meet at a vertex, the Euler characteristic says nothing about the genus
// (cone counts, §5.1) and the cut's disk check fails (layout).
#include "mesh/TriangleMesh.h"

namespace contour::powell_sabin {

// Throws std::invalid_argument naming the first non-manifold vertex.
void requireManifoldVertices(const TriangleMesh& mesh);

} // namespace contour::powell_sabin
