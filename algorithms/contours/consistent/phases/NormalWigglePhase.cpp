// Vertex wiggling in the normal direction (Bénard 2014 §6.4, final step):
// vertices may leave the limit surface.
#include "contours/consistent/edits/CuspEndRetriangulation.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/NormalWiggle.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/RadialExtension.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace contour::consistent {

namespace {

Vec3 onSurface(const MeshVertex& x) {
    return x.position - x.normalOffset * x.normal;
}

// The largest offset allowed at v: `fraction` times the mean distance from
// f(u_v) to the one-ring's f(u_w) (the paper's "average distance to the
// vertices in the one-ring", taken on the surface so that it does not depend
// on the order in which neighbours were wiggled).
double offsetBound(const ConsistentMesh& m, Index v, double fraction) {
    const std::vector<Index> ring = m.neighbours(v);
    if (ring.empty())
        return 0.0;
    double sum = 0.0;
    for (Index w : ring)
        sum += (onSurface(m.vertex(w)) - onSurface(m.vertex(v))).norm();
    return fraction * sum / static_cast<double>(ring.size());
}

// Pixels between the images of two points.
double imageShift(const Camera& camera, const Vec3& a, const Vec3& b) {
    return (camera.project(a).pixel - camera.project(b).pixel).norm();
}

// The offsets tried at a vertex whose largest offset is `bound`: `samples`
// even offsets (pairs ±α in increasing |α|) and `fine` offsets of each sign
// below the even step, log-uniformly over six decades; increasing |α|, +
// before -.
std::vector<double> normalOffsets(double bound, int samples, int fine) {
    const int pairs = (samples + 1) / 2;
    std::vector<double> offsets;
    for (int k = 1; k <= pairs; ++k)
        for (double sign : {1.0, -1.0})
            if (static_cast<int>(offsets.size()) < samples)
                offsets.push_back(sign * bound * k / pairs);
    const double step = pairs > 0 ? bound / pairs : bound;
    for (int k = 1; k <= fine; ++k)
        for (double sign : {1.0, -1.0})
            offsets.push_back(sign * step * std::pow(10.0, -6.0 * k / fine));
    std::stable_sort(offsets.begin(), offsets.end(), [](double a, double b) {
        return std::abs(a) < std::abs(b) || (std::abs(a) == std::abs(b) && a > b);
    });
    return offsets;
}

// Position f(u) + α n(u) for `samples` offsets α spread evenly over
// [-bound, bound] (pairs ±α in increasing |α|, plus α = 0 when the vertex is
// already off the surface); the first offset, in that order, reaching the
// fewest inconsistent faces around v wins, so ties take the smallest |α|.
// Labels (g at the preimage) do not change, so VBOs, degenerate edges and
// parameter space are untouched; a face of the star may not turn over in 3D.
//
// `fine` (normal-wiggle-fine-offsets, not in the paper): also `fine`
// offsets of each sign below the even step bound / (samples / 2), spread
// log-uniformly over six decades, so that much smaller displacements are
// tried too. A cusp's inside fan (Fig. 18e)
// is a very thin image wedge: the uniform step jumps over it (torus, 26
// views: 24 inside-fan faces left with 100 offsets, 8 with 400).
bool wiggleAlongNormal(ConsistentMesh& m, Index v, int samples, int fine, double fraction,
                       int phase, NormalWiggleStats& st) {
    const MeshVertex current = m.vertex(v);
    const std::vector<Index> star = m.vertexFaces(v);
    LocalEdit edit(m);
    edit.addFaces(star);
    const LocalScore now = edit.score();
    if (now.inconsistent == 0)
        return false;
    std::vector<char> turned(star.size());
    for (size_t i = 0; i < star.size(); ++i)
        turned[i] = edit.turnedOver(edit.faces()[i]);
    const double bound = offsetBound(m, v, fraction);
    const Vec3 base = onSurface(current);
    std::vector<double> offsets;
    if (current.normalOffset != 0.0)
        offsets.push_back(0.0);
    for (double alpha : normalOffsets(bound, samples, fine))
        offsets.push_back(alpha);
    std::optional<MeshVertex> best;
    int bestCount = now.inconsistent;
    for (double alpha : offsets) {
        if (alpha == current.normalOffset)
            continue;
        MeshVertex x = current;
        x.normalOffset = alpha;
        x.position = base + alpha * current.normal;
        x.provenance = Provenance::Wiggled;
        x.phase = phase;
        edit.moveVertex(v, x);
        const int count = edit.inconsistent();
        if (count >= bestCount)
            continue;
        bool ok = true;
        for (size_t i = 0; ok && i < star.size(); ++i)
            ok = turned[i] || !edit.turnedOver(edit.faces()[i]);
        if (!ok) {
            ++st.rejectedFold;
            continue;
        }
        best = x;
        bestCount = count;
    }
    if (!best)
        return false;
    m.setVertex(v, *best, phase);
    return true;
}

// Not in the paper (extends §6.4's normal wiggle): the two ends a, b of an
// edge of an inconsistent face move along their normals together, each
// among `samples` even and samples / 2 fine offsets (and its current one),
// judged on the union of their stars: strictly fewer inconsistent faces,
// no face of it turned over in 3D that was not before. A face whose
// corners must both move to face the right way (a radial end next to its
// C vertex in the image, Fig. 18e's thin wedges) is out of reach of one
// vertex at a time when each single move turns a neighbour over.
//
// `maxContourShift` (pixels): offsets that would move a C vertex (the
// contour drawn) farther than this in the image are not tried.
bool wigglePairAlongNormal(ConsistentMesh& m, Index a, Index b, int samples, double fraction,
                           int phase, NormalWiggleStats& st,
                           double maxContourShift = std::numeric_limits<double>::infinity()) {
    // The union of the stars in three parts: the faces of a alone (they
    // depend on a's offset only), of b alone, and of both (the two faces
    // of edge a-b), so that a pair of offsets re-judges two faces only.
    enum Part { kA, kB, kBoth };
    std::array<LocalEdit, 3> edits{LocalEdit(m), LocalEdit(m), LocalEdit(m)};
    const auto has = [&](Index f, Index v) {
        const Triangle& t = m.face(f);
        return t[0] == v || t[1] == v || t[2] == v;
    };
    for (Index f : m.vertexFaces(a))
        edits[has(f, b) ? kBoth : kA].addFace(m.face(f));
    for (Index f : m.vertexFaces(b))
        if (!has(f, a))
            edits[kB].addFace(m.face(f));
    int now = 0;
    std::array<std::vector<char>, 3> turned;
    for (int k = 0; k < 3; ++k) {
        now += edits[k].inconsistent();
        for (const Triangle& t : edits[k].faces())
            turned[k].push_back(edits[k].turnedOver(t));
    }
    if (now == 0)
        return false;
    ++st.pairsTried;
    // No face of the part turned over in 3D that was not before.
    const auto keepsFacing = [&](int k) {
        const std::vector<Triangle>& faces = edits[k].faces();
        for (size_t i = 0; i < faces.size(); ++i)
            if (!turned[k][i] && edits[k].turnedOver(faces[i]))
                return false;
        return true;
    };
    const MeshVertex ca = m.vertex(a), cb = m.vertex(b);
    const auto moved = [&](const MeshVertex& c, double alpha) {
        MeshVertex x = c;
        x.normalOffset = alpha;
        x.position = onSurface(c) + alpha * c.normal;
        x.provenance = Provenance::Wiggled;
        x.phase = phase;
        return x;
    };
    // Each vertex's moves (its current offset excluded: one vertex at a
    // time was tried already), with the count and the facing check of its
    // own part.
    struct Move {
        MeshVertex x;
        int count;
        bool ok;
    };
    const auto moves = [&](const MeshVertex& c, Index v, int k) {
        std::vector<Move> out;
        for (double alpha : normalOffsets(offsetBound(m, v, fraction), samples, samples / 2)) {
            if (alpha == c.normalOffset)
                continue;
            const MeshVertex x = moved(c, alpha);
            if (c.label == VertexLabel::Contour &&
                imageShift(m.camera(), onSurface(c), x.position) > maxContourShift)
                continue;
            edits[k].moveVertex(v, x);
            out.push_back({x, edits[k].inconsistent(), keepsFacing(k)});
        }
        return out;
    };
    const std::vector<Move> movesA = moves(ca, a, kA), movesB = moves(cb, b, kB);
    int bestCount = now;
    const Move *bestA = nullptr, *bestB = nullptr;
    for (const Move& ma : movesA)
        for (const Move& mb : movesB) {
            if (ma.count + mb.count >= bestCount)
                continue;
            edits[kBoth].moveVertex(a, ma.x);
            edits[kBoth].moveVertex(b, mb.x);
            const int count = ma.count + mb.count + edits[kBoth].inconsistent();
            if (count >= bestCount)
                continue;
            if (!ma.ok || !mb.ok || !keepsFacing(kBoth)) {
                ++st.rejectedFold;
                continue;
            }
            bestA = &ma;
            bestB = &mb;
            bestCount = count;
        }
    if (!bestA)
        return false;
    m.setVertex(a, bestA->x, phase);
    m.setVertex(b, bestB->x, phase);
    ++st.pairsAccepted;
    return true;
}

void runNormalWiggle(const PhaseContext& ctx, Snapshot& s) {
    const NormalWiggleOptions o = normalWiggleOptions(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    OptimizationTally tally;
    NormalWiggleStats st;
    wiggleVertices(ctx, m, o, phase, tally, st);
    // Then pairs, each accepted pair followed by single moves again.
    for (int sweep = 0; o.pairSamples > 0 && sweep < o.maxSweeps; ++sweep) {
        bool progress = false;
        for (Index f : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (faceIsConsistent(m, f))
                continue;
            const Triangle t = m.face(f);
            for (int i = 0; i < 3 && !progress; ++i)
                progress = wigglePairAlongNormal(m, t[i], t[(i + 1) % 3], o.pairSamples, o.fraction,
                                                 phase, st);
        }
        // Once the face's own edges give nothing: a corner of the face
        // with a neighbour off the face (normal-wiggle-ring-pairs, not in
        // the paper). Mostly the far end q of a radial edge with its C end
        // p (bigguy, 26 views: 46 of 74 such pairs). q lies within about a
        // tenth of a pixel of p in the image (Fig. 16f's thin strip), so q
        // cannot move alone without upsetting the radial triangles at p;
        // the radial edge moved as a whole shifts the strip, and the face
        // q-q'-y beyond it (y just on the wrong side of the chord q-q')
        // turns the right way.
        for (Index f : progress || !o.ringPairs ? std::vector<Index>{} : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (faceIsConsistent(m, f))
                continue;
            const Triangle t = m.face(f);
            for (int i = 0; i < 3 && !progress; ++i)
                for (Index b : m.neighbours(t[i])) {
                    if (b == t[0] || b == t[1] || b == t[2])
                        continue;
                    progress = wigglePairAlongNormal(m, t[i], b, o.pairSamples, o.fraction, phase,
                                                     st, o.ringShift);
                    if (progress) {
                        ++st.ringPairsAccepted;
                        break;
                    }
                }
        }
        if (!progress)
            break;
        OptimizationTally again;
        wiggleVertices(ctx, m, o, phase, again, st);
        tally.tried += again.tried;
        tally.accepted += again.accepted;
    }
    const NormalOffsetStats offsets = normalOffsetStats(m);
    publish(s, m);
    publishTally(s, tally, "vertices", "normal-wiggle-max-sweeps");
    publishNormalOffsetStats(s, offsets);
    s.setCounter(counters::kOffsetsRejected3DFold, static_cast<double>(st.rejectedFold));
    s.setCounter(counters::kVertexPairsTried, static_cast<double>(st.pairsTried));
    s.setCounter(counters::kVertexPairsMoved, static_cast<double>(st.pairsAccepted));
    s.setCounter(counters::kRingPairsMoved, static_cast<double>(st.ringPairsAccepted));
}

} // namespace

NormalWiggleOptions normalWiggleOptions(const ParameterSet& p) {
    NormalWiggleOptions o;
    o.samples = p.getInt("normal-wiggle-samples");
    o.fine = p.getInt("normal-wiggle-fine-offsets");
    o.fraction = p.getDouble("normal-wiggle-max-offset");
    o.maxSweeps = p.getInt("normal-wiggle-max-sweeps");
    o.pairSamples = p.getInt("normal-wiggle-pair-offsets");
    o.ringPairs = p.getBool("normal-wiggle-ring-pairs");
    // 0: no bound.
    o.ringShift = p.getDouble("normal-wiggle-ring-pair-shift");
    if (o.ringShift <= 0.0)
        o.ringShift = std::numeric_limits<double>::infinity();
    return o;
}

void wiggleVertices(const PhaseContext& ctx, ConsistentMesh& m, const NormalWiggleOptions& o,
                    int phase, OptimizationTally& tally, NormalWiggleStats& st) {
    sweepInconsistent(ctx, m, o.maxSweeps, true, tally, [&](Index v) {
        return wiggleAlongNormal(m, v, o.samples, o.fine, o.fraction, phase, st);
    });
}

NormalOffsetStats normalOffsetStats(const ConsistentMesh& m) {
    NormalOffsetStats out;
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const MeshVertex& x = m.vertex(v);
        const double bound = offsetBound(m, v, 1.0);
        out.offVertices += x.normalOffset != 0.0;
        if (bound > 0.0)
            out.largest = std::max(out.largest, std::abs(x.normalOffset) / bound);
        // How far the drawn contour moved: a C vertex off the surface.
        if (x.label == VertexLabel::Contour && x.normalOffset != 0.0)
            out.contourShift =
                std::max(out.contourShift, imageShift(m.camera(), x.position, onSurface(x)));
    }
    return out;
}

