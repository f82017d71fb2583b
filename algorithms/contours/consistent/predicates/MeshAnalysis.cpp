#include "contours/consistent/predicates/MeshAnalysis.h"

#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/predicates/FaceClassification.h"

#include <tbb/parallel_for.h>

namespace contour::consistent {

Analysis analyse(const ConsistentMesh& m, const TriangleMesh* published) {
    Analysis a;
    const Index nf = m.faceCount();
    a.facing.resize(nf);
    a.vbo.resize(nf);
    a.consistent.resize(nf);
    a.folded.resize(nf);
    a.noChart.resize(nf);
    const std::vector<std::optional<int>> orientation = m.parameterOrientations();
    // Per face in parallel (each writes its own slots), counted in order.
    tbb::parallel_for(Index(0), nf, [&](Index f) {
        const Facing facing = faceFacing(m, f);
        const Vbo vbo = faceVbo(m, f);
        a.facing[f] = static_cast<int>(facing);
        a.vbo[f] = static_cast<int>(vbo);
        a.consistent[f] = isConsistent(vbo, facing) ? 1 : 0;
        const std::optional<int>& o = orientation[static_cast<size_t>(f)];
        a.folded[f] = o && *o <= 0 ? 1 : 0;
        a.noChart[f] = o ? 0 : 1;
    });
    for (Index f = 0; f < nf; ++f) {
        a.inconsistent += a.consistent[f] == 0;
        if (static_cast<Vbo>(a.vbo[f]) == Vbo::Undefined && a.undefinedVbo++ == 0)
            a.firstUndefined = describeFace(m, f);
        if (a.folded[f] && a.foldedFaces++ == 0)
            a.firstFolded = describeFace(m, f);
    }
    // The edges in m.edges() order (faces in order, each edge at its a < b
    // half-edge or its only one), with the face across each half-edge
    // looked up in parallel.
    std::vector<Index> across(3 * static_cast<size_t>(nf));
    tbb::parallel_for(Index(0), nf, [&](Index f) {
        const Triangle& t = m.face(f);
        for (int i = 0; i < 3; ++i) {
            Index g = kInvalidIndex;
            if (published) {
                const Index o = published->opposite(TriangleMesh::halfedge(f, i));
                g = o == kInvalidIndex ? kInvalidIndex : o / 3;
            } else {
                g = m.faceOfHalfedge(t[(i + 1) % 3], t[i]);
            }
            across[3 * static_cast<size_t>(f) + i] = g;
        }
    });
    for (Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i) {
            const Index u = m.face(f)[i], v = m.face(f)[(i + 1) % 3];
            const Index f0 = f, f1 = across[3 * static_cast<size_t>(f) + i];
            if (!(u < v || f1 == kInvalidIndex))
                continue;
            const VertexLabel lu = m.vertex(u).label, lv = m.vertex(v).label;
            if (static_cast<int>(lu) * static_cast<int>(lv) < 0 && a.fbEdges++ == 0)
                a.firstFb = "edge " + std::to_string(u) + "-" + std::to_string(v);
            if (f0 != kInvalidIndex && f1 != kInvalidIndex &&
                isDegenerateEdge(lu, lv, static_cast<Vbo>(a.vbo[f0]),
                                 static_cast<Vbo>(a.vbo[f1])) &&
                a.degenerate++ == 0)
                a.firstDegenerate = "edge " + std::to_string(u) + "-" + std::to_string(v) +
                                    " between " + describeFace(m, f0) + " and " +
                                    describeFace(m, f1);
        }
    for (Index v = 0; v < m.vertexCount(); ++v) {
        a.contourVertices += m.vertex(v).label == VertexLabel::Contour;
        a.cusps += m.vertex(v).cusp;
    }
    return a;
}

} // namespace contour::consistent
