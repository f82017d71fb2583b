#include "visibility/SurfaceIntersections.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <algorithm>
#include <map>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tuple>

namespace contour {

namespace {

using Filter = CGAL::Exact_predicates_inexact_constructions_kernel;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index,
                                                      CGAL::Box_intersection_d::ID_EXPLICIT>;

// The smallest mesh simplex holding a point on one face: a vertex, an edge
// or the face's interior. Two of them (one per sheet) name an intersection
// point combinatorially, so chaining never compares coordinates.
struct Simplex {
    int dim = 2; // 0 vertex, 1 edge, 2 face
    Index id = kInvalidIndex;
    auto operator<=>(const Simplex&) const = default;
};

struct Key {
    Simplex a, b; // a <= b
    auto operator<=>(const Key&) const = default;
};

Key makeKey(const Simplex& s, const Simplex& t) {
    return s <= t ? Key{s, t} : Key{t, s};
}

// box_intersection_d's cutoff: below this many boxes a subtree is scanned
// directly. CGAL's default (10) is slow on meshes (overlaps are local and
// dense); 2000 is what CGAL's own self-intersection test uses.
constexpr std::ptrdiff_t kBoxCutoff = 2000;

struct Segment {
    Index faces[2];
    Vec3 ends[2];
    Simplex simplex[2][2]; // [end][sheet]: the simplex of ends[end] on faces[sheet]
    Key key[2];
};

Exact::Point_3 exactPoint(const Vec3& p) {
    return {p.x(), p.y(), p.z()};
}

// Exact classification of a point known to lie on triangle f.
Simplex classify(const TriangleMesh& mesh, Index f, const Exact::Point_3& p) {
    const Triangle& t = mesh.triangle(f);
    Exact::Point_3 corner[3];
    for (int c = 0; c < 3; ++c)
        corner[c] = exactPoint(mesh.position(t[c]));
    for (int c = 0; c < 3; ++c)
        if (p == corner[c])
            return {0, t[c]};
    for (int c = 0; c < 3; ++c)
        if (Exact::Segment_3(corner[c], corner[(c + 1) % 3]).has_on(p))
            return {1, mesh.edge(TriangleMesh::halfedge(f, c))};
    return {2, f};
}

bool shareVertex(const Triangle& a, const Triangle& b) {
    for (Index u : a)
        for (Index v : b)
            if (u == v)
                return true;
    return false;
}

CurvePoint curvePoint(const TriangleMesh& mesh, const Segment& s, int end) {
    CurvePoint point;
    point.position = s.ends[end];
    for (int sheet = 0; sheet < 2; ++sheet) {
        const Simplex& simplex = s.simplex[end][sheet];
        if (simplex.dim == 0 && point.vertex == kInvalidIndex) {
            point.vertex = simplex.id;
        } else if (simplex.dim == 1 && point.edge == kInvalidIndex) {
            // t along the edge's stored half-edge, like the interpolated contours.
            const Index h = mesh.edgeHalfedge(simplex.id);
            const Vec3& a = mesh.position(mesh.from(h));
            const Vec3 d = mesh.position(mesh.to(h)) - a;
            const double len2 = d.squaredNorm();
            point.edge = simplex.id;
            point.t = len2 > 0.0 ? std::clamp((point.position - a).dot(d) / len2, 0.0, 1.0) : 0.0;
        }
    }
    return point;
}

Vec3 toVec3(const Exact::Point_3& p) {
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

enum class PairKind : std::uint8_t { None, Segment, Degenerate };

int sign(CGAL::Orientation o) {
    return o == CGAL::POSITIVE ? 1 : o == CGAL::NEGATIVE ? -1 : 0;
}

// The generic case with exact predicates only (fast, thread-safe): when no
// vertex of either triangle lies on the other's plane and no edge line passes
// through an edge of the other triangle, the intersection is empty or a
// segment whose two ends are where an edge of one triangle crosses the
// interior of the other. Those crossings name the ends exactly; only their
// coordinates are computed in floating point (one plane–line intersection).
// Anything else is Degenerate and goes to the exact constructions.
PairKind genericSegment(const TriangleMesh& mesh, Index f, Index g, Segment& out) {
    const Index faces[2] = {f, g};
    Filter::Point_3 p[2][3];
    for (int t = 0; t < 2; ++t)
        for (int c = 0; c < 3; ++c) {
            const Vec3& q = mesh.position(mesh.triangle(faces[t])[c]);
            p[t][c] = Filter::Point_3(q.x(), q.y(), q.z());
        }
    // side[t][c]: vertex c of triangle t against the other triangle's plane.
    int side[2][3];
    for (int t = 0; t < 2; ++t) {
        const auto& o = p[1 - t];
        int positive = 0, negative = 0;
        for (int c = 0; c < 3; ++c) {
            side[t][c] = sign(CGAL::orientation(o[0], o[1], o[2], p[t][c]));
            positive += side[t][c] > 0;
            negative += side[t][c] < 0;
        }
        if (positive == 3 || negative == 3)
            return PairKind::None;
        if (positive + negative < 3)
            return PairKind::Degenerate;
    }
    int found = 0;
    for (int t = 0; t < 2; ++t) {
        const auto& o = p[1 - t];
        for (int c = 0; c < 3; ++c) {
            const int d = (c + 1) % 3;
            if (side[t][c] == side[t][d])
                continue;
            const int s0 = sign(CGAL::orientation(p[t][c], p[t][d], o[0], o[1]));
            const int s1 = sign(CGAL::orientation(p[t][c], p[t][d], o[1], o[2]));
            const int s2 = sign(CGAL::orientation(p[t][c], p[t][d], o[2], o[0]));
            if (s0 == 0 || s1 == 0 || s2 == 0)
                return PairKind::Degenerate;
            if (s0 != s1 || s1 != s2)
                continue;
            if (found == 2)
                return PairKind::Degenerate; // cannot happen in generic position
            // Edge c of triangle t crosses the interior of the other one.
            const Triangle& other = mesh.triangle(faces[1 - t]);
            const Vec3& a = mesh.position(mesh.triangle(faces[t])[c]);
            const Vec3& b = mesh.position(mesh.triangle(faces[t])[d]);
            const Vec3& q0 = mesh.position(other[0]);
            const Vec3 n = (mesh.position(other[1]) - q0).cross(mesh.position(other[2]) - q0);
            const double tt = std::clamp(n.dot(q0 - a) / n.dot(b - a), 0.0, 1.0);
            out.ends[found] = a + tt * (b - a);
            out.simplex[found][t] = {1, mesh.edge(TriangleMesh::halfedge(faces[t], c))};
            out.simplex[found][1 - t] = {2, faces[1 - t]};
            ++found;
        }
    }
    if (found == 0)
        return PairKind::None;
    if (found != 2)
        return PairKind::Degenerate;
    out.faces[0] = f;
    out.faces[1] = g;
    for (int end = 0; end < 2; ++end)
        out.key[end] = makeKey(out.simplex[end][0], out.simplex[end][1]);
    return PairKind::Segment;
}

} // namespace

SurfaceIntersectionCurves surfaceIntersectionCurves(const TriangleMesh& mesh) {
    SurfaceIntersectionCurves result;
    const Index faceCount = mesh.faceCount();

    // Candidate pairs: overlapping face bounding boxes (CGAL's box
    // intersection, a streamed segment tree).
    std::vector<Box> boxes;
    boxes.reserve(faceCount);
    for (Index f = 0; f < faceCount; ++f) {
        const Triangle& t = mesh.triangle(f);
        CGAL::Bbox_3 box;
        for (Index v : t) {
            const Vec3& p = mesh.position(v);
            box += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
        }
        boxes.emplace_back(box, f);
    }
    // Two slabs on either side of the median face along the box's longest
    // axis, searched in parallel: a face whose box reaches the median plane
    // is in both, and two overlapping boxes lie together in one slab (or
    // both sides of the plane would separate them). Pairs found twice (both
    // boxes reach the plane) are removed by the sort below, so the result
    // does not depend on the number of threads.
    const BoundingBox bounds = mesh.boundingBox();
    const Vec3 extent = bounds.max - bounds.min;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (extent[k] > extent[axis])
            axis = k;
    std::vector<double> centres(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i)
        centres[i] = 0.5 * (boxes[i].min_coord(axis) + boxes[i].max_coord(axis));
    double split = 0.0;
    if (!centres.empty()) {
        auto middle = centres.begin() + static_cast<std::ptrdiff_t>(centres.size() / 2);
        std::nth_element(centres.begin(), middle, centres.end());
        split = *middle;
    }
    std::vector<Box> slab[2];
    for (const Box& box : boxes) {
        if (box.min_coord(axis) <= split)
            slab[0].push_back(box);
        if (box.max_coord(axis) >= split)
            slab[1].push_back(box);
    }
    std::vector<std::pair<Index, Index>> pairs[2];
    auto search = [&](int side) {
        CGAL::box_self_intersection_d(
            slab[side].begin(), slab[side].end(),
            [&](const Box& a, const Box& b) {
                // Faces sharing a vertex (or an edge) are skipped: on a manifold
                // mesh they meet there, and that is not an intersection curve. A
                // fold that makes two such faces cross elsewhere is missed (see
                // the header).
                if (!shareVertex(mesh.triangle(a.info()), mesh.triangle(b.info())))
                    pairs[side].emplace_back(std::min(a.info(), b.info()),
                                             std::max(a.info(), b.info()));
            },
            kBoxCutoff);
    };
    tbb::parallel_invoke([&] { search(0); }, [&] { search(1); });
    std::vector<std::pair<Index, Index>> candidates = std::move(pairs[0]);
    candidates.insert(candidates.end(), pairs[1].begin(), pairs[1].end());
    tbb::parallel_sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    result.candidatePairs = static_cast<long long>(candidates.size());

    auto exactTriangle = [&](Index f) {
        const Triangle& t = mesh.triangle(f);
        return Exact::Triangle_3(exactPoint(mesh.position(t[0])), exactPoint(mesh.position(t[1])),
                                 exactPoint(mesh.position(t[2])));
    };

    // Generic pairs with exact predicates, in parallel; the others (a vertex
    // on the other plane, edges meeting, coplanar faces) with CGAL's exact
    // triangle–triangle intersection (exact constructions kernel), serially,
    // and their ends classified exactly onto mesh vertices/edges/faces.
    std::vector<Segment> found(candidates.size());
    std::vector<PairKind> kind(candidates.size(), PairKind::None);
    tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
        kind[i] = genericSegment(mesh, candidates[i].first, candidates[i].second, found[i]);
    });
    std::vector<Segment> segments;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (kind[i] == PairKind::Segment) {
            segments.push_back(found[i]);
            continue;
        }
        if (kind[i] != PairKind::Degenerate)
            continue;
        ++result.exactPairs;
        const auto [f, g] = candidates[i];
        const auto meet = CGAL::intersection(exactTriangle(f), exactTriangle(g));
        if (!meet)
            continue;
        if (const Exact::Segment_3* seg = boost::get<Exact::Segment_3>(&*meet)) {
            Segment s{{f, g}, {toVec3(seg->source()), toVec3(seg->target())}, {}, {}};
            for (int end = 0; end < 2; ++end) {
                const Exact::Point_3 point = end == 0 ? seg->source() : seg->target();
                for (int sheet = 0; sheet < 2; ++sheet)
                    s.simplex[end][sheet] = classify(mesh, s.faces[sheet], point);
                s.key[end] = makeKey(s.simplex[end][0], s.simplex[end][1]);
            }
            segments.push_back(s);
        } else if (boost::get<Exact::Point_3>(&*meet)) {
            ++result.touchingPairs;
        } else {
            ++result.coplanarPairs; // a triangle or polygon: coplanar overlap
        }
    }
    result.intersectingPairs = static_cast<long long>(segments.size());

    // A curve piece lying along a mesh edge is reported by both faces of that
    // edge (by up to four pairs when it lies on an edge of each sheet), with
    // the same keys at both ends: keep one. Two different segments cannot
    // share both keys, since a key names one point.
    {
        std::map<std::pair<Key, Key>, std::size_t> seen;
        std::vector<Segment> unique;
        unique.reserve(segments.size());
        for (Segment& s : segments) {
            const auto id = std::minmax(s.key[0], s.key[1]);
            if (seen.emplace(std::pair<Key, Key>(id.first, id.second), unique.size()).second)
                unique.push_back(std::move(s));
        }
        result.duplicateSegments = static_cast<long long>(segments.size() - unique.size());
        segments = std::move(unique);
    }

    // Chaining: two segment ends with the same key are the same point of the
    // curve (one sheet crosses the other through the same mesh edge or
    // vertex). A key with exactly two ends joins them; any other count is a
    // chain end (an open end, or a branch where more than two segments meet).
    std::map<Key, std::vector<std::pair<std::size_t, int>>> ends;
    for (std::size_t i = 0; i < segments.size(); ++i)
        for (int end = 0; end < 2; ++end)
            ends[segments[i].key[end]].emplace_back(i, end);
    for (const auto& [key, list] : ends) {
        if (list.size() == 1)
            ++result.openEnds;
        else if (list.size() > 2)
            ++result.branchPoints;
    }

    std::vector<std::uint8_t> used(segments.size(), 0);
    // Walks from segment `start`, entering it at end `entry`, and returns the
    // polyline; `firstSheet` is the index in faces[] of the sheet reported as
    // segmentElement, kept on the same sheet along the curve.
    auto walk = [&](std::size_t start, int entry, int firstSheet) {
        Polyline line;
        line.type = CurveType::SurfaceIntersection;
        line.source = SegmentSource::Face;
        std::vector<Index> second;
        const Key startKey = segments[start].key[entry];
        line.points.push_back(curvePoint(mesh, segments[start], entry));
        std::size_t current = start;
        int in = entry, sheet = firstSheet;
        for (;;) {
            used[current] = 1;
            const Segment& s = segments[current];
            const int out = 1 - in;
            line.segmentElement.push_back(s.faces[sheet]);
            second.push_back(s.faces[1 - sheet]);
            const Key& key = s.key[out];
            const auto& list = ends.at(key);
            if (list.size() == 2 && key == startKey && list[0].first != list[1].first &&
                (list[0].first == start || list[1].first == start)) {
                line.closed = true; // back at the start: closed loops do not repeat it
                break;
            }
            line.points.push_back(curvePoint(mesh, s, out));
            if (list.size() != 2)
                break;
            const auto& next =
                list[0].first == current && list[0].second == out ? list[1] : list[0];
            if (used[next.first])
                break;
            // Keep the sheet: the next segment's face whose simplex at the
            // shared point is this sheet's simplex.
            const Simplex& mine = s.simplex[out][sheet];
            const Segment& n = segments[next.first];
            sheet = n.simplex[next.second][0] == mine ? 0 : 1;
            current = next.first;
            in = next.second;
        }
        result.curves.push_back(std::move(line));
        result.secondFaces.push_back(std::move(second));
    };

    // Open chains first, from every chain end; then the closed loops.
    for (const auto& [key, list] : ends) {
        if (list.size() == 2)
            continue;
        for (const auto& [segment, end] : list)
            if (!used[segment])
                walk(segment, end, 0);
    }
    for (std::size_t i = 0; i < segments.size(); ++i)
        if (!used[i])
            walk(i, 0, 0);
    return result;
}

} // namespace contour
