// Vertex removal of the optimization phase: an extension of Bénard 2014
// §6.4 built from the vertex deletion of §6.3 (h) (Fig. 16e
// right: flips around a vertex until it has valence 3, then its three faces
// merge).
//
// Why: the faces left after the §6.4 sweeps are mostly the Fig. 13 kind
// next to the radial strip (the "16f pair" and "one radial end" faces of
// bench_consistent --classify): the radial ends q1, q2 of two neighbouring
// contour vertices sit on the contour in the image (a radial curve leaves
// along the view ray), and a vertex y beyond the strip lies within a
// fraction of a pixel of the contour, on the wrong side of the chord q1-q2
// because the contour is curved. Every move of §6.4 is local to one vertex
// or edge, and y has no position in its one-ring that clears every chord
// it faces (the wiggle samples them), so the sweeps stop. Removing y and
// re-triangulating its one-ring connects the strip to the vertices behind
// y, which lie well inside the correct side. The removal is one more kind
// of local edit, judged like the others: fewer inconsistent faces among
// those it changes, no fold (parameter space or 3D), every VBO defined, no
// degenerate CC edge. Placed after edge splitting, before the normal wiggle
// (measured over 26 views: spot 97 -> 89, bob 91 -> 72, bumpy torus 21 -> 14
// final inconsistent faces, no view raised; placed before the optimization
// flips it removes more on bob but raises some views of spot).
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/edits/RingRetriangulation.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/phases/OptimizationFlip.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/TriangleQuality.h"
#include "contours/consistent/predicates/TriangulationCost.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

namespace contour::consistent {

namespace {

struct RemovalSettings {
    int maxValence = 16;
    bool cuspEdits = true;
};

struct RemovalStats {
    long long ringsTried = 0, noTriangulation = 0, noGain = 0, rejected = 0, unplanned = 0,
              removed = 0;
};

// v's one-ring as a closed polygon, counter-clockwise (the order of the
// faces v-a-b around v); empty when v is on the boundary or its ring is not
// a simple cycle.
std::vector<Index> orderedRing(const ConsistentMesh& m, Index v) {
    const std::vector<Index>& star = m.vertexFaces(v);
    std::vector<std::pair<Index, Index>> next;
    for (Index f : star) {
        const Triangle t = rotatedTo(m.face(f), v);
        next.emplace_back(t[1], t[2]);
    }
    return simpleCycle(next);
}

// Best triangulation of a polygon (dynamic programming over its
// sub-polygons), by TriangulationCost.
using Cost = TriangulationCost;

class VertexRemover {
public:
    VertexRemover(ConsistentMesh& m, const RemovalSettings& set, int phase)
        : m_(m), set_(set), phase_(phase) {
        box_.min = Vec3::Constant(std::numeric_limits<double>::infinity());
        box_.max = -box_.min;
        for (Index v = 0; v < m_.vertexCount(); ++v) {
            box_.min = box_.min.cwiseMin(m_.vertex(v).position);
            box_.max = box_.max.cwiseMax(m_.vertex(v).position);
        }
    }

    RemovalStats stats;

