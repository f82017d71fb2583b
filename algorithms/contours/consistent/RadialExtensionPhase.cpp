// Radial edge extension (Bénard 2014 §6.4, Fig. 15i, Fig. 16f; notes
// §2.4.1): inconsistent faces just beyond the radial strip are fixed by
// sliding the far end of a radial edge along its radial curve and flipping
// the edge opposite it.
#include "contours/consistent/ConsistentPhaseSupport.h"
#include "contours/consistent/ConsistentPhases.h"
#include "contours/consistent/LocalEdit.h"
#include "contours/consistent/OptimizationPhaseSupport.h"
#include "contours/consistent/RadialTriangles.h"

#include <algorithm>
#include <cmath>

namespace contour::consistent {

namespace {

struct ExtensionSettings {
    int samples = 10;
    double tolerance = 0.0; // on radialPlaneDistance, absolute
    int maxIterations = 100;
};

struct ExtensionStats {
    long long crossings = 0, candidates = 0, rejected = 0, flips = 0, unconverged = 0;
};

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

    // One radial edge p-q: every inconsistent face q-x-y around q whose
    // opposite edge x-y crosses p's radial plane; the radial curve is
    // sampled in that face and in the face y-x-z across x-y, and q moves to
    // the sample that removes the most inconsistent faces (with the flip of
    // x-y, or without it), ties to the best minimum Bank-Smith quality.
    bool extend(Index p, Index q) {
        const MeshVertex& qv = m_.vertex(q);
        if (qv.cusp || m_.isBoundaryVertex(q))
            return false;
        for (Index w : m_.neighbours(q))
            if (w != p && m_.edgeTag(q, w) != kNoTag)
                return false;
        if (m_.edgeTag(p, q) != kRadialEdge)
            return false;
        const std::vector<Index> star = m_.vertexFaces(q);
        for (Index f : star) {
            if (faceIsConsistent(m_, f))
                continue;
            Triangle t = m_.face(f);
            while (t[0] != q)
                std::rotate(t.begin(), t.begin() + 1, t.end());
            const Index x = t[1], y = t[2];
            const double hx = h(p, m_.vertex(x).position), hy = h(p, m_.vertex(y).position);
            if (!(hx * hy < 0.0))
                continue;
            ++stats.crossings;
            if (tryMoves(p, q, f, x, y))
                return true;
        }
        return false;
    }

private:
    ConsistentMesh& m_;
    ExtensionSettings set_;
    int phase_;

    double h(Index p, const Vec3& position) const {
        return radialPlaneDistance(m_.camera(), m_.vertex(p), position);
    }
    double h(Index p, const Preimage& u) const { return h(p, m_.surface().evaluate(u).position); }

    // Root of h_p on the segment a-b in parameter space (appendix B), or
    // nothing when h_p does not change sign, a chart is missing or the
    // bisection does not reach the tolerance.
    std::optional<Preimage> root(Index p, const Preimage& a, const Preimage& b) {
        double ha = h(p, a);
        const double hb = h(p, b);
        if (!(ha * hb <= 0.0))
            return std::nullopt;
        double lo = 0.0, hi = 1.0;
        for (int it = 0; it < set_.maxIterations; ++it) {
            const double mid = 0.5 * (lo + hi);
            const std::optional<Preimage> u = m_.interpolate(a, b, mid);
            if (!u)
                return std::nullopt;
            const double hm = h(p, *u);
            if (std::abs(hm) <= set_.tolerance)
                return u;
            if ((hm < 0.0) == (ha < 0.0)) {
                lo = mid;
                ha = hm;
            } else {
                hi = mid;
            }
        }
        ++stats.unconverged;
        return std::nullopt;
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
            if (v.label != label)
                continue;
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
                if (trial.inconsistent >= 0 || (best && !betterScore(trial, bestScore)))
                    continue;
                bool ok = edit.labelsValid() && edit.parameterValid() && edit.shiftable(q);
                // No face turns over in 3D: the star's faces one by one, the
                // two faces of the flip against the two they replace.
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

void runRadialExtension(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    ExtensionSettings set;
    set.samples = ctx.parameters.getInt("extension-samples");
    // The radial edges' own tolerance (§6.3 g), so that an extended edge
    // still passes their post-condition.
    const double scale = sceneScale(m);
    set.tolerance = (ctx.parameters.has("radial-root-tolerance")
                         ? ctx.parameters.getDouble("radial-root-tolerance")
                         : 1e-10) *
                    scale;
    if (ctx.parameters.has("radial-root-max-iterations"))
        set.maxIterations = ctx.parameters.getInt("radial-root-max-iterations");
    const int maxSweeps = ctx.parameters.getInt("extension-max-sweeps");
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
        tally.accepted += accepted;
        if (accepted == 0)
            break;
        count = static_cast<long long>(inconsistentFaces(m).size());
        tally.sweepLimitHit = tally.sweeps == maxSweeps && count > 0;
    }
    publish(s, m);
    publishTally(s, tally, "radial edges", "extension-max-sweeps");
    s.setCounter("radial plane crossings found", static_cast<double>(ext.stats.crossings));
    s.setCounter("radial curve samples", static_cast<double>(ext.stats.candidates));
    s.setCounter("samples rejected (fold, appendix C, VBO or degenerate edge)",
                 static_cast<double>(ext.stats.rejected));
    s.setCounter("flips", static_cast<double>(ext.stats.flips));
    s.setCounter("unconverged radial roots", static_cast<double>(ext.stats.unconverged));
    if (m.edgeTags().empty() || s.counter("radial edges", 0.0) == 0.0)
        s.notes.push_back("radial edge extension: the mesh has no radial edges (radial edge "
                          "insertion, §6.3 g, did not run or inserted none), nothing to extend");
}

std::vector<InvariantCheck> checkRadialExtension(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

void addRadialExtensionPhase(Method& m) {
    m.parameters.push_back(
        {"extension-samples",
         "Extension: samples",
         "Radial edge extension samples the radial curve of p across the inconsistent face and "
         "the face beyond it at this many lines per face (§6.4; the density is unspecified in "
         "the paper).",
         ParameterType::Int,
         10,
         1,
         1000,
         {}});
    m.parameters.push_back({"extension-max-sweeps",
                            "Extension: sweeps",
                            "Largest number of sweeps over the radial edges (§6.4: \"repeated as "
                            "long as the number of inconsistent triangles decreases\").",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.phases.push_back(
        {"radial-extension",
         "§6.4 Radial Edge Extension (Fig. 15i, 16f): for a radial edge p-q whose far end q "
         "touches an inconsistent face whose opposite edge crosses p's radial plane, q slides "
         "along p's radial curve (sampled in that face and the one beyond) and the opposite "
         "edge is flipped, keeping the move that removes the most inconsistent faces; no fold, "
         "appendix C respected; sweeps while the count decreases.",
         runRadialExtension, checkRadialExtension});
}

} // namespace contour::consistent
