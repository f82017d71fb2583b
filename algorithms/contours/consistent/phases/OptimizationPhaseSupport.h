#pragma once
// What the five optimization phases of Bénard 2014 §6.4 share:
// the sweep bookkeeping ("repeat until nothing improves", bounded by a
// sweep limit), their counters and their post-conditions.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "pipeline/Method.h"

#include <functional>
#include <string>
#include <vector>

namespace contour::consistent {

struct OptimizationTally {
    long long before = 0;   // inconsistent faces when the phase starts
    long long tried = 0;    // moves evaluated (vertices, faces or radial edges visited)
    long long accepted = 0; // moves applied
    int sweeps = 0;
    bool sweepLimitHit = false; // the last sweep still improved
};

// Counters "inconsistent faces before", `tried`, `accepted`, "sweeps", and
// a note when the sweep limit stopped the phase. Call after publish()
// (which writes "inconsistent faces", the count after).
void publishTally(Snapshot& s, const OptimizationTally& t, const CounterName& tried,
                  const CounterName& accepted, const std::string& sweepParameter);
// The same with the counters "<what> tried" and "<what> accepted" by label.
void publishTally(Snapshot& s, const OptimizationTally& t, const std::string& what,
                  const std::string& sweepParameter);

// "Repeat until nothing improves" (§6.4) over the inconsistent faces: each
// sweep visits the faces that are inconsistent when it starts (skipping
// those an earlier move of the sweep made consistent) or, with
// `visitVertices`, their vertices, calls `tryMove` on each (true: a move was
// applied), and stops after a sweep that applied nothing or after
// `maxSweeps`. Fills tally.before, tried, accepted, sweeps, sweepLimitHit.
void sweepInconsistent(const PhaseContext& ctx, ConsistentMesh& m, int maxSweeps,
                       bool visitVertices, OptimizationTally& tally,
                       const std::function<bool(Index)>& tryMove);

// A cusp keeps the valence 4 of Fig. 18d until radial edges are added
// around it (contourInsertionChecks in PhaseChecks.h); with
// `cuspEdits` off (optimization-cusp-edits), any cusp keeps its valence.
// False for kInvalidIndex.
bool lockedCusp(const ConsistentMesh& m, Index w, bool cuspEdits);

// Post-conditions after every §6.4 phase: the common ones (embedding, no
// parameter fold, charts, no degenerate CC edge), those of contour insertion
// (no FB edge, every VBO defined, |g| at C vertices, cusp valence 4), the
// radial edges' (when radial edge insertion ran and `radialOnSurface`: the
// normal wiggle moves vertices off the surface, where h_p is no longer
// evaluated at f(u)), and "the phase did not increase the inconsistent
// faces".
std::vector<InvariantCheck> optimizationChecks(const PhaseContext& ctx, const Snapshot& s,
                                               bool radialOnSurface);

} // namespace contour::consistent
