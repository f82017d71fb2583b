// The consistent mesh's contour generator (Bénard 2014 §8.1):
// the edges between an F-VBO face and a B-VBO face, chained into polylines.
#include "contours/common/EdgePolylines.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "pipeline/FieldNames.h"

namespace contour::consistent {

namespace {

// The mesh's contour generator on a consistent mesh: the edges between an
// F-VBO face and a B-VBO face (§4), chained through vertices of degree 2.
void runChaining(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& vbo = *s.field(fields::kVbo)->labels();
    const std::vector<int>& facing = *s.field(fields::kFacing)->labels();
    std::vector<Index> generator;
    long long meshContourEdges = 0;
    std::vector<int> label(mesh.edgeCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const Index h = mesh.edgeHalfedge(e);
        if (mesh.isBoundary(h))
            continue;
        const Index f0 = TriangleMesh::face(h), f1 = TriangleMesh::face(mesh.opposite(h));
        meshContourEdges += (facing[f0] > 0) != (facing[f1] > 0);
        if (vbo[f0] * vbo[f1] < 0) {
            generator.push_back(e);
            label[e] = 1;
        }
    }
    s.setField(fields::kContourEdge,
               {FieldLocation::Edge, std::move(label),
                "1 on the contour generator (an F-VBO face next to a B-VBO face)"});
    s.setCounter(counters::kContourGeneratorEdges, static_cast<double>(generator.size()));
    s.setCounter(counters::kMeshContourEdges, static_cast<double>(meshContourEdges));
    publishCurves(s, edgePolylines(mesh, generator, CurveType::Contour),
                  ctx.parameters.getBool("include-boundaries"));
    const double inconsistent = s.counter(counters::kInconsistentFaces, 0.0);
    if (inconsistent > 0.0)
        s.notes.push_back(
            std::to_string(static_cast<long long>(inconsistent)) + " of " +
            std::to_string(mesh.faceCount()) +
            " faces are still inconsistent (the paper reaches about 0.05 %): near them the "
            "contour generator's topology may differ from the smooth contour's");
}

// docs/dev/invariants.md item 10: contour-generator vertices have degree 2 except on
// boundaries, and every contour-generator edge is a CC edge.
std::vector<InvariantCheck> checkChaining(const PhaseContext&, const Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& edgeLabel = *s.field(fields::kContourEdge)->labels();
    const std::vector<int>& vertexLabel = *s.field(fields::kLabel)->labels();
    InvariantCheck degree = check("every contour-generator vertex has degree 2 (no bifurcation)");
    InvariantCheck cc = check("every contour-generator edge joins two C vertices");
    std::vector<int> count(mesh.vertexCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (!edgeLabel[e])
            continue;
        const Index h = mesh.edgeHalfedge(e);
        ++count[mesh.from(h)];
        ++count[mesh.to(h)];
        if ((vertexLabel[mesh.from(h)] != 0 || vertexLabel[mesh.to(h)] != 0))
            violate(cc, "edge " + std::to_string(e));
    }
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (count[v] != 0 && count[v] != 2 && !mesh.isBoundaryVertex(v))
            violate(degree, "vertex " + std::to_string(v));
    return {degree, cc};
}

} // namespace

void addChainingPhase(Method& m) {
    m.parameters.push_back({"include-boundaries",
                            "Include boundaries",
                            "Also chain the mesh's boundary edges as curves.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.addPhase({"chaining",
                "The contour generator (edges between an F-VBO and a B-VBO face) "
                "chained into polylines, and the boundaries.",
                runChaining, checkChaining});
}

} // namespace contour::consistent
