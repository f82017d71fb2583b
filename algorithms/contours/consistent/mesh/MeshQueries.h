#pragma once
// Queries on the editable mesh that every layer above asks and that need
// nothing but the mesh: its scale (tolerances are relative to it), the faces
// around a set of vertices, and a face described for notes and invariant
// examples.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <string>
#include <vector>

namespace contour::consistent {

// Bounding-box diagonal of the initial mesh (the surface's level-1
// tessellation): tolerances are relative to it, the same in every phase.
double sceneScale(const ConsistentMesh& m);

// The faces around the given vertices, each once, sorted.
std::vector<Index> facesAround(const ConsistentMesh& m, const std::vector<Index>& vertices);

// "face f: v (domain face, u, v, label, provenance, phase) ..." for notes
// and invariant examples.
std::string describeFace(const ConsistentMesh& m, Index f);

} // namespace contour::consistent
