#pragma once
// Exact local visibility predicates of the tutorial's appendix C.2, written
// against the camera (perspective: the eye; orthographic: the point at
// infinity along the view direction), on the exact orientation predicates of
// geometry/Predicates.h.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"

#include <vector>

namespace contour {

// Side of x with respect to the plane through a, b and the camera: +1, -1,
// or 0 on the plane. Only comparisons of two results are meaningful
// (SAMESIDE(a, b, cam, x, y) = both > 0 or both ≤ 0).
int cameraPlaneSide(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& x);

// Side of the camera with respect to the plane of triangle (a, b, c):
// FRONTSIDE(a, b, c, cam), +1 on the side its normal points to.
int cameraSideOfTriangle(const Camera& camera, const Vec3& a, const Vec3& b, const Vec3& c);

// Tutorial app. C.2, boundary curtain fold test, used for every curve edge at
// a vertex: face (p, q, r) of p's one-ring occludes the edge p→e next to p
// iff SAMESIDE(p, q, r, cam, e) is false, SAMESIDE(cam, p, q, e, r) and
// SAMESIDE(cam, p, r, e, q) are true.
bool oneRingFaceOccludes(const Camera& camera, const Vec3& p, const Vec3& q, const Vec3& r,
                         const Vec3& e);

// The faces around vertex v (its one-ring), each once.
std::vector<Index> vertexFaces(const TriangleMesh& mesh, Index v);

// How many faces of p's one-ring occlude the mesh edge p→e next to p (faces
// that contain e are the edge's own faces and never occlude it).
int oneRingOccluders(const TriangleMesh& mesh, const Camera& camera, Index p, Index e);

} // namespace contour
