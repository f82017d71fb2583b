#include "mesh/PolygonMesh.h"

#include "mesh/PolygonTriangulation.h"

namespace contour {

void PolygonMesh::addFace(std::span<const Index> polygon) {
    indices.insert(indices.end(), polygon.begin(), polygon.end());
    offsets.push_back(static_cast<Index>(indices.size()));
}

bool PolygonMesh::isTriangleMesh() const {
    for (Index f = 0; f < faceCount(); ++f)
        if (face(f).size() != 3)
            return false;
    return faceCount() > 0;
}

bool PolygonMesh::isQuadMesh() const {
    for (Index f = 0; f < faceCount(); ++f)
        if (face(f).size() != 4)
            return false;
    return faceCount() > 0;
}

BoundingBox PolygonMesh::boundingBox() const {
    BoundingBox box;
    for (const Vec3& p : positions)
        box.extend(p);
    return box;
}

TriangleMesh PolygonMesh::triangulate() const {
    std::vector<Triangle> triangles;
    std::vector<Index> source;
    triangles.reserve(indices.size());
    source.reserve(indices.size());
    for (Index f = 0; f < faceCount(); ++f) {
        const auto p = face(f);
        if (p.size() == 4) {
            const double d02 = (positions[p[0]] - positions[p[2]]).squaredNorm();
            const double d13 = (positions[p[1]] - positions[p[3]]).squaredNorm();
            if (d02 <= d13) {
                triangles.push_back({p[0], p[1], p[2]});
                triangles.push_back({p[0], p[2], p[3]});
            } else {
                triangles.push_back({p[0], p[1], p[3]});
                triangles.push_back({p[1], p[2], p[3]});
            }
            source.insert(source.end(), 2, f);
            continue;
        }
        for (const auto& t : triangulatePolygon(positions, p)) {
            triangles.push_back(t);
            source.push_back(f);
        }
    }
    return TriangleMesh(positions, std::move(triangles), std::move(source));
}

} // namespace contour
