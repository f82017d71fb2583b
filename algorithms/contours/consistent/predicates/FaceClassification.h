#pragma once
// One face of the editable mesh classified (Bénard 2014 §4-§5): its facing,
// its VBO (Definition 1), whether it is consistent (Definition 2), its
// domain face, its cusp edges.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/VertexBasedOrientation.h"

#include <vector>

namespace contour::consistent {

// Definition 2 for one face: the VBO of its labels against its exact facing.
Vbo faceVbo(const ConsistentMesh& m, Index f);
Facing faceFacing(const ConsistentMesh& m, Index f);
bool faceIsConsistent(const ConsistentMesh& m, Index f);
// The domain face holding the face's centroid (appendix B interpolation),
// kInvalidIndex when its corners have no common chart.
Index faceDomainFace(const ConsistentMesh& m, Index f);
// Inconsistent faces among the faces around the given vertices (each face
// once): the local objective of the optimization phases (§6.4).
int inconsistentFacesAround(const ConsistentMesh& m, const std::vector<Index>& vertices);
// How many of the triangle's edges are cusp edges (§6.2 d).
int cuspEdgesOf(const ConsistentMesh& m, const Triangle& t);

} // namespace contour::consistent
