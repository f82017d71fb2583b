#pragma once
// The polygon control cage, kept exactly as loaded (quads, n-gons, triangles).
// Later issues subdivide it; the mesh and interpolated methods triangulate it.
#include "mesh/TriangleMesh.h"

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace contour {

class PolygonMesh {
public:
    std::vector<Vec3> positions;
    // Faces in compressed form: face f is indices[offsets[f] .. offsets[f+1]).
    std::vector<Index> offsets{0};
    std::vector<Index> indices;

    // Subdivision tags (OBJ "t crease" and "t corner"), used by the
    // Catmull-Clark and Loop surfaces: sharpness of the edge between vertices
    // a and b, and of single vertices, on OpenSubdiv's scale (0 smooth, 10 or
    // more infinitely sharp).
    struct EdgeCrease {
        Index a, b;
        double sharpness;
    };
    std::vector<EdgeCrease> creases;
    std::vector<std::pair<Index, double>> cornerSharpness;

    // Texture coordinates (OBJ "vt"), kept only when every face corner names
    // one: corner k of `indices` has textureCoordinates[cornerTexture[k]].
    // The Powell-Sabin method reads a cone parameterization from them.
    std::vector<Vec2> textureCoordinates;
    std::vector<Index> cornerTexture;
    bool hasTextureCoordinates() const { return !cornerTexture.empty(); }

    Index vertexCount() const { return static_cast<Index>(positions.size()); }
    Index faceCount() const { return static_cast<Index>(offsets.size()) - 1; }
    std::span<const Index> face(Index f) const {
        return {indices.data() + offsets[f], static_cast<size_t>(offsets[f + 1] - offsets[f])};
    }
    void addFace(std::span<const Index> polygon);
    void addFace(std::initializer_list<Index> polygon) {
        addFace(std::span<const Index>(polygon.begin(), polygon.size()));
    }
    bool isTriangleMesh() const;
    bool isQuadMesh() const;
    BoundingBox boundingBox() const;

    // Triangulates each polygon: quads along their shorter diagonal (the
    // split that bends the surface least), other polygons as a fan from their
    // first corner. Each triangle remembers its source polygon.
    TriangleMesh triangulate() const;
};

} // namespace contour
