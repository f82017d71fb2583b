#pragma once
// Exact geometric predicates that decide topology (docs/dev/conventions.md).
// Backed by CGAL's filtered exact predicates; kept in one .cpp so CGAL's
// templates compile once.
#include "core/Types.h"

namespace contour {

// Sign of det[b-a, c-a, d-a]: +1 when d lies on the side that the normal
// (b-a) x (c-a) points to, -1 on the other side, 0 when coplanar. Equals
// the tutorial's FRONTSIDE(a, b, c, d) (appendix C) and -ORIENT3D.
int frontSide(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Sign of det[b-a, c-a, direction]: the orthographic counterpart of
// frontSide(), with the camera at infinity along `direction`.
int frontSideOfDirection(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& direction);

// Sign of the 2D orientation of (a, b, c): +1 counter-clockwise.
int orientation2d(const Vec2& a, const Vec2& b, const Vec2& c);

// True when a, b, c are exactly collinear (a degenerate triangle).
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace contour
