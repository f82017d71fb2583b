// Cusp refinement: not in the paper (CuspRefinement.h).
#include "contours/consistent/edits/CuspRefinement.h"

#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/predicates/FoldTest.h"

#include <algorithm>
#include <map>
#include <set>

namespace contour::consistent {

namespace {

// The root of g on the cusp edge x-y (bisection, `iterations` steps, as
// contour insertion will do, §6.2 e): where the cusp lies; the edge's middle
// without a chart.
Vec3 cuspPoint(const ConsistentMesh& m, Index x, Index y, int iterations) {
    if (m.vertex(x).label != VertexLabel::Front)
        std::swap(x, y);
    const ConsistentMesh::Segment xy = m.segment(m.vertex(x).preimage, m.vertex(y).preimage);
    // g > 0 at x (t = 0): the end whose sign a positive sample shares.
    BisectionOptions options;
    options.maxIterations = iterations;
    const BisectionResult<double> r = bisect(
        [&](double t) -> std::optional<double> {
            const std::optional<Preimage> p = xy.at(t);
            if (!p)
                return std::nullopt;
            return m.evaluateWithoutCurvature(*p).g;
        },
        [](double g) { return g; }, BisectionBracket{0.0, 1.0, 1.0, -1.0}, options);
    if (r.outcome == BisectionOutcome::Failed)
        return 0.5 * (m.vertex(x).position + m.vertex(y).position);
    const std::optional<Preimage> p = xy.at(0.5 * (r.bracket.lo + r.bracket.hi));
    return p ? m.evaluateWithoutCurvature(*p).position
             : 0.5 * (m.vertex(x).position + m.vertex(y).position);
}

// The faces within `rings` face rings of cusp edge x-y (ring 1: the faces
// at x or y; ring k + 1: the faces at a corner of ring k), keeping only
// faces with a corner within `pixels` of the cusp in the image when
// pixels > 0 (growth goes on from kept faces only). The two faces on the
// cusp edge are always kept.
std::set<Index> regionAround(const ConsistentMesh& m, Index x, Index y, const Vec2& cusp, int rings,
                             double pixels) {
    const Camera& camera = m.camera();
    const auto near = [&](Index f) {
        if (pixels <= 0.0)
            return true;
        for (Index w : m.face(f))
            if ((camera.project(m.vertex(w).position).pixel - cusp).norm() <= pixels)
                return true;
        return false;
    };
    std::set<Index> region;
    for (Index f : {m.faceOfHalfedge(x, y), m.faceOfHalfedge(y, x)})
        if (f != kInvalidIndex)
            region.insert(f);
    std::vector<Index> front{x, y};
    std::set<Index> seen{x, y};
    for (int ring = 0; ring < rings && !front.empty(); ++ring) {
        std::vector<Index> next;
        for (Index f : facesAround(m, front)) {
            if (!near(f))
                continue;
            region.insert(f);
            for (Index w : m.face(f))
                if (seen.insert(w).second)
                    next.push_back(w);
        }
        std::sort(next.begin(), next.end());
        front = std::move(next);
    }
    return region;
}

// Splits interior edge a-b at the parameter-space midpoint when no new face
// folds (parameter space, appendix B, or 3D against the limit normals) and
// the midpoint is not on g = 0. A cusp edge keeps its tag on the half that
// still changes sign (the cusp lies at its root of g, Fig. 16b). Returns the
// new vertex or kInvalidIndex.
Index splitAtMiddle(ConsistentMesh& m, Index a, Index b, int phase, CuspRefinementCounts& n) {
    const auto [c, d] = m.oppositeVertices(a, b);
    if (c == kInvalidIndex || d == kInvalidIndex)
        return kInvalidIndex;
    const std::optional<Preimage> mid =
        m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, 0.5);
    if (!mid || !splitKeepsCharts(m, a, b, *mid)) {
        ++n.rejectedChart;
        return kInvalidIndex;
    }
    MeshVertex v = m.evaluate(*mid);
    if (v.label == VertexLabel::Contour) {
        ++n.rejectedContour;
        return kInvalidIndex;
    }
    v.provenance = Provenance::Inserted;
    v.phase = phase;
    LocalEdit before(m), after(m);
    before.addFaces({m.faceOfHalfedge(a, b), m.faceOfHalfedge(b, a)});
    const Index x = after.addVertex(v);
    after.addFace({a, x, c});
    after.addFace({x, b, c});
    after.addFace({b, x, d});
    after.addFace({x, a, d});
    if (after.turnedOver() > before.turnedOver()) {
        ++n.rejected3d;
        return kInvalidIndex;
    }
    const bool cuspEdge = (m.edgeTag(a, b) & kCuspEdge) != 0;
    const Index w = m.splitEdge(a, b, v, phase);
    if (cuspEdge) {
        m.addEdgeTag(m.vertex(a).label != v.label ? a : b, w, kCuspEdge);
        ++n.cuspEdgeSplits;
    }
    ++n.splits;
    return w;
}

// §6.1's sign-crossing search (InitializationPhase.cpp) on the FF and BB
// edges at the given new vertices: `samples` samples of sign(g) per edge;
// split at the first of the other label; `rounds` rounds on the edges the
// splits create.
void crossingSearch(ConsistentMesh& m, std::vector<Index> created, int samples, int rounds,
                    int phase, CuspRefinementCounts& n) {
    for (int round = 0; round < rounds && !created.empty(); ++round) {
        std::sort(created.begin(), created.end());
        std::vector<std::array<Index, 2>> edges;
        for (Index v : created)
            for (Index w : m.neighbours(v))
                if (m.vertex(v).label == m.vertex(w).label &&
                    (v < w || !std::binary_search(created.begin(), created.end(), w)))
                    edges.push_back({v, w});
        std::sort(edges.begin(), edges.end());
        created.clear();
        for (const auto& [a, b] : edges) {
            const VertexLabel la = m.vertex(a).label;
            if (la == VertexLabel::Contour || la != m.vertex(b).label)
                continue;
            for (int k = 1; k <= samples; ++k) {
                const std::optional<Preimage> p =
                    m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage,
                                  static_cast<double>(k) / (samples + 1));
                if (!p)
                    break;
                const MeshVertex probe = m.evaluateWithoutCurvature(*p);
                if (probe.label == la)
                    continue;
                if (probe.label == VertexLabel::Contour || !splitKeepsCharts(m, a, b, *p))
                    break;
                MeshVertex v = m.evaluate(*p);
                v.provenance = Provenance::Inserted;
                created.push_back(m.splitEdge(a, b, v, phase));
                ++n.crossingSplits;
                break;
            }
        }
    }
}

