#include "visibility/SurfaceIntersections.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tuple>

namespace contour {

namespace {

using Filter = CGAL::Exact_predicates_inexact_constructions_kernel;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;

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

// A face pair that is not disjoint: its segment (generic position) or
// Degenerate (decided by the exact constructions).
struct PairResult {
    Index f, g; // f < g
    PairKind kind;
    Segment segment;
};

struct FaceBox {
    Vec3 min, max;
};

// A face's plane for the filter below: its first corner a, n = (b − a) ×
// (c − a) in floating point, and |n|'s bound term by term.
struct FacePlane {
    Vec3 a, n, magnitude;
};

FacePlane facePlane(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = b - a, v = c - a;
    const Vec3 magnitude(std::abs(u.y() * v.z()) + std::abs(u.z() * v.y()),
                         std::abs(u.z() * v.x()) + std::abs(u.x() * v.z()),
                         std::abs(u.x() * v.y()) + std::abs(u.y() * v.x()));
    return {a, u.cross(v), magnitude};
}

// The sign of orient3d(a, b, c, q) when the double-precision determinant is
// certain, 0 when it is not: Shewchuk's static bound (7ε + 56ε²) times the
// permanent, for the same differences and products (Shewchuk 1997, "Adaptive
// precision floating-point arithmetic", orient3d error bound A).
int certainSide(const FacePlane& plane, const Vec3& q) {
    constexpr double eps = 0.5 * std::numeric_limits<double>::epsilon();
    // Twice the bound, as a margin for the evaluation order (and FMA).
    constexpr double bound = 2.0 * (7.0 + 56.0 * eps) * eps;
    const Vec3 w = q - plane.a;
    const double det = plane.n.dot(w);
    const double permanent = plane.magnitude.dot(w.cwiseAbs());
    if (det > bound * permanent)
        return 1;
    if (-det > bound * permanent)
        return -1;
    return 0;
}

// True when genericSegment() would certainly return None because of its
// first test: the first face's corners all strictly on one side of the
// second face's plane, or (the first face's corners all off that plane and)
// the second face's corners all strictly on one side of the first face's
// plane. Only a certain answer skips the pair, so the outcome (and which pairs
// reach the exact constructions) is the same as without the filter.
bool certainlySeparated(const FacePlane planes[2], const Vec3 corners[2][3]) {
    bool offPlane = true;
    for (int t = 0; t < 2; ++t) {
        int positive = 0, negative = 0;
        for (int c = 0; c < 3; ++c) {
            const int side = certainSide(planes[1 - t], corners[t][c]);
            positive += side > 0;
            negative += side < 0;
        }
        if (offPlane && (positive == 3 || negative == 3))
            return true;
        offPlane = positive + negative == 3;
    }
    return false;
}

// Broad phase: a uniform grid of cubic cells two face boxes wide (twice the
// mean of the boxes' largest sides: measured on the ~115k-face consistent
// meshes, 1× makes 2.3 times more entries, 3-4× longer scans), hashed by
// sorting (cell, face) entries. Each face is entered in every cell its box
// touches; two overlapping boxes share at least the cell of the minimum
// corner of their intersection, and the pair is reported there only, so each
// pair is tested once. Faces of a mesh are small and local, so a cell holds a
// handful of faces and the work is linear in the faces, where CGAL's
// box-intersection segment tree spent most of its time enumerating the
// neighbours that share a vertex (about 6 per face, skipped anyway).
class FaceGrid {
public:
    explicit FaceGrid(const TriangleMesh& mesh) {
        const Index faceCount = mesh.faceCount();
        boxes_.resize(static_cast<std::size_t>(faceCount));
        planes_.reserve(static_cast<std::size_t>(faceCount));
        double side = 0.0;
        BoundingBox bounds;
        for (Index f = 0; f < faceCount; ++f) {
            const Triangle& t = mesh.triangle(f);
            FaceBox& box = boxes_[static_cast<std::size_t>(f)];
            box.min = box.max = mesh.position(t[0]);
            for (int c = 1; c < 3; ++c) {
                box.min = box.min.cwiseMin(mesh.position(t[c]));
                box.max = box.max.cwiseMax(mesh.position(t[c]));
            }
            planes_.push_back(
                facePlane(mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2])));
            side += (box.max - box.min).maxCoeff();
            bounds.extend(box.min);
            bounds.extend(box.max);
        }
        if (faceCount == 0)
            return;
        origin_ = bounds.min;
        const double extent = (bounds.max - bounds.min).maxCoeff();
        // Cell coordinates take 21 bits each in the key.
        minimumCell_ = std::max(extent / double(kMaxCell), 1e-300);
        setCell(kCellSides * side / faceCount);
    }

