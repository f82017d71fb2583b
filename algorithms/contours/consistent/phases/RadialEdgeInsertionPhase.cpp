// Radial edge insertion (Bénard 2014 §6.3 g, Fig. 15g, 16d, 17, 18e; notes
// §2.3, §6.1 item 6).
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/numerics/JointRootSearch.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/FoldTest.h"
#include "contours/consistent/predicates/RadialTriangles.h"

#include <algorithm>
#include <cmath>

namespace contour::consistent {

namespace {

// Why a side of a C vertex got no radial edge (each failed attempt is
// counted under exactly one reason).
enum class Outcome {
    Inserted,
    NoCrossing,     // p's radial plane crosses no opposite edge on that side
    NoSignChange,   // h_p has the same sign at the two edge midpoints
    AcrossContour,  // the root's label is not the side's (g changes sign inside)
    Fold,           // Fig. 17: folds, and no flip of the adjacent edge removes it
    ParameterFold,  // a new face would fold in parameter space
    NoChart,        // appendix B: no common chart, cancelled
    Unconverged,    // bisection did not reach radial-root-tolerance
    Defect,         // the edit would leave an undefined VBO or a degenerate edge
    CuspAmbiguous,  // a cusp whose outside region (Fig. 18e) is not identified
    LessConsistent, // radial-keep-consistency: more inconsistent faces than before
    NextToCusp,     // would raise the valence of a cusp left without radial edges
    CuspInside,     // radial-cusp-inside-hops: the inside region of a nearby cusp (Fig. 18e)
};
constexpr int kOutcomes = 13;
constexpr CounterName kOutcomeCounters[kOutcomes] = {
    counters::kRadialEdgesInserted,
    counters::kSkippedNoCrossingFace,
    counters::kSkippedNoSignChangeBetweenMidpoints,
    counters::kSkippedRootAcrossTheContour,
    counters::kSkippedFoldNoFlipFixesIt,
    counters::kSkippedParameterSpaceFold,
    counters::kSkippedNoCommonChart,
    counters::kSkippedUnconvergedRoot,
    counters::kSkippedVBODefect,
    counters::kSkippedCuspOutsideRegionAmbiguous,
    counters::kSkippedMoreInconsistentFaces,
    counters::kSkippedNextToACuspWithoutRadialEdges,
    counters::kSkippedInsideRegionOfANearbyCusp,
};

struct Settings {
    double tolerance = 0.0; // distance to the radial plane, absolute
    int maxIterations = 100;
    double jointMinBarycentric = 0.05;
    long long jointMaxEvaluations = 20000;
    bool keepConsistency = true;
    int cuspInsideHops = 0;
    // radial-cusp-inside-pixels: the inside region also reaches C vertices
    // this far from the cusp along the contour in the image (0: hops only).
    double cuspInsidePixels = 0.0;
    // radial-cusp-pair-pixels: a C vertex between two cusps whose inside
    // regions lie on opposite sides, within this many pixels of both along
    // the contour, gets radial edges on both sides (0: off).
    double cuspPairPixels = 0.0;
    bool edgeFallback = true;
    bool bothSidesWhenAmbiguous = true;

    // The phase's parameters, read once per run; `scale` is the bounding-box
    // diagonal the radial tolerance is relative to.
    static Settings read(const ParameterSet& p, double scale) {
        Settings set;
        const RadialEdgeOptions radial = RadialEdgeOptions::read(p);
        set.tolerance = radial.rootTolerance * scale;
        set.maxIterations = radial.rootMaxIterations;
        set.jointMinBarycentric = p.getDouble("radial-joint-min-barycentric");
        set.jointMaxEvaluations = p.getInt("radial-joint-max-evaluations");
        set.keepConsistency = radial.keepConsistency;
        set.cuspInsideHops = p.getInt("radial-cusp-inside-hops");
        set.cuspInsidePixels = p.getDouble("radial-cusp-inside-pixels");
        set.cuspPairPixels = p.getDouble("radial-cusp-pair-pixels");
        set.edgeFallback = p.getBool("radial-cusp-opposite-edge");
        set.bothSidesWhenAmbiguous = p.getBool("radial-cusp-both-sides");
        return set;
    }
};

// The preimage at barycentric coordinates b of the corners t (appendix B
// interpolation twice: along the edge opposite the largest weight, then
// towards that corner).
std::optional<Preimage> preimageAt(const ConsistentMesh& m, const Triangle& t,
                                   const Barycentric& b) {
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (b[i] > b[k])
            k = i;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const long double s = b[i] + b[j];
    std::optional<Preimage> q = m.vertex(t[i]).preimage;
    if (s > 0.0L)
        q = m.interpolate(*q, m.vertex(t[j]).preimage, static_cast<double>(b[j] / s));
    if (!q)
        return std::nullopt;
    return m.interpolate(m.vertex(t[k]).preimage, *q, static_cast<double>(s));
}

class RadialInserter {
public:
    RadialInserter(ConsistentMesh& mesh, const Settings& settings, int phase)
        : m_(mesh), set_(settings), phase_(phase) {}

