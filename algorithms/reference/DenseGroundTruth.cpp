#include "reference/DenseGroundTruth.h"

#include "camera/Facing.h"
#include "contours/consistent/mesh/DomainCharts.h"
#include "core/SmallLoopCrossings.h"
#include "pipeline/FieldNames.h"
#include "surface/SurfaceFields.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <utility>

namespace contour {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The rule of the interpolated method: g exactly 0 counts as back-facing.
bool isFront(double g) {
    return g > 0.0;
}

// A lattice edge with a sign change, seen from one cell of one face. Its key
// is the pair of global samples, lower first; A is the lower one.
struct Candidate {
    std::uint64_t key = 0;
    Index face = kInvalidIndex;
    Vec2 uvA, uvB;
    double gA = 0.0, gB = 0.0;
};

struct Segment {
    std::uint64_t a = 0, b = 0; // crossing keys
    Index face = kInvalidIndex;
};

struct FaceResult {
    std::vector<Candidate> candidates;
    std::vector<Segment> segments;
};

std::uint64_t edgeKey(Index a, Index b) {
    const auto low = static_cast<std::uint64_t>(std::min(a, b));
    const auto high = static_cast<std::uint64_t>(std::max(a, b));
    return (low << 32) | high;
}

// The crossing on the lattice edge (a, b) at local lattice points pa, pb.
Candidate makeCandidate(Index face, int n, Index a, Index b, const std::array<int, 2>& pa,
                        const std::array<int, 2>& pb, const std::vector<double>& g) {
    const double step = 1.0 / n;
    Vec2 uvA(pa[0] * step, pa[1] * step), uvB(pb[0] * step, pb[1] * step);
    double gA = g[a], gB = g[b];
    if (a > b) {
        std::swap(uvA, uvB);
        std::swap(gA, gB);
    }
    return {edgeKey(a, b), face, uvA, uvB, gA, gB};
}

} // namespace

int GroundTruth::closedLoops() const {
    int n = 0;
    for (const GroundTruthLoop& loop : loops)
        n += loop.closed;
    return n;
}

DenseGroundTruth::DenseGroundTruth(std::shared_ptr<const SmoothSurface> surface,
                                   GroundTruthOptions options)
    : surface_(std::move(surface)), options_(options) {
    if (!surface_)
        throw std::invalid_argument("DenseGroundTruth: no surface");
    if (options_.samples < 1 || options_.samples > 4096)
        throw std::invalid_argument("DenseGroundTruth: samples must be in 1..4096");
    const auto start = Clock::now();
    const int n = options_.samples;
    const PolygonMesh& domain = surface_->domain();
    const Index faces = domain.faceCount();

    // Global edges of the domain.
    std::map<std::pair<Index, Index>, Index> edges;
    faceEdge_.assign(static_cast<size_t>(faces) * 4, kInvalidIndex);
    for (Index f = 0; f < faces; ++f) {
        const auto c = domain.face(f);
        for (size_t e = 0; e < c.size(); ++e) {
            const Index a = c[e], b = c[(e + 1) % c.size()];
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto [it, inserted] = edges.try_emplace(key, static_cast<Index>(edgeLow_.size()));
            if (inserted)
                edgeLow_.push_back(key.first);
            faceEdge_[static_cast<size_t>(f) * 4 + e] = it->second;
        }
    }
    // Numbering of the samples.
    Index next = domain.vertexCount() + static_cast<Index>(edgeLow_.size()) * (n - 1);
    interiorOffset_.resize(static_cast<size_t>(faces));
    for (Index f = 0; f < faces; ++f) {
        interiorOffset_[f] = next;
        next += surface_->isQuad(f) ? (n - 1) * (n - 1) : (n - 1) * (n - 2) / 2;
    }
    // Each sample is evaluated in the first face that has it.
    std::vector<Preimage> preimages(static_cast<size_t>(next));
    for (Index f = 0; f < faces; ++f) {
        const bool quad = surface_->isQuad(f);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= (quad ? n : n - j); ++i) {
                Preimage& p = preimages[node(f, i, j)];
                if (p.face == kInvalidIndex)
                    p = {f, static_cast<double>(i) / n, static_cast<double>(j) / n};
            }
    }
    positions_.resize(preimages.size());
    normals_.resize(preimages.size());
    constexpr size_t kChunk = size_t(1) << 16;
    std::vector<SurfacePoint> points;
    for (size_t first = 0; first < preimages.size(); first += kChunk) {
        const size_t count = std::min(kChunk, preimages.size() - first);
        points.resize(count);
        surface_->evaluate(std::span<const Preimage>(preimages.data() + first, count), points);
        for (size_t k = 0; k < count; ++k) {
            positions_[first + k] = points[k].position;
            normals_[first + k] = points[k].normal();
        }
    }
    samplingSeconds_ = secondsSince(start);
}

