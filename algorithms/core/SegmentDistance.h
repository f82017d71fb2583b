#pragma once
// The distance from a point to a segment in the plane (images, parameter
// charts).
#include "core/Types.h"

#include <algorithm>

namespace contour {

inline double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

} // namespace contour
