#pragma once
// Ray tests for quantitative invisibility (tutorial §4.4, app. C.1; Bénard
// 2014 §8.4): the number of mesh faces between a point of a curve and the
// camera. One Embree scene of the mesh's triangles; every crossing is counted
// through an intersection filter that records the face and rejects the hit,
// so traversal goes on to the far end of the segment.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"

#include <memory>
#include <span>
#include <vector>

namespace contour {

// One ray test's result, kept to be reused by a later stage that needs the
// same ray (same point, same ignored faces): the count and the faces hit, as
// RayCaster::occluders returns them. count < 0: no ray was cast.
struct RayResult {
    int count = -1;
    std::vector<Index> hits;
};

class RayCaster {
public:
    explicit RayCaster(const TriangleMesh& mesh); // one Embree scene
    ~RayCaster();
    RayCaster(const RayCaster&) = delete;
    RayCaster& operator=(const RayCaster&) = delete;

    // Faces crossing the open segment from p towards the camera (perspective: up to the eye;
    // orthographic: along camera.toCamera(p) past the scene), each face counted once,
    // ignoring the faces in `ignore`. Optionally returns the faces hit.
    // Thread-safe: each call has its own traversal context.
    int occluders(const Vec3& p, const Camera& camera, std::span<const Index> ignore,
                  std::vector<Index>* hits = nullptr) const;

    // The same count over every face with exact predicates only (no
    // Embree): O(faces), for re-checking a ray test that disagrees with
    // propagation (a float ray can still slip past a fold edge it grazes).
    int exactOccluders(const Vec3& p, const Camera& camera, std::span<const Index> ignore) const;

    // Faces that come within this distance of p (a small fraction of the
    // scene's diagonal) are tested with exact predicates in double precision
    // instead of Embree's single-precision traversal: rays from contour
    // points graze the surface next to them, where float rounding misses or
    // invents crossings (seen on the consistent meshes' tiny edges).
    double nearEpsilon() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace contour