Index DenseGroundTruth::node(Index f, int i, int j) const {
    const int n = options_.samples;
    const auto c = surface_->domain().face(f);
    const auto onEdge = [&](int e, int k) {
        const Index edge = faceEdge_[static_cast<size_t>(f) * 4 + e];
        const int fromLow = c[e] == edgeLow_[edge] ? k : n - k;
        return surface_->domain().vertexCount() + edge * (n - 1) + (fromLow - 1);
    };
    if (surface_->isQuad(f)) {
        if (j == 0)
            return i == 0 ? c[0] : i == n ? c[1] : onEdge(0, i);
        if (j == n)
            return i == 0 ? c[3] : i == n ? c[2] : onEdge(2, n - i);
        if (i == n)
            return onEdge(1, j);
        if (i == 0)
            return onEdge(3, n - j);
        return interiorOffset_[f] + (j - 1) * (n - 1) + (i - 1);
    }
    if (j == 0)
        return i == 0 ? c[0] : i == n ? c[1] : onEdge(0, i);
    if (i == 0)
        return j == n ? c[2] : onEdge(2, n - j);
    if (i + j == n)
        return onEdge(1, j);
    // Row j (1 .. n - 2) holds i = 1 .. n - 1 - j.
    const Index row = (j - 1) * (n - 1) - (j - 1) * j / 2;
    return interiorOffset_[f] + row + (i - 1);
}