    long long counts[kOutcomes] = {};
    long long jointVertices = 0, jointFallbacks = 0, foldFlips = 0, undone = 0, laterFaces = 0,
              beyondMidpoints = 0, onOppositeEdge = 0, pairVertices = 0;
    double maxResidual = 0.0;

    // §6.3 (g) for one C vertex: one radial edge on each side (F, B), or, at
    // a cusp, two on the outside region (Fig. 18e).
    void process(Index p) {
        if (!m_.vertex(p).cusp) {
            const VertexLabel inside = cuspInsideSide(p);
            pairVertices += inside == VertexLabel::Contour && betweenOppositeCusps_;
            for (VertexLabel side : {VertexLabel::Front, VertexLabel::Back})
                if (radialEdgesOnSide(m_, p, side) == 0)
                    ++counts[static_cast<int>(side == inside ? Outcome::CuspInside
                                                             : insertOnSide(p, side))];
            return;
        }
        // Fig. 18e: the outside region is where the radial curve leaves the
        // cusp twice, i.e. the side whose fan the radial plane crosses more.
        const size_t front = crossings(p, VertexLabel::Front).size();
        const size_t back = crossings(p, VertexLabel::Back).size();
        const int have = radialEdgesOnSide(m_, p, VertexLabel::Front) +
                         radialEdgesOnSide(m_, p, VertexLabel::Back);
        if (front == back) {
            // One crossing on each side: no side is the outside, but each
            // side's radial curve leaves the cusp once, so each side gets
            // one radial edge (radial-cusp-both-sides; the cusp then counts
            // as complete, two radial edges).
            if (!set_.bothSidesWhenAmbiguous || front != 1) {
                counts[static_cast<int>(Outcome::CuspAmbiguous)] += std::max(0, 2 - have);
                return;
            }
            for (VertexLabel side : {VertexLabel::Front, VertexLabel::Back})
                if (radialEdgesOnSide(m_, p, side) == 0)
                    ++counts[static_cast<int>(insertOnSide(p, side))];
            return;
        }
        const VertexLabel outside = front > back ? VertexLabel::Front : VertexLabel::Back;
        for (int k = radialEdgesOnSide(m_, p, outside); k < 2; ++k)
            ++counts[static_cast<int>(insertOnSide(p, outside))];
    }

private:
    ConsistentMesh& m_;
    const Settings& set_;
    const int phase_;
    // Set by cuspInsideSide(): p lies between two cusps with opposite
    // inside sides (radial-cusp-pair-pixels).
    bool betweenOppositeCusps_ = false;

    // Fig. 18e: no radial triangles in a cusp's "inside" region (the side
    // opposite its two radial edges). With radial-cusp-inside-hops k > 0,
    // that region also covers the side of the C vertices up to k contour
    // edges from the cusp: their radial curves on that side run across the
    // thin image wedge between the cusp's two branches and meet the other
    // branch. Returns that side, or Contour (none) when p is farther, or the
    // cusp's outside is unknown (no radial edges, cusps are processed first).
    //
    // With radial-cusp-inside-pixels P > 0 the region also covers the C
    // vertices whose path of C-C edges to the cusp is at most P pixels long
    // in the image, however many edges that takes (not in the paper: the
    // wedge is thin for a distance in the image, not for a number of edges,
    // which differs between coarse and dense meshes).
    //
    // With radial-cusp-pair-pixels P > 0, a C vertex that reaches two cusps
    // whose inside regions are on opposite sides (F inside one, B inside
    // the other: the two cusps of a swallowtail-like zig-zag of the
    // contour), along contour paths of at most P pixels in all, is in
    // neither inside region and gets both radial edges (Contour is
    // returned; not in the paper: each cusp's wedge is closed by the other
    // cusp there, and skipping the side of whichever cusp the search meets
    // first left inconsistent faces beside such pairs).
    VertexLabel cuspInsideSide(Index p) {
        betweenOppositeCusps_ = false;
        if (set_.cuspInsideHops <= 0 && set_.cuspInsidePixels <= 0.0)
            return VertexLabel::Contour;
        const Camera& camera = m_.camera();
        const auto pixel = [&](Index v) {
            return camera.project(m_.vertex(v).position).pixel;
        };
        struct Reached {
            Index v;
            double pixels;
        };
        std::vector<Reached> frontier{{p, 0.0}};
        std::vector<Index> seen{p};
        VertexLabel first = VertexLabel::Contour;
        // Nearest cusp with F inside, with B inside (pixels along the contour).
        double nearest[2] = {INFINITY, INFINITY};
        for (int hop = 0; !frontier.empty(); ++hop) {
            std::vector<Reached> next;
            for (const Reached& r : frontier)
                for (Index w : m_.neighbours(r.v)) {
                    if (m_.vertex(w).label != VertexLabel::Contour ||
                        std::find(seen.begin(), seen.end(), w) != seen.end())
                        continue;
                    const double pixels = r.pixels + (pixel(w) - pixel(r.v)).norm();
                    const bool withinHops = hop < set_.cuspInsideHops;
                    const bool withinPixels = pixels <= set_.cuspInsidePixels;
                    if (!withinHops && !withinPixels)
                        continue;
                    seen.push_back(w);
                    if (m_.vertex(w).cusp) {
                        const int front = radialEdgesOnSide(m_, w, VertexLabel::Front);
                        const int back = radialEdgesOnSide(m_, w, VertexLabel::Back);
                        if (front != back) {
                            const VertexLabel in =
                                front > back ? VertexLabel::Back : VertexLabel::Front;
                            if (first == VertexLabel::Contour)
                                first = in;
                            double& d = nearest[in == VertexLabel::Front ? 0 : 1];
                            d = std::min(d, pixels);
                        }
                        continue;
                    }
                    next.push_back({w, pixels});
                }
            frontier = std::move(next);
            // The first cusp met decides, unless a pair is looked for.
            if (first != VertexLabel::Contour && set_.cuspPairPixels <= 0.0)
                return first;
        }
        if (nearest[0] + nearest[1] <= set_.cuspPairPixels) {
            betweenOppositeCusps_ = true;
            return VertexLabel::Contour;
        }
        return first;
    }

