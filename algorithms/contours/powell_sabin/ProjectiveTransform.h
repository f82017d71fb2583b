#pragma once
// The view transform of the Powell-Sabin method (Capouellez et al. 2023 §3):
// a perspective view becomes orthographic along +z after the camera-space map
// [x, y, d] -> [x/d, y/d, -1/d] (d > 0 the depth in front of the eye), which
// keeps depth order and orientation (its Jacobian determinant is 1/d^4). The
// spline is fitted to the transformed vertices, so the surface is
// view-dependent, as in the paper. Orthographic views are rigid: camera
// coordinates [x, y, d] with the same viewing direction.
#include "camera/Camera.h"

#include <Eigen/Core>

namespace contour::powell_sabin {

class ProjectiveTransform {
public:
    explicit ProjectiveTransform(const Camera& camera);
    bool isPerspective() const { return perspective_; }
    // World point -> transformed point; the view is then along +z.
    Vec3 apply(const Vec3& world) const;
    // Transformed point -> world point (d = -1/z must be positive).
    Vec3 invert(const Vec3& transformed) const;
    // d invert / d transformed at `transformed` (to map tangents back).
    Eigen::Matrix3d inverseJacobian(const Vec3& transformed) const;

private:
    Vec3 eye_, right_, up_, forward_;
    bool perspective_ = true;
};

} // namespace contour::powell_sabin
