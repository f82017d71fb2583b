// Edge flipping of the optimization phase (Bénard 2014 §6.4 "Edge
// Flipping").
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/OptimizationFlip.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/RadialTriangles.h"

#include <initializer_list>

namespace contour::consistent {

namespace {

struct FlipStats {
    long long rejectedFold = 0, rejectedTiny = 0, rejectedLabels = 0, pairs = 0;
};

// A flip changes the valence of every vertex it touches; a cusp keeps the
// valence 4 of Fig. 18d until radial edges are added around it (Fig. 18e),
// or always with optimization-cusp-edits off.
bool valenceLocked(const ConsistentMesh& m, std::initializer_list<Index> vertices, bool cuspEdits) {
    for (Index w : vertices)
        if (m.vertex(w).cusp && (!cuspEdits || !onRadialEdge(m, w)))
            return true;
    return false;
}

// The flip of a-b may be considered at all: untagged, interior, c-d not
// an edge yet, no cusp whose valence is locked.
bool flipAllowed(const ConsistentMesh& m, Index a, Index b, bool cuspEdits) {
    if (m.edgeTag(a, b) != kNoTag || m.faceOfHalfedge(a, b) == kInvalidIndex ||
        m.faceOfHalfedge(b, a) == kInvalidIndex)
        return false;
    const auto [c, d] = m.oppositeVertices(a, b);
    if (c == d || m.faceOfHalfedge(c, d) != kInvalidIndex ||
        m.faceOfHalfedge(d, c) != kInvalidIndex)
        return false;
    return !valenceLocked(m, {a, b, c, d}, cuspEdits);
}

// The flipped faces in `after` (scored `trial`) pass §6.4's rules against
// the faces they replace in `before`: no triangle below `minQuality`, defined
// VBOs and no degenerate CC edge, no fold; the reason is counted when not.
bool flipResultAcceptable(const LocalEdit& before, const LocalEdit& after, const LocalScore& trial,
                          double minQuality, FlipStats& st) {
    if (trial.minQuality < minQuality) {
        ++st.rejectedTiny;
        return false;
    }
    if (!after.labelsValid()) {
        ++st.rejectedLabels;
        return false;
    }
    if (!after.parameterValid() || after.turnedOver() > before.turnedOver()) {
        ++st.rejectedFold;
        return false;
    }
    return true;
}

// Scores the candidate edit `before` -> `after`: it must remove inconsistent
// faces, beat `best` when there is one (betterScore) and be acceptable
// (flipResultAcceptable, which counts its rejections in `st`). On success
// `best` becomes its score. Shared by single flips and flip pairs.
bool improvesOnBest(const LocalEdit& before, const LocalEdit& after, bool haveBest,
                    LocalScore& best, double minQuality, FlipStats& st) {
    LocalScore trial = after.score();
    trial.inconsistent -= before.score().inconsistent;
    if (trial.inconsistent >= 0 || (haveBest && !betterScore(trial, best)) ||
        !flipResultAcceptable(before, after, trial, minQuality, st))
        return false;
    best = trial;
    return true;
}

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
        if (!flipAllowed(m, a, b, cuspEdits))
            continue;
        const Index f0 = m.faceOfHalfedge(a, b), f1 = m.faceOfHalfedge(b, a);
        const auto [c, d] = m.oppositeVertices(a, b);
        before.clear();
        before.addFaces({f0, f1});
        after.clear();
        after.addFace({a, d, c});
        after.addFace({b, c, d});
        // Compare improvements across the three candidate edges.
        if (improvesOnBest(before, after, bestEdge[0] != kInvalidIndex, best, minQuality, st))
            bestEdge = {a, b};
    }
    return bestEdge[0] != kInvalidIndex && m.flipEdge(bestEdge[0], bestEdge[1], phase);
}