    // The bisection of h_p along a segment whose ends h_p separates (lo on
    // the negative side or not), to the radial tolerance.
    BisectionOptions radialRootSearch() const {
        BisectionOptions o;
        o.step = BisectionStep::Midpoint;
        o.sign = BisectionSign::Negative;
        o.maxIterations = set_.maxIterations;
        o.tolerance = set_.tolerance;
        return o;
    }

    double distance(Index p, const Vec3& q) const {
        return radialPlaneDistance(m_.camera(), m_.vertex(p), q);
    }

    // Faces p-a-b (counter-clockwise) around p on `side` (their other
    // corners are `side` or C) whose opposite edge a-b p's radial plane
    // crosses: sgn h_p(f(u_a)) != sgn h_p(f(u_b)) (§6.3 g). Faces that
    // already hold one of p's radial edges are not candidates. Nearest
    // crossing first.
    struct Crossing {
        Triangle corners; // p, a, b
        double distance;
    };
    std::vector<Crossing> crossings(Index p, VertexLabel side) const {
        std::vector<Crossing> out;
        for (Index f : m_.vertexFaces(p)) {
            const Triangle t = rotatedTo(m_.face(f), p);
            const VertexLabel la = m_.vertex(t[1]).label, lb = m_.vertex(t[2]).label;
            const VertexLabel region = la == VertexLabel::Contour ? lb : la;
            if (region != side || (lb != VertexLabel::Contour && lb != side))
                continue;
            if (isRadialEdge(m_, p, t[1]) || isRadialEdge(m_, p, t[2]))
                continue;
            const Vec3 &a = m_.vertex(t[1]).position, &b = m_.vertex(t[2]).position;
            const double ha = distance(p, a), hb = distance(p, b);
            if (!((ha < 0.0 && hb > 0.0) || (ha > 0.0 && hb < 0.0)))
                continue;
            const Vec3 x = a + ha / (ha - hb) * (b - a);
            out.push_back({t, (x - m_.vertex(p).position).norm()});
        }
        std::sort(out.begin(), out.end(),
                  [](const Crossing& x, const Crossing& y) { return x.distance < y.distance; });
        return out;
    }

    Outcome insertOnSide(Index p, VertexLabel side) {
        const std::vector<Crossing> candidates = crossings(p, side);
        if (candidates.empty())
            return Outcome::NoCrossing;
        const Triangle t = candidates.front().corners;
        // Two C vertices p, p2 (§6.3 g, Fig. 16d right): when p2's radial
        // plane crosses the face too and p2 still needs a radial edge on
        // this side, look for the joint zero of h_p and h_p2 in the face.
        for (int i : {1, 2}) {
            const Index p2 = t[i], q = t[3 - i];
            if (m_.vertex(p2).label != VertexLabel::Contour || m_.vertex(p2).cusp ||
                radialEdgesOnSide(m_, p2, side) > 0)
                continue;
            const double h0 = distance(p2, m_.vertex(p).position),
                         h1 = distance(p2, m_.vertex(q).position);
            if (!((h0 < 0.0 && h1 > 0.0) || (h0 > 0.0 && h1 < 0.0)))
                continue;
            if (insertJoint(t, p, p2, side) == Outcome::Inserted) {
                ++jointVertices;
                return Outcome::Inserted;
            }
            // No usable joint zero: the radial edges one after the other.
            ++jointFallbacks;
        }
        // The nearest crossing face first, as the paper; when its
        // insertion is impossible, the next faces whose opposite edge the
        // plane crosses (the fan can hold several near a fold of the radial
        // curve). The first failure's reason is the one counted.
        Outcome first = insertOneVertex(t, side);
        for (size_t i = 1; i < candidates.size() && first != Outcome::Inserted; ++i)
            if (insertOneVertex(candidates[i].corners, side) == Outcome::Inserted) {
                ++laterFaces;
                return Outcome::Inserted;
            }
        // A cusp's radial curve leaves it tangent to the contour (Fig. 18e),
        // so the root between the midpoints of its edges often projects
        // beyond the CC edge, where Fig. 17 allows no flip. The radial
        // vertex then goes on the opposite edge itself (not in the paper).
        if (first != Outcome::Inserted && set_.edgeFallback && m_.vertex(p).cusp)
            for (const Crossing& c : candidates)
                if (insertOnOppositeEdge(c.corners, side) == Outcome::Inserted) {
                    ++onOppositeEdge;
                    return Outcome::Inserted;
                }
        return first;
    }

