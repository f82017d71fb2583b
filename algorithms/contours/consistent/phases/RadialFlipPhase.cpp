// Edge flipping towards standard radial triangles (Bénard 2014 §6.3 h,
// Fig. 15h, 16e; docs/dev/invariants.md item 7).
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/FoldTest.h"
#include "contours/consistent/predicates/RadialTriangles.h"

#include <algorithm>
#include <deque>

namespace contour::consistent {

namespace {

class RadialFlipper {
public:
    RadialFlipper(ConsistentMesh& mesh, int phase, bool fallback, bool keepConsistency,
                  bool fanSequences)
        : m_(mesh), phase_(phase), fallback_(fallback), keepConsistency_(keepConsistency),
          fanSequences_(fanSequences), queued_(mesh.vertexCount(), 0) {}

    long long flips = 0, rejectedFold = 0, fallbackAttempts = 0, fallbackNotApplicable = 0,
              fallbackFailed = 0, deletions = 0, fallbackFlips = 0, fanAttempts = 0, fanUndone = 0,
              fanClears = 0, fanFlips = 0;

    void run(const PhaseContext& ctx) {
        for (Index v = 0; v < m_.vertexCount(); ++v)
            if (m_.vertex(v).label == VertexLabel::Contour)
                enqueue(v);
        long long steps = 0;
        while (!queue_.empty()) {
            if (++steps % 256 == 0)
                ctx.checkCancelled();
            const Index p = queue_.front();
            queue_.pop_front();
            queued_[p] = 0;
            if (improveAround(p))
                enqueue(p);
        }
    }

private:
    ConsistentMesh& m_;
    const int phase_;
    const bool fallback_;
    const bool keepConsistency_;
    const bool fanSequences_;
    std::vector<char> queued_;
    std::deque<Index> queue_;

    void enqueue(Index v) {
        if (v == kInvalidIndex || m_.vertex(v).label != VertexLabel::Contour || queued_[v])
            return;
        queued_[v] = 1;
        queue_.push_back(v);
    }

    bool label(Index v, VertexLabel l) const { return m_.vertex(v).label == l; }

    bool consistent(const Triangle& t) const {
        const MeshVertex &a = m_.vertex(t[0]), &b = m_.vertex(t[1]), &c = m_.vertex(t[2]);
        return isConsistent(vertexBasedOrientation(a.label, b.label, c.label),
                            triangleFacing(m_.camera(), a.position, b.position, c.position));
    }

    // The flip of a-b (faces a-b-c, b-a-d -> a-d-c, b-c-d): change in the
    // number of standard radial triangles, or nullopt when the flip is not
    // allowed (boundary, tagged edge, an undefined VBO after it, or, with
    // radial-keep-consistency, more inconsistent faces). Only the two faces
    // change: flips never touch a radial edge, so which vertices lie on
    // radial edges does not change.
    std::optional<int> flipGain(Index a, Index b) const {
        if (m_.edgeTag(a, b) != kNoTag)
            return std::nullopt;
        const Index f0 = m_.faceOfHalfedge(a, b), f1 = m_.faceOfHalfedge(b, a);
        if (f0 == kInvalidIndex || f1 == kInvalidIndex)
            return std::nullopt;
        const auto [c, d] = m_.oppositeVertices(a, b);
        // A cusp keeps the valence 4 of Fig. 18d until radial edges are
        // added around it (Fig. 18e).
        for (Index w : {a, b, c, d})
            if (m_.vertex(w).cusp && !onRadialEdge(m_, w))
                return std::nullopt;
        const Triangle n0{a, d, c}, n1{b, c, d};
        for (const Triangle& t : {n0, n1})
            if (vertexBasedOrientation(m_.vertex(t[0]).label, m_.vertex(t[1]).label,
                                       m_.vertex(t[2]).label) == Vbo::Undefined)
                return std::nullopt;
        if (keepConsistency_ &&
            static_cast<int>(consistent(n0)) + consistent(n1) <
                static_cast<int>(consistent(m_.face(f0))) + consistent(m_.face(f1)))
            return std::nullopt;
        return static_cast<int>(isStandardRadial(m_, n0)) + isStandardRadial(m_, n1) -
               isStandardRadial(m_, m_.face(f0)) - isStandardRadial(m_, m_.face(f1));
    }

