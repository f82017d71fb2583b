// Edge flipping of the optimization phase (Bénard 2014 §6.4 "Edge
// Flipping"; notes §2.4.2).
#include "contours/consistent/ConsistentPhaseSupport.h"
#include "contours/consistent/ConsistentPhases.h"
#include "contours/consistent/LocalEdit.h"
#include "contours/consistent/OptimizationPhaseSupport.h"
#include "contours/consistent/RadialTriangles.h"

namespace contour::consistent {

namespace {

struct FlipStats {
    long long rejectedFold = 0, rejectedTiny = 0, rejectedLabels = 0;
};

// §6.4: try the three edges of inconsistent face f; apply the flip that
// removes the most inconsistent faces of the two it rewrites, ties to the
// best minimum Bank-Smith quality. Flips creating a triangle below
// `minQuality` ("tiny triangles", threshold unspecified in the paper), a
// fold (parameter space or 3D), an undefined VBO or a degenerate CC edge
// are discarded. Tagged edges (radial, cusp) are kept: a flip drops the tag.
bool flipBest(ConsistentMesh& m, Index f, double minQuality, bool cuspEdits, int phase,
              FlipStats& st) {
    const Triangle t = m.face(f);
    LocalEdit before(m), after(m);
    LocalScore best;
    std::array<Index, 2> bestEdge{kInvalidIndex, kInvalidIndex};
    for (int i = 0; i < 3; ++i) {
        const Index a = t[i], b = t[(i + 1) % 3];
        if (m.edgeTag(a, b) != kNoTag)
            continue;
        const Index f0 = m.faceOfHalfedge(a, b), f1 = m.faceOfHalfedge(b, a);
        if (f0 == kInvalidIndex || f1 == kInvalidIndex)
            continue;
        const auto [c, d] = m.oppositeVertices(a, b);
        if (c == d || m.faceOfHalfedge(c, d) != kInvalidIndex ||
            m.faceOfHalfedge(d, c) != kInvalidIndex)
            continue;
        // A flip changes the valence of all four vertices; a cusp keeps the
        // valence 4 of Fig. 18d until radial edges are added around it
        // (Fig. 18e), or always with optimization-cusp-edits off.
        bool locked = false;
        for (Index w : {a, b, c, d})
            locked = locked || (m.vertex(w).cusp && (!cuspEdits || !onRadialEdge(m, w)));
        if (locked)
            continue;
        before.clear();
        before.addFaces({f0, f1});
        const LocalScore now = before.score();
        after.clear();
        after.addFace({a, d, c});
        after.addFace({b, c, d});
        LocalScore trial = after.score();
        // Compare improvements across the three candidate edges.
        trial.inconsistent -= now.inconsistent;
        if (trial.inconsistent >= 0 || (bestEdge[0] != kInvalidIndex && !betterScore(trial, best)))
            continue;
        if (trial.minQuality < minQuality) {
            ++st.rejectedTiny;
            continue;
        }
        if (!after.labelsValid()) {
            ++st.rejectedLabels;
            continue;
        }
        if (!after.parameterValid() || after.turnedOver() > before.turnedOver()) {
            ++st.rejectedFold;
            continue;
        }
        best = trial;
        bestEdge = {a, b};
    }
    return bestEdge[0] != kInvalidIndex && m.flipEdge(bestEdge[0], bestEdge[1], phase);
}

void runOptimizationFlips(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const double minQuality = ctx.parameters.getDouble("flip-min-quality");
    const int maxSweeps = ctx.parameters.getInt("flip-max-sweeps");
    const bool cuspEdits = ctx.parameters.getBool("optimization-cusp-edits");
    OptimizationTally tally;
    FlipStats st;
    sweepInconsistent(ctx, m, maxSweeps, false, tally,
                      [&](Index f) { return flipBest(m, f, minQuality, cuspEdits, phase, st); });
    publish(s, m);
    publishTally(s, tally, "faces", "flip-max-sweeps");
    s.setCounter("flips", static_cast<double>(tally.accepted));
    s.setCounter("flips rejected (tiny triangle)", static_cast<double>(st.rejectedTiny));
    s.setCounter("flips rejected (fold)", static_cast<double>(st.rejectedFold));
    s.setCounter("flips rejected (VBO or degenerate edge)", static_cast<double>(st.rejectedLabels));
}

std::vector<InvariantCheck> checkOptimizationFlips(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

void addOptimizationFlipPhase(Method& m) {
    m.parameters.push_back(
        {"flip-min-quality",
         "Flip: smallest quality",
         "An optimization flip is discarded when a triangle it creates has a Bank-Smith quality "
         "below this (§6.4 discards flips that make \"tiny triangles\"; the threshold is "
         "unspecified in the paper).",
         ParameterType::Double,
         0.01,
         0.0,
         1.0,
         {}});
    m.parameters.push_back({"flip-max-sweeps",
                            "Flip: sweeps",
                            "Largest number of sweeps over the inconsistent faces in the "
                            "optimization flips (§6.4; the paper gives no stopping rule).",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.parameters.push_back(
        {"optimization-cusp-edits",
         "Optimization: edit at cusps",
         "Optimization flips and edge splits (§6.4) may change the valence of a cusp vertex "
         "once radial edges surround it (Fig. 18e): the valence 4 of Fig. 18d is needed only "
         "for radial edge insertion, and §6.4 sets no such limit. Off: no flip or split ever "
         "touches a cusp's valence.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.phases.push_back(
        {"optimization-flips",
         "§6.4 Edge Flipping: for every inconsistent face, the flip of one of its edges that "
         "removes the most inconsistent faces, ties to the best minimum Bank-Smith quality; no "
         "fold, no tiny triangle, every VBO defined, no degenerate edge; sweeps until no flip "
         "helps.",
         runOptimizationFlips, checkOptimizationFlips});
}

} // namespace contour::consistent
