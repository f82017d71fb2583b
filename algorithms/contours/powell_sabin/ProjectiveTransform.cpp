#include "contours/powell_sabin/ProjectiveTransform.h"

namespace contour::powell_sabin {

ProjectiveTransform::ProjectiveTransform(const Camera& camera)
    : eye_(camera.eye), right_(camera.right()), up_(camera.trueUp()), forward_(camera.forward()),
      perspective_(!camera.isOrthographic()) {}

Vec3 ProjectiveTransform::apply(const Vec3& world) const {
    const Vec3 d = world - eye_;
    const Vec3 c(d.dot(right_), d.dot(up_), d.dot(forward_));
    if (!perspective_)
        return c;
    return Vec3(c.x() / c.z(), c.y() / c.z(), -1.0 / c.z());
}

Vec3 ProjectiveTransform::invert(const Vec3& t) const {
    Vec3 c = t;
    if (perspective_) {
        const double depth = -1.0 / t.z();
        c = Vec3(t.x() * depth, t.y() * depth, depth);
    }
    return eye_ + c.x() * right_ + c.y() * up_ + c.z() * forward_;
}

Eigen::Matrix3d ProjectiveTransform::inverseJacobian(const Vec3& t) const {
    Eigen::Matrix3d frame;
    frame << right_, up_, forward_;
    if (!perspective_)
        return frame;
    // c = (x d, y d, d) with d = -1/z: dc/dt.
    const double depth = -1.0 / t.z();
    const double dDepth = 1.0 / (t.z() * t.z());
    Eigen::Matrix3d dc;
    dc << depth, 0.0, t.x() * dDepth, 0.0, depth, t.y() * dDepth, 0.0, 0.0, dDepth;
    return frame * dc;
}

} // namespace contour::powell_sabin
