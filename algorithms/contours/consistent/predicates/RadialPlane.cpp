#include "contours/consistent/predicates/RadialPlane.h"

namespace contour::consistent {

double radialPlane(const Camera& camera, const MeshVertex& p, const Vec3& q) {
    return p.normal.cross(camera.toCamera(p.position)).dot(q - p.position);
}

double radialPlaneSine(const Camera& camera, const MeshVertex& p, const Vec3& q) {
    const Vec3 axis = p.normal.cross(camera.toCamera(p.position));
    const double scale = axis.norm() * (q - p.position).norm();
    return scale > 0.0 ? axis.dot(q - p.position) / scale : 0.0;
}

} // namespace contour::consistent
