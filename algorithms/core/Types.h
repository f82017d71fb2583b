#pragma once
// Basic types shared by every algorithm module.
#include <Eigen/Core>
#include <Eigen/Geometry> // cross products
#include <cstdint>
#include <limits>

namespace contour {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Index = std::int32_t;
inline constexpr Index kInvalidIndex = -1;

struct BoundingBox {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

    void extend(const Vec3& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
    bool isEmpty() const { return (max.array() < min.array()).any(); }
    Vec3 center() const { return 0.5 * (min + max); }
    double diagonal() const { return isEmpty() ? 0.0 : (max - min).norm(); }
};

} // namespace contour