    // Flips the first non-radial FC / BC edge p-x whose flip increases the
    // number of standard radial triangles without folding (§6.3 h). A flip
    // that would fold triggers the Fig. 16e (right) fallback on x.
    bool improveAround(Index p) {
        // A cusp keeps the valence 4 of Fig. 18d until radial edges are
        // added around it (Fig. 18e).
        if (m_.vertex(p).cusp && !onRadialEdge(m_, p))
            return false;
        for (Index x : m_.neighbours(p)) {
            if (label(x, VertexLabel::Contour))
                continue;
            const std::optional<int> gain = flipGain(p, x);
            if (!gain || *gain <= 0)
                continue;
            const FlipFold fold = flipFolds(m_, p, x);
            if (fold.impossible)
                continue;
            if (fold.folds()) {
                ++rejectedFold;
                if (fallback_ && deleteByFlips(x))
                    return true;
                continue;
            }
            const auto [c, d] = m_.oppositeVertices(p, x);
            if (!m_.flipEdge(p, x, phase_))
                continue;
            ++flips;
            enqueue(c);
            enqueue(d);
            return true;
        }
        return fanSequences_ && clearFans(p);
    }

    // The flip of a-b as one step of a sequence (no gain asked of it): not
    // tagged, no undefined VBO, no bare cusp, no fold.
    bool flippable(Index a, Index b) const {
        if (m_.edgeTag(a, b) != kNoTag || m_.faceOfHalfedge(a, b) == kInvalidIndex ||
            m_.faceOfHalfedge(b, a) == kInvalidIndex)
            return false;
        const auto [c, d] = m_.oppositeVertices(a, b);
        for (Index w : {a, b, c, d})
            if (m_.vertex(w).cusp && !onRadialEdge(m_, w))
                return false;
        for (const Triangle& t : {Triangle{a, d, c}, Triangle{b, c, d}})
            if (vertexBasedOrientation(m_.vertex(t[0]).label, m_.vertex(t[1]).label,
                                       m_.vertex(t[2]).label) == Vbo::Undefined)
                return false;
        return !flipWouldFold(m_, a, b);
    }

    // §6.3 h when no single flip gains: p's fan between its radial edge p-r
    // and the next C neighbour or radial-edge vertex c holds vertices x1..xk
    // (neither C nor on a radial edge), and each flip of p-xi alone leaves
    // the count of standard radial triangles unchanged; the k flips together
    // leave the standard radial triangle p-r-c (CC edge p-c, or c on another
    // radial edge). The sequence is flipped
    // from r's side, restarting from c's side when a flip would fold (as
    // the Fig. 16e fallback walks a fan), and kept only if the standard
    // radial triangles around increase (and, with radial-keep-consistency,
    // the inconsistent faces do not).
    bool clearFans(Index p) {
        const std::vector<Index> ringp = ring(p);
        const int n = static_cast<int>(ringp.size());
        if (n < 4)
            return false;
        for (int i = 0; i < n; ++i) {
            const Index r = ringp[i];
            if (!isRadialEdge(m_, p, r))
                continue;
            for (int dir : {1, -1}) {
                std::vector<Index> xs;
                Index c = kInvalidIndex;
                for (int k = 1; k < n; ++k) {
                    const Index w = ringp[((i + dir * k) % n + n) % n];
                    // The fan ends at a C vertex (p-r-c gets a CC edge) or
                    // at a vertex on another C vertex's radial edge (p-r-c
                    // gets its second radial vertex).
                    if (label(w, VertexLabel::Contour) ||
                        (onRadialEdge(m_, w) && !isRadialEdge(m_, p, w))) {
                        c = w;
                        break;
                    }
                    if (isRadialEdge(m_, p, w) || m_.vertex(w).label != m_.vertex(r).label)
                        break;
                    xs.push_back(w);
                }
                if (c == kInvalidIndex || xs.empty() || isRadialEdge(m_, p, c))
                    continue;
                ++fanAttempts;
                if (clearFan(p, r, c, xs))
                    return true;
            }
        }
        return false;
    }