    // p = t[0]: the root r of h_p along the opposite edge a-b (appendix B
    // path between their preimages) splits a-b (2 -> 4 faces) and p-r
    // becomes radial. Checked before the edit (a split has no undo): r on
    // `side`, a-b untagged and interior, no cusp left without radial edges
    // gains valence, defined VBOs and no degenerate edge, no parameter fold,
    // no face turned over in 3D, and (radial-keep-consistency) no more
    // inconsistent faces.
    Outcome insertOnOppositeEdge(const Triangle& t, VertexLabel side) {
        const Index p = t[0], a = t[1], b = t[2];
        const Index o = m_.oppositeVertices(a, b)[1];
        if (o == kInvalidIndex || m_.edgeTag(a, b) != kNoTag)
            return Outcome::Fold;
        if (m_.vertex(o).cusp && !onRadialEdge(m_, o))
            return Outcome::NextToCusp;
        const Preimage &ua = m_.vertex(a).preimage, &ub = m_.vertex(b).preimage;
        const double ha = distance(p, m_.vertex(a).position);
        const double hb = distance(p, m_.vertex(b).position);
        if (!((ha < 0.0) != (hb < 0.0)))
            return Outcome::NoSignChange;
        const BisectionResult<MeshVertex> found = bisect(
            [&](double along) -> std::optional<MeshVertex> {
                const std::optional<Preimage> u = m_.interpolate(ua, ub, along);
                if (!u)
                    return std::nullopt;
                return m_.evaluate(*u);
            },
            [&](const MeshVertex& v) { return distance(p, v.position); }, {0.0, 1.0, ha, hb},
            radialRootSearch());
        if (found.outcome == BisectionOutcome::Failed)
            return Outcome::NoChart;
        if (found.outcome != BisectionOutcome::Converged)
            return Outcome::Unconverged;
        const std::optional<MeshVertex>& root = found.last;
        MeshVertex r = *root;
        r.provenance = Provenance::Inserted;
        if (r.label == VertexLabel::Contour)
            r.label = side;
        if (r.label != side)
            return Outcome::AcrossContour;
        const Index fp = m_.faceOfHalfedge(a, b), fo = m_.faceOfHalfedge(b, a);
        LocalEdit before(m_), edit(m_);
        before.addFaces({fp, fo});
        const Index v = edit.addVertex(r);
        edit.addFace({p, a, v});
        edit.addFace({p, v, b});
        edit.addFace({b, v, o});
        edit.addFace({v, a, o});
        if (!edit.labelsValid())
            return Outcome::Defect;
        if (!edit.parameterValid())
            return Outcome::ParameterFold;
        if (edit.turnedOver() > 0)
            return Outcome::Fold;
        if (set_.keepConsistency && edit.inconsistent() > before.inconsistent())
            return Outcome::LessConsistent;
        const Index w = m_.splitEdge(a, b, r, phase_);
        m_.addEdgeTag(p, w, kRadialEdge);
        maxResidual = std::max(maxResidual, std::abs(distance(p, r.position)));
        return Outcome::Inserted;
    }

    // One C vertex p = t[0] (Fig. 16d left): bisection of h_p(f(u_ab(s)))
    // between the midpoints u_a, u_b of p's two edges in the face.
    Outcome insertOneVertex(const Triangle& t, VertexLabel side) {
        // The paper's segment joins the midpoints (lambda = 1/2) of p's
        // edges. On the curved surface h_p can keep its sign between them
        // although it changes sign between the opposite corners (lambda = 1,
        // where the surface points are the corners themselves): then the
        // segments parallel to the opposite edge at lambda = 3/4 and 7/8 are
        // searched (not in the paper; counted as "radial roots past the
        // midpoints").
        Outcome first = Outcome::NoSignChange;
        for (double lambda : {0.5, 0.75, 0.875}) {
            const Outcome o = insertOneVertex(t, side, lambda);
            if (o == Outcome::Inserted) {
                beyondMidpoints += lambda > 0.5;
                return o;
            }
            if (lambda == 0.5)
                first = o;
            if (o != Outcome::NoSignChange)
                break;
        }
        return first;
    }

