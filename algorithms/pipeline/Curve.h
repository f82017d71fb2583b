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

// A cusp found on the curve itself (traced contours: the radial curvature
// changes sign along it, Bénard 2014 §6.2 d): at parameter tau of segment
// `segment`, with the radial curvature of the curve just before and just
// after it (the sign convention of SurfaceFields.h). The view-graph builder
// makes it a curtain fold of the smooth surface.
struct CurveCusp {
    Index segment = 0;
    double tau = 0.0;
    double kappaBefore = 0.0, kappaAfter = 0.0;
};

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
    // Cusps known on the curve, in order along it (empty for curves whose
    // cusps are mesh vertices).
    std::vector<CurveCusp> cusps;

    size_t segmentCount() const {
        return points.size() < 2 ? 0 : closed ? points.size() : points.size() - 1;
    }
};

} // namespace contour