    bool tryRemove(Index v) {
        const MeshVertex& x = m_.vertex(v);
        if (x.label == VertexLabel::Contour || x.cusp || m_.vertexFaces(v).empty() ||
            m_.isBoundaryVertex(v))
            return false;
        // Tolerances are relative to the vertices' bounding box (sceneScale):
        // a vertex on that box stays, so that every later check (e.g. the
        // radial edges' |h_p(r)|, met at the tolerance itself) is unchanged.
        for (int d = 0; d < 3; ++d)
            if (x.position[d] <= box_.min[d] || x.position[d] >= box_.max[d])
                return false;
        const std::vector<Index> ring = orderedRing(m_, v);
        const int k = static_cast<int>(ring.size());
        if (k < 4 || k > set_.maxValence)
            return false;
        for (Index w : ring) {
            // The edges v-w disappear: they must carry no tag (a radial or
            // cusp edge is kept), and a cusp keeps the valence 4 of Fig. 18d
            // until it has radial edges (as in edge splitting).
            if (m_.edgeTag(v, w) != kNoTag)
                return false;
            if (m_.vertex(w).cusp && (!set_.cuspEdits || !onRadialEdge(m_, w)))
                return false;
        }
        ++stats.ringsTried;
        LocalEdit before(m_);
        before.addFaces(m_.vertexFaces(v));
        const LocalScore now = before.score();
        const int turnedBefore = before.turnedOver();

        // cost[i][j]: best triangulation of ring[i..j] (j - i >= 2), with
        // the split vertex in split[i][j]. First with the cheap conditions
        // only (labels, diagonals): a lower bound on the inconsistent faces
        // that most rings already fail to beat; then with the charts and 3D
        // folds too.
        std::vector<std::vector<Cost>> cost;
        std::vector<std::vector<int>> split;
        LocalEdit one(m_);
        for (const bool full : {false, true}) {
            cost.assign(k, std::vector<Cost>(k));
            split.assign(k, std::vector<int>(k, -1));
            for (int len = 2; len < k; ++len)
                for (int i = 0; i + len < k; ++i) {
                    const int j = i + len;
                    // The diagonal ring[i]-ring[j] (not for the closing side
                    // 0-(k-1), an edge of the ring) must not exist elsewhere.
                    if (!(i == 0 && j == k - 1) && !diagonalAllowed(ring[i], ring[j]))
                        continue;
                    for (int s = i + 1; s < j; ++s) {
                        const Cost left = s - i >= 2 ? cost[i][s] : Cost{0, 2.0};
                        const Cost right = j - s >= 2 ? cost[s][j] : Cost{0, 2.0};
                        if (!left.valid() || !right.valid())
                            continue;
                        const Triangle t{ring[i], ring[s], ring[j]};
                        if (!triangleAllowed(one, t, full))
                            continue;
                        Cost c;
                        c.inconsistent =
                            left.inconsistent + right.inconsistent + !one.consistent(t);
                        c.minQuality = std::min(
                            {left.minQuality, right.minQuality,
                             bankSmithQuality(m_.vertex(t[0]).position, m_.vertex(t[1]).position,
                                              m_.vertex(t[2]).position)});
                        if (better(c, cost[i][j])) {
                            cost[i][j] = c;
                            split[i][j] = s;
                        }
                    }
                }
            if (!cost[0][k - 1].valid() || cost[0][k - 1].inconsistent >= now.inconsistent)
                break;
        }
        const Cost best = cost[0][k - 1];
        if (!best.valid()) {
            ++stats.noTriangulation;
            return false;
        }
        if (best.inconsistent >= now.inconsistent) {
            ++stats.noGain;
            return false;
        }
        std::vector<Triangle> faces;
        collect(ring, split, 0, k - 1, faces);
        LocalEdit after(m_);
        for (const Triangle& t : faces)
            after.addFace(t);
        // Degenerate CC edges across the ring and folds, on the whole edit.
        if (!after.labelsValid() || !after.parameterValid() || after.turnedOver() > turnedBefore) {
            ++stats.rejected;
            return false;
        }
        // The removal as §6.3 (h) deletes a vertex: each flip of an edge v-w
        // cuts off an ear of the target triangulation until v has valence 3,
        // then its three faces merge; planned first, so that the mesh never
        // refuses an edit half-way.
        RingRetriangulation edits(m_, m_.vertexFaces(v));
        if (!edits.cutEars(v, ring, faces, {}) || !edits.removeValence3Vertex(v) ||
            !edits.endsIn(faces)) {
            ++stats.unplanned;
            return false;
        }
        edits.apply(m_, nullptr, phase_);
        ++stats.removed;
        return true;
    }

private:
    ConsistentMesh& m_;
    RemovalSettings set_;
    int phase_;
    struct {
        Vec3 min, max;
    } box_;

    bool diagonalAllowed(Index a, Index b) const {
        if (m_.faceOfHalfedge(a, b) != kInvalidIndex || m_.faceOfHalfedge(b, a) != kInvalidIndex)
            return false;
        // A new CC edge would be a contour edge the root finding did not
        // make; a new FB edge a crossing without a C vertex.
        const int la = static_cast<int>(m_.vertex(a).label),
                  lb = static_cast<int>(m_.vertex(b).label);
        return !(la == 0 && lb == 0) && la * lb >= 0;
    }

    // A triangle of the new fan: defined VBO and, when `full`,
    // counter-clockwise in every common chart and not turned over in 3D
    // against its corners' normals.
    bool triangleAllowed(LocalEdit& one, const Triangle& t, bool full) const {
        if (one.vbo(t) == Vbo::Undefined)
            return false;
        if (!full)
            return true;
        if (one.turnedOver(t))
            return false;
        const std::optional<int> o = m_.parameterOrientation(
            {m_.vertex(t[0]).preimage, m_.vertex(t[1]).preimage, m_.vertex(t[2]).preimage});
        return o && *o > 0;
    }

