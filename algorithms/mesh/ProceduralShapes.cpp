#include "mesh/ProceduralShapes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace contour {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Triangulations larger than this are refused: half-edge indices must fit in
// Index (int32), and a mesh this big would not fit in memory anyway.
constexpr long long kMaxTriangles = 200'000'000;

// Shape constants of the named shapes (makeProceduralShape).
constexpr double kTorusMajor = 1.0;
constexpr double kTorusMinor = 0.4;
const Vec3 kEllipsoidRadii(1.2, 0.8, 0.5);

// Segments around the tube of a torus: half the segments around its axis.
int tubeSegments(int resolution) {
    return std::max(3, resolution / 2);
}
// Latitude bands of a sphere, pole to pole.
int sphereRings(int resolution) {
    return resolution / 2;
}

void requireResolution(const char* shape, int resolution, int minimum) {
    if (resolution < minimum)
        throw std::invalid_argument(std::string(shape) + ": resolution " +
                                    std::to_string(resolution) + " is too small (minimum " +
                                    std::to_string(minimum) + ")");
}

// Triangles in the triangulation of each shape (PolygonMesh::triangulate:
// two per quad, n - 2 per n-gon).
long long sphereTriangles(long long n) {
    return 2 * n * (n / 2 - 1);
}
long long torusTriangles(long long n) {
    return 2 * n * tubeSegments(static_cast<int>(n));
}
long long saddleTriangles(long long n) {
    return 2 * n * n;
}

void requireSize(const char* shape, int resolution, long long triangles) {
    if (triangles > kMaxTriangles)
        throw std::invalid_argument(std::string(shape) + ": resolution " +
                                    std::to_string(resolution) + " gives " +
                                    std::to_string(triangles) + " triangles (maximum " +
                                    std::to_string(kMaxTriangles) + ")");
}

// Appends a latitude-longitude sphere, mapped through `place` (a point of the
// unit sphere to a point of the shape), to `mesh`. Vertex 0 of the block is
// the north pole (+z), then rings of n vertices from north to south, then the
// south pole. Quads (i, j) -> (i+1, j) -> (i+1, j+1) -> (i, j+1) run south
// then east, so (south x east) points outward: counter-clockwise from outside.
void appendSphere(PolygonMesh& mesh, int n, const std::function<Vec3(const Vec3&)>& place) {
    const int rings = sphereRings(n);
    const Index base = mesh.vertexCount();
    mesh.positions.push_back(place(Vec3(0, 0, 1)));
    for (int i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * i / rings;
        for (int j = 0; j < n; ++j) {
            const double phi = kTwoPi * j / n;
            mesh.positions.push_back(place(Vec3(std::sin(theta) * std::cos(phi),
                                                std::sin(theta) * std::sin(phi), std::cos(theta))));
        }
    }
    mesh.positions.push_back(place(Vec3(0, 0, -1)));
    const Index north = base;
    const Index south = base + 1 + (rings - 1) * n;
    // Ring i (1-based from the north) vertex j.
    const auto ring = [&](int i, int j) -> Index {
        return base + 1 + (i - 1) * n + (j % n);
    };
    for (int j = 0; j < n; ++j)
        mesh.addFace({north, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < n; ++j)
            mesh.addFace({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)});
    for (int j = 0; j < n; ++j)
        mesh.addFace({ring(rings - 1, j), south, ring(rings - 1, j + 1)});
}

// A torus around the z axis whose tube radius may vary with (u, v): u around
// the z axis, v around the tube. d/du x d/dv is the outward normal, so quads
// (u_i, v_j) -> (u_i+1, v_j) -> (u_i+1, v_j+1) -> (u_i, v_j+1) are
// counter-clockwise seen from outside.
PolygonMesh torusMesh(double majorRadius, int n,
                      const std::function<double(double, double)>& tubeRadius) {
    const int m = tubeSegments(n);
    PolygonMesh mesh;
    mesh.positions.reserve(static_cast<size_t>(n) * m);
    for (int i = 0; i < n; ++i) {
        const double u = kTwoPi * i / n;
        for (int j = 0; j < m; ++j) {
            const double v = kTwoPi * j / m;
            const double r = tubeRadius(u, v);
            const double rho = majorRadius + r * std::cos(v);
            mesh.positions.emplace_back(rho * std::cos(u), rho * std::sin(u), r * std::sin(v));
        }
    }
    const auto at = [&](int i, int j) -> Index {
        return (i % n) * m + (j % m);
    };
    mesh.indices.reserve(4 * static_cast<size_t>(n) * m);
    mesh.offsets.reserve(static_cast<size_t>(n) * m + 1);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j)
            mesh.addFace({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    return mesh;
}

void requirePositive(const char* shape, const char* what, double value) {
    if (!(value > 0.0) || !std::isfinite(value))
        throw std::invalid_argument(std::string(shape) + ": " + what +
                                    " must be positive and finite");
}

struct ShapeEntry {
    const char* name;
    std::function<PolygonMesh(int)> make;
    std::function<long long(long long)> triangles;
    int minimumResolution;
};

const std::vector<ShapeEntry>& shapeTable() {
    static const std::vector<ShapeEntry> table = {
        {"sphere", [](int n) { return makeSphere(1.0, n); }, sphereTriangles, 4},
        {"ellipsoid", [](int n) { return makeEllipsoid(kEllipsoidRadii, n); }, sphereTriangles, 4},
        {"torus", [](int n) { return makeTorus(kTorusMajor, kTorusMinor, n); }, torusTriangles, 3},
        {"bumpy-torus", [](int n) { return makeBumpyTorus(kTorusMajor, kTorusMinor, n); },
         torusTriangles, 3},
        {"saddle", [](int n) { return makeSaddlePatch(n); }, saddleTriangles, 1},
        {"two-spheres", [](int n) { return makeTwoSpheres(n); },
         [](long long n) { return 2 * sphereTriangles(n); }, 4},
    };
    return table;
}

const ShapeEntry& findShape(const std::string& name) {
    for (const ShapeEntry& entry : shapeTable())
        if (name == entry.name)
            return entry;
    std::string known;
    for (const ShapeEntry& entry : shapeTable())
        known += (known.empty() ? "" : ", ") + std::string(entry.name);
    throw std::invalid_argument("unknown procedural shape \"" + name + "\" (known: " + known + ")");
}

} // namespace

