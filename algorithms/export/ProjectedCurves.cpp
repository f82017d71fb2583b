#include "export/ProjectedCurves.h"

namespace contour {

namespace {

void closePiece(std::vector<Vec2>& piece, ProjectedPolyline& out) {
    // One point alone has no segment to draw.
    if (piece.size() >= 2) {
        for (size_t i = 1; i < piece.size(); ++i)
            out.lengthPixels += (piece[i] - piece[i - 1]).norm();
        out.pieces.push_back(std::move(piece));
    }
    piece.clear();
}

ProjectedPolyline projectOne(const Polyline& line, size_t index, const Camera& camera) {
    ProjectedPolyline out;
    out.index = index;
    out.type = line.type;
    out.closed = line.closed;
    out.pointCount = line.points.size();
    const size_t n = line.points.size();
    std::vector<Vec2> pixel(n);
    std::vector<char> drawable(n);
    for (size_t i = 0; i < n; ++i) {
        const ProjectedPoint p = camera.project(line.points[i].position);
        pixel[i] = p.pixel;
        // An orthographic camera sees along parallel rays: every point projects.
        drawable[i] = (camera.isOrthographic() || p.depth > 0.0) && p.pixel.allFinite();
        out.hiddenPoints += !drawable[i];
    }
    if (n == 0)
        return out;
    std::vector<Vec2> piece;
    if (out.hiddenPoints == 0) {
        piece = pixel;
        if (line.closed && n >= 3)
            piece.push_back(pixel.front());
        closePiece(piece, out);
        return out;
    }
    // Walk the points once (once around plus back to the start for a closed
    // curve, beginning at a hidden point so that no run wraps around).
    size_t start = 0;
    size_t steps = n;
    if (line.closed) {
        while (drawable[start])
            ++start;
        steps = n + 1;
    }
    for (size_t k = 0; k < steps; ++k) {
        const size_t i = (start + k) % n;
        if (drawable[i])
            piece.push_back(pixel[i]);
        else
            closePiece(piece, out);
    }
    closePiece(piece, out);
    return out;
}

} // namespace

std::vector<ProjectedPolyline> projectCurves(const std::vector<Polyline>& curves,
                                             const Camera& camera) {
    std::vector<ProjectedPolyline> out;
    out.reserve(curves.size());
    for (size_t i = 0; i < curves.size(); ++i)
        out.push_back(projectOne(curves[i], i, camera));
    return out;
}

std::vector<std::vector<Vec2>> projectChain(const ViewChain& chain, const Camera& camera) {
    std::vector<std::vector<Vec2>> pieces;
    bool open = false;
    for (const Vec3& point : chain.points) {
        const ProjectedPoint p = camera.project(point);
        if ((camera.isOrthographic() || p.depth > 0.0) && p.pixel.allFinite()) {
            if (!open)
                pieces.emplace_back();
            pieces.back().push_back(p.pixel);
            open = true;
        } else {
            open = false;
        }
    }
    std::erase_if(pieces, [](const std::vector<Vec2>& piece) { return piece.size() < 2; });
    return pieces;
}

} // namespace contour
