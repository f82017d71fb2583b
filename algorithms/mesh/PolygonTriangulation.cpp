#include "mesh/PolygonTriangulation.h"

#include "core/Predicates.h"

#include <cmath>

namespace contour {

namespace {

std::vector<std::array<Index, 3>> fan(std::span<const Index> polygon) {
    std::vector<std::array<Index, 3>> out;
    for (size_t i = 1; i + 1 < polygon.size(); ++i)
        out.push_back({polygon[0], polygon[i], polygon[i + 1]});
    return out;
}

// p inside or on the boundary of the counter-clockwise triangle abc.
bool insideOrOn(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
    return orientation2d(a, b, p) >= 0 && orientation2d(b, c, p) >= 0 &&
           orientation2d(c, a, p) >= 0;
}

} // namespace

std::vector<std::array<Index, 3>> triangulatePolygon(std::span<const Vec3> positions,
                                                     std::span<const Index> polygon) {
    const size_t n = polygon.size();
    if (n <= 4)
        return fan(polygon);
    // Newell's normal: robust for non-convex and slightly non-planar faces.
    Vec3 normal = Vec3::Zero();
    for (size_t i = 0; i < n; ++i) {
        const Vec3& p = positions[polygon[i]];
        const Vec3& q = positions[polygon[(i + 1) % n]];
        normal += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                       (p.x() - q.x()) * (p.y() + q.y()));
    }
    if (!(normal.norm() > 0.0))
        return fan(polygon);
    normal.normalize();
    const Vec3 axisU = normal.unitOrthogonal();
    const Vec3 axisV = normal.cross(axisU);
    std::vector<Vec2> flat(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3& p = positions[polygon[i]];
        flat[i] = Vec2(p.dot(axisU), p.dot(axisV)); // counter-clockwise about the normal
    }
    std::vector<size_t> ring(n);
    for (size_t i = 0; i < n; ++i)
        ring[i] = i;
    std::vector<std::array<Index, 3>> out;
    while (ring.size() > 3) {
        const size_t m = ring.size();
        bool clipped = false;
        for (size_t k = 0; k < m && !clipped; ++k) {
            const size_t a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
            if (orientation2d(flat[a], flat[b], flat[c]) <= 0)
                continue; // reflex or flat corner: not an ear
            bool empty = true;
            for (size_t r : ring)
                if (r != a && r != b && r != c && insideOrOn(flat[a], flat[b], flat[c], flat[r]))
                    empty = false;
            if (!empty)
                continue;
            out.push_back({polygon[a], polygon[b], polygon[c]});
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
            clipped = true;
        }
        if (!clipped)
            return fan(polygon); // not simple in projection: keep the old behaviour
    }
    out.push_back({polygon[ring[0]], polygon[ring[1]], polygon[ring[2]]});
    return out;
}

} // namespace contour
