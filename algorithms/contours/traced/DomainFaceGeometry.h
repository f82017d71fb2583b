#pragma once
// Parameter-space geometry of one domain face (SmoothSurface.h: quads are
// [0,1]^2, triangles u, v >= 0, u + v <= 1, both counter-clockwise): which
// side of an edge a point is on and where a segment leaves the face. The
// tracer works in one face's chart at a time (Summers 2016 §3.4.2).
#include "surface/SmoothSurface.h"

#include <array>

namespace contour::traced {

// The corners of a face's chart in order.
inline int cornerCount(bool quad) {
    return quad ? 4 : 3;
}

// Outward normal (not unit) of local edge `edge` (corner edge -> edge + 1):
// the edge direction turned clockwise, since faces are counter-clockwise.
inline Vec2 outwardNormal(bool quad, int edge) {
    const Vec2 a = SmoothSurface::cornerCoordinates(quad, edge);
    const Vec2 b = SmoothSurface::cornerCoordinates(quad, (edge + 1) % cornerCount(quad));
    const Vec2 d = b - a;
    return {d.y(), -d.x()};
}

// Signed distance-like value of x against edge `edge`: > 0 outside.
inline double outside(bool quad, int edge, const Vec2& x) {
    const Vec2 a = SmoothSurface::cornerCoordinates(quad, edge);
    return outwardNormal(quad, edge).dot(x - a);
}

inline bool insideFace(bool quad, const Vec2& x, double slack = 0.0) {
    for (int e = 0; e < cornerCount(quad); ++e)
        if (outside(quad, e, x) > slack)
            return false;
    return true;
}

// The point at parameter t in [0, 1] along local edge `edge`.
inline Vec2 pointOnEdge(bool quad, int edge, double t) {
    const Vec2 a = SmoothSurface::cornerCoordinates(quad, edge);
    const Vec2 b = SmoothSurface::cornerCoordinates(quad, (edge + 1) % cornerCount(quad));
    return a + t * (b - a);
}

// Where segment a -> b (a inside or on the face) first leaves it: the
// fraction s of the segment and the edge crossed; edge -1 when b is inside.
struct FaceExit {
    double s = 1.0;
    int edge = -1;
};
inline FaceExit segmentExit(bool quad, const Vec2& a, const Vec2& b) {
    FaceExit exit;
    for (int e = 0; e < cornerCount(quad); ++e) {
        const double da = outside(quad, e, a), db = outside(quad, e, b);
        if (db <= 0.0 || db <= da)
            continue;
        const double s = da >= 0.0 ? 0.0 : -da / (db - da);
        if (s < exit.s || exit.edge < 0) {
            exit.s = s;
            exit.edge = e;
        }
    }
    return exit;
}

} // namespace contour::traced
