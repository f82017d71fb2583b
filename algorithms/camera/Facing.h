#pragma once
// The single definition of facing in the code base (docs/dev/conventions.md,
// Bénard 2014 §3): g(p) = (c - p) · n with outward normals; g > 0 is
// front-facing. The tutorial flips this sign in §3.7.2, §6.2.1 and §7.2
// (notes, errata 1); do not copy its formulas' signs.
#include "camera/Camera.h"

#include <cstdint>

namespace contour {

enum class Facing : std::int8_t { Back = -1, EdgeOn = 0, Front = 1 };

// g = (c - p) · n for a point p with normal n (orthographic: (eye - target) · n).
inline double facingFunction(const Camera& camera, const Vec3& p, const Vec3& n) {
    return camera.toCamera(p).dot(n);
}

// Exact facing of triangle (a, b, c) with normal (b-a) x (c-a): the sign of
// the orientation of the camera against the triangle's plane.
Facing triangleFacing(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace contour