GroundTruth DenseGroundTruth::compute(const Camera& camera) const {
    const auto start = Clock::now();
    const int n = options_.samples;
    const Index faces = surface_->domain().faceCount();

    // g at every sample (positions and normals do not depend on the view).
    std::vector<double> g(positions_.size());
    tbb::parallel_for(size_t(0), g.size(),
                      [&](size_t k) { g[k] = facingFunction(camera, positions_[k], normals_[k]); });

    // Marching squares / triangles per face.
    std::vector<FaceResult> perFace(static_cast<size_t>(faces));
    tbb::parallel_for(Index(0), faces, [&](Index f) {
        FaceResult& out = perFace[f];
        const bool quad = surface_->isQuad(f);
        std::vector<Index> ids(static_cast<size_t>(n + 1) * (n + 1), kInvalidIndex);
        const auto id = [&](int i, int j) {
            return ids[static_cast<size_t>(j) * (n + 1) + i];
        };
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= (quad ? n : n - j); ++i)
                ids[static_cast<size_t>(j) * (n + 1) + i] = node(f, i, j);
        // One cell with corners p[0..m) counter-clockwise; edge k joins corner
        // k and k + 1. Emits a segment per pair of crossing edges.
        const auto cell = [&](const std::array<int, 2>* p, int m) {
            std::array<Index, 4> v{};
            std::array<double, 4> gv{};
            std::array<bool, 4> front{};
            for (int k = 0; k < m; ++k) {
                v[k] = id(p[k][0], p[k][1]);
                gv[k] = g[v[k]];
                front[k] = isFront(gv[k]);
            }
            std::array<int, 4> crossing{};
            int count = 0;
            for (int k = 0; k < m; ++k) {
                const int l = (k + 1) % m;
                if (front[k] != front[l]) {
                    crossing[count++] = k;
                    out.candidates.push_back(makeCandidate(f, n, v[k], v[l], p[k], p[l], g));
                }
            }
            const auto key = [&](int k) {
                return edgeKey(v[k], v[(k + 1) % m]);
            };
            if (count == 2) {
                out.segments.push_back({key(crossing[0]), key(crossing[1]), f});
            } else if (count == 4) {
                // Saddle: the asymptotic decider. The bilinear interpolant's
                // value at its saddle point tells which diagonal is connected;
                // cut off the two corners of the other sign.
                const double den = gv[0] + gv[2] - gv[1] - gv[3];
                const bool centreFront = (gv[0] * gv[2] - gv[1] * gv[3]) / den > 0.0;
                for (int k = 0; k < 4; ++k)
                    if (front[k] != centreFront)
                        out.segments.push_back({key((k + 3) % 4), key(k), f});
            }
        };
        if (quad) {
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const std::array<int, 2> p[4] = {
                        {i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                    cell(p, 4);
                }
        } else {
            for (int j = 0; j < n; ++j)
                for (int i = 0; i + j < n; ++i) {
                    const std::array<int, 2> up[3] = {{i, j}, {i + 1, j}, {i, j + 1}};
                    cell(up, 3);
                    if (i + j < n - 1) {
                        const std::array<int, 2> down[3] = {{i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                        cell(down, 3);
                    }
                }
        }
    });

    // One crossing per lattice edge, computed in the lowest face that has it.
    std::vector<Candidate> all;
    std::vector<Segment> segments;
    for (FaceResult& r : perFace) {
        all.insert(all.end(), r.candidates.begin(), r.candidates.end());
        segments.insert(segments.end(), r.segments.begin(), r.segments.end());
    }
    perFace.clear();
    std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
        return a.key != b.key ? a.key < b.key : a.face < b.face;
    });
    all.erase(std::unique(all.begin(), all.end(),
                          [](const Candidate& a, const Candidate& b) { return a.key == b.key; }),
              all.end());
    const size_t crossings = all.size();
    std::vector<Vec3> position(crossings);
    std::vector<Preimage> preimage(crossings);
    std::vector<double> kr(crossings);
    tbb::parallel_for(size_t(0), crossings, [&](size_t c) {
        const Candidate& k = all[c];
        // Regula falsi on the true g, keeping the bracket [a, b].
        double a = 0.0, b = 1.0, ga = k.gA, gb = k.gB;
        double t = ga / (ga - gb);
        const auto at = [&](double s) {
            const Vec2 uv = (1.0 - s) * k.uvA + s * k.uvB;
            return Preimage{k.face, uv.x(), uv.y()};
        };
        for (int step = 0; step < options_.refineSteps; ++step) {
            const double gt = orientation(surface_->evaluate(at(t)), camera);
            if (gt == 0.0 || !std::isfinite(gt))
                break;
            if (isFront(gt) == isFront(ga)) {
                a = t;
                ga = gt;
            } else {
                b = t;
                gb = gt;
            }
            t = a + (b - a) * ga / (ga - gb);
        }
        preimage[c] = at(t);
        const SurfacePoint sp = surface_->evaluate(preimage[c]);
        position[c] = sp.position;
        kr[c] = radialCurvature(sp, camera);
    });
    const auto indexOf = [&](std::uint64_t key) {
        const auto it =
            std::lower_bound(all.begin(), all.end(), key,
                             [](const Candidate& x, std::uint64_t k) { return x.key < k; });
        return static_cast<int>(it - all.begin());
    };

    // Chain segments through shared crossings.
    std::vector<std::array<int, 2>> ends(segments.size());
    std::vector<std::array<int, 2>> adjacent(crossings, {-1, -1});
    for (size_t s = 0; s < segments.size(); ++s) {
        ends[s] = {indexOf(segments[s].a), indexOf(segments[s].b)};
        for (int c : ends[s]) {
            if (adjacent[c][0] < 0)
                adjacent[c][0] = static_cast<int>(s);
            else if (adjacent[c][1] < 0)
                adjacent[c][1] = static_cast<int>(s);
            else
                throw std::logic_error("DenseGroundTruth: a crossing joins more than 2 segments");
        }
    }
    GroundTruth truth;
    truth.samples = n;
    std::vector<char> used(segments.size(), 0);
    const auto walk = [&](int startCrossing, int startSegment) {
        GroundTruthLoop loop;
        std::vector<int> order{startCrossing};
        int c = startCrossing, s = startSegment;
        while (true) {
            used[s] = 1;
            loop.faces.push_back(segments[s].face);
            loop.segmentFaces.push_back(segments[s].face);
            const int other = ends[s][0] == c ? ends[s][1] : ends[s][0];
            if (other == startCrossing) {
                loop.closed = true;
                break;
            }
            order.push_back(other);
            const auto& adj = adjacent[other];
            const int nextSegment = adj[0] >= 0 && !used[adj[0]]   ? adj[0]
                                    : adj[1] >= 0 && !used[adj[1]] ? adj[1]
                                                                   : -1;
            if (nextSegment < 0)
                break;
            c = other;
            s = nextSegment;
        }
        std::sort(loop.faces.begin(), loop.faces.end());
        loop.faces.erase(std::unique(loop.faces.begin(), loop.faces.end()), loop.faces.end());
        for (int k : order) {
            loop.points.push_back(position[k]);
            loop.preimages.push_back(preimage[k]);
            loop.radialCurvature.push_back(kr[k]);
        }
        truth.loops.push_back(std::move(loop));
    };
    // Open chains first (from a crossing with one segment), then cycles.
    for (size_t c = 0; c < crossings; ++c)
        if (adjacent[c][0] >= 0 && adjacent[c][1] < 0 && !used[adjacent[c][0]])
            walk(static_cast<int>(c), adjacent[c][0]);
    for (size_t s = 0; s < segments.size(); ++s)
        if (!used[s])
            walk(ends[s][0], static_cast<int>(s));

    // Cusps: sign changes of the radial curvature along each loop, skipping
    // points where it is NaN or exactly zero.
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        GroundTruthLoop& loop = truth.loops[l];
        std::vector<size_t> finite;
        for (size_t k = 0; k < loop.radialCurvature.size(); ++k)
            if (std::isfinite(loop.radialCurvature[k]) && loop.radialCurvature[k] != 0.0)
                finite.push_back(k);
        const size_t m = finite.size();
        const size_t pairs = loop.closed ? (m >= 2 ? m : 0) : (m >= 1 ? m - 1 : 0);
        for (size_t q = 0; q < pairs; ++q) {
            const size_t i = finite[q], j = finite[(q + 1) % m];
            const double ki = loop.radialCurvature[i], kj = loop.radialCurvature[j];
            if ((ki > 0.0) == (kj > 0.0))
                continue;
            const size_t count = loop.points.size();
            const bool neighbours = (i + 1) % count == j;
            const Vec3 p =
                neighbours
                    ? Vec3(loop.points[i] + ki / (ki - kj) * (loop.points[j] - loop.points[i]))
                    : Vec3(0.5 * (loop.points[i] + loop.points[j]));
            truth.cusps.push_back({p, static_cast<int>(l)});
            ++loop.cusps;
        }
    }
    truth.seconds = secondsSince(start);
    return truth;
}

