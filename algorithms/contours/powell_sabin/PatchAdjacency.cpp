// Patch-side adjacency of the Powell-Sabin spline from the 12-split's
// numbering and the layout's half-edges (Capouellez et al. 2023 §4.2, §5.2).
#include "contours/powell_sabin/PatchAdjacency.h"

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace contour::powell_sabin {
namespace {

// Split points and sub-triangle corners: Ps12Patch.h.
constexpr int vPoint(int i) {
    return ps12CornerPoint(i);
}
constexpr int mPoint(int s) {
    return ps12MidpointPoint(s);
}
constexpr int kCPoint = kPs12CentroidPoint;
constexpr const std::array<std::array<int, 3>, kPs12Patches>& kSubTriangles =
    ps12SubTriangleCorners;

// The two sub-edges on face side s, each as (local patch, patch side): the
// half V_s -> M_s in patch 2s (side 0), the half M_s -> V_{s+1} in patch
// 2(s+1)+1 (side 2).
constexpr std::pair<int, int> firstHalf(int s) {
    return {2 * s, 0};
}
constexpr std::pair<int, int> secondHalf(int s) {
    return {2 * ((s + 1) % 3) + 1, 2};
}

} // namespace

const char* toString(PatchSideKind kind) {
    switch (kind) {
    case PatchSideKind::MacroPatch:
        return "macro-patch";
    case PatchSideKind::MeshEdge:
        return "mesh edge";
    case PatchSideKind::CutEdge:
        return "cut edge";
    case PatchSideKind::Boundary:
        return "boundary";
    }
    return "?";
}

const char* toString(PatchNodeKind kind) {
    switch (kind) {
    case PatchNodeKind::Vertex:
        return "vertex";
    case PatchNodeKind::EdgeMidpoint:
        return "edge midpoint";
    case PatchNodeKind::MedianPoint:
        return "median point";
    case PatchNodeKind::Centroid:
        return "centroid";
    }
    return "?";
}

PatchAdjacency::PatchAdjacency(const ConeLayout& layout, const PowellSabinSpline& spline) {
    const TriangleMesh& mesh = layout.mesh;
    const Index faces = mesh.faceCount();
    const Index vertices = mesh.vertexCount();
    const Index edges = mesh.edgeCount();
    if (spline.patches.size() != static_cast<std::size_t>(kPs12Patches) * faces)
        throw std::invalid_argument(
            "PatchAdjacency: the spline has " + std::to_string(spline.patches.size()) +
            " patches, the layout's " + std::to_string(faces) + " faces need " +
            std::to_string(static_cast<std::size_t>(kPs12Patches) * faces));
    if (layout.cutEdge.size() != static_cast<std::size_t>(edges))
        throw std::invalid_argument("PatchAdjacency: cutEdge has " +
                                    std::to_string(layout.cutEdge.size()) + " entries for " +
                                    std::to_string(edges) + " edges");
    if (layout.isCone.size() != static_cast<std::size_t>(vertices))
        throw std::invalid_argument("PatchAdjacency: isCone has " +
                                    std::to_string(layout.isCone.size()) + " entries for " +
                                    std::to_string(vertices) + " vertices");

    const Index patches = kPs12Patches * faces;
    neighbours_.assign(static_cast<std::size_t>(patches), {});
    cornerNodes_.assign(static_cast<std::size_t>(patches), {});

    // Nodes.
    const Index nodes = vertices + edges + 4 * faces;
    nodeKind_.resize(static_cast<std::size_t>(nodes));
    nodeElement_.resize(static_cast<std::size_t>(nodes));
    coneNode_.assign(static_cast<std::size_t>(nodes), 0);
    boundaryNode_.assign(static_cast<std::size_t>(nodes), 0);
    for (Index v = 0; v < vertices; ++v) {
        nodeKind_[v] = PatchNodeKind::Vertex;
        nodeElement_[v] = v;
        coneNode_[v] = layout.isCone[v] != 0;
        boundaryNode_[v] = mesh.isBoundaryVertex(v);
    }
    for (Index e = 0; e < edges; ++e) {
        nodeKind_[vertices + e] = PatchNodeKind::EdgeMidpoint;
        nodeElement_[vertices + e] = e;
        boundaryNode_[vertices + e] = mesh.isBoundaryEdge(e);
    }
    for (Index f = 0; f < faces; ++f) {
        for (int i = 0; i < 3; ++i) {
            nodeKind_[vertices + edges + 3 * f + i] = PatchNodeKind::MedianPoint;
            nodeElement_[vertices + edges + 3 * f + i] = f;
        }
        nodeKind_[vertices + edges + 3 * faces + f] = PatchNodeKind::Centroid;
        nodeElement_[vertices + edges + 3 * faces + f] = f;
    }
    auto splitPointNode = [&](Index f, int point) -> Index {
        if (point < 3)
            return mesh.triangle(f)[point];
        if (point < 6)
            return vertices + mesh.edge(TriangleMesh::halfedge(f, point - 3));
        if (point < 9)
            return vertices + edges + 3 * f + (point - 6);
        return vertices + edges + 3 * faces + f;
    };

    // Sides inside a macro-patch: the two sub-triangles that share a pair of
    // split points (each interior sub-edge is in exactly two).
    std::map<std::pair<int, int>, std::pair<int, int>> inside;
    for (int l = 0; l < kPs12Patches; ++l)
        for (int s = 0; s < 3; ++s) {
            const int a = kSubTriangles[l][s], b = kSubTriangles[l][(s + 1) % 3];
            const auto key = std::minmax(a, b);
            auto [it, fresh] = inside.emplace(key, std::pair(l, s));
            if (!fresh) {
                for (Index f = 0; f < faces; ++f) {
                    neighbours_[kPs12Patches * f + l][s] = {kPs12Patches * f + it->second.first,
                                                            it->second.second,
                                                            PatchSideKind::MacroPatch};
                    neighbours_[kPs12Patches * f + it->second.first][it->second.second] = {
                        kPs12Patches * f + l, s, PatchSideKind::MacroPatch};
                }
            }
        }

    for (Index f = 0; f < faces; ++f) {
        for (int l = 0; l < kPs12Patches; ++l)
            for (int c = 0; c < 3; ++c)
                cornerNodes_[kPs12Patches * f + l][c] = splitPointNode(f, kSubTriangles[l][c]);
        // Across face side s: half-edge 3f+s runs V_s -> V_{s+1}; its opposite
        // 3g+s' runs V_{s+1} -> V_s, so f's first half (from V_s) meets g's
        // second half (towards V_s) and the other way round.
        for (int s = 0; s < 3; ++s) {
            const Index h = TriangleMesh::halfedge(f, s);
            const auto [l0, s0] = firstHalf(s);
            const auto [l1, s1] = secondHalf(s);
            if (mesh.isBoundary(h))
                continue; // the default: Boundary, no neighbour
            const Index o = mesh.opposite(h);
            const Index g = TriangleMesh::face(o);
            const int so = static_cast<int>(o % 3);
            const PatchSideKind kind =
                layout.cutEdge[mesh.edge(h)] ? PatchSideKind::CutEdge : PatchSideKind::MeshEdge;
            const auto [m0, t0] = firstHalf(so);
            const auto [m1, t1] = secondHalf(so);
            neighbours_[kPs12Patches * f + l0][s0] = {kPs12Patches * g + m1, t1, kind};
            neighbours_[kPs12Patches * f + l1][s1] = {kPs12Patches * g + m0, t0, kind};
        }
    }

    // Patches around every node (compressed rows).
    cornerStart_.assign(static_cast<std::size_t>(nodes) + 1, 0);
    for (const auto& c : cornerNodes_)
        for (Index n : c)
            ++cornerStart_[n + 1];
    for (Index n = 0; n < nodes; ++n)
        cornerStart_[n + 1] += cornerStart_[n];
    corners_.resize(static_cast<std::size_t>(cornerStart_[nodes]));
    std::vector<Index> fill(cornerStart_.begin(), cornerStart_.end() - 1);
    for (Index p = 0; p < patches; ++p)
        for (int c = 0; c < 3; ++c)
            corners_[fill[cornerNodes_[p][c]]++] = {p, c};
}

const PatchSideNeighbour& PatchAdjacency::neighbour(Index patch, int side) const {
    if (patch < 0 || patch >= patchCount() || side < 0 || side > 2)
        throw std::out_of_range("PatchAdjacency: side " + std::to_string(side) + " of patch " +
                                std::to_string(patch) + " (of " + std::to_string(patchCount()) +
                                ") does not exist");
    return neighbours_[patch][side];
}

Index PatchAdjacency::cornerNode(Index patch, int corner) const {
    if (patch < 0 || patch >= patchCount() || corner < 0 || corner > 2)
        throw std::out_of_range("PatchAdjacency: corner " + std::to_string(corner) + " of patch " +
                                std::to_string(patch) + " (of " + std::to_string(patchCount()) +
                                ") does not exist");
    return cornerNodes_[patch][corner];
}

Index PatchAdjacency::checkedNode(Index node) const {
    if (node < 0 || node >= nodeCount())
        throw std::out_of_range("PatchAdjacency: node " + std::to_string(node) +
                                " is out of range [0, " + std::to_string(nodeCount()) + ")");
    return node;
}

PatchNodeKind PatchAdjacency::nodeKind(Index node) const {
    return nodeKind_[checkedNode(node)];
}

Index PatchAdjacency::nodeElement(Index node) const {
    return nodeElement_[checkedNode(node)];
}

bool PatchAdjacency::isConeNode(Index node) const {
    return coneNode_[checkedNode(node)] != 0;
}

bool PatchAdjacency::isBoundaryNode(Index node) const {
    return boundaryNode_[checkedNode(node)] != 0;
}

std::span<const PatchCorner> PatchAdjacency::patchesAt(Index node) const {
    checkedNode(node);
    return std::span<const PatchCorner>(corners_).subspan(
        static_cast<std::size_t>(cornerStart_[node]),
        static_cast<std::size_t>(cornerStart_[node + 1] - cornerStart_[node]));
}

double sideParameter(const std::array<Vec2, 3>& domain, int side, const Vec2& uv) {
    if (side < 0 || side > 2)
        throw std::out_of_range("sideParameter: side " + std::to_string(side) + " is not in 0..2");
    const Vec2& a = domain[side];
    const Vec2 e = domain[(side + 1) % 3] - a;
    const double length2 = e.squaredNorm();
    if (!(length2 > 0.0))
        throw std::invalid_argument("sideParameter: side " + std::to_string(side) +
                                    " of the domain has no length");
    return (uv - a).dot(e) / length2;
}

} // namespace contour::powell_sabin
