#include "mesh/TriangleMesh.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace contour {

namespace {
struct DirectedEdge {
    Index low, high, halfedge;
    bool operator<(const DirectedEdge& o) const {
        return low != o.low ? low < o.low : high != o.high ? high < o.high : halfedge < o.halfedge;
    }
};
} // namespace

TriangleMesh TriangleMesh::withPositions(std::vector<Vec3> positions) const {
    if (positions.size() != positions_.size())
        throw std::invalid_argument(
            "TriangleMesh::withPositions: " + std::to_string(positions.size()) + " positions for " +
            std::to_string(positions_.size()) + " vertices");
    TriangleMesh out = *this;
    out.positions_ = std::move(positions);
    return out;
}

TriangleMesh::TriangleMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
                           std::vector<Index> sourcePolygon)
    : positions_(std::move(positions)), triangles_(std::move(triangles)),
      sourcePolygon_(std::move(sourcePolygon)) {
    const Index nv = vertexCount();
    const Index nh = halfedgeCount();
    if (!sourcePolygon_.empty() && static_cast<Index>(sourcePolygon_.size()) != faceCount())
        throw std::invalid_argument("sourcePolygon must have one entry per triangle");
    for (Index f = 0; f < faceCount(); ++f) {
        const Triangle& t = triangles_[f];
        for (Index v : t)
            if (v < 0 || v >= nv)
                throw std::invalid_argument("triangle " + std::to_string(f) +
                                            " has an out-of-range vertex index");
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            throw std::invalid_argument("triangle " + std::to_string(f) + " repeats a vertex");
    }

    // Pair half-edges by sorting undirected keys, no hash map: bucketed by
    // the lower vertex (counting sort), then each small bucket sorted; the
    // same order as one std::sort of all keys, in O(n) for bounded valence.
    std::vector<DirectedEdge> keys(nh);
    std::vector<Index> bucketStart(static_cast<size_t>(nv) + 1, 0);
    for (Index h = 0; h < nh; ++h)
        ++bucketStart[static_cast<size_t>(std::min(from(h), to(h))) + 1];
    for (size_t v = 0; v < static_cast<size_t>(nv); ++v)
        bucketStart[v + 1] += bucketStart[v];
    {
        std::vector<Index> next(bucketStart.begin(), bucketStart.end() - 1);
        for (Index h = 0; h < nh; ++h) {
            const Index a = from(h), b = to(h);
            keys[static_cast<size_t>(next[static_cast<size_t>(std::min(a, b))]++)] = {
                std::min(a, b), std::max(a, b), h};
        }
    }
    for (size_t v = 0; v < static_cast<size_t>(nv); ++v)
        std::sort(keys.begin() + bucketStart[v], keys.begin() + bucketStart[v + 1]);
    opposite_.assign(nh, kInvalidIndex);
    halfedgeEdge_.assign(nh, kInvalidIndex);
    edgeHalfedge_.reserve(nh / 2 + 1);
    for (size_t i = 0; i < keys.size();) {
        size_t j = i + 1;
        while (j < keys.size() && keys[j].low == keys[i].low && keys[j].high == keys[i].high)
            ++j;
        const Index h0 = keys[i].halfedge;
        if (j - i > 2)
            throw std::invalid_argument("edge (" + std::to_string(keys[i].low) + ", " +
                                        std::to_string(keys[i].high) + ") is non-manifold");
        const Index e = static_cast<Index>(edgeHalfedge_.size());
        halfedgeEdge_[h0] = e;
        if (j - i == 2) {
            const Index h1 = keys[i + 1].halfedge;
            if (from(h0) == from(h1))
                throw std::invalid_argument("faces " + std::to_string(face(h0)) + " and " +
                                            std::to_string(face(h1)) +
                                            " are inconsistently oriented");
            opposite_[h0] = h1;
            opposite_[h1] = h0;
            halfedgeEdge_[h1] = e;
        } else {
            ++boundaryEdgeCount_;
        }
        edgeHalfedge_.push_back(h0);
        i = j;
    }

    vertexHalfedge_.assign(nv, kInvalidIndex);
    for (Index h = 0; h < nh; ++h) {
        const Index v = from(h);
        if (vertexHalfedge_[v] == kInvalidIndex || opposite_[h] == kInvalidIndex)
            vertexHalfedge_[v] = h;
    }
}

bool TriangleMesh::isBoundaryVertex(Index v) const {
    const Index h = vertexHalfedge_[v];
    return h == kInvalidIndex || opposite_[h] == kInvalidIndex;
}

Vec3 TriangleMesh::faceAreaNormal(Index f) const {
    const Triangle& t = triangles_[f];
    return (positions_[t[1]] - positions_[t[0]]).cross(positions_[t[2]] - positions_[t[0]]);
}

Vec3 TriangleMesh::faceNormal(Index f) const {
    return faceAreaNormal(f).normalized();
}

BoundingBox TriangleMesh::boundingBox() const {
    BoundingBox box;
    for (const Vec3& p : positions_)
        box.extend(p);
    return box;
}

} // namespace contour