namespace {

// Projected polylines: per segment, its ends, its curve and the image arc
// length at its ends.
struct ImagePolylines {
    std::vector<std::array<Vec2, 2>> segments;
    std::vector<Index> curve;
    std::vector<double> arcStart;
    std::vector<CurveArc> curves;

    void add(const std::vector<Vec2>& points, bool closed) {
        const size_t n = points.size();
        const Index c = static_cast<Index>(curves.size());
        double arc = 0.0;
        for (size_t k = 0; k + (closed ? 0 : 1) < n && n >= 2; ++k) {
            const Vec2 a = points[k], b = points[(k + 1) % n];
            segments.push_back({a, b});
            curve.push_back(c);
            arcStart.push_back(arc);
            arc += (b - a).norm();
        }
        curves.push_back({arc, closed});
    }
};

// The pairs (i, j), i < j, of image segments that cross properly, with the
// crossing's parameter along each. Segments sharing an end point never do,
// so no adjacency test is needed. The pairs tested are those
// whose bounding boxes share a cell of a uniform grid (about one segment per
// cell); a pair is counted only in the cell holding the lower corner of the
// two boxes' overlap, so each pair is decided once, by the same predicate as
// a test of every pair.
struct ProperCrossing {
    size_t first = 0, second = 0;
    double alongFirst = 0.0, alongSecond = 0.0;
};
std::vector<ProperCrossing> properCrossings(const std::vector<std::array<Vec2, 2>>& segments) {
    const auto orient = [](const Vec2& a, const Vec2& b, const Vec2& p) {
        return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
    };
    std::vector<ProperCrossing> found;
    const auto cross = [&](size_t i, size_t j) {
        const auto& [a, b] = segments[i];
        const auto& [p, q] = segments[j];
        const double pa = orient(p, q, a), pb = orient(p, q, b);
        const double ap = orient(a, b, p), aq = orient(a, b, q);
        if (pa * pb < 0.0 && ap * aq < 0.0)
            found.push_back({std::min(i, j), std::max(i, j),
                             i < j ? pa / (pa - pb) : ap / (ap - aq),
                             i < j ? ap / (ap - aq) : pa / (pa - pb)});
    };
    if (segments.empty())
        return found;
    Vec2 lo = segments[0][0], hi = lo;
    for (const auto& s : segments)
        for (const Vec2& p : s) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    const int cells =
        std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segments.size()))), 1, 1024);
    const Vec2 size = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
    const auto cellOf = [&](double x, double low, double extent) {
        return std::clamp(static_cast<int>((x - low) / extent * cells), 0, cells - 1);
    };
    std::vector<std::vector<size_t>> grid(static_cast<size_t>(cells) * cells);
    std::vector<std::array<Vec2, 2>> boxes(segments.size());
    for (size_t i = 0; i < segments.size(); ++i) {
        boxes[i] = {segments[i][0].cwiseMin(segments[i][1]),
                    segments[i][0].cwiseMax(segments[i][1])};
        for (int y = cellOf(boxes[i][0].y(), lo.y(), size.y());
             y <= cellOf(boxes[i][1].y(), lo.y(), size.y()); ++y)
            for (int x = cellOf(boxes[i][0].x(), lo.x(), size.x());
                 x <= cellOf(boxes[i][1].x(), lo.x(), size.x()); ++x)
                grid[static_cast<size_t>(y) * cells + x].push_back(i);
    }
    for (int y = 0; y < cells; ++y)
        for (int x = 0; x < cells; ++x) {
            const std::vector<size_t>& in = grid[static_cast<size_t>(y) * cells + x];
            for (size_t u = 0; u < in.size(); ++u)
                for (size_t w = u + 1; w < in.size(); ++w) {
                    const size_t i = in[u], j = in[w];
                    const Vec2 overlapLo = boxes[i][0].cwiseMax(boxes[j][0]);
                    if (overlapLo.x() > std::min(boxes[i][1].x(), boxes[j][1].x()) ||
                        overlapLo.y() > std::min(boxes[i][1].y(), boxes[j][1].y()))
                        continue;
                    if (cellOf(overlapLo.x(), lo.x(), size.x()) != x ||
                        cellOf(overlapLo.y(), lo.y(), size.y()) != y)
                        continue;
                    cross(i, j);
                }
        }
    return found;
}

