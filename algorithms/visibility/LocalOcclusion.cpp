#include "visibility/LocalOcclusion.h"

#include "core/Predicates.h"

namespace contour {

int cameraPlaneSide(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& x) {
    if (!camera.isOrthographic())
        return frontSide(a, b, camera.eye, x);
    // Plane through a, b, parallel to the view direction d: sign of
    // det[b − a, d, x − a] = −det[b − a, x − a, d].
    return -frontSideOfDirection(a, b, x, camera.toCamera(a));
}

int cameraSideOfTriangle(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& c) {
    if (!camera.isOrthographic())
        return frontSide(a, b, c, camera.eye);
    return frontSideOfDirection(a, b, c, camera.toCamera(a));
}

namespace {
bool sameSide(int s, int t) {
    return (s > 0) == (t > 0);
}
} // namespace

bool oneRingFaceOccludes(const Camera& camera, const Vec3& p, const Vec3& q, const Vec3& r,
                         const Vec3& e) {
    // 1. The face's plane separates the camera from e.
    if (sameSide(cameraSideOfTriangle(camera, p, q, r), frontSide(p, q, r, e)))
        return false;
    // 2.–3. Seen from the camera, e lies inside the face's angle at p.
    return sameSide(cameraPlaneSide(camera, p, q, e), cameraPlaneSide(camera, p, q, r)) &&
           sameSide(cameraPlaneSide(camera, p, r, e), cameraPlaneSide(camera, p, r, q));
}

std::vector<Index> vertexFaces(const TriangleMesh& mesh, Index v) {
    std::vector<Index> faces;
    const Index start = mesh.vertexHalfedge(v);
    if (start == kInvalidIndex)
        return faces;
    Index h = start;
    do {
        faces.push_back(TriangleMesh::face(h));
        h = mesh.rotate(h);
    } while (h != kInvalidIndex && h != start);
    return faces;
}

int oneRingOccluders(const TriangleMesh& mesh, const Camera& camera, Index p, Index e) {
    int count = 0;
    for (Index f : vertexFaces(mesh, p)) {
        const Triangle& t = mesh.triangle(f);
        if (t[0] == e || t[1] == e || t[2] == e)
            continue;
        // Rotate the face so that it reads (p, q, r) counter-clockwise.
        const int k = t[0] == p ? 0 : t[1] == p ? 1 : 2;
        const Vec3& q = mesh.position(t[(k + 1) % 3]);
        const Vec3& r = mesh.position(t[(k + 2) % 3]);
        count += oneRingFaceOccludes(camera, mesh.position(p), q, r, mesh.position(e));
    }
    return count;
}

} // namespace contour
