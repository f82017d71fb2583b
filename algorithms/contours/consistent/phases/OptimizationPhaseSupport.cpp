#include "contours/consistent/phases/OptimizationPhaseSupport.h"

#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"

namespace contour::consistent {

void publishTally(Snapshot& s, const OptimizationTally& t, const CounterName& tried,
                  const CounterName& accepted, const std::string& sweepParameter) {
    s.setCounter(counters::kInconsistentFacesBefore, static_cast<double>(t.before));
    s.setCounter(tried, static_cast<double>(t.tried));
    s.setCounter(accepted, static_cast<double>(t.accepted));
    s.setCounter(counters::kSweeps, t.sweeps);
    if (t.sweepLimitHit)
        s.notes.push_back("stopped by " + sweepParameter + " (" + std::to_string(t.sweeps) +
                          " sweeps) while moves still improved consistency");
}

void publishTally(Snapshot& s, const OptimizationTally& t, const std::string& what,
                  const std::string& sweepParameter) {
    s.setCounter(counters::kInconsistentFacesBefore, static_cast<double>(t.before));
    s.setCounter(what + " tried", static_cast<double>(t.tried));
    s.setCounter(what + " accepted", static_cast<double>(t.accepted));
    s.setCounter(counters::kSweeps, t.sweeps);
    if (t.sweepLimitHit)
        s.notes.push_back("stopped by " + sweepParameter + " (" + std::to_string(t.sweeps) +
                          " sweeps) while moves still improved consistency");
}

std::vector<InvariantCheck> optimizationChecks(const PhaseContext& ctx, const Snapshot& s,
                                               bool radialOnSurface) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, true);
    if (radialOnSurface && ctx.parameters.has("radial-root-tolerance"))
        out.push_back(radialEdgeCheck(ctx, m));
    InvariantCheck monotone = check("the phase did not increase the inconsistent faces");
    const double before = s.counter(counters::kInconsistentFacesBefore, -1.0);
    const long long after = static_cast<long long>(inconsistentFaces(m).size());
    if (before >= 0.0 && static_cast<double>(after) > before)
        violate(monotone, std::to_string(after) + " inconsistent faces after, " +
                              std::to_string(static_cast<long long>(before)) + " before");
    out.push_back(monotone);
    return out;
}

void sweepInconsistent(const PhaseContext& ctx, ConsistentMesh& m, int maxSweeps,
                       bool visitVertices, OptimizationTally& tally,
                       const std::function<bool(Index)>& tryMove) {
    sweepInconsistent(m, maxSweeps, visitVertices, tally, tryMove,
                      [&ctx] { ctx.checkCancelled(); });
}

} // namespace contour::consistent
