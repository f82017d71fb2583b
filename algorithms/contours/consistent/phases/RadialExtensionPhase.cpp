// Radial edge extension (Bénard 2014 §6.4, Fig. 15i, Fig. 16f; notes
// §2.4.1): inconsistent faces just beyond the radial strip are fixed by
// sliding the far end of a radial edge along its radial curve and flipping
// the edge opposite it.
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/RadialExtension.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/RadialTriangles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace contour::consistent {

namespace {

struct ExtensionSettings {
    int samples = 10;
    double tolerance = 0.0; // on radialPlaneDistance, absolute
    int maxIterations = 100;
    int pushDepth = 0; // extension-cusp-push-depth
    int maxSweeps = 0; // extension-max-sweeps
};

struct ExtensionStats {
    long long crossings = 0, candidates = 0, rejected = 0, flips = 0, unconverged = 0;
    // Why samples were not taken: q would change side, no fewer
    // inconsistent faces, undefined VBO or degenerate CC edge, parameter
    // fold, appendix C, a face turned over in 3D.
    long long sideChange = 0, noGain = 0, labels = 0, param = 0, appendixC = 0, turned = 0;
    long long pairs = 0, pairMoves = 0;
    long long pushTried = 0, pushMoves = 0, pushFlips = 0;
    std::array<long long, 4>
        pairRejected{}; // VBO/degenerate, param fold, appendix C, 3D // two radial ends (Fig. 16f)
};

// Zero crossings of v's one-ring outer boundary in the edit's faces (C
// vertices plus edges between F and B), the quantity of appendix C rule 3.
int ringZeroCrossings(const LocalEdit& e, Index v) {
    int crossings = 0;
    std::vector<Index> ringContour;
    for (const Triangle& t : e.faces()) {
        const auto it = std::find(t.begin(), t.end(), v);
        if (it == t.end())
            continue;
        const int i = static_cast<int>(it - t.begin());
        const Index t1 = t[(i + 1) % 3], t2 = t[(i + 2) % 3];
        crossings +=
            static_cast<int>(e.vertex(t1).label) * static_cast<int>(e.vertex(t2).label) < 0;
        for (Index w : {t1, t2})
            if (e.vertex(w).label == VertexLabel::Contour &&
                std::find(ringContour.begin(), ringContour.end(), w) == ringContour.end())
                ringContour.push_back(w);
    }
    return crossings + static_cast<int>(ringContour.size());
}

// Appendix C for the far end v of a radial edge moved along its radial
// curve (label kept): rules 1 and 4 as LocalEdit::shiftable, and rule 3 as
// the appendix words it, "creates no X": a one-ring that already had more
// than two zero crossings before the edit (q next to two C vertices of the
// contour and an FB-free crossing, common at the far ends of radial edges)
// may keep them, as long as the edit adds none. LocalEdit::shiftable alone
// rejected most Fig. 16f moves for a count the move does not change.
bool extensionShiftable(const ConsistentMesh& m, const LocalEdit& before, const LocalEdit& after,
                        Index v) {
    if (after.shiftable(v))
        return true;
    const MeshVertex& x = after.vertex(v);
    if (x.label == VertexLabel::Contour || x.cusp)
        return false;
    for (const Triangle& t : after.faces())
        if (std::find(t.begin(), t.end(), v) != t.end())
            for (Index w : t)
                if (w != v && !m.interpolate(x.preimage, after.vertex(w).preimage, 0.5))
                    return false;
    return ringZeroCrossings(after, v) <= std::max(2, ringZeroCrossings(before, v));
}

class Extender {
public:
    Extender(ConsistentMesh& m, const ExtensionSettings& set, int phase)
        : m_(m), set_(set), phase_(phase) {}

    ExtensionStats stats;

    // The radial edges p-q (p the C end) whose far end q touches an
    // inconsistent face and lies on no other tagged edge (moving q along p's
    // radial curve would take it off another radial plane).
    std::vector<std::array<Index, 2>> candidates() const {
        std::vector<std::array<Index, 2>> out;
        for (const auto& [k, tag] : m_.edgeTags()) {
            if (!(tag & kRadialEdge))
                continue;
            const auto [a, b] = ConsistentMesh::edgeFromKey(k);
            const bool aC = m_.vertex(a).label == VertexLabel::Contour;
            if (aC == (m_.vertex(b).label == VertexLabel::Contour))
                continue;
            const Index p = aC ? a : b, q = aC ? b : a;
            out.push_back({p, q});
        }
        std::sort(out.begin(), out.end());
        return out;
    }

    // One radial edge p-q: every face q-x-y around q whose opposite edge
    // x-y crosses p's radial plane (the radial curve's continuation beyond
    // q); the radial curve is sampled in that face and in the face y-x-z
    // across x-y, and q moves to the sample that removes the most
    // inconsistent faces of its star (with the flip of x-y, or without it),
    // ties to the best minimum Bank-Smith quality. The face need not be
    // inconsistent itself: in Fig. 16f the inconsistent face lies beside the
    // radial curve, between two radial ends close to the contour, and is
    // fixed by moving q further out (the strip widens).
    bool extend(Index p, Index q) {
        if (!movable(p, q))
            return false;
        const std::vector<Index> star = m_.vertexFaces(q);
        // Inconsistent faces first (the paper's case), then the others.
        std::vector<Index> order;
        for (Index f : star)
            if (!faceIsConsistent(m_, f))
                order.push_back(f);
        for (Index f : star)
            if (faceIsConsistent(m_, f))
                order.push_back(f);
        for (Index f : order) {
            Triangle t = m_.face(f);
            while (t[0] != q)
                std::rotate(t.begin(), t.begin() + 1, t.end());
            const Index x = t[1], y = t[2];
            if (x == p || y == p)
                continue;
            const double hx = h(p, m_.vertex(x).position), hy = h(p, m_.vertex(y).position);
            if (!(hx * hy < 0.0))
                continue;
            ++stats.crossings;
            if (tryMoves(p, q, f, x, y))
                return true;
        }
        return false;
    }

    // q is the far end of radial edge p-q and may slide along p's radial
    // curve: not a cusp, not on the boundary, on no other tagged edge.
    bool movable(Index p, Index q) const {
        if (m_.vertex(q).cusp || m_.isBoundaryVertex(q) || m_.edgeTag(p, q) != kRadialEdge)
            return false;
        for (Index w : m_.neighbours(q))
            if (w != p && m_.edgeTag(q, w) != kNoTag)
                return false;
        return true;
    }

    // Fig. 16f with two radial ends: an inconsistent face q1-q2-y between
    // the far ends of two radial edges p1-q1 and p2-q2 close to the contour
    // (a thin strip) is often fixed only when both ends move out together;
    // each alone leaves the face (or its neighbour) inconsistent. Both slide
    // along their radial curves (samples in the star face the curve enters
    // beyond q), keeping the pair that removes the most inconsistent faces
    // of the two stars, with the same checks as a single move.
    bool extendPair(Index p1, Index q1, Index p2, Index q2) {
        const std::vector<MeshVertex> s1 = outwardSamples(p1, q1), s2 = outwardSamples(p2, q2);
        if (s1.empty() || s2.empty())
            return false;
        ++stats.pairs;
        std::vector<Index> star = m_.vertexFaces(q1);
        for (Index f : m_.vertexFaces(q2))
            if (std::find(star.begin(), star.end(), f) == star.end())
                star.push_back(f);
        LocalEdit before(m_), edit(m_);
        before.addFaces(star);
        std::vector<char> turned(star.size());
        for (size_t i = 0; i < star.size(); ++i)
            turned[i] = before.turnedOver(before.faces()[i]);
        const LocalScore plain = before.score();
        int best1 = -1, best2 = -1;
        LocalScore bestScore;
        for (size_t i = 0; i < s1.size(); ++i)
            for (size_t j = 0; j < s2.size(); ++j) {
                edit.clear();
                edit.addFaces(star);
                edit.moveVertex(q1, s1[i]);
                edit.moveVertex(q2, s2[j]);
                LocalScore trial = edit.score();
                trial.inconsistent -= plain.inconsistent;
                if (trial.inconsistent >= 0 || (best1 >= 0 && !betterScore(trial, bestScore)))
                    continue;
                int reason = !edit.labelsValid()      ? 0
                             : !edit.parameterValid() ? 1
                             : !extensionShiftable(m_, before, edit, q1) ||
                                     !extensionShiftable(m_, before, edit, q2)
                                 ? 2
                                 : -1;
                for (size_t k = 0; reason < 0 && k < star.size(); ++k)
                    if (!turned[k] && edit.turnedOver(edit.faces()[k]))
                        reason = 3;
                if (reason >= 0) {
                    ++stats.pairRejected[reason];
                    continue;
                }
                best1 = static_cast<int>(i);
                best2 = static_cast<int>(j);
                bestScore = trial;
            }
        if (best1 < 0)
            return false;
        m_.setVertex(q1, s1[best1], phase_);
        m_.setVertex(q2, s2[best2], phase_);
        ++stats.pairMoves;
        return true;
    }

    // A cusp's radial curve leaves it along the view ray (Fig. 18e: κr = 0
    // there, so its image moves with the cube of the distance along it), and
    // the far end q of a cusp's radial edge lands within a hundredth of a
    // pixel of the cusp; faces q-x-y across the cusp's image wedge are then
    // inconsistent, and no single move of extend() (q inside its star, one
    // flip) removes them: each step alone leaves as many. Here q is pushed
    // out along p's radial curve through up to `pushDepth` faces, flipping
    // each edge x-y the curve crosses beyond q (the flip of §6.4 i, repeated)
    // and moving q into the last face reached (or into a face of the way
    // without its flip); the move that removes the most inconsistent faces
    // of the region, with the checks of a single move, wins (ties: the best
    // minimum quality, then the first found, depth first). Not in the
    // paper: §6.4 i looks one face ahead.
    bool push(Index p, Index q) {
        if (set_.pushDepth <= 0 || !movable(p, q))
            return false;
        ++stats.pushTried;
        PushState st;
        for (Index f : m_.vertexFaces(q)) {
            st.absorbed.push_back(f);
            st.faces.push_back(m_.face(f));
        }
        LocalEdit before(m_);
        before.addFaces(st.absorbed);
        pushPlain_ = before.score();
        pushTurned_ = before.turnedOver();
        pushBest_.reset();
        pushBestFlips_.clear();
        pushSearch(p, q, st, 0);
        if (!pushBest_)
            return false;
        // The search rehearsed every flip; should the mesh still refuse one,
        // the flips made are undone (the new edge of each is q-z).
        std::vector<std::array<Index, 2>> made;
        for (const auto& [x, y] : pushBestFlips_) {
            const Index z = m_.oppositeVertices(x, y)[1];
            if (!m_.flipEdge(x, y, phase_)) {
                for (auto it = made.rbegin(); it != made.rend(); ++it)
                    m_.flipEdge((*it)[0], (*it)[1], phase_);
                return false;
            }
            made.push_back({q, z});
        }
        stats.pushFlips += static_cast<long long>(made.size());
        m_.setVertex(q, *pushBest_, phase_);
        ++stats.pushMoves;
        return true;
    }

private:
    // The region a push edits: its current triangles, the mesh faces they
    // replace, and the flips made so far.
    struct PushState {
        std::vector<Triangle> faces;
        std::vector<Index> absorbed;
        std::vector<std::array<Index, 2>> flips;
    };
    LocalScore pushPlain_;
    int pushTurned_ = 0;
    std::optional<MeshVertex> pushBest_;
    LocalScore pushBestScore_;
    std::vector<std::array<Index, 2>> pushBestFlips_;

    // Is a-b an edge of the region's triangles or of a mesh face outside it?
    bool pushHasEdge(const PushState& st, Index a, Index b) const {
        for (const Triangle& t : st.faces)
            for (int i = 0; i < 3; ++i)
                if ((t[i] == a && t[(i + 1) % 3] == b) || (t[i] == b && t[(i + 1) % 3] == a))
                    return true;
        for (Index f : {m_.faceOfHalfedge(a, b), m_.faceOfHalfedge(b, a)})
            if (f != kInvalidIndex &&
                std::find(st.absorbed.begin(), st.absorbed.end(), f) == st.absorbed.end())
                return true;
        return false;
    }

    // q moved to each root of h_p on `samples` segments a(s)-b(s) (s = k /
    // samples, k in [k0, k1]) between the preimages of (a0 -> a1) and
    // (b0 -> b1), judged on the region.
    void pushSamples(Index p, Index q, const PushState& st, Index a0, Index a1, Index b0, Index b1,
                     int k0, int k1) {
        const auto pre = [&](Index v) {
            return m_.vertex(v).preimage;
        };
        const VertexLabel label = m_.vertex(q).label;
        LocalEdit before(m_), edit(m_);
        before.addFaces(st.absorbed);
        for (int k = k0; k <= k1; ++k) {
            const std::optional<MeshVertex> sample =
                curveSample(p, pre(a0), pre(a1), pre(b0), pre(b1),
                            static_cast<double>(k) / set_.samples, label);
            if (!sample)
                continue;
            const MeshVertex& v = *sample;
            edit.clear();
            for (const Triangle& t : st.faces)
                edit.addFace(t);
            edit.moveVertex(q, v);
            LocalScore trial = edit.score();
            trial.inconsistent -= pushPlain_.inconsistent;
            if (trial.inconsistent >= 0 || (pushBest_ && !betterScore(trial, pushBestScore_)))
                continue;
            if (!edit.labelsValid() || !edit.parameterValid() ||
                !extensionShiftable(m_, before, edit, q) || edit.turnedOver() > pushTurned_)
                continue;
            pushBest_ = v;
            pushBestScore_ = trial;
            pushBestFlips_ = st.flips;
        }
    }

    void pushSearch(Index p, Index q, const PushState& st, int depth) {
        const auto h0 = [&](Index v) {
            return h(p, m_.vertex(v).position);
        };
        // Past the first level only the two faces of the last flip hold the
        // curve's continuation.
        const size_t first = depth == 0 ? 0 : st.faces.size() - 2;
        for (size_t i = first; i < st.faces.size(); ++i) {
            const Triangle& face = st.faces[i];
            Triangle t = face;
            if (std::find(t.begin(), t.end(), q) == t.end())
                continue;
            while (t[0] != q)
                std::rotate(t.begin(), t.begin() + 1, t.end());
            const Index x = t[1], y = t[2];
            if (x == p || y == p || !(h0(x) * h0(y) < 0.0))
                continue;
            // q inside q-x-y, no further flip.
            pushSamples(p, q, st, q, x, q, y, 1, set_.samples - 1);
            if (depth >= set_.pushDepth)
                continue;
            // Flip x-y (faces q-x-y and y-x-z become x-z-q and y-q-z).
            Triangle beyond{kInvalidIndex, kInvalidIndex, kInvalidIndex};
            Index absorbedFace = kInvalidIndex;
            for (const Triangle& u : st.faces)
                for (int k = 0; k < 3; ++k)
                    if (u[k] == y && u[(k + 1) % 3] == x)
                        beyond = u;
            if (beyond[0] == kInvalidIndex) {
                const Index g = m_.faceOfHalfedge(y, x);
                if (g == kInvalidIndex ||
                    std::find(st.absorbed.begin(), st.absorbed.end(), g) != st.absorbed.end())
                    continue;
                beyond = m_.face(g);
                absorbedFace = g;
            }
            Index z = kInvalidIndex;
            for (Index w : beyond)
                if (w != x && w != y)
                    z = w;
            // A cusp keeps its valence (Fig. 18d), tagged edges and the
            // mesh contour's CC edges stay.
            const bool contourEdge = m_.vertex(x).label == VertexLabel::Contour &&
                                     m_.vertex(y).label == VertexLabel::Contour;
            if (z == kInvalidIndex || z == q || z == p || m_.vertex(x).cusp || m_.vertex(y).cusp ||
                m_.vertex(z).cusp || contourEdge || m_.edgeTag(x, y) != kNoTag ||
                pushHasEdge(st, q, z))
                continue;
            PushState next = st;
            if (absorbedFace != kInvalidIndex)
                next.absorbed.push_back(absorbedFace);
            next.faces.erase(
                std::remove_if(next.faces.begin(), next.faces.end(),
                               [&](const Triangle& u) { return u == face || u == beyond; }),
                next.faces.end());
            next.faces.push_back({x, z, q});
            next.faces.push_back({y, q, z});
            next.flips.push_back({x, y});
            // q beyond x-y, in y-x-z (segments parallel to x-y).
            pushSamples(p, q, next, x, z, y, z, 1, set_.samples - 1);
            pushSearch(p, q, next, depth + 1);
        }
    }

    ConsistentMesh& m_;
    ExtensionSettings set_;
    int phase_;

    double h(Index p, const Vec3& position) const {
        return radialPlaneDistance(m_.camera(), m_.vertex(p), position);
    }
    // The bisection below needs positions only (evaluate()'s same bits).
    double h(Index p, const Preimage& u) const { return h(p, m_.surface().evaluatePosition(u)); }

    // Root of h_p on the segment a-b in parameter space (appendix B), or
    // nothing when h_p does not change sign, a chart is missing or the
    // bisection does not reach the tolerance.
    std::optional<Preimage> root(Index p, const Preimage& a, const Preimage& b) {
        const double ha = h(p, a);
        const double hb = h(p, b);
        if (!(ha * hb <= 0.0))
            return std::nullopt;
        const ConsistentMesh::Segment ab = m_.segment(a, b);
        BisectionOptions search;
        search.step = BisectionStep::Midpoint;
        search.sign = BisectionSign::Negative;
        search.maxIterations = set_.maxIterations;
        search.tolerance = set_.tolerance;
        BisectionResult<Preimage> r =
            bisect([&](double along) { return ab.at(along); },
                   [&](const Preimage& u) { return h(p, u); }, {0.0, 1.0, ha, hb}, search);
        if (r.outcome == BisectionOutcome::Exhausted)
            ++stats.unconverged;
        if (r.outcome != BisectionOutcome::Converged)
            return std::nullopt;
        return std::move(r.last);
    }

    // Samples of p's radial curve beyond q, in the face q-x-y of q's star
    // whose opposite edge it crosses (lines parallel to x-y, as in
    // tryMoves), evaluated, on q's side of the contour.
    std::vector<MeshVertex> outwardSamples(Index p, Index q) {
        std::vector<MeshVertex> out;
        const VertexLabel label = m_.vertex(q).label;
        for (Index f : m_.vertexFaces(q)) {
            Triangle t = m_.face(f);
            while (t[0] != q)
                std::rotate(t.begin(), t.begin() + 1, t.end());
            const Index x = t[1], y = t[2];
            if (x == p || y == p)
                continue;
            if (!(h(p, m_.vertex(x).position) * h(p, m_.vertex(y).position) < 0.0))
                continue;
            const Preimage &uq = m_.vertex(q).preimage, &ux = m_.vertex(x).preimage,
                           &uy = m_.vertex(y).preimage;
            for (int k = 1; k <= set_.samples; ++k)
                if (const auto v = curveSample(p, uq, ux, uq, uy,
                                               static_cast<double>(k) / set_.samples, label))
                    out.push_back(*v);
            break;
        }
        return out;
    }

    // The point of p's radial curve on the segment between the preimages at
    // s along a0 -> a1 and along b0 -> b1 (appendix B paths), evaluated and
    // marked as this phase's move; nothing when a chart is missing, h_p
    // keeps its sign there or the point is not on `label`'s side.
    std::optional<MeshVertex> curveSample(Index p, const Preimage& a0, const Preimage& a1,
                                          const Preimage& b0, const Preimage& b1, double s,
                                          VertexLabel label) {
        const auto a = m_.interpolate(a0, a1, s), b = m_.interpolate(b0, b1, s);
        if (!a || !b)
            return std::nullopt;
        const auto r = root(p, *a, *b);
        if (!r)
            return std::nullopt;
        MeshVertex v = m_.evaluate(*r);
        if (v.label != label)
            return std::nullopt;
        v.provenance = Provenance::Wiggled;
        v.phase = phase_;
        return v;
    }

    bool tryMoves(Index p, Index q, Index f, Index x, Index y) {
        const Index g = m_.faceOfHalfedge(y, x);
        Index z = kInvalidIndex;
        if (g != kInvalidIndex)
            for (Index w : m_.face(g))
                if (w != x && w != y)
                    z = w;
        // The flip changes the valence of x, y and z (a cusp keeps its own,
        // Fig. 18d) and must create a new edge q-z.
        const bool canFlip = z != kInvalidIndex && !m_.vertex(x).cusp && !m_.vertex(y).cusp &&
                             !m_.vertex(z).cusp && z != q &&
                             m_.faceOfHalfedge(q, z) == kInvalidIndex &&
                             m_.faceOfHalfedge(z, q) == kInvalidIndex;
        const auto pre = [&](Index v) {
            return m_.vertex(v).preimage;
        };
        // Radial curve samples: its crossings of `samples` segments across
        // q-x-y parallel to x-y, and of samples - 1 across y-x-z.
        std::vector<Preimage> roots;
        const int n = set_.samples;
        for (int k = 1; k <= n; ++k) {
            const double s = static_cast<double>(k) / n;
            const auto a = m_.interpolate(pre(q), pre(x), s), b = m_.interpolate(pre(q), pre(y), s);
            if (a && b)
                if (const auto r = root(p, *a, *b))
                    roots.push_back(*r);
        }
        for (int k = 1; canFlip && k < n; ++k) {
            const double s = static_cast<double>(k) / n;
            const auto a = m_.interpolate(pre(x), pre(z), s), b = m_.interpolate(pre(y), pre(z), s);
            if (a && b)
                if (const auto r = root(p, *a, *b))
                    roots.push_back(*r);
        }
        const std::vector<Index> star = m_.vertexFaces(q);
        LocalEdit before(m_), edit(m_);
        before.addFaces(star);
        std::vector<char> turned(star.size());
        for (size_t i = 0; i < star.size(); ++i)
            turned[i] = before.turnedOver(before.faces()[i]);
        const LocalScore plain = before.score();
        LocalScore flipped = plain;
        int turnedFlip = 0;
        if (canFlip) {
            LocalEdit pair(m_);
            pair.addFaces({f, g});
            flipped.inconsistent += !faceIsConsistent(m_, g);
            turnedFlip = pair.turnedOver();
        }
        std::optional<MeshVertex> best;
        bool bestFlip = false;
        LocalScore bestScore;
        const VertexLabel label = m_.vertex(q).label;
        for (const Preimage& r : roots) {
            MeshVertex v = m_.evaluate(r);
            // q stays on its side of the contour (its radial edge's side).
            if (v.label != label) {
                ++stats.sideChange;
                continue;
            }
            ++stats.candidates;
            v.provenance = Provenance::Wiggled;
            v.phase = phase_;
            for (bool flip : {false, true}) {
                if (flip && !canFlip)
                    continue;
                edit.clear();
                for (Index sf : star)
                    if (!flip || sf != f)
                        edit.addFaces({sf});
                if (flip) {
                    edit.addFace({x, z, q});
                    edit.addFace({y, q, z});
                }
                edit.moveVertex(q, v);
                LocalScore trial = edit.score();
                trial.inconsistent -= flip ? flipped.inconsistent : plain.inconsistent;
                if (trial.inconsistent >= 0 || (best && !betterScore(trial, bestScore))) {
                    stats.noGain += trial.inconsistent >= 0;
                    continue;
                }
                bool ok = true;
                if (!edit.labelsValid()) {
                    ++stats.labels;
                    ok = false;
                } else if (!edit.parameterValid()) {
                    ++stats.param;
                    ok = false;
                } else if (!extensionShiftable(m_, before, edit, q)) {
                    ++stats.appendixC;
                    ok = false;
                }
                // No face turns over in 3D: the star's faces one by one, the
                // two faces of the flip against the two they replace.
                const bool checksOk = ok;
                int newTurned = 0;
                size_t i = 0;
                for (size_t j = 0; ok && j < star.size(); ++j) {
                    if (flip && star[j] == f)
                        continue;
                    ok = turned[j] || !edit.turnedOver(edit.faces()[i]);
                    ++i;
                }
                for (; ok && i < edit.faces().size(); ++i)
                    newTurned += edit.turnedOver(edit.faces()[i]);
                ok = ok && newTurned <= turnedFlip;
                if (!ok && checksOk)
                    ++stats.turned;
                if (!ok) {
                    ++stats.rejected;
                    continue;
                }
                best = v;
                bestFlip = flip;
                bestScore = trial;
            }
        }
        if (!best)
            return false;
        if (bestFlip) {
            if (!m_.flipEdge(x, y, phase_))
                return false;
            ++stats.flips;
        }
        m_.setVertex(q, *best, phase_);
        return true;
    }
};

ExtensionSettings extensionSettings(const PhaseContext& ctx, const ConsistentMesh& m) {
    ExtensionSettings set;
    set.samples = ctx.parameters.getInt("extension-samples");
    // The radial edges' own tolerance (§6.3 g), so that an extended edge
    // still passes their post-condition.
    const double scale = sceneScale(m);
    const RadialEdgeOptions radial = RadialEdgeOptions::read(ctx.parameters);
    set.tolerance = radial.rootTolerance * scale;
    set.maxIterations = radial.rootMaxIterations;
    set.pushDepth = ctx.parameters.getInt("extension-cusp-push-depth");
    set.maxSweeps = ctx.parameters.getInt("extension-max-sweeps");
    return set;
}

// One pass of Extender::push over the cusps' radial ends that touch an
// inconsistent face; returns the number moved.
long long pushCuspEnds(const PhaseContext& ctx, ConsistentMesh& m, Extender& ext,
                       OptimizationTally* tally, bool everyEnd = false) {
    long long accepted = 0;
    for (const auto& [p, q] : ext.candidates()) {
        ctx.checkCancelled();
        if (!everyEnd && !m.vertex(p).cusp)
            continue;
        const std::vector<Index>& star = m.vertexFaces(q);
        if (!std::any_of(star.begin(), star.end(),
                         [&](Index f) { return !faceIsConsistent(m, f); }))
            continue;
        if (tally)
            ++tally->tried;
        accepted += ext.push(p, q);
    }
    return accepted;
}

void runRadialExtension(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const ExtensionSettings set = extensionSettings(ctx, m);
    const int maxSweeps = set.maxSweeps;
    Extender ext(m, set, s.phaseIndex);
    OptimizationTally tally;
    tally.before = static_cast<long long>(inconsistentFaces(m).size());
    long long count = tally.before;
    for (; tally.sweeps < maxSweeps && count > 0;) {
        ++tally.sweeps;
        long long accepted = 0;
        for (const auto& [p, q] : ext.candidates()) {
            ctx.checkCancelled();
            // Still a radial edge p-q whose far end touches an inconsistent
            // face (an earlier move may have changed that)?
            const std::vector<Index>& star = m.vertexFaces(q);
            if (!std::any_of(star.begin(), star.end(),
                             [&](Index f) { return !faceIsConsistent(m, f); }))
                continue;
            ++tally.tried;
            accepted += ext.extend(p, q);
        }
        // Faces still inconsistent with two movable radial ends: both move,
        // once single moves stopped improving (pair sampling is the costly
        // part, and single moves are preferred).
        std::unordered_map<Index, Index> nearEnd; // far end q -> its C end p
        if (accepted == 0)
            for (const auto& [p, q] : ext.candidates())
                if (ext.movable(p, q))
                    nearEnd.emplace(q, p);
        for (Index f : nearEnd.empty() ? std::vector<Index>{} : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (f >= static_cast<Index>(m.faceCount()) || faceIsConsistent(m, f))
                continue;
            std::vector<Index> ends;
            for (Index v : m.face(f))
                if (nearEnd.count(v))
                    ends.push_back(v);
            if (ends.size() < 2 || nearEnd[ends[0]] == nearEnd[ends[1]])
                continue;
            ++tally.tried;
            accepted += ext.extendPair(nearEnd[ends[0]], ends[0], nearEnd[ends[1]], ends[1]);
        }
        // Cusps' radial ends still touching inconsistent faces: pushed out
        // through several faces (extension-cusp-push-depth), once single and
        // pair moves stopped improving.
        if (accepted == 0 && set.pushDepth > 0)
            accepted += pushCuspEnds(ctx, m, ext, &tally);
        tally.accepted += accepted;
        if (accepted == 0)
            break;
        count = static_cast<long long>(inconsistentFaces(m).size());
        tally.sweepLimitHit = tally.sweeps == maxSweeps && count > 0;
    }
    publish(s, m);
    publishTally(s, tally, counters::kRadialEdgesTried, counters::kRadialEdgesAccepted,
                 "extension-max-sweeps");
    s.setCounter(counters::kRadialPlaneCrossingsFound, static_cast<double>(ext.stats.crossings));
    s.setCounter(counters::kRadialCurveSamples, static_cast<double>(ext.stats.candidates));
    s.setCounter(counters::kSamplesRejectedFoldAppendixCVBOOrDegenerateEdge,
                 static_cast<double>(ext.stats.rejected));
    s.setCounter(counters::kSamplesOnTheOtherSideOfTheContour,
                 static_cast<double>(ext.stats.sideChange));
    s.setCounter(counters::kMovesWithoutFewerInconsistentFaces,
                 static_cast<double>(ext.stats.noGain));
    s.setCounter(counters::kRejectedUndefinedVBOOrDegenerateCCEdge,
                 static_cast<double>(ext.stats.labels));
    s.setCounter(counters::kRejectedParameterFold, static_cast<double>(ext.stats.param));
    s.setCounter(counters::kRejectedAppendixC, static_cast<double>(ext.stats.appendixC));
    s.setCounter(counters::kRejectedFaceTurnedOverIn3D, static_cast<double>(ext.stats.turned));
    s.setCounter(counters::kFlips, static_cast<double>(ext.stats.flips));
    s.setCounter(counters::kFaceWithTwoRadialEndsPairsSampled,
                 static_cast<double>(ext.stats.pairs));
    const CounterName reasons[] = {
        counters::kFaceWithTwoRadialEndsRejectedUndefinedVBOOrDegenerateCCEdge,
        counters::kFaceWithTwoRadialEndsRejectedParameterFold,
        counters::kFaceWithTwoRadialEndsRejectedAppendixC,
        counters::kFaceWithTwoRadialEndsRejectedFaceTurnedOverIn3D};
    for (int r = 0; r < 4; ++r)
        s.setCounter(reasons[r], static_cast<double>(ext.stats.pairRejected[r]));
    s.setCounter(counters::kFaceWithTwoRadialEndsBothMoved,
                 static_cast<double>(ext.stats.pairMoves));
    s.setCounter(counters::kUnconvergedRadialRoots, static_cast<double>(ext.stats.unconverged));
    s.setCounter(counters::kCuspRadialEndsPushesTried, static_cast<double>(ext.stats.pushTried));
    s.setCounter(counters::kCuspRadialEndsPushed, static_cast<double>(ext.stats.pushMoves));
    s.setCounter(counters::kCuspRadialEndsFlipsOfPushes, static_cast<double>(ext.stats.pushFlips));
    if (m.edgeTags().empty() || s.counter(counters::kRadialEdges, 0.0) == 0.0)
        s.notes.push_back("radial edge extension: the mesh has no radial edges (radial edge "
                          "insertion, §6.3 g, did not run or inserted none), nothing to extend");
}

std::vector<InvariantCheck> checkRadialExtension(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

CuspPushCounts pushCuspRadialEnds(const PhaseContext& ctx, ConsistentMesh& m, int phase,
                                  bool everyEnd) {
    const ExtensionSettings set = extensionSettings(ctx, m);
    Extender ext(m, set, phase);
    CuspPushCounts out;
    if (set.pushDepth > 0)
        for (int sweep = 0; sweep < ctx.parameters.getInt("extension-max-sweeps"); ++sweep)
            if (pushCuspEnds(ctx, m, ext, nullptr) == 0)
                break;
    // Then every radial end (extension-push-every-end-final): last, so a
    // push, kept only with fewer inconsistent faces, pre-empts no other move.
    // Earlier, with the cusps' pushes, 2 views of 26 ended worse (spot).
    const long long cuspMoves = ext.stats.pushMoves;
    if (set.pushDepth > 0 && everyEnd)
        for (int sweep = 0; sweep < ctx.parameters.getInt("extension-max-sweeps"); ++sweep)
            if (pushCuspEnds(ctx, m, ext, nullptr, true) == 0)
                break;
    out.tried = ext.stats.pushTried;
    out.moved = ext.stats.pushMoves;
    out.everyEndMoved = ext.stats.pushMoves - cuspMoves;
    out.flips = ext.stats.pushFlips;
    return out;
}

void addRadialExtensionPhase(Method& m) {
    m.parameters.push_back(
        {"extension-samples",
         "Extension: samples",
         "Lines per face on which radial edge extension samples p's radial curve in the "
         "inconsistent face and the face beyond it (§6.4; the paper gives no density).",
         ParameterType::Int,
         10,
         1,
         1000,
         {}});
    m.parameters.push_back(
        {"extension-max-sweeps",
         "Extension: sweeps",
         "Largest number of sweeps over the radial edges (§6.4: \"repeated as long as "
         "the number of inconsistent triangles decreases\").",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.parameters.push_back(
        {"extension-cusp-push-depth",
         "Extension: cusp push depth",
         "Not in the paper (§6.4 looks one face ahead): the far end of a cusp's radial "
         "edge at an inconsistent face is pushed along the cusp's radial curve through "
         "up to this many faces, flipping each edge the curve crosses. 0: off.",
         ParameterType::Int,
         5,
         0,
         10,
         {}});
    m.addPhase(
        {"radial-extension",
         "§6.4 Radial Edge Extension (Fig. 15i, 16f): for a radial edge p-q whose far end q "
         "touches an inconsistent face, q slides along p's radial curve beyond q (sampled in "
         "the face of q's star whose opposite edge crosses p's radial plane and the one beyond) "
         "and that opposite edge may be flipped, keeping the move that removes the most "
         "inconsistent faces; then faces still inconsistent between two radial ends move both "
         "ends together; no fold, appendix C (rule 3 as \"creates no X\"); sweeps while the "
         "count decreases.",
         runRadialExtension, checkRadialExtension});
}

} // namespace contour::consistent
