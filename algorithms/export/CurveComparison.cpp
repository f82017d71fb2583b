#include "export/CurveComparison.h"

#include "core/SegmentDistance.h"
#include "export/ProjectedCurves.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
        if (!line.empty())
            visit(line.front());
        for (std::size_t i = 1; i < line.size(); ++i) {
            const Vec2& a = line[i - 1];
            const Vec2& b = line[i];
            const int samples = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
            for (int s = 1; s <= samples; ++s)
                visit(a + (b - a) * (static_cast<double>(s) / samples));
        }
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

} // namespace contour