    Outcome insertOneVertex(const Triangle& t, VertexLabel side, double lambda) {
        const Index p = t[0];
        const Preimage& up = m_.vertex(p).preimage;
        const std::optional<Preimage> ua = m_.interpolate(up, m_.vertex(t[1]).preimage, lambda);
        const std::optional<Preimage> ub = m_.interpolate(up, m_.vertex(t[2]).preimage, lambda);
        if (!ua || !ub)
            return Outcome::NoChart;
        auto sample = [&](double s) -> std::optional<MeshVertex> {
            const std::optional<Preimage> u = m_.interpolate(*ua, *ub, s);
            if (!u)
                return std::nullopt;
            return m_.evaluate(*u);
        };
        const std::optional<MeshVertex> va = sample(0.0), vb = sample(1.0);
        if (!va || !vb)
            return Outcome::NoChart;
        const double ha = distance(p, va->position), hb = distance(p, vb->position);
        if (!((ha < 0.0 && hb > 0.0) || (ha > 0.0 && hb < 0.0)))
            return Outcome::NoSignChange;
        const BisectionResult<MeshVertex> found = bisect(
            sample, [&](const MeshVertex& v) { return distance(p, v.position); },
            {0.0, 1.0, ha, hb}, radialRootSearch());
        if (found.outcome == BisectionOutcome::Failed)
            return Outcome::NoChart;
        if (found.outcome != BisectionOutcome::Converged)
            return Outcome::Unconverged;
        const std::optional<MeshVertex>& root = found.last;
        return place(t, *root, side, {p});
    }

    // Two C vertices p1, p2 of face t (Fig. 16d right): a joint zero of
    // h_p1(f(u)) and h_p2(f(u)) by recursive bisection of the face in
    // parameter space (the cusp search's method, JointRootSearch.h).
    Outcome insertJoint(const Triangle& t, Index p1, Index p2, VertexLabel side) {
        const auto charts = m_.chartCoordinates(
            {m_.vertex(t[0]).preimage, m_.vertex(t[1]).preimage, m_.vertex(t[2]).preimage});
        if (charts.empty())
            return Outcome::NoChart;
        std::array<Point2L, 3> corners;
        std::array<std::array<double, 2>, 3> values;
        for (int i = 0; i < 3; ++i) {
            corners[i] = {charts[0][i].x(), charts[0][i].y()};
            const Vec3& x = m_.vertex(t[i]).position;
            values[i] = {distance(p1, x), distance(p2, x)};
        }
        const JointFunctions functions = [&](const Point2L&, const Barycentric& b) {
            const std::optional<Preimage> u = preimageAt(m_, t, b);
            if (!u)
                return std::array<double, 2>{NAN, NAN};
            const Vec3 x = m_.surface().evaluate(*u).position;
            return std::array<double, 2>{distance(p1, x), distance(p2, x)};
        };
        JointRootOptions options;
        options.minArea = 1e-30L;
        options.minEdge = 1e-12L; // double-precision evaluation floor
        options.mergeDistance = 1e-9L;
        options.maxEvaluations = set_.jointMaxEvaluations;
        const JointRootResult r = findJointRoots(corners, values, functions, options);
        // The root farthest from the corners, away from them by at least
        // radial-joint-min-barycentric (no sliver next to an edge).
        std::optional<MeshVertex> best;
        long double bestMin = -1.0L;
        for (const JointRoot& root : r.roots) {
            const long double lmin =
                std::min({root.barycentric[0], root.barycentric[1], root.barycentric[2]});
            if (lmin < set_.jointMinBarycentric || lmin <= bestMin)
                continue;
            const std::optional<Preimage> u = preimageAt(m_, t, root.barycentric);
            if (!u)
                continue;
            const MeshVertex v = m_.evaluate(*u);
            if (std::abs(distance(p1, v.position)) > set_.tolerance ||
                std::abs(distance(p2, v.position)) > set_.tolerance)
                continue;
            best = v;
            bestMin = lmin;
        }
        if (!best)
            return Outcome::NoCrossing;
        return place(t, *best, side, {p1, p2});
    }

