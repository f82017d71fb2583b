#pragma once
// Re-triangulation of a small disc of faces around an inconsistent face at
// the far end of a cusp's radial edge (Bénard 2014 §6.3 Fig. 18e, §6.4;
// not in the paper): the final faces of the bumpy torus are faces r-x-c,
// c a cusp's radial end, whose chord r-x passes on the wrong side of c in
// the thin, curved image of the surface beside the cusp. No move of one
// vertex inside the faces around them fixes them (their outline already
// faces the wrong way); other edges of a few faces around do.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "pipeline/Method.h"

namespace contour::consistent {

struct CuspEndRetriangulationCounts {
    long long faces = 0;   // inconsistent faces at a cusp's radial end searched
    long long applied = 0; // re-triangulations applied
};

// For every inconsistent face with a corner at the far end of a cusp's
// radial edge: the connected sets of up to `maxFaces` faces holding it,
// grown across untagged, non-CC edges, that form a disc with every vertex
// on its outline, each re-triangulated optimally (fewest inconsistent
// faces, then the best minimum Bank-Smith quality; every VBO defined, no
// degenerate CC edge, no new CC or FB edge, no edge at a cusp, no fold in
// parameter space or 3D). The best disc with strictly fewer inconsistent
// faces is applied through flips (vertices do not move, so no other face
// changes); repeated while a face gains.
CuspEndRetriangulationCounts retriangulateAtCuspEnds(const PhaseContext& ctx, ConsistentMesh& m,
                                                     int maxFaces, int phase);

} // namespace contour::consistent
