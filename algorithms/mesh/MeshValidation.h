#pragma once
// Rejects meshes that no contour method can work on: empty meshes, NaN/inf
// coordinates, out-of-range indices, degenerate faces (repeated corner or zero
// area, decided with exact predicates), non-manifold edges and vertices, and
// inconsistently oriented neighbours. Throws MeshError naming `file`, the
// element (e.g. "face 17", "vertex 3", "edge (4, 9)") and the problem.
#include "mesh/PolygonMesh.h"

#include <string>

namespace contour {

void validatePolygonMesh(const PolygonMesh& mesh, const std::string& file);

} // namespace contour
