// Edge splitting of the optimization phase (Bénard 2014 §6.4 "Edge
// Splitting").
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/OptimizationFlip.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"

namespace contour::consistent {

namespace {

struct SplitStats {
    long long cancelledSamples = 0, rejected = 0, wiggled = 0;
};

struct SplitSettings {
    int samples = 10;
    // Rows of the regular lattice sampling the two faces beside a split
    // edge (0: no wiggle of the new vertex), as the parameter wiggle's.
    int wiggleRows = 0;
    bool cuspEdits = true;
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
// split drops the tag). With `wiggleRows`, the new vertex is also wiggled
// (§6.4: splitting "gives the wiggling step more opportunities"): its
// one-ring after the split is the two faces beside the edge, sampled on the
// parameter wiggle's lattice, so a split that only pays off once its vertex
// moves is found too.
bool splitBest(ConsistentMesh& m, Index f, const SplitSettings& set, int phase, SplitStats& st) {
    const int samples = set.samples;
    const Triangle t = m.face(f);
    LocalEdit before(m), after(m);
    LocalScore best;
    std::optional<MeshVertex> bestVertex;
    std::array<Index, 2> bestEdge{kInvalidIndex, kInvalidIndex};
    bool bestWiggled = false;
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
            cusp = cusp || lockedCusp(m, w, set.cuspEdits);
        if (cusp)
            continue;
        before.clear();
        before.addFaces({f});
        const Index g = m.faceOfHalfedge(b, a);
        if (g != kInvalidIndex)
            before.addFaces({g});
        const LocalScore now = before.score();
        const int turnedBefore = before.turnedOver();
        // The edge's samples, then (wiggle) the lattice points of the two
        // faces beside it, rows parallel to a-b from the far corner.
        std::vector<std::optional<Preimage>> points;
        const Preimage &pa = m.vertex(a).preimage, &pb = m.vertex(b).preimage;
        for (int k = 1; k <= samples; ++k)
            points.push_back(m.interpolate(pa, pb, static_cast<double>(k) / (samples + 1)));
        const size_t onEdge = points.size();
        for (Index corner : {c, d}) {
            if (set.wiggleRows < 3 || c == kInvalidIndex || d == kInvalidIndex)
                break;
            const Preimage& pc = m.vertex(corner).preimage;
            for (int row = 2; row < set.wiggleRows; ++row) {
                const double level = static_cast<double>(row) / set.wiggleRows;
                const std::optional<Preimage> ra = m.interpolate(pc, pa, level);
                const std::optional<Preimage> rb = m.interpolate(pc, pb, level);
                for (int j = 1; j < row; ++j)
                    points.push_back(ra && rb
                                         ? m.interpolate(*ra, *rb, static_cast<double>(j) / row)
                                         : std::optional<Preimage>());
            }
        }
        for (size_t k = 0; k < points.size(); ++k) {
            const std::optional<Preimage>& p = points[k];
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
            bestWiggled = k >= onEdge;
        }
    }
    if (!bestVertex)
        return false;
    m.splitEdge(bestEdge[0], bestEdge[1], *bestVertex, phase);
    st.wiggled += bestWiggled;
    return true;
}

// The phase's parameters, read once per run.
struct EdgeSplitOptions {
    int samples = 0;       // split-samples
    int wiggleSamples = 0; // split-wiggle-samples
    int maxSweeps = 0;     // split-max-sweeps
    CuspEditOptions cusps;
    static EdgeSplitOptions read(const ParameterSet& p) {
        EdgeSplitOptions o;
        o.samples = p.getInt("split-samples");
        o.wiggleSamples = p.getInt("split-wiggle-samples");
        o.maxSweeps = p.getInt("split-max-sweeps");
        o.cusps = CuspEditOptions::read(p);
        return o;
    }
};

void runEdgeSplitting(const PhaseContext& ctx, Snapshot& s) {
    const EdgeSplitOptions options = EdgeSplitOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    SplitSettings set;
    set.samples = options.samples;
    // The smallest regular lattice (as the parameter wiggle's) with at
    // least split-wiggle-samples interior points per face: (n-1)(n-2)/2.
    if (const int wanted = options.wiggleSamples; wanted > 0) {
        set.wiggleRows = 3;
        while ((set.wiggleRows - 1) * (set.wiggleRows - 2) / 2 < wanted)
            ++set.wiggleRows;
    }
    set.cuspEdits = options.cusps.cuspEdits;
    const int maxSweeps = options.maxSweeps;
    OptimizationTally tally;
    SplitStats st;
    sweepInconsistent(ctx, m, maxSweeps, false, tally,
                      [&](Index f) { return splitBest(m, f, set, phase, st); });
    publish(s, m);
    publishTally(s, tally, counters::kFacesTried, counters::kFacesAccepted, "split-max-sweeps");
    s.setCounter(counters::kSplits, static_cast<double>(tally.accepted));
    s.setCounter(counters::kSamplesRejectedFoldVBOOrDegenerateEdge,
                 static_cast<double>(st.rejected));
    s.setCounter(counters::kSamplesWithoutAChart, static_cast<double>(st.cancelledSamples));
    s.setCounter(counters::kSplitsWithTheNewVertexWiggled, static_cast<double>(st.wiggled));
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
    m.parameters.push_back(
        {"split-wiggle-samples",
         "Split: wiggle samples per face",
         "Not in the paper: also try the split's new vertex at this many lattice points "
         "of each of the two faces beside the edge, a split then a wiggle of the new "
         "vertex (§6.4). 0: only the split-samples points on the edge.",
         ParameterType::Int,
         0,
         0,
         10000,
         {}});
    m.parameters.push_back(
        {"split-max-sweeps",
         "Split: sweeps",
         "Largest number of sweeps over the inconsistent faces in edge splitting (§6.4; "
         "the paper gives no stopping rule).",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.addPhase(
        {"edge-splitting",
         "§6.4 Edge Splitting: every edge of an inconsistent face sampled at split-samples "
         "points; the split that leaves the fewest inconsistent faces (strictly fewer), ties "
         "to the best minimum Bank-Smith quality; no fold, every VBO defined, no degenerate "
         "edge; sweeps until no split helps.",
         runEdgeSplitting, checkEdgeSplitting});
}

} // namespace contour::consistent
