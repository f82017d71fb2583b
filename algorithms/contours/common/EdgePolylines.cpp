#include "contours/common/EdgePolylines.h"

#include "contours/common/BoundaryCurves.h"
#include "contours/common/ContourChaining.h"

namespace contour {

std::vector<Polyline> edgePolylines(const TriangleMesh& mesh, std::span<const Index> edges,
                                    CurveType type) {
    std::vector<ChainSegment> segments;
    segments.reserve(edges.size());
    for (Index e : edges) {
        const Index h = mesh.edgeHalfedge(e);
        segments.push_back({mesh.from(h), mesh.to(h), e});
    }
    std::vector<Polyline> lines;
    for (const Chain& chain : chainSegments(segments, mesh.vertexCount())) {
        Polyline line;
        line.type = type;
        line.closed = chain.closed;
        line.source = SegmentSource::MeshEdge;
        for (Index v : chain.nodes)
            line.points.push_back({mesh.position(v), v, kInvalidIndex, 0.0});
        for (Index seg : chain.segments)
            line.segmentElement.push_back(segments[seg].element);
        lines.push_back(std::move(line));
    }
    return lines;
}

void publishCurves(Snapshot& s, std::vector<Polyline> contours, bool includeBoundaries) {
    long long loops = 0;
    for (const Polyline& line : contours)
        loops += line.closed;
    s.setCounter(counters::kContourChains, static_cast<double>(contours.size()));
    s.setCounter(counters::kClosedLoops, static_cast<double>(loops));
    s.setCounter(counters::kOpenChains, static_cast<double>(contours.size() - loops));
    if (includeBoundaries) {
        std::vector<Polyline> boundary = boundaryPolylines(*s.mesh);
        s.setCounter(counters::kBoundaryCurves, static_cast<double>(boundary.size()));
        contours.insert(contours.end(), std::make_move_iterator(boundary.begin()),
                        std::make_move_iterator(boundary.end()));
    }
    s.curves = std::make_shared<const std::vector<Polyline>>(std::move(contours));
}

} // namespace contour
