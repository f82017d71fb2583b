#pragma once
// The radial plane of a contour point (Bénard 2014 §5):
// h_p(q) = (n_p × (c - p)) · (q - p); it contains p, the view ray through p
// and the normal, so its trace on the surface runs across the contour.
#include "camera/Camera.h"
#include "contours/consistent/mesh/ConsistentMesh.h"

namespace contour::consistent {

// h_p(q) for the contour vertex p.
double radialPlane(const Camera& camera, const MeshVertex& p, const Vec3& q);

// h_p(q) / (|n_p × (c - p)| |q - p|): the sine of the angle between p-q and
// the radial plane (0 when q lies on it).
double radialPlaneSine(const Camera& camera, const MeshVertex& p, const Vec3& q);

} // namespace contour::consistent
