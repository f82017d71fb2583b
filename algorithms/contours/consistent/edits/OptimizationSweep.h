#pragma once
// "Repeat until nothing improves" (Bénard 2014 §6.4): the sweeps of a local
// move over the inconsistent faces (or their vertices), bounded by a sweep
// limit, and what they tried and applied.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <functional>

namespace contour::consistent {

struct OptimizationTally {
    long long before = 0;   // inconsistent faces when the sweeps start
    long long tried = 0;    // moves evaluated (vertices, faces or radial edges visited)
    long long accepted = 0; // moves applied
    int sweeps = 0;
    bool sweepLimitHit = false; // the last sweep still improved
};

// Each sweep visits the faces that are inconsistent when it starts
// (skipping those an earlier move of the sweep made consistent) or, with
// `visitVertices`, their vertices, calls `tryMove` on each (true: a move was
// applied), and stops after a sweep that applied nothing or after
// `maxSweeps`. `checkCancelled` (may be empty) runs before each visit and
// stops the sweeps by throwing. Fills tally.before, tried, accepted, sweeps,
// sweepLimitHit.
void sweepInconsistent(ConsistentMesh& m, int maxSweeps, bool visitVertices,
                       OptimizationTally& tally, const std::function<bool(Index)>& tryMove,
                       const std::function<void()>& checkCancelled);

} // namespace contour::consistent