    // Inserts r inside face t (1 -> 3 split) and tags partners-r radial,
    // after the fold prevention of Fig. 17: the projection of r onto the
    // face's plane must fall inside the face; when it falls beyond exactly
    // one edge j-k, the adjacent edge j-k is flipped (r then splits the
    // union of the face and its neighbour) if that leaves no fold.
    Outcome place(const Triangle& t, MeshVertex r, VertexLabel side,
                  const std::vector<Index>& partners) {
        // The inserted vertex's label is sign(g) at its preimage; a root
        // across the contour (an FB edge or CFB face would follow) is
        // skipped. g == 0 exactly is not a contour root: keep the side.
        r.provenance = Provenance::Inserted;
        if (r.label == VertexLabel::Contour)
            r.label = side;
        if (r.label != side)
            return Outcome::AcrossContour;
        std::array<Vec3, 3> x;
        for (int i = 0; i < 3; ++i)
            x[i] = m_.vertex(t[i]).position;
        const Vec3 l = projectedBarycentrics(x[0], x[1], x[2], r.position);
        int outside = 0, corner = -1;
        for (int i = 0; i < 3; ++i)
            if (!(l[i] > 0.0)) {
                ++outside;
                corner = i;
            }
        const Preimage& ur = r.preimage;
        auto pre = [&](Index v) {
            return m_.vertex(v).preimage;
        };
        Index j = kInvalidIndex, k = kInvalidIndex, o = kInvalidIndex;
        std::vector<std::array<Preimage, 3>> faces;
        if (outside == 0) {
            for (int i = 0; i < 3; ++i)
                faces.push_back({pre(t[i]), pre(t[(i + 1) % 3]), ur});
        } else if (outside == 1) {
            j = t[(corner + 1) % 3];
            k = t[(corner + 2) % 3];
            const Index i = t[corner];
            const int tag = m_.edgeTag(j, k);
            const bool cc = m_.vertex(j).label == VertexLabel::Contour &&
                            m_.vertex(k).label == VertexLabel::Contour;
            o = m_.oppositeVertices(j, k)[1];
            if (tag != kNoTag || cc || o == kInvalidIndex ||
                m_.faceOfHalfedge(k, j) == kInvalidIndex)
                return Outcome::Fold;
            const Vec3 reference = faceNormal(m_, m_.faceOfHalfedge(t[0], t[1])) +
                                   faceNormal(m_, m_.faceOfHalfedge(k, j));
            const Vec3 &xj = m_.vertex(j).position, &xk = m_.vertex(k).position,
                       &xo = m_.vertex(o).position;
            if (turnsOver(xj, xo, r.position, reference) ||
                turnsOver(xk, r.position, xo, reference))
                return Outcome::Fold;
            faces = {{pre(i), pre(j), ur},
                     {pre(k), pre(i), ur},
                     {pre(j), pre(o), ur},
                     {pre(k), ur, pre(o)}};
        } else {
            return Outcome::Fold;
        }
        for (const auto& f : faces)
            if (!keepsParameterOrientation(m_, f))
                return Outcome::ParameterFold;
        // A cusp keeps the valence 4 of Fig. 18d unless it gets its own
        // radial edges (cusps are processed first).
        for (Index w : {t[0], t[1], t[2], o})
            if (w != kInvalidIndex && m_.vertex(w).cusp && !onRadialEdge(m_, w) &&
                std::find(partners.begin(), partners.end(), w) == partners.end())
                return Outcome::NextToCusp;
        const Index f = m_.faceOfHalfedge(t[0], t[1]);
        int inconsistentBefore = !faceIsConsistent(m_, f);
        if (o != kInvalidIndex)
            inconsistentBefore += !faceIsConsistent(m_, m_.faceOfHalfedge(k, j));
        const Index v = m_.splitFace(f, r, phase_);
        bool flipped = false;
        if (o != kInvalidIndex) {
            flipped = m_.flipEdge(j, k, phase_);
            if (!flipped) {
                undo(v, false, o);
                return Outcome::Fold;
            }
        }
        if (defectAround(v)) {
            undo(v, flipped, o);
            ++undone;
            return Outcome::Defect;
        }
        if (set_.keepConsistency && inconsistentFacesAround(m_, {v}) > inconsistentBefore) {
            undo(v, flipped, o);
            return Outcome::LessConsistent;
        }
        foldFlips += flipped;
        for (Index p : partners) {
            m_.addEdgeTag(p, v, kRadialEdge);
            maxResidual = std::max(maxResidual, std::abs(distance(p, r.position)));
        }
        return Outcome::Inserted;
    }

    void undo(Index v, bool flipped, Index o) {
        if (flipped)
            m_.flipEdge(v, o, phase_);
        m_.removeValence3Vertex(v, phase_);
    }

