#pragma once
// Analysis camera: perspective (eye, target, up, vertical field of view) or
// orthographic (same frame, a world-space view height). Projects to pixels of
// a viewport with x to the right and y down, origin at the top-left corner.
#include "core/Types.h"

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace contour {

enum class Projection { Perspective, Orthographic };

struct Viewport {
    int width = 800;
    int height = 600;
    double aspect() const { return static_cast<double>(width) / height; }
    bool operator==(const Viewport&) const = default;
};

struct ProjectedPoint {
    Vec2 pixel;   // pixel coordinates, x right, y down
    double depth; // distance along the viewing direction from the eye (> 0 in front)
};

class Camera {
public:
    Projection projection = Projection::Perspective;
    Vec3 eye{0, 0, 5};
    Vec3 target{0, 0, 0};
    Vec3 up{0, 1, 0};
    double fovYDegrees = 30.0; // perspective only
    double orthoHeight = 2.0;  // world-space height of the view, orthographic only
    Viewport viewport;

    bool isOrthographic() const { return projection == Projection::Orthographic; }
    // Exactly the same camera (every field equal).
    bool operator==(const Camera&) const = default;

    // Unit vector from the eye towards the target.
    Vec3 forward() const;
    // Orthonormal camera frame: right, true up, and back (= -forward).
    Vec3 right() const;
    Vec3 trueUp() const;

    // The vector from p towards the camera: c - p in perspective, the constant
    // direction towards the camera in orthographic projection. Facing is the
    // sign of its dot product with the outward normal (Facing.h).
    Vec3 toCamera(const Vec3& p) const {
        return isOrthographic() ? Vec3(eye - target) : Vec3(eye - p);
    }

    ProjectedPoint project(const Vec3& p) const;
    // Inverse of project(): the world point at that pixel and depth.
    Vec3 unproject(const Vec2& pixel, double depth) const;

    // The four corners of the image plane at `depth` (top-left, top-right,
    // bottom-right, bottom-left), e.g. to draw the frustum.
    std::vector<Vec3> frustumCorners(double depth) const;

    // Checks the camera is usable: finite numbers, eye != target, up not
    // parallel to the view direction, field of view in (0, 180), positive
    // viewport. Returns an empty string when valid, else the problem.
    std::string validate() const;

    nlohmann::json toJson() const;
    // Throws std::runtime_error with the offending field on bad input.
    static Camera fromJson(const nlohmann::json& j);
    static Camera readJson(const std::string& path);
    void writeJson(const std::string& path) const;

    // A camera looking at the whole box from `direction` (eye at centre +
    // |diagonal| * direction), with the given viewport.
    static Camera framing(const BoundingBox& box, const Vec3& direction, const Viewport& viewport);
    // The 26-view protocol (docs/dev/benchmarks.md): for i, j, k in {0, 1, 2} except
    // (1, 1, 1), p = min + (i, j, k)/2 (max - min), camera at
    // centre + |diagonal| normalize(p - centre), looking at the centre.
    static std::vector<Camera> views26(const BoundingBox& box, const Viewport& viewport);
};

} // namespace contour
