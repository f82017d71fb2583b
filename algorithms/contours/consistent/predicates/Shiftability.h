#pragma once
// Appendix C of Bénard 2014: may a vertex move to a new
// preimage?
#include "contours/consistent/mesh/ConsistentMesh.h"

namespace contour::consistent {

// May vertex `v` move to preimage `p` and take label `newLabel`? Rules 1-4
// of appendix C: no fold in parameter space, no CCC triangle, no "X" (at
// most two zero crossings on the one-ring's outer boundary), interpolation
// to every neighbour still possible; and, beyond appendix C, no degenerate
// CC edge (docs/dev/invariants.md item 4). A C vertex is never shifted (it sits on a
// root).
bool shiftable(const ConsistentMesh& m, Index v, const Preimage& p, VertexLabel newLabel);

// Rule 1 alone: moving v to p folds none of its faces in parameter space
// (and every face keeps a common chart).
bool shiftKeepsParameterOrientation(const ConsistentMesh& m, Index v, const Preimage& p);

} // namespace contour::consistent
