#include "export/CurveComparison.h"

#include "core/SegmentDistance.h"
#include "export/ProjectedCurves.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>

namespace contour {

std::vector<ImagePolyline> drawnCurves(const Snapshot& snapshot, const Camera& camera) {
    std::vector<ImagePolyline> out;
    if (snapshot.viewGraph) {
        for (const ViewChain& chain : snapshot.viewGraph->chains)
            if (chain.visible() && chain.image.size() >= 2)
                out.push_back(chain.image);
        return out;
    }
    if (!snapshot.curves)
        return out;
    for (ProjectedPolyline& p : projectCurves(*snapshot.curves, camera))
        for (ImagePolyline& piece : p.pieces)
            if (piece.size() >= 2)
                out.push_back(std::move(piece));
    return out;
}

namespace {

double length(const ImagePolyline& line) {
    double total = 0.0;
    for (std::size_t i = 1; i < line.size(); ++i)
        total += (line[i] - line[i - 1]).norm();
    return total;
}

// Hand-written: a uniform grid over the segments of one side, each segment
// filed in every cell its box grown by the tolerance touches, so that a
// point's own cell lists every segment within the tolerance. None of our
// libraries offers a 2D segment-proximity query that is simpler.
class SegmentGrid {
public:
    SegmentGrid(const std::vector<ImagePolyline>& lines, double tolerance)
        : lines_(lines), tolerance_(tolerance), cell_(std::max(2.0 * tolerance, 1.0)) {
        for (std::size_t l = 0; l < lines.size(); ++l)
            for (std::size_t i = 1; i < lines[l].size(); ++i) {
                const Vec2& a = lines[l][i - 1];
                const Vec2& b = lines[l][i];
                const long long x0 = coord(std::min(a.x(), b.x()) - tolerance);
                const long long x1 = coord(std::max(a.x(), b.x()) + tolerance);
                const long long y0 = coord(std::min(a.y(), b.y()) - tolerance);
                const long long y1 = coord(std::max(a.y(), b.y()) + tolerance);
                for (long long x = x0; x <= x1; ++x)
                    for (long long y = y0; y <= y1; ++y)
                        cells_[key(x, y)].push_back(
                            {static_cast<std::uint32_t>(l), static_cast<std::uint32_t>(i)});
            }
    }

    // The distance to the nearest segment if one is within the tolerance.
    std::optional<double> nearest(const Vec2& p) const {
        const auto it = cells_.find(key(coord(p.x()), coord(p.y())));
        if (it == cells_.end())
            return std::nullopt;
        std::optional<double> best;
        for (const auto& [l, i] : it->second)
            if (const double d = pointSegmentDistance(p, lines_[l][i - 1], lines_[l][i]);
                d <= tolerance_ && (!best || d < *best))
                best = d;
        return best;
    }

    bool near(const Vec2& p) const {
        const auto it = cells_.find(key(coord(p.x()), coord(p.y())));
        if (it == cells_.end())
            return false;
        for (const auto& [l, i] : it->second)
            if (pointSegmentDistance(p, lines_[l][i - 1], lines_[l][i]) <= tolerance_)
                return true;
        return false;
    }

private:
    long long coord(double v) const { return static_cast<long long>(std::floor(v / cell_)); }
    static long long key(long long x, long long y) { return (x << 32) ^ (y & 0xffffffffLL); }

    const std::vector<ImagePolyline>& lines_;
    double tolerance_;
    double cell_;
    std::unordered_map<long long, std::vector<std::pair<std::uint32_t, std::uint32_t>>> cells_;
};

// The polyline's vertices and points between them at most `step` apart.
template <typename Visit> void forEachSample(const ImagePolyline& line, double step, Visit visit) {
    if (!line.empty())
        visit(line.front());
    for (std::size_t i = 1; i < line.size(); ++i) {
        const Vec2& a = line[i - 1];
        const Vec2& b = line[i];
        const int samples = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int k = 1; k <= samples; ++k)
            visit(a + (b - a) * (static_cast<double>(k) / samples));
    }
}

// The runs of `lines` with no curve of `other` within the tolerance.
void unmatchedRuns(const std::vector<ImagePolyline>& lines, const SegmentGrid& other,
                   double tolerance, std::vector<ImagePolyline>& runs, double& runLength) {
    const double step = std::max(tolerance / 4.0, 1e-3);
    for (const ImagePolyline& line : lines) {
        ImagePolyline run;
        auto flush = [&] {
            if (run.size() >= 2) {
                runLength += length(run);
                runs.push_back(std::move(run));
            }
            run.clear();
        };
        auto visit = [&](const Vec2& p) {
            if (other.near(p))
                flush();
            else
                run.push_back(p);
        };
        forEachSample(line, step, visit);
        flush();
    }
}

} // namespace