// The proper crossings of the polylines that bound no loop smaller than
// `smallLoopPixels` (core/SmallLoopCrossings.h).
int crossingsOutsideSmallLoops(const ImagePolylines& lines, double smallLoopPixels) {
    const std::vector<ProperCrossing> found = properCrossings(lines.segments);
    if (!(smallLoopPixels > 0.0))
        return static_cast<int>(found.size());
    std::vector<CurveCrossing> along;
    along.reserve(found.size());
    for (const ProperCrossing& x : found) {
        const auto arcAt = [&](size_t segment, double t) {
            const auto& [a, b] = lines.segments[segment];
            return lines.arcStart[segment] + t * (b - a).norm();
        };
        along.push_back({lines.curve[x.first], arcAt(x.first, x.alongFirst), lines.curve[x.second],
                         arcAt(x.second, x.alongSecond)});
    }
    const std::vector<std::uint8_t> small =
        smallLoopCrossings(along, lines.curves, smallLoopPixels);
    return static_cast<int>(std::count(small.begin(), small.end(), std::uint8_t(0)));
}

} // namespace

int imageCrossings(const GroundTruth& truth, const Camera& camera, double smallLoopPixels) {
    ImagePolylines lines;
    for (const GroundTruthLoop& loop : truth.loops) {
        std::vector<Vec2> points;
        for (const Vec3& p : loop.points)
            points.push_back(camera.project(p).pixel);
        lines.add(points, loop.closed);
    }
    return crossingsOutsideSmallLoops(lines, smallLoopPixels);
}

