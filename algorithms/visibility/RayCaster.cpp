#include "visibility/RayCaster.h"

#include "core/Predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <embree3/rtcore.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace contour {

namespace {

// The traversal context handed to the filter: Embree passes the
// RTCIntersectContext pointer through, so it is the first member.
struct CountingContext {
    RTCIntersectContext context;
    std::span<const Index> ignore;
    std::vector<Index>* faces;
    const std::vector<Index>* near; // sorted: tested exactly, not by Embree
};

// Records every face the ray crosses and rejects the hit (valid = 0), so
// Embree keeps traversing up to tfar instead of stopping at the closest hit
// (tutorial §4.4: QI = the number of surfaces between the point and the eye).
void countingFilter(const RTCFilterFunctionNArguments* args) {
    auto* counting = reinterpret_cast<CountingContext*>(args->context);
    for (unsigned int i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1)
            continue;
        const auto face = static_cast<Index>(RTCHitN_primID(args->hit, args->N, i));
        args->valid[i] = 0;
        if (std::find(counting->ignore.begin(), counting->ignore.end(), face) !=
                counting->ignore.end() ||
            std::binary_search(counting->near->begin(), counting->near->end(), face))
            continue;
        counting->faces->push_back(face);
    }
}

bool collectFace(RTCPointQueryFunctionArguments* args) {
    static_cast<std::vector<Index>*>(args->userPtr)->push_back(static_cast<Index>(args->primID));
    return false;
}

// Tutorial app. C.2: the open segment p–eye crosses triangle abc iff p and
// the eye lie strictly on opposite sides of its plane and the line through
// them passes strictly inside its three edges (exact orientation signs).
// Orthographic: the eye is the point at infinity along `direction`.
bool crossesExactly(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p,
                    const Camera& camera) {
    const int sp = frontSide(a, b, c, p);
    if (sp == 0)
        return false;
    if (camera.isOrthographic()) {
        const Vec3 d = camera.toCamera(p);
        if (frontSideOfDirection(a, b, c, d) != -sp)
            return false;
        const int o1 = frontSideOfDirection(p, a, b, d);
        const int o2 = frontSideOfDirection(p, b, c, d);
        const int o3 = frontSideOfDirection(p, c, a, d);
        return o1 != 0 && o1 == o2 && o2 == o3;
    }
    if (frontSide(a, b, c, camera.eye) != -sp)
        return false;
    const int o1 = frontSide(p, camera.eye, a, b);
    const int o2 = frontSide(p, camera.eye, b, c);
    const int o3 = frontSide(p, camera.eye, c, a);
    return o1 != 0 && o1 == o2 && o2 == o3;
}

} // namespace

struct RayCaster::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    double nearEpsilon = 0.0;
    double sceneExtent = 1.0;
    Vec3 sceneCenter = Vec3::Zero();
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
};

RayCaster::RayCaster(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        throw std::runtime_error("Embree: cannot create a device (error " +
                                 std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) +
                                 ")");
    impl_->scene = rtcNewScene(impl_->device);
    // Robust traversal: a ray through a shared edge or vertex must not slip
    // between the two faces (a missed occluder changes QI by one).
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
    // Medium quality: the scene is built per view (consistent meshes change
    // with the camera) and serves a few hundred rays, so build time dominates.
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_MEDIUM);

    const BoundingBox box = mesh.boundingBox();
    impl_->sceneExtent = std::max(box.diagonal(), 1e-12);
    impl_->sceneCenter = box.isEmpty() ? Vec3::Zero() : box.center();
    // Float geometry carries a relative rounding of ~6e-8 of the
    // coordinates' magnitude; within 1e-4 of the scene's size of p the
    // faces are tested exactly.
    impl_->nearEpsilon = 1e-4 * (impl_->sceneExtent + impl_->sceneCenter.norm());
    impl_->positions.assign(mesh.positions().begin(), mesh.positions().end());
    impl_->triangles.assign(mesh.triangles().begin(), mesh.triangles().end());

    if (mesh.faceCount() > 0) {
        RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    3 * sizeof(float), static_cast<size_t>(mesh.vertexCount())));
        for (Index v = 0; v < mesh.vertexCount(); ++v) {
            const Vec3& p = mesh.position(v);
            for (int k = 0; k < 3; ++k)
                vertices[3 * v + k] = static_cast<float>(p[k]);
        }
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), static_cast<size_t>(mesh.faceCount())));
        for (Index f = 0; f < mesh.faceCount(); ++f)
            for (int k = 0; k < 3; ++k)
                indices[3 * f + k] = static_cast<unsigned>(mesh.triangle(f)[k]);
        rtcSetGeometryIntersectFilterFunction(geometry, countingFilter);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(impl_->scene, geometry);
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(impl_->scene);
}

RayCaster::~RayCaster() {
    if (impl_->scene)
        rtcReleaseScene(impl_->scene);
    if (impl_->device)
        rtcReleaseDevice(impl_->device);
}

