#include "contours/consistent/predicates/FaceClassification.h"

#include "contours/consistent/mesh/MeshQueries.h"

namespace contour::consistent {

Vbo faceVbo(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    return vertexBasedOrientation(m.vertex(t[0]).label, m.vertex(t[1]).label, m.vertex(t[2]).label);
}

Facing faceFacing(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    return triangleFacing(m.camera(), m.vertex(t[0]).position, m.vertex(t[1]).position,
                          m.vertex(t[2]).position);
}

bool faceIsConsistent(const ConsistentMesh& m, Index f) {
    return isConsistent(faceVbo(m, f), faceFacing(m, f));
}

Index faceDomainFace(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    const std::optional<Preimage> mid =
        m.interpolate(m.vertex(t[0]).preimage, m.vertex(t[1]).preimage, 0.5);
    if (!mid)
        return kInvalidIndex;
    const std::optional<Preimage> centroid =
        m.interpolate(*mid, m.vertex(t[2]).preimage, 1.0 / 3.0);
    return centroid ? centroid->face : kInvalidIndex;
}

int inconsistentFacesAround(const ConsistentMesh& m, const std::vector<Index>& vertices) {
    int n = 0;
    for (Index f : facesAround(m, vertices))
        n += !faceIsConsistent(m, f);
    return n;
}

int cuspEdgesOf(const ConsistentMesh& m, const Triangle& t) {
    int n = 0;
    for (int i = 0; i < 3; ++i)
        n += (m.edgeTag(t[i], t[(i + 1) % 3]) & kCuspEdge) != 0;
    return n;
}

} // namespace contour::consistent