int imageCrossings(const std::vector<Polyline>& curves, const Camera& camera,
                   double smallLoopPixels) {
    ImagePolylines lines;
    for (const Polyline& line : curves) {
        if (line.type != CurveType::Contour)
            continue;
        std::vector<Vec2> points;
        for (const CurvePoint& p : line.points)
            points.push_back(camera.project(p.position).pixel);
        lines.add(points, line.closed);
    }
    return crossingsOutsideSmallLoops(lines, smallLoopPixels);
}

std::vector<MethodLoop> methodLoops(const Snapshot& snapshot) {
    std::vector<MethodLoop> loops;
    if (!snapshot.curves)
        return loops;
    const Field* field = snapshot.field(fields::kDomainFace);
    if (!field || !field->labels())
        throw std::invalid_argument("methodLoops: the snapshot has no per-face domain_face field");
    const std::vector<int>& domainFace = *field->labels();
    const TriangleMesh& mesh = *snapshot.mesh;
    for (const Polyline& line : *snapshot.curves) {
        if (line.type != CurveType::Contour)
            continue;
        MethodLoop loop;
        loop.closed = line.closed;
        for (size_t i = 0; i < line.segmentElement.size(); ++i) {
            const Index element = line.segmentElement[i];
            std::array<Index, 2> crossed{kInvalidIndex, kInvalidIndex};
            if (line.source == SegmentSource::Face) {
                crossed[0] = domainFace[element];
            } else {
                const Index h = mesh.edgeHalfedge(element);
                crossed[0] = domainFace[TriangleMesh::face(h)];
                if (!mesh.isBoundary(h))
                    crossed[1] = domainFace[TriangleMesh::face(mesh.opposite(h))];
            }
            for (const Index f : crossed) {
                if (f == kInvalidIndex)
                    continue;
                loop.faces.push_back(f);
                for (size_t k : {i, (i + 1) % line.points.size()})
                    loop.facePoints.emplace_back(f, line.points[k].position);
            }
        }
        std::sort(loop.faces.begin(), loop.faces.end());
        loop.faces.erase(std::unique(loop.faces.begin(), loop.faces.end()), loop.faces.end());
        loops.push_back(std::move(loop));
    }
    return loops;
}

