#include "contours/BoundaryCurves.h"

#include "contours/ContourChaining.h"

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
    std::vector<ChainSegment> segments;
    for (Index e : boundaryEdges(mesh)) {
        const Index h = mesh.edgeHalfedge(e);
        segments.push_back({mesh.from(h), mesh.to(h), e});
    }
    std::vector<Polyline> lines;
    for (const Chain& chain : chainSegments(segments, mesh.vertexCount())) {
        Polyline line;
        line.type = CurveType::Boundary;
        line.closed = chain.closed;
        line.source = SegmentSource::MeshEdge;
        for (Index v : chain.nodes)
            line.points.push_back({mesh.position(v), v, kInvalidIndex, 0.0});
        for (Index s : chain.segments)
            line.segmentElement.push_back(segments[s].element);
        lines.push_back(std::move(line));
    }
    return lines;
}

} // namespace contour
