#include "BatchCameras.h"

#include "BatchRun.h"

#include <ostream>
#include <string>

namespace contour::batch {

namespace {

// The default view: from the front-right, a little above (a 3/4 view).
const Vec3 kDefaultViewDirection(1.0, 0.5, 2.0);

void applyViewportSize(const CameraOverrides& c, Camera& camera) {
    if (c.width)
        camera.viewport.width = *c.width;
    if (c.height)
        camera.viewport.height = *c.height;
}

Camera readCameraFile(const BatchOptions& o) {
    Camera camera;
    try {
        camera = Camera::readJson(o.cameraFile);
    } catch (const std::exception& e) {
        throw BatchFailure(e.what());
    }
    applyViewportSize(o.camera, camera);
    return camera;
}

// Projection settings that apply to every camera, also the 26 views.
void applyProjection(const CameraOverrides& c, Camera& camera) {
    if (c.orthographic)
        camera.projection = Projection::Orthographic;
    if (c.fovYDegrees)
        camera.fovYDegrees = *c.fovYDegrees;
    if (c.orthoHeight)
        camera.orthoHeight = *c.orthoHeight;
}

std::vector<Camera> views26(const BatchOptions& o, const BoundingBox& box,
                            const Viewport& viewport) {
    std::vector<Camera> cameras = Camera::views26(box, viewport);
    for (size_t i = 0; i < cameras.size(); ++i) {
        applyProjection(o.camera, cameras[i]);
        if (const std::string problem = cameras[i].validate(); !problem.empty())
            throw BatchFailure(o.meshPath + ": view " + std::to_string(i) +
                               " of the 26-view protocol has no valid camera (" + problem +
                               "); is the mesh flat?");
    }
    return cameras;
}

Camera framingCamera(const BatchOptions& o, const BoundingBox& box, const Viewport& viewport) {
    Camera camera = Camera::framing(box, kDefaultViewDirection, viewport);
    if (o.camera.eye)
        camera.eye = *o.camera.eye;
    if (o.camera.target)
        camera.target = *o.camera.target;
    if (o.camera.up) {
        camera.up = *o.camera.up;
    } else {
        // Without --up, keep the default up away from the viewing direction.
        const Vec3 view = camera.target - camera.eye;
        const double length = view.norm();
        if (length > 0.0 && view.cross(camera.up).norm() < 1e-6 * length)
            camera.up = Vec3(0, 0, 1);
    }
    applyProjection(o.camera, camera);
    if (const std::string problem = camera.validate(); !problem.empty())
        throw UsageError("camera: " + problem);
    return camera;
}

} // namespace

std::optional<Camera> givenCamera(const BatchOptions& o, std::ostream& out) {
    std::optional<Camera> camera;
    if (!o.cameraFile.empty())
        camera = readCameraFile(o);
    if (o.sessionCamera) {
        camera = *o.sessionCamera;
        applyViewportSize(o.camera, *camera);
        for (const std::string& warning : o.sessionWarnings)
            out << "session: " << warning << "\n";
    }
    return camera;
}

std::vector<Camera> placeCameras(const BatchOptions& o, const BoundingBox& box,
                                 const std::optional<Camera>& given) {
    Viewport viewport;
    viewport.width = o.camera.width.value_or(viewport.width);
    viewport.height = o.camera.height.value_or(viewport.height);
    if (o.views26)
        return views26(o, box, viewport);
    if (given)
        return {*given};
    return {framingCamera(o, box, viewport)};
}

} // namespace contour::batch
