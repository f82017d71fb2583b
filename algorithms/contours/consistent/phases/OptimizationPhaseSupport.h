#pragma once
// What the five optimization phases of Bénard 2014 §6.4 share: their
// sweeps (OptimizationSweep.h) cancelled through the phase context, their
// counters and their post-conditions.
#include "contours/consistent/edits/OptimizationSweep.h"
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "pipeline/Method.h"

#include <functional>
#include <string>
#include <vector>

namespace contour::consistent {

// Counters "inconsistent faces before", `tried`, `accepted`, "sweeps", and
// a note when the sweep limit stopped the phase. Call after publish()
// (which writes "inconsistent faces", the count after).
void publishTally(Snapshot& s, const OptimizationTally& t, const CounterName& tried,
                  const CounterName& accepted, const std::string& sweepParameter);
// The same with the counters "<what> tried" and "<what> accepted" by label.
void publishTally(Snapshot& s, const OptimizationTally& t, const std::string& what,
                  const std::string& sweepParameter);

// sweepInconsistent() of OptimizationSweep.h, cancelled through `ctx`.
void sweepInconsistent(const PhaseContext& ctx, ConsistentMesh& m, int maxSweeps,
                       bool visitVertices, OptimizationTally& tally,
                       const std::function<bool(Index)>& tryMove);

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
