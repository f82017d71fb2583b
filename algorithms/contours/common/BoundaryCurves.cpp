#include "contours/common/BoundaryCurves.h"

#include "contours/common/EdgePolylines.h"

namespace contour {

std::vector<Index> boundaryEdges(const TriangleMesh& mesh) {
    std::vector<Index> edges;
    if (mesh.boundaryEdgeCount() == 0)
        return edges;
    edges.reserve(mesh.boundaryEdgeCount());
    for (Index e = 0; e < mesh.edgeCount(); ++e)
        if (mesh.isBoundaryEdge(e))
            edges.push_back(e);
    return edges;
}

std::vector<Polyline> boundaryPolylines(const TriangleMesh& mesh) {
    return edgePolylines(mesh, boundaryEdges(mesh), CurveType::Boundary);
}

} // namespace contour