// Two successive flips around inconsistent face f, tried when no single
// flip helps (parameter optimization-flip-pairs, on by default; off, §6.4
// as written, tries "any of the three edges"; on halves the faces left
// inconsistent, and on test_visibility's grazing torus removes 4 spurious
// T-junctions that the dense ground truth does not have): the first flips an edge
// a-b of f (faces a-d-c and b-c-d), the second an outer edge u-w of one of those two faces with the
// mesh face across it. Near the contour a face whose far vertex lies on the wrong side of the chord
// of its near edge in the image (Fig. 13, 16f) often has no single improving flip but one through
// its neighbour. Same acceptance as flipBest, judged on the three final faces against the three
// they replace. Both flips are evaluated before the mesh changes.
bool flipPairBest(ConsistentMesh& m, Index f, double minQuality, bool cuspEdits, int phase,
                  FlipStats& st) {
    const Triangle t = m.face(f);
    LocalEdit before(m), after(m);
    LocalScore best;
    std::array<Index, 4> bestEdges{kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
    for (int i = 0; i < 3; ++i) {
        const Index a = t[i], b = t[(i + 1) % 3];
        if (!flipAllowed(m, a, b, cuspEdits))
            continue;
        const Index f0 = m.faceOfHalfedge(a, b), f1 = m.faceOfHalfedge(b, a);
        const auto [c, d] = m.oppositeVertices(a, b);
        const Triangle n0{a, d, c}, n1{b, c, d};
        for (int k = 0; k < 2; ++k) {
            const Triangle& tk = k == 0 ? n0 : n1;
            const Triangle& other = k == 0 ? n1 : n0;
            for (int j = 0; j < 3; ++j) {
                const Index u = tk[j], w = tk[(j + 1) % 3];
                if ((u == c && w == d) || (u == d && w == c))
                    continue;
                // Outer edge of the quad a-c-b-d: its mesh face across.
                if (m.edgeTag(u, w) != kNoTag)
                    continue;
                const Index g = m.faceOfHalfedge(w, u);
                if (g == kInvalidIndex || g == f0 || g == f1)
                    continue;
                const Index x = tk[(j + 2) % 3];
                Index y = kInvalidIndex;
                for (Index z : m.face(g))
                    if (z != u && z != w)
                        y = z;
                if (y == kInvalidIndex || y == x || y == a || y == b || y == c || y == d ||
                    m.faceOfHalfedge(x, y) != kInvalidIndex ||
                    m.faceOfHalfedge(y, x) != kInvalidIndex)
                    continue;
                if (valenceLocked(m, {a, b, c, d, y}, cuspEdits))
                    continue;
                before.clear();
                before.addFaces({f0, f1, g});
                after.clear();
                after.addFace(other);
                // Faces u-w-x and w-u-y become u-y-x and w-x-y.
                after.addFace({u, y, x});
                after.addFace({w, x, y});
                if (improvesOnBest(before, after, bestEdges[0] != kInvalidIndex, best, minQuality,
                                   st))
                    bestEdges = {a, b, u, w};
            }
        }
    }
    if (bestEdges[0] == kInvalidIndex)
        return false;
    const auto [c, d] = m.oppositeVertices(bestEdges[0], bestEdges[1]);
    if (!m.flipEdge(bestEdges[0], bestEdges[1], phase))
        return false;
    if (!m.flipEdge(bestEdges[2], bestEdges[3], phase)) {
        m.flipEdge(c, d, phase); // not expected (checked above): back to a-b
        return false;
    }
    ++st.pairs;
    return true;
}

// The phase's parameters, read once per run.
struct OptimizationFlipOptions {
    double minQuality = 0.0; // flip-min-quality
    int maxSweeps = 0;       // flip-max-sweeps
    bool pairs = false;      // optimization-flip-pairs
    CuspEditOptions cusps;
    static OptimizationFlipOptions read(const ParameterSet& p) {
        OptimizationFlipOptions o;
        o.minQuality = p.getDouble("flip-min-quality");
        o.maxSweeps = p.getInt("flip-max-sweeps");
        o.pairs = p.getBool("optimization-flip-pairs");
        o.cusps = CuspEditOptions::read(p);
        return o;
    }
};

void runOptimizationFlips(const PhaseContext& ctx, Snapshot& s) {
    const OptimizationFlipOptions options = OptimizationFlipOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const double minQuality = options.minQuality;
    const int maxSweeps = options.maxSweeps;
    const bool cuspEdits = options.cusps.cuspEdits;
    OptimizationTally tally;
    FlipStats st;
    const bool pairs = options.pairs;
    sweepInconsistent(ctx, m, maxSweeps, false, tally, [&](Index f) {
        return flipBest(m, f, minQuality, cuspEdits, phase, st) ||
               (pairs && flipPairBest(m, f, minQuality, cuspEdits, phase, st));
    });
    publish(s, m);
    publishTally(s, tally, counters::kFacesTried, counters::kFacesAccepted, "flip-max-sweeps");
    s.setCounter(counters::kFlips, static_cast<double>(tally.accepted));
    s.setCounter(counters::kFlipsRejectedTinyTriangle, static_cast<double>(st.rejectedTiny));
    s.setCounter(counters::kFlipsRejectedFold, static_cast<double>(st.rejectedFold));
    s.setCounter(counters::kFlipsRejectedVBOOrDegenerateEdge,
                 static_cast<double>(st.rejectedLabels));
    s.setCounter(counters::kTwoFlipSequences, static_cast<double>(st.pairs));
}

std::vector<InvariantCheck> checkOptimizationFlips(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

CuspEditOptions CuspEditOptions::read(const ParameterSet& p) {
    CuspEditOptions o;
    o.cuspEdits = p.getBool("optimization-cusp-edits");
    return o;
}

void addOptimizationFlipPhase(Method& m) {
    m.parameters.push_back(
        {"flip-min-quality",
         "Flip: smallest quality",
         "An optimization flip (§6.4) is discarded when a triangle it creates has a "
         "Bank-Smith quality below this (the paper discards \"tiny triangles\" without a "
         "threshold).",
         ParameterType::Double,
         0.01,
         0.0,
         1.0,
         {}});
    m.parameters.push_back(
        {"flip-max-sweeps",
         "Flip: sweeps",
         "Largest number of sweeps over the inconsistent faces in the optimization flips "
         "(§6.4; the paper gives no stopping rule).",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.parameters.push_back(
        {"optimization-cusp-edits",
         "Optimization: edit at cusps",
         "May optimization flips and edge splits (§6.4) change a cusp vertex's valence "
         "once radial edges surround it (Fig. 18e)? On: as in §6.4, which sets no limit; "
         "the valence 4 of Fig. 18d matters only for radial edge insertion. Off: never.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"optimization-flip-pairs",
         "Flip: two-flip sequences",
         "Not in the paper: when no single flip of an inconsistent face's edges helps "
         "(§6.4 tries \"any of the three edges\"), also try a flip followed by a flip of "
         "an outer edge of one of the two new faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"optimization-flips",
         "§6.4 Edge Flipping: for every inconsistent face, the flip of one of its edges that "
         "removes the most inconsistent faces, ties to the best minimum Bank-Smith quality; no "
         "fold, no tiny triangle, every VBO defined, no degenerate edge; sweeps until no flip "
         "helps.",
         runOptimizationFlips, checkOptimizationFlips});
}

} // namespace contour::consistent