    // An undefined VBO or a degenerate CC edge (Definition 3) on the faces
    // around v or on their edges.
    bool defectAround(Index v) const {
        for (Index f : m_.vertexFaces(v)) {
            if (faceVbo(m_, f) == Vbo::Undefined)
                return true;
            const Triangle& t = m_.face(f);
            for (int i = 0; i < 3; ++i) {
                const Index a = t[i], b = t[(i + 1) % 3];
                const Index f0 = m_.faceOfHalfedge(a, b), f1 = m_.faceOfHalfedge(b, a);
                if (f0 != kInvalidIndex && f1 != kInvalidIndex &&
                    isDegenerateEdge(m_.vertex(a).label, m_.vertex(b).label, faceVbo(m_, f0),
                                     faceVbo(m_, f1)))
                    return true;
            }
        }
        return false;
    }
};

void runRadialEdgeInsertion(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const Settings set = Settings::read(ctx.parameters, sceneScale(m));
    RadialInserter inserter(m, set, s.phaseIndex);
    // Only C vertices and their fans are visited; inserted vertices are
    // never C, so the list is fixed.
    std::vector<Index> contour;
    for (Index v = 0; v < m.vertexCount(); ++v)
        if (m.vertex(v).label == VertexLabel::Contour)
            contour.push_back(v);
    // Cusps first, so that a cusp left without radial edges is known when
    // its neighbours' edges are inserted.
    std::stable_partition(contour.begin(), contour.end(),
                          [&](Index v) { return m.vertex(v).cusp; });
    for (size_t i = 0; i < contour.size(); ++i) {
        if (i % 256 == 0)
            ctx.checkCancelled();
        inserter.process(contour[i]);
    }
    const RadialCoverage coverage = radialCoverage(m);
    const StandardRadialShare share = standardRadialShare(m);
    publish(s, m);
    long long skipped = 0;
    for (int k = 0; k < kOutcomes; ++k) {
        s.setCounter(kOutcomeCounters[k], static_cast<double>(inserter.counts[k]));
        if (k != static_cast<int>(Outcome::Inserted))
            skipped += inserter.counts[k];
    }
    s.setCounter(counters::kRadialInsertionsSkipped, static_cast<double>(skipped));
    s.setCounter(counters::kJointRadialVerticesTwoC, static_cast<double>(inserter.jointVertices));
    s.setCounter(counters::kJointSearchesWithoutAUsableRoot,
                 static_cast<double>(inserter.jointFallbacks));
    s.setCounter(counters::kFoldPreventionFlips, static_cast<double>(inserter.foldFlips));
    s.setCounter(counters::kRadialRootsPastTheMidpoints,
                 static_cast<double>(inserter.beyondMidpoints));
    s.setCounter(counters::kCVerticesBetweenOppositeCuspsBothSides,
                 static_cast<double>(inserter.pairVertices));
    s.setCounter(counters::kCuspRadialEdgesOnTheOppositeEdge,
                 static_cast<double>(inserter.onOppositeEdge));
    s.setCounter(counters::kRadialEdgesInAFartherCrossingFace,
                 static_cast<double>(inserter.laterFaces));
    s.setCounter(counters::kInsertionsUndoneVBODefect, static_cast<double>(inserter.undone));
    s.setCounter(counters::kCVerticesWithTheirRadialEdges, static_cast<double>(coverage.complete));
    s.setCounter(counters::kCVertexSidesWithoutARadialEdge,
                 static_cast<double>(coverage.missingSides));
    s.setCounter(counters::kMaxHPRPerDiagonal, inserter.maxResidual / sceneScale(m));
    s.setCounter(counters::kFacesTouchingNonCuspCVertices, static_cast<double>(share.contourFaces));
    s.setCounter(counters::kStandardRadialSharePercent, share.percent());
    if (coverage.missingSides > 0)
        s.notes.push_back(std::to_string(coverage.missingSides) +
                          " sides of C vertices have no radial edge (§6.3 g post-condition); "
                          "the 'skipped: ...' counters give the reasons");
}

std::vector<InvariantCheck> checkRadialEdgeInsertion(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, true);
    out.push_back(radialEdgeCheck(ctx, m));
    InvariantCheck labels =
        check("every vertex radial edge insertion added is labelled sign(g) (F or B), never C");
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const MeshVertex& x = m.vertex(v);
        if (x.phase != s.phaseIndex || x.provenance != Provenance::Inserted)
            continue;
        if (x.label == VertexLabel::Contour || (x.g != 0.0 && x.label != labelFromG(x.g)))
            violate(labels, "vertex " + std::to_string(v) + " label " +
                                std::to_string(static_cast<int>(x.label)) + " g " +
                                std::to_string(x.g));
    }
    out.push_back(labels);
    InvariantCheck coverage = check("every side of a C vertex without a radial edge (two at a "
                                    "cusp) was counted as a skipped insertion");
    const long long missing = radialCoverage(m).missingSides;
    const double skipped = s.counter(counters::kRadialInsertionsSkipped, 0.0);
    if (static_cast<double>(missing) > skipped) {
        coverage.violations = missing - static_cast<long long>(skipped);
        coverage.firstExample = std::to_string(missing) + " sides missing, " +
                                std::to_string(static_cast<long long>(skipped)) + " skips counted";
    }
    out.push_back(coverage);
    return out;
}

} // namespace

