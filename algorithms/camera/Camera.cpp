#include "camera/Camera.h"

#include "core/AtomicFile.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>

namespace contour {

namespace {
double tanHalfFov(double fovYDegrees) {
    return std::tan(0.5 * fovYDegrees * std::numbers::pi / 180.0);
}

Vec3 readVec3(const nlohmann::json& j, const char* key) {
    if (!j.contains(key))
        throw std::runtime_error(std::string("camera: missing \"") + key + "\"");
    const auto& a = j.at(key);
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() ||
        !a[2].is_number())
        throw std::runtime_error(std::string("camera: \"") + key +
                                 "\" must be an array of 3 numbers");
    return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
}
} // namespace

Vec3 Camera::forward() const {
    return (target - eye).normalized();
}
Vec3 Camera::right() const {
    return forward().cross(up).normalized();
}
Vec3 Camera::trueUp() const {
    return right().cross(forward());
}

ProjectedPoint Camera::project(const Vec3& p) const {
    const Vec3 f = forward(), r = right(), u = r.cross(f);
    const Vec3 d = p - eye;
    const double x = d.dot(r), y = d.dot(u), z = d.dot(f);
    double ndcX, ndcY;
    if (isOrthographic()) {
        const double halfH = 0.5 * orthoHeight;
        ndcX = x / (halfH * viewport.aspect());
        ndcY = y / halfH;
    } else {
        const double t = tanHalfFov(fovYDegrees);
        ndcX = x / (z * t * viewport.aspect());
        ndcY = y / (z * t);
    }
    return {Vec2(0.5 * (ndcX + 1.0) * viewport.width, 0.5 * (1.0 - ndcY) * viewport.height), z};
}

Vec3 Camera::unproject(const Vec2& pixel, double depth) const {
    const Vec3 f = forward(), r = right(), u = r.cross(f);
    const double ndcX = 2.0 * pixel.x() / viewport.width - 1.0;
    const double ndcY = 1.0 - 2.0 * pixel.y() / viewport.height;
    double x, y;
    if (isOrthographic()) {
        const double halfH = 0.5 * orthoHeight;
        x = ndcX * halfH * viewport.aspect();
        y = ndcY * halfH;
    } else {
        const double t = tanHalfFov(fovYDegrees);
        x = ndcX * depth * t * viewport.aspect();
        y = ndcY * depth * t;
    }
    return eye + x * r + y * u + depth * f;
}

std::vector<Vec3> Camera::frustumCorners(double depth) const {
    const double w = viewport.width, h = viewport.height;
    return {unproject({0, 0}, depth), unproject({w, 0}, depth), unproject({w, h}, depth),
            unproject({0, h}, depth)};
}

std::string Camera::validate() const {
    if (!eye.allFinite() || !target.allFinite() || !up.allFinite())
        return "eye, target and up must be finite";
    if ((target - eye).norm() <= 0.0)
        return "eye and target coincide";
    if (up.norm() <= 0.0 || (target - eye).normalized().cross(up.normalized()).norm() < 1e-9)
        return "up is zero or parallel to the viewing direction";
    if (!isOrthographic() && !(fovYDegrees > 0.0 && fovYDegrees < 180.0))
        return "vertical field of view must be in (0, 180) degrees";
    if (isOrthographic() && !(orthoHeight > 0.0 && std::isfinite(orthoHeight)))
        return "orthographic view height must be positive";
    if (viewport.width <= 0 || viewport.height <= 0)
        return "viewport width and height must be positive";
    return {};
}

nlohmann::json Camera::toJson() const {
    nlohmann::json j;
    j["projection"] = isOrthographic() ? "orthographic" : "perspective";
    j["eye"] = {eye.x(), eye.y(), eye.z()};
    j["target"] = {target.x(), target.y(), target.z()};
    j["up"] = {up.x(), up.y(), up.z()};
    j["fov_y_degrees"] = fovYDegrees;
    j["ortho_height"] = orthoHeight;
    j["viewport"] = {{"width", viewport.width}, {"height", viewport.height}};
    return j;
}

Camera Camera::fromJson(const nlohmann::json& j) {
    if (!j.is_object())
        throw std::runtime_error("camera: expected a JSON object");
    Camera c;
    const std::string projection = j.value("projection", std::string("perspective"));
    if (projection == "perspective")
        c.projection = Projection::Perspective;
    else if (projection == "orthographic")
        c.projection = Projection::Orthographic;
    else
        throw std::runtime_error(
            "camera: \"projection\" must be \"perspective\" or \"orthographic\", not \"" +
            projection + "\"");
    c.eye = readVec3(j, "eye");
    c.target = readVec3(j, "target");
    c.up = j.contains("up") ? readVec3(j, "up") : Vec3(0, 1, 0);
    if (j.contains("fov_y_degrees")) {
        if (!j["fov_y_degrees"].is_number())
            throw std::runtime_error("camera: \"fov_y_degrees\" must be a number");
        c.fovYDegrees = j["fov_y_degrees"].get<double>();
    }
    if (j.contains("ortho_height")) {
        if (!j["ortho_height"].is_number())
            throw std::runtime_error("camera: \"ortho_height\" must be a number");
        c.orthoHeight = j["ortho_height"].get<double>();
    }
    if (j.contains("viewport")) {
        const auto& v = j["viewport"];
        if (!v.is_object() || !v.value("width", nlohmann::json()).is_number_integer() ||
            !v.value("height", nlohmann::json()).is_number_integer())
            throw std::runtime_error(
                "camera: \"viewport\" must be {\"width\": int, \"height\": int}");
        c.viewport = {v["width"].get<int>(), v["height"].get<int>()};
    }
    if (const std::string problem = c.validate(); !problem.empty())
        throw std::runtime_error("camera: " + problem);
    return c;
}

Camera Camera::readJson(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot open camera file");
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
    }
    try {
        return fromJson(j);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

void Camera::writeJson(const std::string& path) const {
    writeFileAtomically(path, toJson().dump(2) + "\n");
}

Camera Camera::framing(const BoundingBox& box, const Vec3& direction, const Viewport& viewport) {
    Camera c;
    c.viewport = viewport;
    c.target = box.center();
    const double diag = box.diagonal() > 0 ? box.diagonal() : 1.0;
    c.eye = c.target + diag * direction.normalized();
    // Keep up away from the viewing direction.
    c.up = Vec3(0, 1, 0);
    if (direction.normalized().cross(c.up).norm() < 1e-6)
        c.up = Vec3(0, 0, 1);
    // The box's bounding sphere (radius diag/2) seen from distance diag
    // subtends 2 asin(1/2) = 60 degrees: use that so the model fills the view.
    c.fovYDegrees = 60.0;
    c.orthoHeight = diag;
    return c;
}

std::vector<Camera> Camera::views26(const BoundingBox& box, const Viewport& viewport) {
    std::vector<Camera> cameras;
    const Vec3 centre = box.center();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                if (i == 1 && j == 1 && k == 1)
                    continue;
                const Vec3 p = box.min + 0.5 * Vec3(i, j, k).cwiseProduct(box.max - box.min);
                cameras.push_back(framing(box, p - centre, viewport));
            }
    return cameras;
}

} // namespace contour
