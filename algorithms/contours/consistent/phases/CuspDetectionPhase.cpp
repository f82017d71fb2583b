// Cusp detection (Bénard 2014 §6.2 d, Fig. 15d, 16b, 18a-b).
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/numerics/ContourCuspSearch.h"
#include "contours/consistent/numerics/JointRootSearch.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/FoldTest.h"
#include "contours/consistent/predicates/Shiftability.h"

#include <cmath>
#include <map>

namespace contour::consistent {

namespace {

// The surface evaluates in double: below this longest edge (in domain
// parameters, about 900 ulps at coordinate 1) the corners of a bisected
// triangle are too few ulps apart for their signs to mean anything, so the
// search stops there whatever cusp-area-threshold says. With the paper's
// 1e-20 the search stops first at edges of about 1.4e-10, far above it.
constexpr long double kMinEdge = 1e-13L;
// Evaluations per face (a g = 0 and a κr = 0 curve running side by side
// keep many small triangles alive); a face that exhausts it is counted.
constexpr long long kMaxEvaluationsPerFace = 50000;
// A face changed by one cusp is searched again (a cusp it also held is found
// in the new faces); rounds bound that.
constexpr int kMaxRounds = 8;
// Two cusps closer than this (times the scene's diagonal) are one: a cusp
// on a mesh edge is found from both faces, and again from the faces an
// earlier round created around it. The search places a cusp to about
// 1e-10 of a domain face.
constexpr double kSameCusp = 1e-7;
// A split point this close (as a fraction of the split edge) to an end is
// that end: the cusp lies on the edge from the opposite vertex to it.
constexpr double kOnEdge = 1e-6;

struct Candidate {
    Triangle corners; // the face's vertices when it was searched
    Barycentric barycentric;
    Vec3 position;
};

// The preimage at barycentric coordinates b in face `t` (appendix B
// interpolation, twice: within the edge opposite the largest weight, then
// towards that corner, so no weight is divided by a tiny sum).
std::optional<Preimage> preimageAt(const ConsistentMesh& m, const Triangle& t,
                                   const Barycentric& b) {
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (b[i] > b[k])
            k = i;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const long double s = b[i] + b[j];
    const Preimage& pi = m.vertex(t[i]).preimage;
    std::optional<Preimage> q = pi;
    if (s > 0.0L)
        q = m.interpolate(pi, m.vertex(t[j]).preimage, static_cast<double>(b[j] / s));
    if (!q)
        return std::nullopt;
    return m.interpolate(m.vertex(t[k]).preimage, *q, static_cast<double>(s));
}

bool hasCuspEdge(const ConsistentMesh& m, Index v) {
    for (Index w : m.neighbours(v))
        if (m.edgeTag(v, w) & kCuspEdge)
            return true;
    return false;
}

// Moving w to p keeps every edge at w interpolable.
bool shiftKeepsEdges(const ConsistentMesh& m, Index w, const Preimage& p) {
    for (Index x : m.neighbours(w))
        if (!edgeInterpolates(m, p, m.vertex(x).preimage))
            return false;
    return true;
}

// Contour insertion's bisection of g (§6.2 e, ContourInsertionPhase.cpp) on
// the edge from o to S(s) on a-b, from its F end to its B end: whether it
// reaches |g| <= gTolerance within maxRootIterations steps.
bool insertionRootConverges(const ConsistentMesh& m, Index o, Index a, Index b, double s,
                            const ContourCuspOptions& roots) {
    const std::optional<Preimage> q = m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, s);
    if (!q)
        return false;
    const MeshVertex& vo = m.vertex(o);
    const bool front = vo.label == VertexLabel::Front;
    const Preimage px = front ? vo.preimage : *q, py = front ? *q : vo.preimage;
    BisectionOptions search;
    search.step = BisectionStep::Midpoint;
    search.sign = BisectionSign::Positive; // g > 0 at px (lo)
    search.maxIterations = roots.maxRootIterations;
    search.tolerance = roots.gTolerance;
    return bisect(
               [&](double along) -> std::optional<double> {
                   const std::optional<Preimage> p = m.interpolate(px, py, along);
                   if (!p)
                       return std::nullopt;
                   return m.evaluateWithoutCurvature(*p).g;
               },
               [](double g) { return g; }, {0.0, 1.0, 1.0, -1.0}, search)
               .outcome == BisectionOutcome::Converged;
}

// A face's edge A-B (opposite its odd corner O) that crosses g = 0 twice:
// the contour leaves the face through A-B and comes back, so no label sees
// that piece of it (nor a cusp on it). S(s) lies on O's side.
struct DoubleCrossing {
    Triangle corners; // the face when it was searched
    int odd = -1;     // O's position in corners; A and B follow it
    double s = 0.0;
};

struct Counts {
    long long found = 0, splits = 0, shifts = 0, onEdge = 0, evaluations = 0, budget = 0,
              undefined = 0, noChart = 0, interpolationFailed = 0, undefinedSamples = 0,
              brokenArcs = 0, jumps = 0, moved = 0, doubleCrossingSplits = 0;
    bool contourSearch = false;
    std::map<std::string, long long> skipped;
};

// cusp-contour-samples: κr sampled on the contour's crossing of a face whose
// corners have one odd label (ContourCuspSearch.h). The cusp's barycentric
// coordinates put it on the line from the odd corner O to S(s) on A-B, so
// placeCusp splits A-B at s, the same S.
void searchAlongContour(const ConsistentMesh& m, const Triangle& t,
                        const ContourCuspOptions& options, std::vector<Candidate>& out,
                        std::vector<DoubleCrossing>& doubleCrossings, Counts& n) {
    int odd = -1;
    for (int i = 0; i < 3; ++i) {
        const VertexLabel l = m.vertex(t[i]).label;
        if (l == VertexLabel::Contour)
            return; // placeCusp could not use it either
        if (l != m.vertex(t[(i + 1) % 3]).label && l != m.vertex(t[(i + 2) % 3]).label)
            odd = i;
    }
    if (odd < 0)
        return;
    const int ia = (odd + 1) % 3, ib = (odd + 2) % 3;
    ContourCuspStats stats;
    for (const ContourPoint& c : contourCuspsInFace(m, t[odd], t[ia], t[ib], options, stats)) {
        Barycentric b{0.0L, 0.0L, 0.0L};
        b[odd] = 1.0L - c.t;
        b[ia] = static_cast<long double>(c.t) * (1.0L - c.s);
        b[ib] = static_cast<long double>(c.t) * c.s;
        out.push_back({t, b, c.position});
    }
    // A sign change of κr across a gap: the cusp lies on the piece of
    // contour beyond A-B. One split per face (the next round searches the
    // new faces again).
    if (!stats.brokenArcGaps.empty())
        doubleCrossings.push_back({t, odd, stats.brokenArcGaps.front()});
    n.evaluations += stats.evaluations;
    n.undefinedSamples += stats.undefinedSamples;
    n.brokenArcs += static_cast<long long>(stats.brokenArcGaps.size());
    n.jumps += stats.jumps;
}

// §6.2 d: per face, g and κr at the corners; both changing sign → the joint
// root search in the face's common chart (the mesh is not modified).
std::vector<Candidate> searchFaces(const ConsistentMesh& m, const PhaseContext& ctx,
                                   const JointRootOptions& options, int subdivision,
                                   const ContourCuspOptions& contour, bool onlyChangedFaces,
                                   int phase, std::vector<DoubleCrossing>& doubleCrossings,
                                   Counts& n) {
    std::vector<Candidate> out;
    const int k = 1 << subdivision; // lattice steps per face side
    for (Index f = 0; f < m.faceCount(); ++f) {
        if (f % 4096 == 0)
            ctx.checkCancelled();
        if (onlyChangedFaces && m.facePhase(f) != phase)
            continue;
        const Triangle t = m.face(f);
        if (contour.samples > 0) {
            searchAlongContour(m, t, contour, out, doubleCrossings, n);
            continue;
        }
        std::array<std::array<double, 2>, 3> values;
        for (int i = 0; i < 3; ++i)
            values[i] = {m.vertex(t[i]).g, m.vertex(t[i]).radialCurvature};
        // The paper tests both functions at the face's corners; with
        // cusp-search-subdivision, g alone decides here and both are tested
        // at the corners of the sub-triangles.
        if (!mayChangeSign(values[0][0], values[1][0], values[2][0]) ||
            (k == 1 && !mayChangeSign(values[0][1], values[1][1], values[2][1])))
            continue;
        const auto charts = m.chartCoordinates(
            {m.vertex(t[0]).preimage, m.vertex(t[1]).preimage, m.vertex(t[2]).preimage});
        if (charts.empty()) {
            ++n.noChart;
            continue;
        }
        const auto chartPoint = [&](const Barycentric& b) {
            Point2L p{0.0L, 0.0L};
            for (int i = 0; i < 3; ++i)
                for (int c = 0; c < 2; ++c)
                    p[c] += b[i] * static_cast<long double>(charts[0][i][c]);
            return p;
        };
        const auto evaluateAt = [&](const Barycentric& b) -> std::array<double, 2> {
            const std::optional<Preimage> p = preimageAt(m, t, b);
            if (!p) {
                ++n.interpolationFailed;
                return {std::nan(""), std::nan("")};
            }
            const MeshVertex v = m.evaluate(*p);
            return {v.g, v.radialCurvature};
        };
        // The regular lattice of barycentric points (i, j) / k, i + j <= k
        // (the weights of corners 1 and 2), evaluated once.
        std::vector<Barycentric> lattice;
        std::vector<std::array<double, 2>> latticeValues;
        const auto node = [&](int i, int j) {
            return j * (k + 1) - j * (j - 1) / 2 + i;
        };
        for (int j = 0; j <= k; ++j)
            for (int i = 0; i + j <= k; ++i) {
                const long double b1 = static_cast<long double>(i) / k;
                const long double b2 = static_cast<long double>(j) / k;
                lattice.push_back({1.0L - b1 - b2, b1, b2});
                const int corner = i == 0 && j == 0 ? 0 : i == k ? 1 : j == k ? 2 : -1;
                latticeValues.push_back(corner >= 0 ? values[corner] : evaluateAt(lattice.back()));
                n.evaluations += corner < 0;
            }
        std::vector<std::array<int, 3>> cells;
        for (int j = 0; j < k; ++j)
            for (int i = 0; i + j < k; ++i) {
                cells.push_back({node(i, j), node(i + 1, j), node(i, j + 1)});
                if (i + j + 1 < k)
                    cells.push_back({node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
            }
        for (const auto& cell : cells) {
            std::array<Point2L, 3> corners;
            std::array<std::array<double, 2>, 3> cellValues;
            for (int i = 0; i < 3; ++i) {
                corners[i] = chartPoint(lattice[cell[i]]);
                cellValues[i] = latticeValues[cell[i]];
            }
            // Barycentric coordinates in the cell -> in the face.
            const auto inFace = [&](const Barycentric& c) {
                Barycentric b{0.0L, 0.0L, 0.0L};
                for (int i = 0; i < 3; ++i)
                    for (int q = 0; q < 3; ++q)
                        b[q] += c[i] * lattice[cell[i]][q];
                return b;
            };
            const JointRootResult r = findJointRoots(
                corners, cellValues,
                [&](const Point2L&, const Barycentric& c) { return evaluateAt(inFace(c)); },
                options);
            n.evaluations += r.evaluations;
            n.budget += r.budgetExhausted;
            n.undefined += r.rejectedUndefined;
            for (const JointRoot& root : r.roots) {
                const Barycentric b = inFace(root.barycentric);
                const std::optional<Preimage> p = preimageAt(m, t, b);
                if (!p) {
                    ++n.interpolationFailed;
                    continue;
                }
                out.push_back({t, b, m.evaluate(*p).position});
            }
        }
    }
    return out;
}

// The face that still has exactly these corners, or kInvalidIndex.
Index intactFace(const ConsistentMesh& m, const Triangle& t) {
    const Index f = m.faceOfHalfedge(t[0], t[1]);
    if (f == kInvalidIndex)
        return kInvalidIndex;
    for (Index w : m.face(f))
        if (w == t[2])
            return f;
    return kInvalidIndex;
}

// §6.2 d, Fig. 16b: put the cusp on an FB edge. O is the corner whose label
// differs from the two others (A, B: the face's only FF or BB edge). The line
// from O through the cusp meets A-B at S = (λA A + λB B) / (λA + λB); split
// A-B at S, so that the new edge O-S holds the cusp; or, when S is within
// cusp-shift-fraction of A-B's length from A (or B), the cusp is that close
// to edge O-A (O-B) and the split would leave a sliver: shift that endpoint
// to S instead when it is shiftable (appendix C).
void placeCusp(ConsistentMesh& m, const Candidate& c, double shiftFraction,
               const ContourCuspOptions& roots, int phase, Counts& n) {
    const Triangle& t = c.corners;
    int odd = -1;
    for (int i = 0; i < 3; ++i) {
        const VertexLabel l = m.vertex(t[i]).label;
        if (l == VertexLabel::Contour) {
            ++n.skipped["a corner of its face is a C vertex"];
            return;
        }
        if (l != m.vertex(t[(i + 1) % 3]).label && l != m.vertex(t[(i + 2) % 3]).label)
            odd = i;
    }
    if (odd < 0) {
        ++n.skipped["its face's corners all have the same label"];
        return;
    }
    const int ia = (odd + 1) % 3, ib = (odd + 2) % 3;
    const Index o = t[odd], a = t[ia], b = t[ib];
    const long double sum = c.barycentric[ia] + c.barycentric[ib];
    if (!(sum > 0.0L)) {
        ++n.skipped["it lies on the opposite corner"];
        return;
    }
    double s = static_cast<double>(c.barycentric[ib] / sum);
    // Contour insertion bisects g on the cusp edge O-S (§6.2 e). Near
    // extraordinary vertices the evaluator's sub-patches meet with g (and
    // κr) not quite continuous, and a cusp found there (κr changes sign
    // across such a boundary) can sit where g jumps over 0: that bisection
    // never converges (|g| post-condition). Move S along A-B until the same
    // bisection converges.
    if (!insertionRootConverges(m, o, a, b, s, roots)) {
        bool moved = false;
        for (double offset = roots.jumpOffset; !moved && offset <= 1001.0 * roots.jumpOffset;
             offset *= 10.0)
            for (const double near : {s + offset, s - offset})
                if (!moved && near > 0.0 && near < 1.0 &&
                    insertionRootConverges(m, o, a, b, near, roots)) {
                    s = near;
                    moved = true;
                }
        if (!moved) {
            ++n.skipped["the root of g on its cusp edge does not converge (g jumps over 0)"];
            return;
        }
        ++n.moved;
    }
    const std::optional<Preimage> ps = m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, s);
    if (!ps) {
        ++n.skipped["no common chart for the split point (appendix B)"];
        return;
    }
    MeshVertex split = m.evaluate(*ps);
    if (split.label != m.vertex(a).label) {
        // g changes sign again between the cusp and A-B: O-S would not be
        // an FB edge.
        ++n.skipped["the line through the cusp crosses g = 0 twice"];
        return;
    }
    // The cusp already lies on edge O-A (O-B) to within double precision:
    // splitting there would duplicate A; that edge is the cusp edge.
    for (const auto& [w, on] : {std::pair{a, s < kOnEdge}, std::pair{b, s > 1.0 - kOnEdge}}) {
        if (!on)
            continue;
        if (m.edgeTag(o, w) & kCuspEdge) {
            ++n.skipped["two cusps on one edge"];
            return;
        }
        if (m.faceOfHalfedge(o, w) == kInvalidIndex || m.faceOfHalfedge(w, o) == kInvalidIndex) {
            ++n.skipped["it lies on a boundary edge"];
            return;
        }
        m.addEdgeTag(o, w, kCuspEdge);
        ++n.onEdge;
        return;
    }
    for (const auto& [w, near] :
         {std::pair{a, s < shiftFraction}, std::pair{b, s > 1.0 - shiftFraction}}) {
        if (!near || hasCuspEdge(m, w) || m.faceOfHalfedge(o, w) == kInvalidIndex ||
            m.faceOfHalfedge(w, o) == kInvalidIndex || !shiftable(m, w, *ps, m.vertex(w).label) ||
            !shiftKeepsEdges(m, w, *ps))
            continue;
        m.shiftVertex(w, *ps, m.vertex(w).label, phase);
        m.addEdgeTag(o, w, kCuspEdge);
        ++n.shifts;
        return;
    }
    if (!splitKeepsCharts(m, a, b, *ps)) {
        ++n.skipped["the split would fold a face or leave it without a common chart (appendix "
                    "B)"];
        return;
    }
    split.provenance = Provenance::Inserted;
    const Index v = m.splitEdge(a, b, split, phase);
    m.addEdgeTag(o, v, kCuspEdge);
    ++n.splits;
}

// §6.1's sign-crossing split, for an edge whose double crossing of g = 0
// the initialization's samples missed: A-B is split at S(s), on O's side, so
// that A-S and S-B each cross g = 0 once and contour insertion sees the
// piece of contour beyond A-B. The new faces are searched again for cusps.
bool splitDoubleCrossing(ConsistentMesh& m, const DoubleCrossing& d, int phase) {
    if (intactFace(m, d.corners) == kInvalidIndex)
        return false;
    const Index o = d.corners[d.odd], a = d.corners[(d.odd + 1) % 3],
                b = d.corners[(d.odd + 2) % 3];
    const std::optional<Preimage> p = m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, d.s);
    if (!p || !splitKeepsCharts(m, a, b, *p))
        return false;
    MeshVertex v = m.evaluate(*p);
    if (v.label != m.vertex(o).label)
        return false;
    v.provenance = Provenance::Inserted;
    m.splitEdge(a, b, v, phase);
    return true;
}

// Two cusps so close that their cusp edges share a face (the second cusp
// was found in a face the first one split): inserting both would give the
// first cusp vertex a fifth neighbour, the second one (§6.2 f wants valence
// 4, Fig. 18d). The two edges share a vertex; splitting the face's third edge
// (same labels at both ends) at its midpoint puts a face between them.
// Returns the splits, or -1 when an interpolation failed.
long long separateCuspEdges(ConsistentMesh& m, int phase) {
    long long splits = 0;
    for (bool again = true; again;) {
        again = false;
        for (Index f = 0; f < m.faceCount() && !again; ++f) {
            const Triangle t = m.face(f);
            if (cuspEdgesOf(m, t) < 2)
                continue;
            for (int i = 0; i < 3; ++i) {
                const Index p = t[(i + 1) % 3], q = t[(i + 2) % 3];
                if (m.edgeTag(p, q) & kCuspEdge)
                    continue;
                const std::optional<Preimage> mid =
                    m.interpolate(m.vertex(p).preimage, m.vertex(q).preimage, 0.5);
                if (!mid)
                    return -1;
                if (!splitKeepsCharts(m, p, q, *mid))
                    return -1;
                MeshVertex v = m.evaluate(*mid);
                v.provenance = Provenance::Inserted;
                m.splitEdge(p, q, v, phase);
                ++splits;
                again = true;
                break;
            }
        }
    }
    return splits;
}

// The phase's parameters, read once per run.
struct CuspDetectionOptions {
    double areaThreshold = 0.0; // cusp-area-threshold
    double shiftFraction = 0.0; // cusp-shift-fraction
    int subdivision = 0;        // cusp-search-subdivision
    int contourSamples = 0;     // cusp-contour-samples
    bool splitDoubleCrossings = true; // cusp-double-crossing-split
    // Contour insertion's root search, which the cusp's edge must pass.
    ContourRootOptions roots;
    static CuspDetectionOptions read(const ParameterSet& p) {
        CuspDetectionOptions o;
        o.areaThreshold = p.getDouble("cusp-area-threshold");
        o.shiftFraction = p.getDouble("cusp-shift-fraction");
        o.subdivision = p.getInt("cusp-search-subdivision");
        o.contourSamples = p.getInt("cusp-contour-samples");
        o.splitDoubleCrossings = p.getBool("cusp-double-crossing-split");
        o.roots = ContourRootOptions::read(p);
        return o;
    }
};

void runCuspDetection(const PhaseContext& ctx, Snapshot& s) {
    const CuspDetectionOptions parameters = CuspDetectionOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    JointRootOptions options;
    options.minArea = static_cast<long double>(parameters.areaThreshold);
    options.minEdge = kMinEdge;
    options.maxEvaluations = kMaxEvaluationsPerFace;
    const double shiftFraction = parameters.shiftFraction;
    const int subdivision = parameters.subdivision;
    ContourCuspOptions contour;
    contour.samples = parameters.contourSamples;
    const ContourRootOptions& roots = parameters.roots;
    contour.gTolerance = 0.5 * roots.tolerance * sceneScale(m);
    contour.maxRootIterations = roots.maxIterations;
    const double same = kSameCusp * sceneScale(m);
    Counts n;
    n.contourSearch = contour.samples > 0;
    std::vector<Vec3> handled;
    long long deferred = 0;
    for (int round = 0; round < kMaxRounds; ++round) {
        std::vector<DoubleCrossing> doubleCrossings;
        const std::vector<Candidate> candidates = searchFaces(m, ctx, options, subdivision, contour,
                                                              round > 0, phase, doubleCrossings, n);
        deferred = 0;
        for (const Candidate& c : candidates) {
            bool known = false;
            for (const Vec3& h : handled)
                known = known || (h - c.position).norm() < same;
            if (known)
                continue;
            // A face changed by an earlier cusp of this round: its new faces
            // are searched in the next round.
            if (intactFace(m, c.corners) == kInvalidIndex) {
                ++deferred;
                continue;
            }
            handled.push_back(c.position);
            ++n.found;
            placeCusp(m, c, shiftFraction, contour, phase, n);
        }
        // After the cusps found in intact faces: a face split by a cusp is
        // searched again in the next round anyway.
        long long split = 0;
        if (parameters.splitDoubleCrossings)
            for (const DoubleCrossing& d : doubleCrossings)
                split += splitDoubleCrossing(m, d, phase);
        n.doubleCrossingSplits += split;
        if (deferred == 0 && split == 0)
            break;
    }
    const long long separations = separateCuspEdges(m, phase);
    publish(s, m);
    s.setCounter(counters::kCuspSeparations, static_cast<double>(separations));
    if (separations < 0)
        s.notes.push_back("two cusp edges share a face and could not be separated (no common "
                          "chart or a fold, appendix B): a cusp vertex will not have valence 4");
    long long skipped = 0;
    for (const auto& [why, count] : n.skipped) {
        skipped += count;
        s.notes.push_back(std::to_string(count) + " cusps skipped (no cusp edge): " + why);
    }
    s.setCounter(counters::kCuspsFound, static_cast<double>(n.found));
    s.setCounter(counters::kCuspSplits, static_cast<double>(n.splits));
    s.setCounter(counters::kCuspShifts, static_cast<double>(n.shifts));
    s.setCounter(counters::kCuspsOnAnEdge, static_cast<double>(n.onEdge));
    s.setCounter(counters::kCuspsMovedOffAJumpOfG, static_cast<double>(n.moved));
    s.setCounter(counters::kCuspsSkipped, static_cast<double>(skipped + deferred));
    s.setCounter(counters::kCuspSearchEvaluations, static_cast<double>(n.evaluations));
    if (deferred > 0)
        s.notes.push_back(std::to_string(deferred) +
                          " cusps skipped: their face was still being "
                          "changed by other cusps after " +
                          std::to_string(kMaxRounds) + " rounds");
    if (n.budget > 0)
        s.notes.push_back(std::to_string(n.budget) + " faces stopped the cusp search after " +
                          std::to_string(kMaxEvaluationsPerFace) +
                          " evaluations (g = 0 and κr = 0 run side by side there); cusps in them "
                          "may be missed");
    if (n.noChart > 0)
        s.notes.push_back(std::to_string(n.noChart) +
                          " faces with sign changes of g and κr were not searched: no common "
                          "chart (appendix B)");
    if (n.interpolationFailed > 0)
        s.notes.push_back(std::to_string(n.interpolationFailed) +
                          " cusp-search points had no common chart (appendix B) and were "
                          "treated as unknown");
    if (n.contourSearch) {
        s.setCounter(counters::kCuspSignChangesAcrossAGap, static_cast<double>(n.brokenArcs));
        s.setCounter(counters::kCuspSignChangesByAJump, static_cast<double>(n.jumps));
        s.setCounter(counters::kCuspDoubleCrossingSplits,
                     static_cast<double>(n.doubleCrossingSplits));
    }
    // The contour search's notes (ContourCuspSearch.h), when their count is > 0.
    const auto note = [&s](long long count, const char* what) {
        if (count > 0)
            s.notes.push_back(std::to_string(count) + what);
    };
    note(n.doubleCrossingSplits,
         " edges opposite a face's odd corner cross g = 0 twice (the contour leaves the face "
         "through them and comes back; the initialization's samples missed it): split there as "
         "§6.1 splits sign crossings, and the new faces searched again for cusps");
    note(n.brokenArcs, " sign changes of the radial curvature across a gap in the contour's "
                       "crossing of a face (the contour leaves through the edge opposite the odd "
                       "corner, which crosses g = 0 twice)");
    note(n.jumps, " sign changes of the radial curvature were jumps over 0, not roots (second "
                  "derivatives not continuous across the evaluator's patch boundaries near "
                  "extraordinary vertices); they are cusps all the same");
    note(n.moved, " cusps were moved 1e-6 to 1e-3 of their face's edge along the contour: g "
                  "jumps over 0 at the sign change (a patch boundary), where the root of g on "
                  "the cusp edge would not converge");
    note(n.undefinedSamples, " radial-curvature samples along the contour were undefined (no "
                             "common chart, g of one sign on the line, or κr NaN or 0) and "
                             "skipped");
    if (n.undefined > 0)
        s.notes.push_back(std::to_string(n.undefined) +
                          " smallest search triangles rejected: κr undefined (view along the "
                          "normal) at a corner");
}

std::vector<InvariantCheck> checkCuspDetection(const PhaseContext& ctx, const Snapshot& s) {
    return cuspPhaseChecks(ctx, s);
}

} // namespace