    void setCell(double side) {
        cell_ = std::max(side, minimumCell_);
        first_.resize(boxes_.size());
        for (std::size_t f = 0; f < boxes_.size(); ++f)
            first_[f] = cellOf(boxes_[f].min);
    }
    double cell() const { return cell_; }

    const FaceBox& box(Index f) const { return boxes_[static_cast<std::size_t>(f)]; }
    const FacePlane& plane(Index f) const { return planes_[static_cast<std::size_t>(f)]; }
    const std::array<std::uint32_t, 3>& firstCell(Index f) const {
        return first_[static_cast<std::size_t>(f)];
    }

    std::array<std::uint32_t, 3> cellOf(const Vec3& p) const {
        std::array<std::uint32_t, 3> c{};
        for (int k = 0; k < 3; ++k) {
            const double x = std::floor((p[k] - origin_[k]) / cell_);
            c[k] = static_cast<std::uint32_t>(x > 0.0 ? std::min(x, double(kMaxCell)) : 0.0);
        }
        return c;
    }

    static std::uint64_t key(const std::array<std::uint32_t, 3>& c) {
        return (std::uint64_t(c[0]) << 42) | (std::uint64_t(c[1]) << 21) | std::uint64_t(c[2]);
    }

private:
    static constexpr std::uint32_t kMaxCell = (1u << 21) - 1;
    static constexpr double kCellSides = 2.0;
    std::vector<FaceBox> boxes_;
    std::vector<FacePlane> planes_;
    std::vector<std::array<std::uint32_t, 3>> first_; // the cell of each box's minimum corner
    Vec3 origin_ = Vec3::Zero();
    double cell_ = 1.0, minimumCell_ = 1e-300;
};