    bool clearFan(Index p, Index r, Index c, const std::vector<Index>& xs) {
        std::vector<Index> region{p, r, c};
        region.insert(region.end(), xs.begin(), xs.end());
        const int before = standardAround(region);
        const int inconsistentBefore = inconsistentFacesAround(m_, region);
        std::vector<std::array<Index, 2>> log;
        std::deque<Index> left(xs.begin(), xs.end());
        bool fromR = true, switched = false;
        while (!left.empty()) {
            const Index w = fromR ? left.front() : left.back();
            if (flippable(p, w)) {
                const auto [a, b] = m_.oppositeVertices(p, w);
                if (m_.flipEdge(p, w, phase_)) {
                    log.push_back({a, b});
                    fromR ? left.pop_front() : left.pop_back();
                    continue;
                }
            }
            if (switched)
                break;
            fromR = !fromR;
            switched = true;
        }
        const bool gains =
            left.empty() && standardAround(region) > before &&
            !(keepConsistency_ && inconsistentFacesAround(m_, region) > inconsistentBefore);
        if (!gains) {
            for (auto it = log.rbegin(); it != log.rend(); ++it)
                m_.flipEdge((*it)[0], (*it)[1], phase_);
            ++fanUndone;
            return false;
        }
        ++fanClears;
        fanFlips += static_cast<long long>(log.size());
        for (Index v : region)
            enqueue(v);
        return true;
    }

    // x's neighbours in counter-clockwise order, empty for a boundary
    // vertex.
    std::vector<Index> ring(Index x) const {
        std::vector<Index> out;
        if (m_.vertexFaces(x).empty() || m_.isBoundaryVertex(x))
            return out;
        const Triangle first = rotatedTo(m_.face(m_.vertexFaces(x).front()), x);
        out.push_back(first[1]);
        for (Index cur = first[2]; cur != first[1];) {
            out.push_back(cur);
            const Index f = m_.faceOfHalfedge(x, cur);
            if (f == kInvalidIndex || out.size() > m_.vertexFaces(x).size())
                return {};
            cur = rotatedTo(m_.face(f), x)[2];
        }
        return out;
    }

    // Standard radial triangles among the faces around `vertices`.
    int standardAround(const std::vector<Index>& vertices) const {
        int n = 0;
        for (Index f : facesAround(m_, vertices))
            n += isStandardRadial(m_, m_.face(f));
        return n;
    }

    bool allowedFlip(Index a, Index b) const {
        return flipGain(a, b).has_value() && !flipWouldFold(m_, a, b);
    }