std::vector<MethodLoop> methodLoopsFromPreimages(const Snapshot& snapshot,
                                                 std::shared_ptr<const SmoothSurface> surface) {
    std::vector<MethodLoop> loops;
    const Field* faceField = snapshot.field(fields::kPreimageFace);
    const Field* uvField = snapshot.field(fields::kPreimageUv);
    if (!snapshot.curves || !faceField || !uvField || !faceField->labels() || !uvField->vectors())
        throw std::invalid_argument("methodLoopsFromPreimages: the snapshot has no preimages");
    const auto& face = *faceField->labels();
    const auto& uv = *uvField->vectors();
    // With the one-ring charts of regular corners (appendix B): a method run
    // with chart-vertex-rings has contour edges between diagonal domain
    // faces, which otherwise get no sample and their faces go missing; where
    // an edge or face chart exists it is tried first, so runs without the
    // option map the same.
    consistent::DomainCharts charts(std::move(surface), 1e-9);
    charts.setVertexRingCharts(true);
    const auto preimage = [&](Index v) {
        return Preimage{face[v], uv[v].x(), uv[v].y()};
    };
    for (const Polyline& line : *snapshot.curves) {
        if (line.type != CurveType::Contour)
            continue;
        MethodLoop loop;
        loop.closed = line.closed;
        // A closed loop's last point joins its first (the points are not
        // repeated): that closing edge crosses faces too.
        const size_t n = line.points.size();
        for (size_t i = 0; i + (line.closed ? 0 : 1) < n; ++i) {
            const size_t j = (i + 1) % n;
            const Index a = line.points[i].vertex, b = line.points[j].vertex;
            if (a == kInvalidIndex || b == kInvalidIndex)
                continue;
            // Both ends and 31 points between: the domain path of an edge may
            // clip a domain face's corner (a C vertex sits on a domain edge
            // or near a corner more often than not).
            constexpr int kSteps = 32;
            for (int k = 0; k <= kSteps; ++k)
                if (const std::optional<Preimage> p = charts.interpolate(
                        preimage(a), preimage(b), static_cast<double>(k) / kSteps)) {
                    loop.faces.push_back(p->face);
                    // On the straight edge (the drawn curve), not on the surface.
                    const double t = static_cast<double>(k) / kSteps;
                    loop.facePoints.emplace_back(p->face, (1.0 - t) * line.points[i].position +
                                                              t * line.points[j].position);
                }
        }
        std::sort(loop.faces.begin(), loop.faces.end());
        loop.faces.erase(std::unique(loop.faces.begin(), loop.faces.end()), loop.faces.end());
        loops.push_back(std::move(loop));
    }
    return loops;
}

namespace {

// Image distance from p to the nearest of the segments.
double imageDistance(const Vec2& p, const std::vector<std::array<Vec2, 2>>& segments) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : segments) {
        const Vec2 ab = b - a;
        const double t =
            ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
        best = std::min(best, (a + t * ab - p).norm());
    }
    return best;
}

// TopologyComparison::worstMismatchPixels and mismatchesBeyond over the
// matched loop pairs.
void measureMismatches(TopologyComparison& r, const GroundTruth& truth, const Snapshot& snapshot,
                       const std::vector<MethodLoop>& method,
                       const std::vector<std::pair<int, int>>& matched, const Camera& camera,
                       double tolerancePixels) {
    r.toleranceMismatchPixels = tolerancePixels;
    const auto pixel = [&](const Vec3& p) {
        return camera.project(p).pixel;
    };
    // Every curve of each side, as image segments.
    std::vector<std::array<Vec2, 2>> truthSegments, methodSegments;
    for (const GroundTruthLoop& loop : truth.loops)
        for (size_t k = 0; k < loop.segmentFaces.size(); ++k)
            truthSegments.push_back(
                {pixel(loop.points[k]), pixel(loop.points[(k + 1) % loop.points.size()])});
    for (const Polyline& line : *snapshot.curves)
        if (line.type == CurveType::Contour)
            for (size_t i = 0; i + 1 < line.points.size() + (line.closed ? 1 : 0); ++i)
                methodSegments.push_back(
                    {pixel(line.points[i].position),
                     pixel(line.points[(i + 1) % line.points.size()].position)});
    for (const auto& [t, m] : matched) {
        const GroundTruthLoop& a = truth.loops[static_cast<size_t>(t)];
        const MethodLoop& b = method[static_cast<size_t>(m)];
        std::vector<Index> onlyTruth, onlyMethod;
        std::set_difference(a.faces.begin(), a.faces.end(), b.faces.begin(), b.faces.end(),
                            std::back_inserter(onlyTruth));
        std::set_difference(b.faces.begin(), b.faces.end(), a.faces.begin(), a.faces.end(),
                            std::back_inserter(onlyMethod));
        for (const Index f : onlyTruth) {
            double worst = 0.0;
            for (size_t k = 0; k < a.segmentFaces.size(); ++k)
                if (a.segmentFaces[k] == f)
                    for (size_t e : {k, (k + 1) % a.points.size()})
                        worst = std::max(worst, imageDistance(pixel(a.points[e]), methodSegments));
            r.worstMismatchPixels = std::max(r.worstMismatchPixels, worst);
            r.mismatchesBeyond += worst > tolerancePixels;
        }
        for (const Index f : onlyMethod) {
            double worst = 0.0;
            for (const auto& [face, point] : b.facePoints)
                if (face == f)
                    worst = std::max(worst, imageDistance(pixel(point), truthSegments));
            r.worstMismatchPixels = std::max(r.worstMismatchPixels, worst);
            r.mismatchesBeyond += worst > tolerancePixels;
        }
    }
}

} // namespace

