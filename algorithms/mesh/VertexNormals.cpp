#include "mesh/VertexNormals.h"

#include <cmath>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour {

NormalWeighting normalWeightingFromName(const std::string& name) {
    if (name == "area")
        return NormalWeighting::Area;
    if (name == "angle")
        return NormalWeighting::Angle;
    if (name == "max")
        return NormalWeighting::Max;
    throw std::invalid_argument("unknown normal weighting \"" + name + "\"");
}

namespace {
// Weighted normal contribution of face f at its corner `corner`.
Vec3 cornerContribution(const TriangleMesh& mesh, Index f, int corner, NormalWeighting w) {
    const Triangle& t = mesh.triangle(f);
    const Vec3& p = mesh.position(t[corner]);
    const Vec3 e1 = mesh.position(t[(corner + 1) % 3]) - p;
    const Vec3 e2 = mesh.position(t[(corner + 2) % 3]) - p;
    const Vec3 cross = e1.cross(e2); // |cross| = 2 area, along the face normal
    switch (w) {
    case NormalWeighting::Area:
        return cross;
    case NormalWeighting::Angle: {
        const double n = cross.norm();
        if (n == 0.0)
            return Vec3::Zero();
        return cross / n * std::atan2(n, e1.dot(e2));
    }
    case NormalWeighting::Max: {
        const double d = e1.squaredNorm() * e2.squaredNorm();
        return d > 0.0 ? Vec3(cross / d) : Vec3::Zero();
    }
    }
    return cross;
}
} // namespace

std::vector<Vec3> vertexNormals(const TriangleMesh& mesh, NormalWeighting weighting) {
    std::vector<Vec3> normals(mesh.vertexCount(), Vec3::Zero());
    // Gather per vertex over its one-ring, so the loop is parallel without
    // atomics. Vertices not used by any face keep a zero normal.
    tbb::parallel_for(Index(0), mesh.vertexCount(), [&](Index v) {
        const Index h0 = mesh.vertexHalfedge(v);
        if (h0 == kInvalidIndex)
            return;
        Vec3 sum = Vec3::Zero();
        Index h = h0;
        do {
            sum += cornerContribution(mesh, TriangleMesh::face(h), h % 3, weighting);
            h = mesh.rotate(h);
        } while (h != kInvalidIndex && h != h0);
        const double n = sum.norm();
        normals[v] = n > 0.0 ? Vec3(sum / n) : Vec3::Zero();
    });
    return normals;
}

} // namespace contour