void addCuspDetectionPhase(Method& m) {
    m.parameters.push_back(
        {"cusp-area-threshold",
         "Cusp area threshold",
         "The cusp search (§6.2 d) bisects a face in parameter space while g and the "
         "radial curvature both change sign over it, and returns its centroid once the "
         "area is below this (paper: 1e-20, in quad precision; here long double, "
         "stopping also at edges below 1e-13).",
         ParameterType::Double,
         1e-20,
         1e-26,
         1e-6,
         {}});
    m.parameters.push_back(
        {"cusp-shift-fraction",
         "Cusp shift fraction",
         "When the split point that puts a cusp on an FB edge (§6.2 d, Fig. 16b) is "
         "within this fraction of the split edge's length of one of its ends, that end "
         "is shifted there if shiftable (appendix C) instead. The paper gives no value.",
         ParameterType::Double,
         0.1,
         0.0,
         0.5,
         {}});
    m.parameters.push_back(
        {"cusp-search-subdivision",
         "Cusp search subdivision",
         "Not in the paper (0: the paper's test of g and the radial curvature at the "
         "face's corners, §6.2 d). k > 0: every face over which g changes sign is split "
         "into 4^k sub-triangles in parameter space, each tested on its own, so that "
         "cusp pairs inside one face are found.",
         ParameterType::Int,
         0,
         0,
         4,
         {}});
    m.parameters.push_back(
        {"cusp-contour-samples",
         "Cusp samples along the contour",
         "Not in the paper (0: the corner test of §6.2 d). n > 0: the radial curvature "
         "is sampled on the contour's crossing of every face whose corners' labels "
         "differ, down to 1/n of the edge near minima of its magnitude; sign changes are "
         "bisected. Replaces the corner test and cusp-search-subdivision.",
         ParameterType::Int,
         32,
         0,
         256,
         {}});
    m.parameters.push_back(
        {"cusp-double-crossing-split",
         "Split double crossings at cusps",
         "Not in the paper. With cusp-contour-samples: where κr changes sign across a gap "
         "(the edge opposite the odd corner crosses g = 0 twice), split that edge as §6.1 "
         "does and search the new faces, so the cusp beyond it is found.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"cusp-detection",
         "§6.2 d (Fig. 15d, 16b, 18b): per face, where g and the radial curvature both change "
         "sign, recursive bisection in parameter space down to cusp-area-threshold; each cusp "
         "is put on an FB edge (tagged as a cusp edge) by splitting the face's FF or BB edge "
         "on the line from the opposite vertex through the cusp, or by shifting a shiftable "
         "vertex when the cusp is within cusp-shift-fraction of a face edge.",
         runCuspDetection, checkCuspDetection});
}

} // namespace contour::consistent