CurveDifference compareCurves(const std::vector<ImagePolyline>& a,
                              const std::vector<ImagePolyline>& b, double tolerancePixels) {
    CurveDifference d;
    d.tolerancePixels = tolerancePixels;
    for (const ImagePolyline& line : a)
        d.lengthA += length(line);
    for (const ImagePolyline& line : b)
        d.lengthB += length(line);
    const SegmentGrid gridA(a, tolerancePixels);
    const SegmentGrid gridB(b, tolerancePixels);
    unmatchedRuns(a, gridB, tolerancePixels, d.onlyInA, d.onlyInALength);
    unmatchedRuns(b, gridA, tolerancePixels, d.onlyInB, d.onlyInBLength);
    return d;
}

CurveDistanceField distanceAlongCurves(const std::vector<ImagePolyline>& lines,
                                       const std::vector<ImagePolyline>& other, double cap,
                                       double step) {
    CurveDistanceField f;
    f.cap = cap;
    const SegmentGrid grid(other, cap);
    std::vector<double> all;
    for (const ImagePolyline& line : lines) {
        ImagePolyline points;
        std::vector<double> distances;
        const auto visit = [&](const Vec2& p) {
            points.push_back(p);
            distances.push_back(grid.nearest(p).value_or(cap));
        };
        forEachSample(line, std::max(step, 1e-3), visit);
        all.insert(all.end(), distances.begin(), distances.end());
        f.points.push_back(std::move(points));
        f.distances.push_back(std::move(distances));
    }
    f.count = static_cast<long long>(all.size());
    if (all.empty())
        return f;
    double sum = 0.0;
    for (const double d : all)
        sum += d;
    f.mean = sum / static_cast<double>(all.size());
    std::sort(all.begin(), all.end());
    f.max = all.back();
    f.p95 = all[std::min(all.size() - 1, static_cast<std::size_t>(0.95 * all.size()))];
    return f;
}

DrawingNodes drawnNodes(const Snapshot& snapshot, const Camera& camera) {
    DrawingNodes out;
    if (!snapshot.viewGraph) {
        out.curves = static_cast<int>(drawnCurves(snapshot, camera).size());
        return out;
    }
    const ViewGraph& g = *snapshot.viewGraph;
    const auto visibleAt = [&](const ViewNode& n) {
        return std::any_of(n.chains.begin(), n.chains.end(), [&](Index c) {
            return g.chains[static_cast<std::size_t>(c)].visible();
        });
    };
    for (const ViewNode& n : g.nodes) {
        if (!visibleAt(n))
            continue;
        if (n.type == ViewNodeType::CurtainFold || n.type == ViewNodeType::BoundaryCurtainFold)
            out.cusps.push_back(n.image);
        else if (n.type == ViewNodeType::ImageIntersection)
            out.tJunctions.push_back(n.image);
    }
    // Components of the visible chains joined at their nodes (union-find
    // over nodes; a closed chain is a component of its own).
    std::vector<Index> parent(g.nodes.size());
    for (std::size_t i = 0; i < parent.size(); ++i)
        parent[i] = static_cast<Index>(i);
    const auto find = [&](Index x) {
        while (parent[static_cast<std::size_t>(x)] != x)
            x = parent[static_cast<std::size_t>(x)] =
                parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        return x;
    };
    std::vector<char> used(g.nodes.size(), 0);
    for (const ViewChain& c : g.chains) {
        if (!c.visible())
            continue;
        if (c.startNode == kInvalidIndex || c.endNode == kInvalidIndex) {
            ++out.curves;
            continue;
        }
        used[static_cast<std::size_t>(c.startNode)] = used[static_cast<std::size_t>(c.endNode)] = 1;
        parent[static_cast<std::size_t>(find(c.startNode))] = find(c.endNode);
    }
    for (std::size_t i = 0; i < parent.size(); ++i)
        out.curves += used[i] && find(static_cast<Index>(i)) == static_cast<Index>(i) ? 1 : 0;
    return out;
}

namespace {

std::vector<Vec2> unmatchedPoints(const std::vector<Vec2>& a, const std::vector<Vec2>& b,
                                  double tolerance) {
    std::vector<Vec2> out;
    for (const Vec2& p : a)
        if (std::none_of(b.begin(), b.end(),
                         [&](const Vec2& q) { return (p - q).norm() <= tolerance; }))
            out.push_back(p);
    return out;
}

} // namespace

NodeDifference compareNodes(const DrawingNodes& a, const DrawingNodes& b, double tolerancePixels) {
    NodeDifference d;
    d.tolerancePixels = tolerancePixels;
    d.a = a;
    d.b = b;
    d.cuspsOnlyInA = unmatchedPoints(a.cusps, b.cusps, tolerancePixels);
    d.cuspsOnlyInB = unmatchedPoints(b.cusps, a.cusps, tolerancePixels);
    d.tJunctionsOnlyInA = unmatchedPoints(a.tJunctions, b.tJunctions, tolerancePixels);
    d.tJunctionsOnlyInB = unmatchedPoints(b.tJunctions, a.tJunctions, tolerancePixels);
    return d;
}

} // namespace contour