void publishNormalOffsetStats(Snapshot& s, const NormalOffsetStats& n) {
    s.setCounter(counters::kVerticesOffSurface, static_cast<double>(n.offVertices));
    s.setCounter(counters::kLargestNormalOffsetRatio, n.largest);
    s.setCounter(counters::kLargestContourShift, n.contourShift);
}

// docs/dev/invariants.md item 2: |α| <= the mean one-ring distance (times
// normal-wiggle-max-offset).
std::vector<InvariantCheck> normalWiggleChecks(const PhaseContext& ctx, const Snapshot& s) {
    std::vector<InvariantCheck> out = optimizationChecks(ctx, s, false);
    const ConsistentMesh m = reload(ctx, s);
    const double fraction = normalWiggleOptions(ctx.parameters).fraction;
    InvariantCheck bound = check("every normal offset is at most normal-wiggle-max-offset times "
                                 "the mean distance to the one-ring (§6.4)");
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const double alpha = std::abs(m.vertex(v).normalOffset);
        const double limit = offsetBound(m, v, fraction);
        if (alpha > 0.0 && !(alpha <= limit * (1.0 + 1e-9)))
            violate(bound, "vertex " + std::to_string(v) + " offset " + std::to_string(alpha) +
                               " bound " + std::to_string(limit));
    }
    out.push_back(bound);
    return out;
}