TopologyComparison compareTopology(const GroundTruth& truth, const Snapshot& snapshot,
                                   std::shared_ptr<const SmoothSurface> surface,
                                   const Camera* camera, double tolerancePixels) {
    TopologyComparison r;
    const std::vector<MethodLoop> method =
        surface && snapshot.field(fields::kPreimageFace)
            ? methodLoopsFromPreimages(snapshot, std::move(surface))
            : methodLoops(snapshot);
    r.truthLoops = static_cast<int>(truth.loops.size());
    r.truthOpenLoops = truth.openLoops();
    r.methodLoops = static_cast<int>(method.size());
    for (const MethodLoop& m : method)
        r.methodOpenLoops += !m.closed;
    r.truthCusps = static_cast<int>(truth.cusps.size());
    r.methodCusps = static_cast<int>(snapshot.counter(counters::kCusps, -1.0));

    struct Pair {
        double jaccard;
        int truth, method;
        bool same;
        int common;
    };
    std::vector<Pair> pairs;
    for (int t = 0; t < r.truthLoops; ++t)
        for (int m = 0; m < r.methodLoops; ++m) {
            const auto& a = truth.loops[t].faces;
            const auto& b = method[m].faces;
            std::vector<Index> common;
            std::set_intersection(a.begin(), a.end(), b.begin(), b.end(),
                                  std::back_inserter(common));
            if (common.empty())
                continue;
            const double united = static_cast<double>(a.size() + b.size() - common.size());
            pairs.push_back({static_cast<double>(common.size()) / united, t, m, a == b,
                             static_cast<int>(common.size())});
        }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& x, const Pair& y) { return x.jaccard > y.jaccard; });
    std::vector<char> truthUsed(r.truthLoops, 0), methodUsed(r.methodLoops, 0);
    std::vector<std::pair<int, int>> matched; // (truth loop, method loop)
    double sum = 0.0;
    for (const Pair& p : pairs) {
        if (truthUsed[p.truth] || methodUsed[p.method])
            continue;
        truthUsed[p.truth] = methodUsed[p.method] = 1;
        matched.emplace_back(p.truth, p.method);
        ++r.matchedLoops;
        r.sameFaceLoops += p.same;
        r.facesInBoth += p.common;
        r.facesOnlyInTruth += static_cast<int>(truth.loops[p.truth].faces.size()) - p.common;
        r.facesOnlyInMethod += static_cast<int>(method[p.method].faces.size()) - p.common;
        sum += p.jaccard;
    }
    r.meanJaccard = r.truthLoops > 0 ? sum / r.truthLoops : (r.methodLoops == 0 ? 1.0 : 0.0);
    if (camera)
        measureMismatches(r, truth, snapshot, method, matched, *camera, tolerancePixels);
    return r;
}

} // namespace contour