    // Fig. 16e right: x is the non-contour end of an FC / BC edge whose
    // flip would fold. q and r are x's neighbours that end radial edges,
    // next to the contour vertices of x's ring; x's edges to the fan beyond
    // q and r are flipped away, from q's side, restarting from r's side when
    // a flip would fold; then x's remaining edges to the contour until x is
    // connected only to q, r and one C vertex c; x is deleted, leaving the
    // standard radial triangle q-c-r. Everything is undone unless the
    // standard radial triangles around increase.
    bool deleteByFlips(Index x) {
        ++fallbackAttempts;
        const MeshVertex& vx = m_.vertex(x);
        if (vx.label == VertexLabel::Contour || onRadialEdge(m_, x)) {
            ++fallbackNotApplicable;
            return false;
        }
        std::vector<Index> ringx = ring(x);
        const int n = static_cast<int>(ringx.size());
        const bool bareCusp = std::any_of(ringx.begin(), ringx.end(), [&](Index w) {
            return m_.vertex(w).cusp && !onRadialEdge(m_, w);
        });
        if (n < 4 || bareCusp) {
            ++fallbackNotApplicable;
            return false;
        }
        // The C vertices of the ring must form one arc; rotate it to the
        // front: ring = C arc, q, far fan ..., r.
        int start = -1, arcs = 0;
        for (int i = 0; i < n; ++i)
            if (label(ringx[i], VertexLabel::Contour) &&
                !label(ringx[(i + n - 1) % n], VertexLabel::Contour)) {
                start = i;
                ++arcs;
            }
        if (arcs != 1) {
            ++fallbackNotApplicable;
            return false;
        }
        std::rotate(ringx.begin(), ringx.begin() + start, ringx.end());
        int arcLength = 0;
        while (arcLength < n && label(ringx[arcLength], VertexLabel::Contour))
            ++arcLength;
        if (arcLength + 2 > n) {
            ++fallbackNotApplicable;
            return false;
        }
        const Index q = ringx[arcLength], r = ringx.back();
        if (!onRadialEdge(m_, q) || !onRadialEdge(m_, r) || q == r) {
            ++fallbackNotApplicable;
            return false;
        }
        std::deque<Index> far(ringx.begin() + arcLength + 1, ringx.end() - 1);
        std::vector<Index> arc(ringx.begin(), ringx.begin() + arcLength);
        std::vector<Index> region = ringx;
        region.push_back(x);
        const int before = standardAround(region);
        const int inconsistentBefore = inconsistentFacesAround(m_, region);
        std::vector<std::array<Index, 2>> log; // new edges, to flip back
        auto flip = [&](Index w) {
            if (!allowedFlip(x, w))
                return false;
            const auto [c, d] = m_.oppositeVertices(x, w);
            if (!m_.flipEdge(x, w, phase_))
                return false;
            log.push_back({c, d});
            return true;
        };
        auto undoAll = [&] {
            for (auto it = log.rbegin(); it != log.rend(); ++it)
                m_.flipEdge((*it)[0], (*it)[1], phase_);
            ++fallbackFailed;
            return false;
        };
        bool fromQ = true, switched = false;
        while (!far.empty()) {
            const Index w = fromQ ? far.front() : far.back();
            if (flip(w)) {
                fromQ ? far.pop_front() : far.pop_back();
                continue;
            }
            if (switched)
                return undoAll();
            fromQ = !fromQ;
            switched = true;
        }
        // x: q, r and the contour arc; flip edges to the arc down to one.
        for (bool progress = true; m_.vertexFaces(x).size() > 3 && progress;) {
            progress = false;
            for (Index c : arc)
                if (m_.faceOfHalfedge(x, c) != kInvalidIndex && flip(c)) {
                    progress = true;
                    break;
                }
        }
        if (m_.vertexFaces(x).size() != 3)
            return undoAll();
        // The triangle that replaces x's three faces (as
        // removeValence3Vertex builds it) must not fold and must gain.
        const Triangle first = rotatedTo(m_.face(m_.vertexFaces(x).front()), x);
        Index third = kInvalidIndex;
        for (Index w : m_.neighbours(x))
            if (w != first[1] && w != first[2])
                third = w;
        const Triangle merged{first[1], first[2], third};
        Vec3 reference = Vec3::Zero();
        for (Index f : m_.vertexFaces(x))
            reference += faceNormal(m_, f);
        const auto& a = m_.vertex(merged[0]);
        const auto& b = m_.vertex(merged[1]);
        const auto& c = m_.vertex(merged[2]);
        if (turnsOver(a.position, b.position, c.position, reference) ||
            !keepsParameterOrientation(m_, {a.preimage, b.preimage, c.preimage}) ||
            vertexBasedOrientation(a.label, b.label, c.label) == Vbo::Undefined)
            return undoAll();
        std::vector<Index> rest(region.begin(), region.end() - 1);
        int after = isStandardRadial(m_, merged);
        int inconsistentAfter = !consistent(merged);
        {
            // Faces around the ring, minus x's three faces.
            std::vector<Index> faces;
            for (Index v : rest)
                for (Index f : m_.vertexFaces(v)) {
                    const Triangle& t = m_.face(f);
                    if (std::find(t.begin(), t.end(), x) == t.end())
                        faces.push_back(f);
                }
            std::sort(faces.begin(), faces.end());
            faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
            for (Index f : faces) {
                after += isStandardRadial(m_, m_.face(f));
                inconsistentAfter += !consistent(m_.face(f));
            }
        }
        if (after <= before || (keepConsistency_ && inconsistentAfter > inconsistentBefore))
            return undoAll();
        if (!m_.removeValence3Vertex(x, phase_))
            return undoAll();
        ++deletions;
        fallbackFlips += static_cast<long long>(log.size());
        for (Index v : rest)
            enqueue(v);
        return true;
    }
};

// The phase's parameters, read once per run.
struct RadialFlipOptions {
    bool foldFallback = false;    // radial-fold-fallback
    bool keepConsistency = false; // radial edge insertion's radial-keep-consistency
    bool fanSequences = false;    // radial-fan-sequences
    static RadialFlipOptions read(const ParameterSet& p) {
        RadialFlipOptions o;
        o.foldFallback = p.getBool("radial-fold-fallback");
        o.keepConsistency = RadialEdgeOptions::read(p).keepConsistency;
        o.fanSequences = p.getBool("radial-fan-sequences");
        return o;
    }
};

void runRadialFlips(const PhaseContext& ctx, Snapshot& s) {
    const RadialFlipOptions options = RadialFlipOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const StandardRadialShare before = standardRadialShare(m);
    const RadialClassification classes = classifyRadialFaces(m);
    const double standardBefore =
        static_cast<double>(std::count(classes.standard.begin(), classes.standard.end(), 1));
    RadialFlipper flipper(m, s.phaseIndex, options.foldFallback, options.keepConsistency,
                          options.fanSequences);
    flipper.run(ctx);
    const StandardRadialShare after = standardRadialShare(m);
    publish(s, m);
    s.setCounter(counters::kStandardRadialFacesBefore, standardBefore);
    s.setCounter(counters::kRadialFlips, static_cast<double>(flipper.flips));
    s.setCounter(counters::kFlipsRejectedFold, static_cast<double>(flipper.rejectedFold));
    s.setCounter(counters::kFoldFallbacksTried, static_cast<double>(flipper.fallbackAttempts));
    s.setCounter(counters::kFoldFallbacksNotApplicable,
                 static_cast<double>(flipper.fallbackNotApplicable));
    s.setCounter(counters::kFoldFallbacksUndone, static_cast<double>(flipper.fallbackFailed));
    s.setCounter(counters::kFoldFallbackFlips, static_cast<double>(flipper.fallbackFlips));
    s.setCounter(counters::kVertexDeletions, static_cast<double>(flipper.deletions));
    s.setCounter(counters::kFanSequencesTried, static_cast<double>(flipper.fanAttempts));
    s.setCounter(counters::kFanSequencesUndone, static_cast<double>(flipper.fanUndone));
    s.setCounter(counters::kFanSequencesFlipped, static_cast<double>(flipper.fanClears));
    s.setCounter(counters::kFanSequenceFlips, static_cast<double>(flipper.fanFlips));
    s.setCounter(counters::kFacesTouchingNonCuspCVertices, static_cast<double>(after.contourFaces));
    s.setCounter(counters::kStandardRadialShareBeforePercent, before.percent());
    s.setCounter(counters::kStandardRadialSharePercent, after.percent());
    if (after.standard < after.contourFaces)
        s.notes.push_back(std::to_string(after.contourFaces - after.standard) + " of " +
                          std::to_string(after.contourFaces) +
                          " faces touching non-cusp C vertices are not standard radial "
                          "triangles (§6.3 h target, not guaranteed)");
}

std::vector<InvariantCheck> checkRadialFlips(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, true);
    out.push_back(radialEdgeCheck(ctx, m));
    InvariantCheck more = check("radial flips never decrease the number of standard radial "
                                "triangles (§6.3 h)");
    const double before = s.counter(counters::kStandardRadialFacesBefore, 0.0);
    const double after = s.counter(counters::kStandardRadialFaces, 0.0);
    if (after < before) {
        more.violations = 1;
        more.firstExample = std::to_string(after) + " < " + std::to_string(before);
    }
    out.push_back(more);
    return out;
}

} // namespace

void addRadialFlipPhase(Method& m) {
    m.parameters.push_back(
        {"radial-fold-fallback",
         "Radial flip fold fallback",
         "When a flip towards standard radial triangles would fold, flip the fan of its "
         "non-contour vertex away and delete that vertex (§6.3 h, Fig. 16e right).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"radial-fan-sequences",
         "Radial flip fan sequences",
         "Not in the paper: when no single flip increases the standard radial triangles "
         "(§6.3 h), a C vertex's fan between its radial edge and the next C or "
         "radial-edge vertex is flipped away as one sequence, kept only if they "
         "increase.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"radial-flips",
         "§6.3 h (Fig. 15h, 16e): every non-radial FC / BC edge incident on a C vertex is "
         "flipped when the flip increases the number of standard radial triangles without a "
         "fold (3D or parameter space), until none qualifies; a flip that would fold instead "
         "flips the fan of its non-contour vertex and deletes that vertex (Fig. 16e right). "
         "With radial-fan-sequences (not in the paper), a fan that single flips cannot clear "
         "is flipped away as one sequence.",
         runRadialFlips, checkRadialFlips});
}

} // namespace contour::consistent
