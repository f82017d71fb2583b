// Edge splitting of the optimization phase (Bénard 2014 §6.4 "Edge
// Splitting"; notes §2.4.4).
#include "contours/consistent/ConsistentPhaseSupport.h"
#include "contours/consistent/ConsistentPhases.h"
#include "contours/consistent/LocalEdit.h"
#include "contours/consistent/OptimizationPhaseSupport.h"

namespace contour::consistent {

namespace {

struct SplitStats {
    long long cancelledSamples = 0, rejected = 0;
};

// §6.4: "edges of inconsistent triangles are sampled at 10 locations and the
// best one (using previous criteria) is selected": over the three edges of
// f and `samples` interior points of each (t = k / (samples + 1), along the
// appendix B interpolation), the split that leaves the fewest inconsistent
// faces among the (up to) four it creates, strictly fewer than the two it
// replaces, ties to the best minimum Bank-Smith quality. The new vertex must
// not be C (a split may not create a contour vertex off a root) and the split
// must keep every VBO defined (so no FB edge), make no degenerate CC edge and
// no fold (parameter space or 3D). CC edges are not split (the new F or B
// vertex would face a B or F vertex across the contour), nor tagged edges (a
// split drops the tag).
bool splitBest(ConsistentMesh& m, Index f, int samples, int phase, SplitStats& st) {
    const Triangle t = m.face(f);
    LocalEdit before(m), after(m);
    LocalScore best;
    std::optional<MeshVertex> bestVertex;
    std::array<Index, 2> bestEdge{kInvalidIndex, kInvalidIndex};
    for (int i = 0; i < 3; ++i) {
        const Index a = t[i], b = t[(i + 1) % 3];
        if (m.edgeTag(a, b) != kNoTag || (m.vertex(a).label == VertexLabel::Contour &&
                                          m.vertex(b).label == VertexLabel::Contour))
            continue;
        const auto [c, d] = m.oppositeVertices(a, b);
        // A split adds a neighbour to all four vertices; a cusp keeps the
        // valence 4 of Fig. 18d.
        bool cusp = false;
        for (Index w : {a, b, c, d})
            cusp = cusp || (w != kInvalidIndex && m.vertex(w).cusp);
        if (cusp)
            continue;
        before.clear();
        before.addFaces({f});
        const Index g = m.faceOfHalfedge(b, a);
        if (g != kInvalidIndex)
            before.addFaces({g});
        const LocalScore now = before.score();
        const int turnedBefore = before.turnedOver();
        for (int k = 1; k <= samples; ++k) {
            const std::optional<Preimage> p = m.interpolate(
                m.vertex(a).preimage, m.vertex(b).preimage, static_cast<double>(k) / (samples + 1));
            if (!p) {
                ++st.cancelledSamples;
                continue;
            }
            MeshVertex x = m.evaluate(*p);
            if (x.label == VertexLabel::Contour)
                continue;
            bool fb = false;
            for (Index w : {a, b, c, d})
                fb = fb || (w != kInvalidIndex &&
                            static_cast<int>(m.vertex(w).label) * static_cast<int>(x.label) < 0);
            if (fb)
                continue;
            x.provenance = Provenance::Inserted;
            x.phase = phase;
            after.clear();
            const Index n = after.addVertex(x);
            after.addFace({a, n, c});
            after.addFace({n, b, c});
            if (d != kInvalidIndex) {
                after.addFace({b, n, d});
                after.addFace({n, a, d});
            }
            LocalScore trial = after.score();
            trial.inconsistent -= now.inconsistent;
            if (trial.inconsistent >= 0 || (bestVertex && !betterScore(trial, best)))
                continue;
            if (!after.labelsValid() || !after.parameterValid() ||
                after.turnedOver() > turnedBefore) {
                ++st.rejected;
                continue;
            }
            best = trial;
            bestVertex = x;
            bestEdge = {a, b};
        }
    }
    if (!bestVertex)
        return false;
    m.splitEdge(bestEdge[0], bestEdge[1], *bestVertex, phase);
    return true;
}

void runEdgeSplitting(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const int samples = ctx.parameters.getInt("split-samples");
    const int maxSweeps = ctx.parameters.getInt("split-max-sweeps");
    OptimizationTally tally;
    SplitStats st;
    sweepInconsistent(ctx, m, maxSweeps, false, tally,
                      [&](Index f) { return splitBest(m, f, samples, phase, st); });
    publish(s, m);
    publishTally(s, tally, "faces", "split-max-sweeps");
    s.setCounter("splits", static_cast<double>(tally.accepted));
    s.setCounter("samples rejected (fold, VBO or degenerate edge)",
                 static_cast<double>(st.rejected));
    s.setCounter("samples without a chart", static_cast<double>(st.cancelledSamples));
}

std::vector<InvariantCheck> checkEdgeSplitting(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

void addEdgeSplitPhase(Method& m) {
    m.parameters.push_back({"split-samples",
                            "Split: samples per edge",
                            "Samples along every edge of an inconsistent face when looking for "
                            "a split (§6.4: 10).",
                            ParameterType::Int,
                            10,
                            1,
                            1000,
                            {}});
    m.parameters.push_back({"split-max-sweeps",
                            "Split: sweeps",
                            "Largest number of sweeps over the inconsistent faces in edge "
                            "splitting (§6.4; the paper gives no stopping rule).",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.phases.push_back(
        {"edge-splitting",
         "§6.4 Edge Splitting: every edge of an inconsistent face sampled at split-samples "
         "points; the split that leaves the fewest inconsistent faces (strictly fewer), ties "
         "to the best minimum Bank-Smith quality; no fold, every VBO defined, no degenerate "
         "edge; sweeps until no split helps.",
         runEdgeSplitting, checkEdgeSplitting});
}

} // namespace contour::consistent
