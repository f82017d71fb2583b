#pragma once
// Half-edge triangle mesh with an implicit layout: the half-edges of face f are
// 3f, 3f+1, 3f+2, and half-edge 3f+i runs from corner i to corner i+1. Only the
// opposite links are stored. Boundary half-edges have no opposite (kInvalidIndex).
// The mesh is immutable after construction; snapshots share it between phases.
#include "core/Types.h"

#include <array>
#include <span>
#include <vector>

namespace contour {

using Triangle = std::array<Index, 3>;

class TriangleMesh {
public:
    TriangleMesh() = default;
    // Preconditions (checked by MeshValidation before any mesh reaches here):
    // indices in range, no degenerate index triple, every edge manifold and
    // consistently oriented. Violations throw std::invalid_argument.
    TriangleMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
                 std::vector<Index> sourcePolygon = {});

    // The same connectivity with other vertex positions (one per vertex),
    // without rebuilding the half-edges: a surface re-evaluated per view.
    // Throws std::invalid_argument when the count differs.
    TriangleMesh withPositions(std::vector<Vec3> positions) const;

    Index vertexCount() const { return static_cast<Index>(positions_.size()); }
    Index faceCount() const { return static_cast<Index>(triangles_.size()); }
    Index halfedgeCount() const { return 3 * faceCount(); }
    Index edgeCount() const { return static_cast<Index>(edgeHalfedge_.size()); }

    const Vec3& position(Index v) const { return positions_[v]; }
    std::span<const Vec3> positions() const { return positions_; }
    const Triangle& triangle(Index f) const { return triangles_[f]; }
    std::span<const Triangle> triangles() const { return triangles_; }
    // Polygon of the loaded control cage this triangle came from.
    Index sourcePolygon(Index f) const { return sourcePolygon_.empty() ? f : sourcePolygon_[f]; }

    // Half-edge navigation.
    static Index halfedge(Index f, int corner) { return 3 * f + corner; }
    static Index face(Index h) { return h / 3; }
    static Index next(Index h) { return h % 3 == 2 ? h - 2 : h + 1; }
    static Index prev(Index h) { return h % 3 == 0 ? h + 2 : h - 1; }
    Index from(Index h) const { return triangles_[h / 3][h % 3]; }
    Index to(Index h) const { return triangles_[h / 3][(h % 3 + 1) % 3]; }
    Index opposite(Index h) const { return opposite_[h]; }
    bool isBoundary(Index h) const { return opposite_[h] == kInvalidIndex; }
    Index edge(Index h) const { return halfedgeEdge_[h]; }
    // The half-edge an edge is stored with (for a boundary edge, its only one).
    Index edgeHalfedge(Index e) const { return edgeHalfedge_[e]; }
    bool isBoundaryEdge(Index e) const { return isBoundary(edgeHalfedge_[e]); }
    // An outgoing half-edge of v; for a boundary vertex the one whose
    // opposite is missing, so that rotate() visits every incident face.
    Index vertexHalfedge(Index v) const { return vertexHalfedge_[v]; }
    bool isBoundaryVertex(Index v) const;
    // Next outgoing half-edge around from(h) (counter-clockwise seen from
    // outside), kInvalidIndex at a boundary.
    Index rotate(Index h) const {
        const Index o = opposite_[prev(h)];
        return o;
    }

    Vec3 faceNormal(Index f) const;     // unit
    Vec3 faceAreaNormal(Index f) const; // (b-a)x(c-a), length = 2 * area
    BoundingBox boundingBox() const;
    Index boundaryEdgeCount() const { return boundaryEdgeCount_; }

private:
    std::vector<Vec3> positions_;
    std::vector<Triangle> triangles_;
    std::vector<Index> sourcePolygon_;
    std::vector<Index> opposite_;
    std::vector<Index> halfedgeEdge_;
    std::vector<Index> edgeHalfedge_;
    std::vector<Index> vertexHalfedge_;
    Index boundaryEdgeCount_ = 0;
};

} // namespace contour
