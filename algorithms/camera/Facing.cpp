#include "camera/Facing.h"

#include "core/Predicates.h"

namespace contour {

Facing triangleFacing(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int s = camera.isOrthographic()
                      ? frontSideOfDirection(a, b, c, camera.eye - camera.target)
                      : frontSide(a, b, c, camera.eye);
    return static_cast<Facing>(s);
}

} // namespace contour
