// Mesh contours (tutorial §3.4, §3.7.1 brute force; convexity from appendix B
// and C): edges between a front face and a back face of the triangle mesh.
#include "camera/Facing.h"
#include "contours/Methods.h"
#include "contours/common/BoundaryCurves.h"
#include "contours/common/EdgePolylines.h"
#include "contours/common/FacingPhase.h"
#include "contours/common/SurfacePhase.h"
#include "core/Predicates.h"
#include "pipeline/FieldNames.h"
#include "visibility/SimplificationPhase.h"
#include "visibility/VisibilityPhase.h"

#include <string>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

enum ContourEdgeLabel { kNotContour = 0, kConvexContour = 1, kConcaveContour = 2 };

// Tutorial §3.4 definition 3.4.3 with appendix C's convexity predicate: edge
// ab with triangles abd and bae is concave iff e lies in front of abd.
void extractContourEdges(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& facing = *s.field(fields::kFacing)->labels();
    std::vector<int> label(mesh.edgeCount(), kNotContour);
    tbb::parallel_for(Index(0), mesh.edgeCount(), [&](Index e) {
        const Index h = mesh.edgeHalfedge(e);
        const Index o = mesh.opposite(h);
        if (o == kInvalidIndex)
            return;
        // Edge-on faces (facing 0) count as not front-facing: g > 0 is front.
        const bool front0 = facing[TriangleMesh::face(h)] > 0;
        const bool front1 = facing[TriangleMesh::face(o)] > 0;
        if (front0 == front1)
            return;
        const Vec3& a = mesh.position(mesh.from(h));
        const Vec3& b = mesh.position(mesh.to(h));
        const Vec3& d = mesh.position(mesh.to(TriangleMesh::next(h)));
        const Vec3& eApex = mesh.position(mesh.to(TriangleMesh::next(o)));
        label[e] = frontSide(a, b, d, eApex) > 0 ? kConcaveContour : kConvexContour;
    });
    ctx.checkCancelled();
    long long convex = 0, concave = 0;
    for (int l : label) {
        convex += l == kConvexContour;
        concave += l == kConcaveContour;
    }
    s.setField(fields::kContourEdge,
               {FieldLocation::Edge, std::move(label),
                "0 not a contour, 1 convex contour edge, 2 concave contour edge"});
    s.setCounter(counters::kContourEdges, static_cast<double>(convex + concave));
    s.setCounter(counters::kConvexContourEdges, static_cast<double>(convex));
    s.setCounter(counters::kConcaveContourEdges, static_cast<double>(concave));
    if (ctx.parameters.getBool("include-boundaries")) {
        std::vector<int> boundary(mesh.edgeCount(), 0);
        for (Index e : boundaryEdges(mesh))
            boundary[e] = 1;
        s.setField(fields::kBoundaryEdge,
                   {FieldLocation::Edge, std::move(boundary), "1 on a boundary edge"});
    }
    s.setCounter(counters::kBoundaryEdges, mesh.boundaryEdgeCount());
}

std::vector<InvariantCheck> checkContourEdges(const PhaseContext&, const Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& facing = *s.field(fields::kFacing)->labels();
    const std::vector<int>& label = *s.field(fields::kContourEdge)->labels();
    InvariantCheck separates{"every contour edge separates a front face from a back face", 0, ""};
    InvariantCheck even{"every interior vertex has an even number of contour edges", 0, ""};
    std::vector<int> count(mesh.vertexCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const Index h = mesh.edgeHalfedge(e);
        const bool isContour = label[e] != kNotContour;
        const bool differs =
            !mesh.isBoundary(h) && (facing[TriangleMesh::face(h)] > 0) !=
                                       (facing[TriangleMesh::face(mesh.opposite(h))] > 0);
        if (isContour != differs && separates.violations++ == 0)
            separates.firstExample = "edge " + std::to_string(e);
        if (isContour) {
            ++count[mesh.from(h)];
            ++count[mesh.to(h)];
        }
    }
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (!mesh.isBoundaryVertex(v) && count[v] % 2 != 0 && even.violations++ == 0)
            even.firstExample = "vertex " + std::to_string(v);
    return {separates, even};
}

// Chains contour edges through vertices where exactly two meet; a chain
// stops at bifurcations (more than two contour edges at a vertex, §4.3).
struct ChainOptions {
    bool dropConcave = false;       // drop-concave
    bool includeBoundaries = false; // include-boundaries
    static ChainOptions read(const ParameterSet& p) {
        ChainOptions o;
        o.dropConcave = p.getBool("drop-concave");
        o.includeBoundaries = p.getBool("include-boundaries");
        return o;
    }
};