RadialEdgeOptions RadialEdgeOptions::read(const ParameterSet& p) {
    RadialEdgeOptions o;
    if (p.has("radial-root-tolerance"))
        o.rootTolerance = p.getDouble("radial-root-tolerance");
    if (p.has("radial-root-max-iterations"))
        o.rootMaxIterations = p.getInt("radial-root-max-iterations");
    if (p.has("radial-keep-consistency"))
        o.keepConsistency = p.getBool("radial-keep-consistency");
    return o;
}

void addRadialEdgeInsertionPhase(Method& m) {
    m.parameters.push_back(
        {"radial-root-tolerance",
         "Radial root tolerance",
         "Bisection of h_p between the midpoints of p's edges (§6.3 g) stops within this "
         "times the bounding-box diagonal of p's radial plane; also the bound checked at "
         "every radial edge's far end. The paper gives no tolerance.",
         ParameterType::Double,
         1e-10,
         1e-16,
         1e-2,
         {}});
    m.parameters.push_back(
        {"radial-root-max-iterations",
         "Radial root iterations",
         "Maximum bisection steps per radial edge (§6.3 g; the paper gives no value); an "
         "unconverged root skips the insertion.",
         ParameterType::Int,
         100,
         1,
         1000,
         {}});
    m.parameters.push_back(
        {"radial-joint-min-barycentric",
         "Joint root margin",
         "A joint zero of h_p1 and h_p2 (two C vertices, §6.3 g, Fig. 16d right) is used "
         "only when its barycentric coordinates are all at least this, else the radial "
         "edges are inserted one by one. 0: any joint zero, as in the paper; above 0 "
         "(not in the paper): no slivers.",
         ParameterType::Double,
         0.05,
         0.0,
         0.33,
         {}});
    m.parameters.push_back(
        {"radial-joint-max-evaluations",
         "Joint root evaluations",
         "Evaluation budget of the joint-zero bisection per face (§6.3 g; the paper "
         "gives no value).",
         ParameterType::Int,
         20000,
         10,
         10000000,
         {}});
    m.parameters.push_back(
        {"radial-keep-consistency",
         "Radialization keeps consistency",
         "Not in the paper: radial edge insertion and radial flips (§6.3 g-h) skip an "
         "edit that leaves more inconsistent faces around it than before. Off: the "
         "paper's rules alone, which leave the repair to §6.4.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"radial-cusp-inside-hops",
         "Cusp inside region (contour edges)",
         "§6.3 (Fig. 18e) builds no radial triangles in a cusp's inside region; the "
         "paper does not say how far it reaches. 0: the cusp vertex only; k: also the C "
         "vertices up to k contour edges away. 1 (the cusp's fan) is the smallest region "
         "that holds no radial triangle.",
         ParameterType::Int,
         1,
         0,
         100,
         {}});
    m.parameters.push_back(
        {"radial-cusp-inside-pixels",
         "Cusp inside region (pixels)",
         "Not in the paper: the inside region of radial-cusp-inside-hops (Fig. 18e) also "
         "covers the C vertices up to this many pixels from the cusp along the contour "
         "in the image, however many contour edges away. 0: hops only.",
         ParameterType::Double,
         10.0,
         0.0,
         1000.0,
         {}});
    m.parameters.push_back(
        {"radial-cusp-pair-pixels",
         "Cusp pairs: both sides between them (pixels)",
         "Not in the paper: a C vertex between two cusps whose inside regions (Fig. 18e) "
         "lie on opposite sides gets radial edges on both sides when its paths along the "
         "contour to the two cusps add up to at most this many pixels. 0: off.",
         ParameterType::Double,
         0.0,
         0.0,
         1000.0,
         {}});
    m.parameters.push_back(
        {"radial-cusp-opposite-edge",
         "Cusp radial edges on the opposite edge",
         "Not in the paper: when the radial root of a cusp projects beyond its CC edge "
         "and the fold test (Fig. 17) skips it, the radial vertex is put on the opposite "
         "edge of the crossing face (a 2-to-4 split) when the fold, VBO and consistency "
         "checks pass.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"radial-cusp-both-sides",
         "Ambiguous cusp: one radial edge per side",
         "Not in the paper: when each side of a cusp is crossed once by its radial "
         "plane, so that the outside region of Fig. 18e is not identified, each side "
         "gets one radial edge instead of none.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"radial-edge-insertion",
         "§6.3 g (Fig. 15g, 16d, 17, 18e): for every C vertex p and each side (at a cusp, two "
         "edges on its outside region), a face whose opposite edge p's radial plane crosses is "
         "split 1-to-3 at the root of h_p between the midpoints of p's edges (two C vertices: "
         "the joint zero of h_p1 and h_p2); p-r is tagged radial; Fig. 17 fold prevention. Not "
         "in the paper: further segments and faces are tried when these fail, and the cusp "
         "fallbacks radial-cusp-opposite-edge and radial-cusp-both-sides.",
         runRadialEdgeInsertion, checkRadialEdgeInsertion});
}

} // namespace contour::consistent