    static void collect(const std::vector<Index>& ring, const std::vector<std::vector<int>>& split,
                        int i, int j, std::vector<Triangle>& out) {
        if (j - i < 2)
            return;
        const int s = split[i][j];
        out.push_back({ring[i], ring[s], ring[j]});
        collect(ring, split, i, s, out);
        collect(ring, split, s, j, out);
    }
};

// The phase's parameters, read once per run.
struct VertexRemovalOptions {
    bool enabled = false; // vertex-removal
    int maxValence = 0;   // removal-max-valence
    int maxSweeps = 0;    // removal-max-sweeps
    CuspEditOptions cusps;
    static VertexRemovalOptions read(const ParameterSet& p) {
        VertexRemovalOptions o;
        o.enabled = p.getBool("vertex-removal");
        o.maxValence = p.getInt("removal-max-valence");
        o.maxSweeps = p.getInt("removal-max-sweeps");
        o.cusps = CuspEditOptions::read(p);
        return o;
    }
};

void runVertexRemoval(const PhaseContext& ctx, Snapshot& s) {
    const VertexRemovalOptions options = VertexRemovalOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    RemovalSettings set;
    set.maxValence = options.maxValence;
    set.cuspEdits = options.cusps.cuspEdits;
    const bool enabled = options.enabled;
    const int maxSweeps = options.maxSweeps;
    OptimizationTally tally;
    VertexRemover remover(m, set, s.phaseIndex);
    if (enabled)
        sweepInconsistent(ctx, m, maxSweeps, true, tally,
                          [&](Index v) { return remover.tryRemove(v); });
    else
        tally.before = static_cast<long long>(inconsistentFaces(m).size());
    publish(s, m);
    publishTally(s, tally, counters::kVerticesTried, counters::kVerticesAccepted,
                 "removal-max-sweeps");
    s.setCounter(counters::kVerticesRemoved, static_cast<double>(remover.stats.removed));
    s.setCounter(counters::kRingsReTriangulated, static_cast<double>(remover.stats.ringsTried));
    s.setCounter(counters::kRingsWithoutAnAllowedTriangulation,
                 static_cast<double>(remover.stats.noTriangulation));
    s.setCounter(counters::kRingsWithoutFewerInconsistentFaces,
                 static_cast<double>(remover.stats.noGain));
    s.setCounter(counters::kRejectedDegenerateCCEdgeOrFold,
                 static_cast<double>(remover.stats.rejected));
    s.setCounter(counters::kRemovalsSkippedTheMeshWouldRefuseAnEdit,
                 static_cast<double>(remover.stats.unplanned));
    if (!enabled)
        s.notes.push_back("vertex removal is off (vertex-removal = false): mesh passed through");
}

std::vector<InvariantCheck> checkVertexRemoval(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

void addVertexRemovalPhase(Method& m) {
    m.parameters.push_back(
        {"vertex-removal",
         "Removal: on",
         "Not in the paper (an extension of §6.4 built from the vertex deletion of §6.3 "
         "h): a vertex of an inconsistent face is removed when re-triangulating its "
         "one-ring leaves fewer inconsistent faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"removal-max-valence",
         "Removal: largest valence",
         "With vertex-removal (not in the paper): vertices with more neighbours than "
         "this are not removed (the re-triangulation is cubic in the valence).",
         ParameterType::Int,
         16,
         4,
         64,
         {}});
    m.parameters.push_back(
        {"removal-max-sweeps",
         "Removal: sweeps",
         "With vertex-removal (not in the paper): largest number of sweeps over the "
         "inconsistent faces' vertices.",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.addPhase(
        {"vertex-removal",
         "Extension of §6.4 (from §6.3 h's vertex deletion): a non-contour vertex of an "
         "inconsistent face, on no radial or cusp edge, is removed and its one-ring "
         "re-triangulated (the triangulation with the fewest inconsistent faces, then the best "
         "minimum Bank-Smith quality) when that leaves strictly fewer inconsistent faces; no "
         "fold, every VBO defined, no new CC or FB edge, no degenerate CC edge.",
         runVertexRemoval, checkVertexRemoval});
}

} // namespace contour::consistent
