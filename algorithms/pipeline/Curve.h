#pragma once
// Curves on the working mesh: what the contour methods extract and the view
// graph cuts into visibility pieces.
#include "core/Types.h"

#include <vector>

namespace contour {

enum class CurveType { Contour, Boundary, SurfaceIntersection };
const char* toString(CurveType type);

// A point of a curve, with the mesh element it lies on: a vertex (mesh
// contours) or a point at parameter t along an edge (interpolated contours).
struct CurvePoint {
    Vec3 position;
    Index vertex = kInvalidIndex;
    Index edge = kInvalidIndex;
    double t = 0.0;
};

enum class SegmentSource { MeshEdge, Face };

struct Polyline {
    CurveType type = CurveType::Contour;
    bool closed = false;
    std::vector<CurvePoint> points;
    // Per segment i (points i -> i+1, and last -> first when closed): the mesh
    // element it comes from, an edge or a face according to `source`.
    SegmentSource source = SegmentSource::MeshEdge;
    std::vector<Index> segmentElement;
    // The points lie on a smooth surface, not on the working mesh's edges
    // (traced contours, Summers 2016): segmentElement names the face each
    // segment lies over, and two segments meet on the surface only where
    // they are consecutive on one curve, not where their faces touch.
    bool offMesh = false;

    size_t segmentCount() const {
        return points.size() < 2 ? 0 : closed ? points.size() : points.size() - 1;
    }
};

} // namespace contour