std::vector<PairResult> testCandidatePairs(const TriangleMesh& mesh, long long* candidateCount) {
    const Index faceCount = mesh.faceCount();
    FaceGrid grid(mesh);
    std::vector<std::size_t> first(static_cast<std::size_t>(faceCount) + 1, 0);
    // A few large faces among small ones would each fill many cells: the
    // cells are made coarser until there are at most 16 entries per face.
    for (;;) {
        double total = 0.0;
        for (Index f = 0; f < faceCount; ++f) {
            const auto& lo = grid.firstCell(f);
            const auto hi = grid.cellOf(grid.box(f).max);
            total +=
                double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
        }
        if (total <= 16.0 * faceCount + 1024.0)
            break;
        grid.setCell(2.0 * grid.cell());
    }
    for (Index f = 0; f < faceCount; ++f) {
        const auto& lo = grid.firstCell(f);
        const auto hi = grid.cellOf(grid.box(f).max);
        first[static_cast<std::size_t>(f) + 1] =
            first[static_cast<std::size_t>(f)] +
            std::size_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    }
    // (cell key, lower x, face) entries, sorted: a cell's faces are one run,
    // ordered by the boxes' lower x, so a scan from one box stops at the
    // first box that starts beyond its upper x (sort and sweep in the cell).
    struct Entry {
        std::uint64_t key;
        double minX;
        Index face;
        bool operator<(const Entry& o) const {
            return std::tie(key, minX, face) < std::tie(o.key, o.minX, o.face);
        }
    };
    std::vector<Entry> entries(first.back());
    tbb::parallel_for(Index(0), faceCount, [&](Index f) {
        const auto& lo = grid.firstCell(f);
        const auto hi = grid.cellOf(grid.box(f).max);
        std::size_t at = first[static_cast<std::size_t>(f)];
        for (std::uint32_t x = lo[0]; x <= hi[0]; ++x)
            for (std::uint32_t y = lo[1]; y <= hi[1]; ++y)
                for (std::uint32_t z = lo[2]; z <= hi[2]; ++z)
                    entries[at++] = {FaceGrid::key({x, y, z}), grid.box(f).min.x(), f};
    });
    tbb::parallel_sort(entries.begin(), entries.end());
    // What the scan reads of each face, in entry order (contiguous reads;
    // the faces' own arrays are visited in random order).
    struct Item {
        FaceBox box;
        std::array<std::uint32_t, 3> firstCell;
        Triangle triangle;
        Index face;
    };
    // Not value-initialised (every item is written below): zeroing ~25 MB
    // showed in the profile.
    const std::unique_ptr<Item[]> items(new Item[entries.size()]);
    tbb::parallel_for(std::size_t(0), entries.size(), [&](std::size_t i) {
        const Index f = entries[i].face;
        items[i] = {grid.box(f), grid.firstCell(f), mesh.triangle(f), f};
    });
    std::vector<std::size_t> runs;
    for (std::size_t i = 0; i < entries.size(); ++i)
        if (i == 0 || entries[i].key != entries[i - 1].key)
            runs.push_back(i);
    runs.push_back(entries.size());

    // Cells in fixed blocks, each block's results in its own slot: the
    // concatenation and the counts do not depend on the scheduling.
    constexpr std::size_t kBlock = 512;
    const std::size_t cellCount = runs.size() - 1;
    const std::size_t blockCount = (cellCount + kBlock - 1) / kBlock;
    std::vector<std::vector<PairResult>> found(blockCount);
    std::vector<long long> counts(blockCount, 0);
    tbb::parallel_for(std::size_t(0), blockCount, [&](std::size_t block) {
        const std::size_t end = std::min(cellCount, (block + 1) * kBlock);
        for (std::size_t cell = block * kBlock; cell < end; ++cell) {
            const std::uint64_t here = entries[runs[cell]].key;
            for (std::size_t i = runs[cell]; i < runs[cell + 1]; ++i) {
                const Item& p = items[i];
                for (std::size_t j = i + 1; j < runs[cell + 1]; ++j) {
                    const Item& q = items[j];
                    if (q.box.min.x() > p.box.max.x())
                        break; // and so do the boxes after it
                    if (p.box.max.y() < q.box.min.y() || q.box.max.y() < p.box.min.y() ||
                        p.box.max.z() < q.box.min.z() || q.box.max.z() < p.box.min.z())
                        continue;
                    // The pair is reported in the cell of its boxes'
                    // intersection's minimum corner only: the larger of the
                    // two boxes' first cells on each axis (the cell index is
                    // monotone in the coordinate).
                    if (FaceGrid::key({std::max(p.firstCell[0], q.firstCell[0]),
                                       std::max(p.firstCell[1], q.firstCell[1]),
                                       std::max(p.firstCell[2], q.firstCell[2])}) != here)
                        continue;
                    // Faces sharing a vertex (or an edge) are skipped: on a
                    // manifold mesh they meet there, and that is not an
                    // intersection curve. A fold that makes two such faces
                    // cross elsewhere is missed (see the header).
                    if (shareVertex(p.triangle, q.triangle))
                        continue;
                    ++counts[block];
                    const Index f = std::min(p.face, q.face), g = std::max(p.face, q.face);
                    const Triangle& tf = mesh.triangle(f);
                    const Triangle& tg = mesh.triangle(g);
                    const FacePlane planes[2] = {grid.plane(f), grid.plane(g)};
                    const Vec3 corners[2][3] = {
                        {mesh.position(tf[0]), mesh.position(tf[1]), mesh.position(tf[2])},
                        {mesh.position(tg[0]), mesh.position(tg[1]), mesh.position(tg[2])}};
                    if (certainlySeparated(planes, corners))
                        continue;
                    PairResult r{f, g, PairKind::None, {}};
                    r.kind = genericSegment(mesh, f, g, r.segment);
                    if (r.kind != PairKind::None)
                        found[block].push_back(r);
                }
            }
        }
    });
    std::vector<PairResult> out;
    *candidateCount = 0;
    for (std::size_t b = 0; b < blockCount; ++b) {
        *candidateCount += counts[b];
        out.insert(out.end(), found[b].begin(), found[b].end());
    }
    std::sort(out.begin(), out.end(), [](const PairResult& x, const PairResult& y) {
        return std::pair(x.f, x.g) < std::pair(y.f, y.g);
    });
    return out;
}

} // namespace

SurfaceIntersectionCurves surfaceIntersectionCurves(const TriangleMesh& mesh) {
    SurfaceIntersectionCurves result;

    // Candidate pairs: faces whose bounding boxes overlap (closed boxes) and
    // that share no vertex, found on a uniform grid (FaceGrid above) and
    // tested at once, in parallel. Only the pairs that are not disjoint are
    // kept; they are sorted by face pair, so the exact tests below and the
    // chaining see them in the same order whatever the thread count.
    std::vector<PairResult> tested = testCandidatePairs(mesh, &result.candidatePairs);

    auto exactTriangle = [&](Index f) {
        const Triangle& t = mesh.triangle(f);
        return Exact::Triangle_3(exactPoint(mesh.position(t[0])), exactPoint(mesh.position(t[1])),
                                 exactPoint(mesh.position(t[2])));
    };

    // Generic pairs were decided with exact predicates above; the others (a
    // vertex on the other plane, edges meeting, coplanar faces) go to CGAL's
    // exact triangle–triangle intersection (exact constructions kernel),
    // serially, and their ends are classified exactly onto mesh
    // vertices/edges/faces.
    std::vector<Segment> segments;
    for (const PairResult& pair : tested) {
        if (pair.kind == PairKind::Segment) {
            segments.push_back(pair.segment);
            continue;
        }
        ++result.exactPairs;
        const Index f = pair.f, g = pair.g;
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