int RayCaster::exactOccluders(const Vec3& p, const Camera& camera,
                              std::span<const Index> ignore) const {
    // Conservative pre-filter (same count; on a 119k-face consistent mesh
    // the 7 recounts of a view took ~40 ms of the phase without it, issue
    // 5's timing). A face crossed by
    // the segment p–eye (or ray p + t·d) contains a point z of it, so its
    // vertices cannot all lie strictly on one side of a plane through that
    // line. Two such planes, normals u, v ⟂ d in floating point: the
    // rounding of u·d (|u·d| ≤ ~1e-16 |d|) and of (x − p)·u is below
    // `margin` by six orders of magnitude, so a face skipped here is one
    // crossesExactly would reject.
    const Vec3 toEye = camera.toCamera(p);
    const double length = toEye.norm();
    std::vector<std::uint8_t> side; // per vertex: bits 0-3 = u>m, u<-m, v>m, v<-m
    if (length > 0.0 && std::isfinite(length)) {
        const Vec3 d = toEye / length;
        const int axis = std::abs(d.x()) < std::abs(d.y())
                             ? (std::abs(d.x()) < std::abs(d.z()) ? 0 : 2)
                             : (std::abs(d.y()) < std::abs(d.z()) ? 1 : 2);
        const Vec3 u = d.cross(Vec3::Unit(axis)).normalized();
        const Vec3 v = d.cross(u).normalized();
        const double reach = impl_->sceneExtent + impl_->sceneCenter.norm() + p.norm() +
                             (camera.isOrthographic() ? 0.0 : length);
        const double margin = 1e-9 * reach;
        side.resize(impl_->positions.size());
        for (size_t i = 0; i < impl_->positions.size(); ++i) {
            const Vec3 x = impl_->positions[i] - p;
            const double su = x.dot(u), sv = x.dot(v);
            side[i] = static_cast<std::uint8_t>((su > margin) | ((su < -margin) << 1) |
                                                ((sv > margin) << 2) | ((sv < -margin) << 3));
        }
    }
    int count = 0;
    for (size_t f = 0; f < impl_->triangles.size(); ++f) {
        const Triangle& t = impl_->triangles[f];
        if (!side.empty() && (side[t[0]] & side[t[1]] & side[t[2]]) != 0)
            continue;
        if (crossesExactly(impl_->positions[t[0]], impl_->positions[t[1]], impl_->positions[t[2]],
                           p, camera) &&
            std::find(ignore.begin(), ignore.end(), static_cast<Index>(f)) == ignore.end())
            ++count;
    }
    return count;
}

double RayCaster::nearEpsilon() const {
    return impl_->nearEpsilon;
}

int RayCaster::occluders(const Vec3& p, const Camera& camera, std::span<const Index> ignore,
                         std::vector<Index>* hits) const {
    Vec3 direction = camera.toCamera(p);
    const double length = direction.norm();
    if (!(length > 0.0))
        return 0;
    direction /= length;
    // Perspective: the open segment ends at the eye. Orthographic: the ray
    // leaves the scene's bounding sphere well before this distance.
    const double far = camera.isOrthographic()
                           ? (p - impl_->sceneCenter).norm() + 2.0 * impl_->sceneExtent
                           : length;
    if (!(far > 0.0))
        return 0;

    // Faces next to p: exact predicates.
    std::vector<Index> near;
    RTCPointQuery query{};
    query.x = static_cast<float>(p.x());
    query.y = static_cast<float>(p.y());
    query.z = static_cast<float>(p.z());
    query.radius = static_cast<float>(impl_->nearEpsilon);
    RTCPointQueryContext queryContext;
    rtcInitPointQueryContext(&queryContext);
    rtcPointQuery(impl_->scene, &query, &queryContext, collectFace, &near);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());

    std::vector<Index> faces;
    for (Index f : near) {
        if (std::find(ignore.begin(), ignore.end(), f) != ignore.end())
            continue;
        const Triangle& t = impl_->triangles[f];
        if (crossesExactly(impl_->positions[t[0]], impl_->positions[t[1]], impl_->positions[t[2]],
                           p, camera))
            faces.push_back(f);
    }

    // The rest: Embree (its hits follow the exact ones in `faces`).
    const size_t exactCount = faces.size();
    CountingContext counting{{}, ignore, &faces, &near};
    rtcInitIntersectContext(&counting.context);

    RTCRayHit rayhit{};
    rayhit.ray.org_x = static_cast<float>(p.x());
    rayhit.ray.org_y = static_cast<float>(p.y());
    rayhit.ray.org_z = static_cast<float>(p.z());
    rayhit.ray.dir_x = static_cast<float>(direction.x());
    rayhit.ray.dir_y = static_cast<float>(direction.y());
    rayhit.ray.dir_z = static_cast<float>(direction.z());
    rayhit.ray.tnear = 0.0f;
    rayhit.ray.tfar = static_cast<float>(far);
    rayhit.ray.mask = 0xFFFFFFFFu;
    rayhit.ray.flags = 0;
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &counting.context, &rayhit);

    // Embree's robust traversal reports both faces of an edge the ray
    // passes near (it must not miss the crossing): every hit is confirmed
    // with the exact test, which counts a crossing through the inside of
    // exactly one of them.
    std::vector<Index> confirmed(faces.begin(),
                                 faces.begin() + static_cast<std::ptrdiff_t>(exactCount));
    for (size_t i = exactCount; i < faces.size(); ++i) {
        const Triangle& t = impl_->triangles[faces[i]];
        if (crossesExactly(impl_->positions[t[0]], impl_->positions[t[1]], impl_->positions[t[2]],
                           p, camera))
            confirmed.push_back(faces[i]);
    }
    faces = std::move(confirmed);

    // Embree may report a face more than once (a hit at a shared edge is
    // tested from several BVH leaves); each face is one crossing.
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    if (hits)
        *hits = faces;
    return static_cast<int>(faces.size());
}

} // namespace contour
