#pragma once
// The edges of a polygon mesh, found from its corners: the half-edge of
// corner c runs from indices[c] to the next corner of the same face, and the
// half-edges along one undirected edge are grouped. Validation (manifold and
// orientation checks) and the orientation report read the same grouping.
#include "mesh/PolygonMesh.h"

#include <span>
#include <vector>

namespace contour {

struct PolygonEdges {
    std::vector<Index> cornerFace; // the face of each corner
    std::vector<Index> next;       // the next corner around the same face
    // The half-edges (corners) along edge e are corners[start[e] ..
    // start[e + 1]), in increasing order; edges are ordered by their lower
    // vertex, then their upper one.
    std::vector<Index> start{0};
    std::vector<Index> corners;

    Index edgeCount() const { return static_cast<Index>(start.size()) - 1; }
    std::span<const Index> halfedges(Index e) const {
        return {corners.data() + start[e], static_cast<size_t>(start[e + 1] - start[e])};
    }
};

// Linear time in practice (counting sort by lower vertex, then a sort of each
// small bucket). Precondition: every face index is in [0, vertexCount).
PolygonEdges polygonEdges(const PolygonMesh& mesh);

} // namespace contour
