#include "visibility/NearFaceTest.h"

#include <cmath>

namespace contour {

NearFace nearFace(const TriangleMesh& mesh, const Camera& camera, Index edge) {
    const Index h = mesh.edgeHalfedge(edge);
    const Index o = mesh.opposite(h);
    if (o == kInvalidIndex)
        return {};
    const Vec3& a = mesh.position(mesh.from(h));
    const Vec3& b = mesh.position(mesh.to(h));
    const Vec3 m = 0.5 * (a + b);
    const Vec3 v = camera.toCamera(m).normalized();
    auto inFace = [&](Index he) -> Vec3 {
        const Vec3& apex = mesh.position(mesh.to(TriangleMesh::next(he)));
        const Vec3 n = mesh.faceNormal(TriangleMesh::face(he));
        Vec3 w = v - v.dot(n) * n;
        // v along the face normal: the face is seen flat on and has no
        // in-face direction; it then never counts as the near one.
        if (w.norm() < 1e-12)
            return Vec3::Zero();
        w.normalize();
        return w.dot(apex - m) < 0.0 ? Vec3(-w) : w;
    };
    const double d = v.dot(inFace(h) - inFace(o));
    return {d > 0.0 ? TriangleMesh::face(h) : TriangleMesh::face(o), std::abs(d)};
}

} // namespace contour
