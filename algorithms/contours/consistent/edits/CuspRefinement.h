#pragma once
// Cusp refinement: not in the paper. Bénard 2014 §6.1 subdivides the whole
// domain once and §6.2 d puts each cusp on an FB edge of that mesh; every
// later move around the cusp (the radial edges of Fig. 18e, the flips,
// wiggles and splits of §6.4) then works with the few large faces of the
// cusp's wedge. Before contour insertion, the edges of the faces near a cusp
// edge are halved at their parameter-space midpoints (appendix B
// interpolation, the new vertex on the limit surface, labelled by sign(g)),
// so the contour, the radial edges and the later moves get more and smaller
// triangles there. Each face whose three edges were halved becomes the
// regular 1 -> 4 split by one flip; the new FF and BB edges get §6.1's
// sign-crossing search, as the initial edges did.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "pipeline/Method.h"

#include <functional>

namespace contour::consistent {

struct CuspRefinementSettings {
    int rings = 1;         // face rings around the cusp edge's ends (0: its two faces)
    int levels = 1;        // repetitions, each on the finer mesh
    double pixels = 0.;    // only faces with a corner this close to the cusp (0: any)
    bool cuspEdges = true; // halve the cusp edge too (the FB half keeps the tag)
    int crossingSamples = 10;
    int crossingRounds = 1;
    int rootIterations = 100; // bisection steps placing the cusp on its edge
};

struct CuspRefinementCounts {
    long long cusps = 0, faces = 0, splits = 0, cuspEdgeSplits = 0, rejectedChart = 0,
              rejected3d = 0, rejectedContour = 0, flips = 0, crossingSplits = 0;
};

// Refines around every cusp edge (between cusp detection and contour
// insertion: labels F or B, cusp edges tagged) whose cusp, the root of g on
// the edge, `select` accepts. A halving is cancelled when a new face would
// fold (parameter space or 3D) or lack a common chart, or the midpoint lies
// on g = 0. Keeps every post-condition of cusp detection.
void refineAroundCusps(ConsistentMesh& m, const CuspRefinementSettings& set,
                       const std::function<bool(const Vec3&)>& select, int phase,
                       CuspRefinementCounts& n);

void publishCuspRefinementCounts(Snapshot& s, const CuspRefinementCounts& n);

} // namespace contour::consistent