void chainContourEdges(const PhaseContext& ctx, Snapshot& s) {
    const ChainOptions options = ChainOptions::read(ctx.parameters);
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& label = *s.field(fields::kContourEdge)->labels();
    const bool dropConcave = options.dropConcave;
    std::vector<Index> edges;
    std::vector<int> degree(mesh.vertexCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (label[e] == kNotContour || (dropConcave && label[e] == kConcaveContour))
            continue;
        edges.push_back(e);
        const Index h = mesh.edgeHalfedge(e);
        ++degree[mesh.from(h)];
        ++degree[mesh.to(h)];
    }
    long long bifurcations = 0;
    for (int d : degree)
        bifurcations += d > 2;
    s.setCounter(counters::kBifurcationVertices, static_cast<double>(bifurcations));
    if (bifurcations > 0)
        s.notes.push_back(std::to_string(bifurcations) +
                          " vertices join more than two contour edges (bifurcations, tutorial "
                          "§4.3): chains stop there");
    publishCurves(s, edgePolylines(mesh, edges, CurveType::Contour), options.includeBoundaries);
}

std::vector<InvariantCheck> checkChains(const PhaseContext& ctx, const Snapshot& s) {
    const std::vector<int>& label = *s.field(fields::kContourEdge)->labels();
    const bool dropConcave = ChainOptions::read(ctx.parameters).dropConcave;
    std::vector<int> uses(label.size(), 0);
    for (const Polyline& line : *s.curves)
        if (line.type == CurveType::Contour)
            for (Index e : line.segmentElement)
                ++uses[e];
    InvariantCheck once{"every chained contour edge is in exactly one chain", 0, ""};
    for (size_t e = 0; e < label.size(); ++e) {
        const bool expected = label[e] == 1 || (label[e] == 2 && !dropConcave);
        if (uses[e] != (expected ? 1 : 0) && once.violations++ == 0)
            once.firstExample = "edge " + std::to_string(e);
    }
    return {once};
}

// The shared facing phase, plus g = (c - p) · n at the vertices when the
// surface phase published exact normals (to colour the smooth surface by g;
// the method itself uses only the faces' facing).
Phase makeMeshFacingPhase() {
    Phase phase = makeFacingPhase();
    phase.description += " On a smooth surface also g = (c - p) · n at every vertex.";
    phase.run = [faces = phase.run](const PhaseContext& ctx, Snapshot& s) {
        faces(ctx, s);
        const Field* normalField = s.field(fields::kVertexNormal);
        if (!normalField)
            return;
        const TriangleMesh& mesh = *s.mesh;
        const std::vector<Vec3>& normals = *normalField->vectors();
        std::vector<double> g(mesh.vertexCount());
        tbb::parallel_for(Index(0), mesh.vertexCount(), [&](Index v) {
            g[v] = facingFunction(ctx.camera, mesh.position(v), normals[v]);
        });
        s.setField(fields::kG, {FieldLocation::Vertex, std::move(g),
                                "g = (c - p) · n with the smooth surface's normal, > 0 front"});
    };
    return phase;
}

} // namespace

Method makeMeshContourMethod() {
    Method m;
    m.name = "mesh";
    m.label = "Mesh contours";
    m.description = "Edges between front-facing and back-facing triangles of the mesh "
                    "(tutorial §3.4), classified convex or concave (appendix B); the mesh is "
                    "the triangulated cage or a tessellation of its smooth surface.";
    m.presets = {defaultPreset()};
    // Each phase's parameters are declared before it (Method::addPhase).
    m.parameters = surfaceParameters();
    m.addPhase(makeSurfacePhase({}));
    m.addPhase(makeMeshFacingPhase());
    m.parameters.push_back({"include-boundaries",
                            "Include boundaries",
                            "Also extract the mesh's boundary edges as curves (tutorial §3.2).",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.addPhase({"extraction",
                "Contour edges (front face next to back face) and boundary edges; "
                "convex/concave classification with an exact predicate.",
                extractContourEdges, checkContourEdges});
    m.parameters.push_back({"drop-concave",
                            "Drop concave contours",
                            "Leave concave contour edges out of the chains: they are never "
                            "visible (tutorial appendix B, theorem B.0.1).",
                            ParameterType::Bool,
                            false,
                            0,
                            0,
                            {}});
    m.addPhase({"chaining", "Chain contour edges into polylines through vertices of degree two.",
                chainContourEdges, checkChains});
    addVisibilityPhase(m, VisibilityFlavor::Mesh);
    addSimplificationPhase(m);
    return m;
}

} // namespace contour