PolygonMesh makeSphere(double radius, int resolution, const Vec3& center) {
    requirePositive("sphere", "radius", radius);
    requireResolution("sphere", resolution, 4);
    requireSize("sphere", resolution, sphereTriangles(resolution));
    PolygonMesh mesh;
    appendSphere(mesh, resolution, [&](const Vec3& p) { return Vec3(center + radius * p); });
    return mesh;
}

PolygonMesh makeEllipsoid(const Vec3& radii, int resolution) {
    for (int k = 0; k < 3; ++k)
        requirePositive("ellipsoid", "every radius", radii[k]);
    requireResolution("ellipsoid", resolution, 4);
    requireSize("ellipsoid", resolution, sphereTriangles(resolution));
    // A positive diagonal scaling keeps the unit sphere's orientation.
    PolygonMesh mesh;
    appendSphere(mesh, resolution, [&](const Vec3& p) { return Vec3(radii.cwiseProduct(p)); });
    return mesh;
}

PolygonMesh makeTorus(double majorRadius, double minorRadius, int resolution) {
    requirePositive("torus", "minor radius", minorRadius);
    if (!(majorRadius > minorRadius) || !std::isfinite(majorRadius))
        throw std::invalid_argument("torus: the major radius must be finite and larger than the "
                                    "minor radius");
    requireResolution("torus", resolution, 3);
    requireSize("torus", resolution, torusTriangles(resolution));
    return torusMesh(majorRadius, resolution, [&](double, double) { return minorRadius; });
}

PolygonMesh makeBumpyTorus(double majorRadius, double minorRadius, int resolution, double amplitude,
                           int bumps) {
    requirePositive("bumpy torus", "minor radius", minorRadius);
    if (!(amplitude >= 0.0 && amplitude < 1.0))
        throw std::invalid_argument("bumpy torus: amplitude must be in [0, 1)");
    if (bumps < 0)
        throw std::invalid_argument("bumpy torus: the number of bumps must not be negative");
    const double largestTube = minorRadius * (1.0 + amplitude);
    if (!(majorRadius > largestTube) || !std::isfinite(majorRadius))
        throw std::invalid_argument("bumpy torus: the major radius must be finite and larger than "
                                    "the largest tube radius r (1 + amplitude)");
    requireResolution("bumpy torus", resolution, 3);
    requireSize("bumpy torus", resolution, torusTriangles(resolution));
    return torusMesh(majorRadius, resolution, [&](double u, double v) {
        return minorRadius * (1.0 + amplitude * std::sin(bumps * u) * std::sin(bumps * v));
    });
}

PolygonMesh makeSaddlePatch(int resolution) {
    requireResolution("saddle", resolution, 1);
    requireSize("saddle", resolution, saddleTriangles(resolution));
    const int n = resolution;
    PolygonMesh mesh;
    mesh.positions.reserve(static_cast<size_t>(n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j) {
        const double y = -1.0 + 2.0 * j / n;
        for (int i = 0; i <= n; ++i) {
            const double x = -1.0 + 2.0 * i / n;
            mesh.positions.emplace_back(x, y, 0.5 * (x * x - y * y));
        }
    }
    // x then y: counter-clockwise seen from +z, so normals point up.
    const auto at = [&](int i, int j) -> Index {
        return j * (n + 1) + i;
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            mesh.addFace({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    return mesh;
}

PolygonMesh makeTwoSpheres(int resolution) {
    requireResolution("two spheres", resolution, 4);
    requireSize("two spheres", resolution, 2 * sphereTriangles(resolution));
    PolygonMesh mesh;
    appendSphere(mesh, resolution, [](const Vec3& p) { return p; });
    appendSphere(mesh, resolution, [](const Vec3& p) { return Vec3(p + Vec3(0, 0, -3)); });
    return mesh;
}

std::vector<std::string> proceduralShapeNames() {
    std::vector<std::string> names;
    for (const ShapeEntry& entry : shapeTable())
        names.emplace_back(entry.name);
    return names;
}

PolygonMesh makeProceduralShape(const std::string& name, int resolution) {
    return findShape(name).make(resolution);
}

PolygonMesh makeProceduralShapeWithFaces(const std::string& name, long long faces) {
    const ShapeEntry& entry = findShape(name);
    if (faces <= 0)
        throw std::invalid_argument(name + ": the number of faces must be positive");
    if (faces > kMaxTriangles)
        throw std::invalid_argument(name + ": " + std::to_string(faces) +
                                    " faces requested (maximum " + std::to_string(kMaxTriangles) +
                                    ")");
    // Triangle counts grow with the resolution (about quadratically): walk up
    // to the first resolution at or above the target and keep the closer of it
    // and the one before.
    int best = entry.minimumResolution;
    long long bestError = std::llabs(entry.triangles(best) - faces);
    for (int n = entry.minimumResolution + 1;; ++n) {
        const long long count = entry.triangles(n);
        const long long error = std::llabs(count - faces);
        if (error < bestError) {
            best = n;
            bestError = error;
        }
        if (count >= faces)
            break;
    }
    return entry.make(best);
}

} // namespace contour
