// Vertex wiggling in the normal direction (Bénard 2014 §6.4, final step;
// notes §2.4.5): vertices may leave the limit surface.
#include "contours/consistent/edits/CuspEndRetriangulation.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/ConsistentPhases.h"
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

struct NormalStats {
    long long rejectedFold = 0, pairsTried = 0, pairsAccepted = 0, ringPairsAccepted = 0;
};

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
                       int phase, NormalStats& st) {
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
                           int phase, NormalStats& st,
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
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const int samples = ctx.parameters.getInt("normal-wiggle-samples");
    const int fine = ctx.parameters.getInt("normal-wiggle-fine-offsets");
    const double fraction = ctx.parameters.getDouble("normal-wiggle-max-offset");
    const int maxSweeps = ctx.parameters.getInt("normal-wiggle-max-sweeps");
    OptimizationTally tally;
    NormalStats st;
    sweepInconsistent(ctx, m, maxSweeps, true, tally, [&](Index v) {
        return wiggleAlongNormal(m, v, samples, fine, fraction, phase, st);
    });
    // Then pairs, each accepted pair followed by single moves again.
    const int pairSamples = ctx.parameters.getInt("normal-wiggle-pair-offsets");
    const bool ringPairs = ctx.parameters.getBool("normal-wiggle-ring-pairs");
    // 0: no bound.
    double ringShift = ctx.parameters.getDouble("normal-wiggle-ring-pair-shift");
    if (ringShift <= 0.0)
        ringShift = std::numeric_limits<double>::infinity();
    for (int sweep = 0; pairSamples > 0 && sweep < maxSweeps; ++sweep) {
        bool progress = false;
        for (Index f : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (faceIsConsistent(m, f))
                continue;
            const Triangle t = m.face(f);
            for (int i = 0; i < 3 && !progress; ++i)
                progress = wigglePairAlongNormal(m, t[i], t[(i + 1) % 3], pairSamples, fraction,
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
        for (Index f : progress || !ringPairs ? std::vector<Index>{} : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (faceIsConsistent(m, f))
                continue;
            const Triangle t = m.face(f);
            for (int i = 0; i < 3 && !progress; ++i)
                for (Index b : m.neighbours(t[i])) {
                    if (b == t[0] || b == t[1] || b == t[2])
                        continue;
                    progress = wigglePairAlongNormal(m, t[i], b, pairSamples, fraction, phase, st,
                                                     ringShift);
                    if (progress) {
                        ++st.ringPairsAccepted;
                        break;
                    }
                }
        }
        if (!progress)
            break;
        OptimizationTally again;
        sweepInconsistent(ctx, m, maxSweeps, true, again, [&](Index v) {
            return wiggleAlongNormal(m, v, samples, fine, fraction, phase, st);
        });
        tally.tried += again.tried;
        tally.accepted += again.accepted;
    }
    // The cusps' radial ends pushed along their radial curves once more
    // (radial edge extension, extension-cusp-push-final), then single
    // offsets again around what moved.
    CuspPushCounts push;
    if (ctx.parameters.getBool("extension-cusp-push-final")) {
        push = pushCuspRadialEnds(ctx, m, phase);
        if (push.moved > 0) {
            OptimizationTally again;
            sweepInconsistent(ctx, m, maxSweeps, true, again, [&](Index v) {
                return wiggleAlongNormal(m, v, samples, fine, fraction, phase, st);
            });
            tally.tried += again.tried;
            tally.accepted += again.accepted;
        }
    }
    // Discs of faces around the inconsistent faces at a cusp's radial end,
    // re-triangulated (cusp-end-retriangulation-faces), last: vertices do
    // not move, only edges inside the disc, so no other face changes.
    const CuspEndRetriangulationCounts retri = retriangulateAtCuspEnds(
        ctx, m, ctx.parameters.getInt("cusp-end-retriangulation-faces"), phase);
    double largest = 0.0, contourShift = 0.0;
    long long offVertices = 0;
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const MeshVertex& x = m.vertex(v);
        const double bound = offsetBound(m, v, 1.0);
        offVertices += x.normalOffset != 0.0;
        if (bound > 0.0)
            largest = std::max(largest, std::abs(x.normalOffset) / bound);
        // How far the drawn contour moved: a C vertex off the surface.
        if (x.label == VertexLabel::Contour && x.normalOffset != 0.0)
            contourShift = std::max(contourShift, imageShift(m.camera(), x.position, onSurface(x)));
    }
    publish(s, m);
    publishTally(s, tally, "vertices", "normal-wiggle-max-sweeps");
    s.setCounter("vertices off the surface", static_cast<double>(offVertices));
    s.setCounter("largest offset / mean one-ring distance", largest);
    s.setCounter("largest image shift of a C vertex off the surface (px)", contourShift);
    s.setCounter("offsets rejected (3D fold)", static_cast<double>(st.rejectedFold));
    s.setCounter("vertex pairs tried", static_cast<double>(st.pairsTried));
    s.setCounter("vertex pairs moved", static_cast<double>(st.pairsAccepted));
    s.setCounter("of them, a corner and a neighbour off the face (normal-wiggle-ring-pairs)",
                 static_cast<double>(st.ringPairsAccepted));
    s.setCounter("cusp radial ends pushed (extension-cusp-push-final)",
                 static_cast<double>(push.moved - push.everyEndMoved));
    s.setCounter("other radial ends pushed (extension-push-every-end-final)",
                 static_cast<double>(push.everyEndMoved));
    s.setCounter("faces at a cusp's radial end searched (cusp-end-retriangulation-faces)",
                 static_cast<double>(retri.faces));
    s.setCounter("discs re-triangulated at a cusp's radial end",
                 static_cast<double>(retri.applied));
}

// Notes §6.1 item 2: |α| <= the mean one-ring distance (times
// normal-wiggle-max-offset).
std::vector<InvariantCheck> checkNormalWiggle(const PhaseContext& ctx, const Snapshot& s) {
    std::vector<InvariantCheck> out = optimizationChecks(ctx, s, false);
    const ConsistentMesh m = reload(ctx, s);
    const double fraction = ctx.parameters.getDouble("normal-wiggle-max-offset");
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

} // namespace

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
         "Not in the paper (§6.4 samples 100 offsets evenly): also try this many offsets of "
         "each sign below the even step, log-uniformly over six decades, for the small "
         "displacements that a cusp's thin inside fan (Fig. 18e) needs. Default 48; 0: the "
         "paper's even offsets only.",
         ParameterType::Int,
         48,
         0,
         1000,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-pair-offsets",
         "Normal wiggle: pairs of vertices",
         "Not in the paper (extends §6.4's normal wiggle): after the one-vertex sweeps, the "
         "two ends of each edge of an inconsistent face move along their normals together, "
         "each among this many even offsets and half as many fine ones, accepted when their "
         "stars have strictly fewer inconsistent faces. 0: off. Over 26 views (patch-contour-slide "
         "off), final inconsistent faces 0 -> 24: spot_control 37 -> 35, bob_control 21 -> 19, "
         "bigguy 196 -> 184, spot_quad 37 -> 31, bob_quad 80 -> 78, killeroo 735 -> 685, "
         "bumpy torus 11 -> 10, the rest unchanged, no view worse. Default 48 (session 9; "
         "24 -> 48 on the session-8 pipeline: spot_control 23 -> 21, bigguy 130 -> 129, "
         "spot_quad 27 -> 26, fertility 56 -> 55, killeroo 451 -> 438, the rest unchanged, "
         "no view worse).",
         ParameterType::Int,
         48,
         0,
         200,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-ring-pairs",
         "Normal wiggle: pairs off the face",
         "Not in the paper (extends normal-wiggle-pair-offsets, which it needs > 0): when no "
         "pair of an inconsistent face's own corners helps, a corner moves along its normal "
         "together with one of its neighbours off the face (same offsets and acceptance: "
         "strictly fewer inconsistent faces in the two stars, nothing turned over). Over 26 "
         "views, final inconsistent faces off -> on: spot_control 21 -> 12, bob_control 5 -> "
         "2, bigguy 129 -> 61, spot_quad 26 -> 13, bob_quad 34 -> 29, fertility 55 -> 25, "
         "killeroo 438 -> 209, bumpy torus 11 -> 5, torus, ellipsoid and sphere 0, no view "
         "worse.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"normal-wiggle-ring-pair-shift",
         "Normal wiggle: ring pairs' contour shift",
         "Largest image displacement, in pixels, of a C vertex moved by a ring pair "
         "(normal-wiggle-ring-pairs): the contour drawn moves with it (not in the paper). 0: no "
         "bound. Bumpy torus, 26 views: no bound 5 faces, contour up to 3.39 px off (views 4, "
         "21); 2 px: 7 faces, 1.90 px; 1 px or 0.5 px: 8 faces, 0.89 px (the one-vertex "
         "wiggle's own).",
         ParameterType::Double,
         0.0,
         0.0,
         100.0,
         {}});
    m.parameters.push_back(
        {"cusp-end-retriangulation-faces",
         "Cusp radial ends: disc re-triangulation",
         "Not in the paper. After the normal wiggle (and again after contour refinement, whose "
         "new C vertices give new outlines), each face still inconsistent with a corner "
         "at the far end c of a cusp's radial edge (Fig. 18e) is searched for a disc of up to "
         "this many faces around it (grown across untagged, non-CC edges, every vertex on its "
         "outline) whose best re-triangulation has strictly fewer inconsistent faces (every "
         "VBO defined, no degenerate CC edge, no new edge at a cusp, no fold); the best disc is "
         "re-triangulated by flips. Beside a cusp the image of the surface is a thin curved "
         "strip, and a face r-x-c whose chord r-x passes on the wrong side of c (bumpy torus "
         "view 4: 1.2 px) has an outline facing the wrong way: no single vertex move fixes it, "
         "other edges of a few faces around do. 0: off. Over 26 views, final inconsistent "
         "faces 0 -> 6: bumpy torus 5 -> 2, spot_control 10 -> 9, bob_control 1 -> 0, bigguy "
         "49 -> 41, spot_quad 11 -> 8, bob_quad 17 -> 14, fertility 19 -> 16, killeroo 163 -> "
         "131, no view worse; 7 or 8 gain nothing more on spot, bob and the bumpy torus.",
         ParameterType::Int,
         6,
         0,
         8,
         {}});
    m.parameters.push_back({"normal-wiggle-max-sweeps",
                            "Normal wiggle: sweeps",
                            "Largest number of sweeps over the vertices of inconsistent faces "
                            "in the normal wiggle (§6.4; unspecified).",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.phases.push_back(
        {"normal-wiggle",
         "§6.4 Vertex Wiggling in the Normal Direction: every vertex of an inconsistent face "
         "moves to f(u) + α n(u), α among normal-wiggle-samples offsets up to the mean "
         "one-ring distance, leaving the fewest inconsistent faces around it (strictly fewer), "
         "ties to the smallest |α|; no face turns over in 3D; sweeps until nothing improves.",
         runNormalWiggle, checkNormalWiggle});
}

} // namespace contour::consistent