// One level of refineAroundCusps: the region of every selected cusp edge,
// its edges halved (cusp edges too with `cuspEdges`), then the regular
// 1 -> 4 pattern by one flip per face whose three edges were halved.
void refineOnce(ConsistentMesh& m, const CuspRefinementSettings& set,
                const std::function<bool(const Vec3&)>& select, int phase,
                CuspRefinementCounts& n) {
    std::vector<std::array<Index, 2>> cusps;
    for (const auto& [k, tag] : m.edgeTags())
        if (tag & kCuspEdge)
            cusps.push_back(ConsistentMesh::edgeFromKey(k));
    std::sort(cusps.begin(), cusps.end());
    std::set<Index> region;
    for (const auto& [x, y] : cusps) {
        const Vec3 cusp = cuspPoint(m, x, y, set.rootIterations);
        if (!select(cusp))
            continue;
        ++n.cusps;
        for (Index f : regionAround(m, x, y, m.camera().project(cusp).pixel, set.rings, set.pixels))
            region.insert(f);
    }
    n.faces += static_cast<long long>(region.size());
    std::vector<Triangle> faces;
    std::set<std::array<Index, 2>> edges;
    for (Index f : region) {
        const Triangle t = m.face(f);
        faces.push_back(t);
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            if (!set.cuspEdges && (m.edgeTag(a, b) & kCuspEdge))
                continue;
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    std::map<std::array<Index, 2>, Index> middle;
    std::vector<Index> created;
    for (const auto& [a, b] : edges) {
        const Index w = splitAtMiddle(m, a, b, phase, n);
        if (w == kInvalidIndex)
            continue;
        middle[{a, b}] = w;
        created.push_back(w);
    }
    // Halving a-b, b-c and c-a of face a-b-c in turn leaves one edge from a
    // midpoint to the opposite corner; flipping it to the edge between the
    // two other midpoints gives four triangles similar to the face.
    const auto midpoint = [&](Index a, Index b) {
        const auto it = middle.find({std::min(a, b), std::max(a, b)});
        return it == middle.end() ? kInvalidIndex : it->second;
    };
    for (const Triangle& t : faces) {
        const std::array<Index, 3> mids{midpoint(t[0], t[1]), midpoint(t[1], t[2]),
                                        midpoint(t[2], t[0])};
        if (std::find(mids.begin(), mids.end(), kInvalidIndex) != mids.end())
            continue;
        for (int i = 0; i < 3; ++i) {
            const Index p = mids[i], q = t[(i + 2) % 3];
            if (m.faceOfHalfedge(p, q) == kInvalidIndex || m.edgeTag(p, q) != kNoTag)
                continue;
            const auto [c, d] = m.oppositeVertices(p, q);
            const Index u = mids[(i + 1) % 3], v = mids[(i + 2) % 3];
            if (!((c == u && d == v) || (c == v && d == u)) || flipWouldFold(m, p, q))
                continue;
            m.flipEdge(p, q, phase);
            ++n.flips;
            break;
        }
    }
    crossingSearch(m, created, set.crossingSamples, set.crossingRounds, phase, n);
}

} // namespace

void refineAroundCusps(ConsistentMesh& m, const CuspRefinementSettings& set,
                       const std::function<bool(const Vec3&)>& select, int phase,
                       CuspRefinementCounts& n) {
    for (int level = 0; level < set.levels; ++level)
        refineOnce(m, set, select, phase, n);
}

void publishCuspRefinementCounts(Snapshot& s, const CuspRefinementCounts& n) {
    s.setCounter(counters::kCuspsRefinedAround, static_cast<double>(n.cusps));
    s.setCounter(counters::kFacesRefined, static_cast<double>(n.faces));
    s.setCounter(counters::kEdgesHalved, static_cast<double>(n.splits));
    s.setCounter(counters::kCuspEdgesHalved, static_cast<double>(n.cuspEdgeSplits));
    s.setCounter(counters::kHalvingsCancelledNoChart, static_cast<double>(n.rejectedChart));
    s.setCounter(counters::kHalvingsCancelled3DFold, static_cast<double>(n.rejected3d));
    s.setCounter(counters::kHalvingsCancelledOnContour, static_cast<double>(n.rejectedContour));
    s.setCounter(counters::kFlipsToThe14Pattern, static_cast<double>(n.flips));
    s.setCounter(counters::kSignCrossingSplitsAfterHalving, static_cast<double>(n.crossingSplits));
}

} // namespace contour::consistent