void addNormalWigglePhase(Method& m) {
    m.parameters.push_back({"normal-wiggle-samples",
                            "Normal wiggle: offsets",
                            "Offsets along the normal line p + α n tried per vertex (§6.4: "
                            "100).",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.parameters.push_back(
        {"normal-wiggle-max-offset",
         "Normal wiggle: largest offset",
         "Largest |α| as a fraction of the vertex's mean distance to its one-ring (§6.4: 1, "
         "\"maximum displacement equal to the average distance to the vertices in the "
         "one-ring\").",
         ParameterType::Double,
         1.0,
         0.0,
         1.0,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-fine-offsets",
         "Normal wiggle: fine offsets",
         "Not in the paper (§6.4 samples its offsets evenly): also try this many offsets "
         "of each sign below the even step, log-uniformly over six decades, for the "
         "small moves a cusp's thin inside fan (Fig. 18e) needs. 0: the even offsets "
         "only.",
         ParameterType::Int,
         48,
         0,
         1000,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-pair-offsets",
         "Normal wiggle: pairs of vertices",
         "Not in the paper: after the one-vertex sweeps (§6.4), the two ends of each "
         "edge of an inconsistent face move along their normals together, each among "
         "this many even and half as many fine offsets, kept when their stars improve. "
         "0: off.",
         ParameterType::Int,
         48,
         0,
         200,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-ring-pairs",
         "Normal wiggle: pairs off the face",
         "Not in the paper: when no pair of an inconsistent face's own corners helps, a "
         "corner moves along its normal together with one of its neighbours off the face "
         "(same offsets and acceptance). Needs normal-wiggle-pair-offsets > 0.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-ring-pair-shift",
         "Normal wiggle: ring pairs' contour shift",
         "With normal-wiggle-ring-pairs (not in the paper): largest image displacement, "
         "in pixels, of a C vertex moved by a ring pair; the drawn contour moves with "
         "it. 0: no bound.",
         ParameterType::Double,
         0.0,
         0.0,
         100.0,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-max-sweeps",
         "Normal wiggle: sweeps",
         "Largest number of sweeps over the vertices of inconsistent faces in the normal "
         "wiggle (§6.4; the paper gives no stopping rule).",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.addPhase(
        {"normal-wiggle",
         "§6.4 Vertex Wiggling in the Normal Direction: every vertex of an inconsistent face "
         "moves to f(u) + α n(u), α among normal-wiggle-samples offsets up to the mean "
         "one-ring distance, leaving the fewest inconsistent faces around it (strictly fewer), "
         "ties to the smallest |α|; no face turns over in 3D; sweeps until nothing improves.",
         runNormalWiggle, normalWiggleChecks});
}

} // namespace contour::consistent
