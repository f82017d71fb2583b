#include "contours/consistent/mesh/MeshQueries.h"

#include "surface/SurfaceFields.h"
#include "surface/SurfaceTessellation.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace contour::consistent {

double sceneScale(const ConsistentMesh& m) {
    // The initial mesh's box (§6.1: the level-1 tessellation at the limit),
    // not the working mesh's: the tolerances a phase searches to and the
    // checks after later phases must be the same numbers, and a wiggle that
    // moves an extreme vertex changes the working mesh's box (monsterfrog
    // view 23: a radial root found at 7.846e-9 failed a later check at
    // 7.843e-9).
    const std::shared_ptr<const SurfaceTessellation> t = sharedTessellation(m.surfacePtr(), 1);
    const double d = t->mesh->boundingBox().diagonal();
    return d > 0.0 ? d : 1.0;
}

bool atSingularPoint(const ConsistentMesh& m, Index v, double scale) {
    const Curvatures k = curvatures(m.surface().evaluate(m.vertex(v).preimage));
    const double largest = std::max(std::abs(k.kMin), std::abs(k.kMax));
    // NaN (no normal) fails the comparison and counts as singular.
    return !(largest * kSingularRadius * scale <= 1.0);
}

std::string describeFace(const ConsistentMesh& m, Index f) {
    std::string out = "face " + std::to_string(f) + ":";
    for (Index v : m.face(f)) {
        const MeshVertex& x = m.vertex(v);
        out += " v" + std::to_string(v) + " (domain face " + std::to_string(x.preimage.face) +
               " u " + std::to_string(x.preimage.u) + " v " + std::to_string(x.preimage.v) +
               ", label " + std::to_string(static_cast<int>(x.label)) + ", provenance " +
               std::to_string(static_cast<int>(x.provenance)) + ", phase " +
               std::to_string(x.phase) + ")";
    }
    return out;
}

std::vector<Index> facesAround(const ConsistentMesh& m, const std::vector<Index>& vertices) {
    std::vector<Index> faces;
    for (Index v : vertices)
        faces.insert(faces.end(), m.vertexFaces(v).begin(), m.vertexFaces(v).end());
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

} // namespace contour::consistent
