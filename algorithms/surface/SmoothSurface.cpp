#include "surface/SmoothSurface.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace contour {

const char* toString(SurfaceKind kind) {
    switch (kind) {
    case SurfaceKind::CatmullClark:
        return "catmull-clark";
    case SurfaceKind::Loop:
        return "loop";
    case SurfaceKind::VertexNormalPatches:
        return "vertex-normal-patches";
    }
    return "unknown";
}

bool SmoothSurface::contains(const Preimage& p) const {
    if (p.face < 0 || p.face >= domain_.faceCount())
        return false;
    if (isQuad(p.face))
        return p.u >= 0.0 && p.u <= 1.0 && p.v >= 0.0 && p.v <= 1.0;
    return p.u >= 0.0 && p.v >= 0.0 && p.u + p.v <= 1.0;
}

void SmoothSurface::evaluate(std::span<const Preimage> preimages, std::span<SurfacePoint> out) const {
    if (preimages.size() != out.size())
        throw std::invalid_argument("evaluate: preimages and output differ in size");
    tbb::parallel_for(size_t(0), preimages.size(), [&](size_t i) { out[i] = evaluate(preimages[i]); });
}

Vec2 SmoothSurface::cornerCoordinates(bool quad, int corner) {
    static const Vec2 quadCorners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const Vec2 triangleCorners[3] = {{0, 0}, {1, 0}, {0, 1}};
    return quad ? quadCorners[corner] : triangleCorners[corner];
}

void SmoothSurface::buildAdjacency() {
    const Index n = domain_.faceCount();
    neighbors_.assign(static_cast<size_t>(n) * 4, EdgeNeighbor{});
    std::map<std::pair<Index, Index>, std::pair<Index, int>> directed;
    for (Index f = 0; f < n; ++f) {
        const auto corners = domain_.face(f);
        if (corners.size() != 3 && corners.size() != 4)
            throw std::logic_error("smooth surface domain faces must be triangles or quads");
        for (int e = 0; e < static_cast<int>(corners.size()); ++e)
            directed[{corners[e], corners[(e + 1) % corners.size()]}] = {f, e};
    }
    for (Index f = 0; f < n; ++f) {
        const auto corners = domain_.face(f);
        for (int e = 0; e < static_cast<int>(corners.size()); ++e) {
            const auto it = directed.find({corners[(e + 1) % corners.size()], corners[e]});
            if (it != directed.end())
                neighbors_[static_cast<size_t>(f) * 4 + e] = {it->second.first, it->second.second};
        }
    }
}

SmoothSurface::EdgeNeighbor SmoothSurface::neighbor(Index face, int edge) const {
    return neighbors_.at(static_cast<size_t>(face) * 4 + edge);
}

Preimage SmoothSurface::transferAcrossEdge(const Preimage& p, int edge) const {
    const EdgeNeighbor nb = neighbor(p.face, edge);
    if (nb.face == kInvalidIndex)
        throw std::out_of_range("transferAcrossEdge: edge " + std::to_string(edge) + " of face " +
                                std::to_string(p.face) + " is a boundary");
    // Edge frame in the source chart: origin at corner `edge`, x along the
    // edge, y its inward normal in parameter space. The neighbour's shared
    // edge runs the other way, and its inside is on the other side.
    const bool quadA = isQuad(p.face), quadB = isQuad(nb.face);
    const int nA = quadA ? 4 : 3, nB = quadB ? 4 : 3;
    const Vec2 a0 = cornerCoordinates(quadA, edge), a1 = cornerCoordinates(quadA, (edge + 1) % nA);
    const Vec2 b0 = cornerCoordinates(quadB, nb.edge), b1 = cornerCoordinates(quadB, (nb.edge + 1) % nB);
    // Affine map x -> b1 + M (x - a0). M takes the edge direction (a1 - a0)
    // to (b0 - b1), and the source's inward normal (left of its edge, faces
    // are counter-clockwise in parameter space) to the neighbour's outward
    // normal, which is the left normal of (b0 - b1).
    const Vec2 ea = a1 - a0, eb = b0 - b1;
    Eigen::Matrix2d src, dst;
    src << ea.x(), -ea.y(), ea.y(), ea.x();
    dst << eb.x(), -eb.y(), eb.y(), eb.x();
    const Eigen::Matrix2d m = dst * src.inverse();
    const Vec2 x = m * (Vec2(p.u, p.v) - a0) + b1;
    return {nb.face, x.x(), x.y()};
}

} // namespace contour
