// Interpolated contours (tutorial §6.2, Hertzmann & Zorin 2000): the zero set
// of g = (c - p) · n interpolated linearly over each triangle from its
// vertices, one segment per face, chained across shared edges.
#include "camera/Facing.h"
#include "contours/Methods.h"
#include "contours/common/BoundaryCurves.h"
#include "contours/common/ContourChaining.h"
#include "contours/common/EdgePolylines.h"
#include "contours/common/FacingPhase.h"
#include "contours/common/SurfacePhase.h"
#include "contours/common/VertexNormalCache.h"
#include "mesh/VertexNormals.h"
#include "pipeline/FieldNames.h"
#include "visibility/SimplificationPhase.h"
#include "visibility/VisibilityPhase.h"

#include <cmath>
#include <limits>
#include <string>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

// Generic position (§6.2 step 2) assumes g != 0 at vertices; a vertex with
// g exactly 0 counts as back-facing, the same rule as edge-on faces.
bool isFront(double g) {
    return g > 0.0;
}

// Tutorial §6.2 steps 1-2: vertex normals, then g per vertex. The surface
// phase published the normals: the exact limit normals of a smooth surface
// (Hertzmann & Zorin 2000), or the weighted averages with surface = none.
void computeVertexFacing(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const auto published = s.fields.find(fields::kVertexNormal);
    const std::shared_ptr<const Field> normalField =
        published != s.fields.end()
            ? published->second
            : cachedVertexNormals(
                  s.mesh, normalWeightingFromName(ctx.parameters.getChoice("normal-weighting")));
    const std::vector<Vec3>& normals = *normalField->vectors();
    ctx.checkCancelled();
    std::vector<double> g(mesh.vertexCount());
    tbb::parallel_for(Index(0), mesh.vertexCount(), [&](Index v) {
        g[v] = facingFunction(ctx.camera, mesh.position(v), normals[v]);
    });
    long long front = 0, zero = 0;
    for (double x : g) {
        front += isFront(x);
        zero += x == 0.0;
    }
    s.fields[fields::kVertexNormal] = normalField;
    s.setField(fields::kG,
               {FieldLocation::Vertex, std::move(g), "g = (c - p) · n, > 0 front-facing"});
    s.setCounter(counters::kFrontVertices, static_cast<double>(front));
    s.setCounter(counters::kBackVertices, static_cast<double>(mesh.vertexCount() - front));
    s.setCounter(counters::kVerticesWithG0, static_cast<double>(zero));
    if (zero > 0)
        s.notes.push_back(std::to_string(zero) + " vertices have g exactly 0 (not in generic "
                                                 "position); they count as back-facing");
    // The faces' own facing, for front/back colouring of the mesh.
    publishFaceFacing(ctx, s);
}

std::vector<InvariantCheck> checkVertexFacing(const PhaseContext&, const Snapshot& s) {
    InvariantCheck finite{"g is finite at every vertex", 0, ""};
    const std::vector<double>& g = *s.field(fields::kG)->scalars();
    for (size_t v = 0; v < g.size(); ++v)
        if (!std::isfinite(g[v]) && finite.violations++ == 0)
            finite.firstExample = "vertex " + std::to_string(v);
    return {finite};
}

// Tutorial §6.2 step 4, with the notes' erratum 2: t = g_i / (g_i - g_j) and
// p = p_i + t (p_j - p_i). The crossing is computed once per edge, so the two
// faces of an edge share it exactly and the chains close.
void extractZeroCrossings(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<double>& g = *s.field(fields::kG)->scalars();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> crossing(mesh.edgeCount(), nan);
    tbb::parallel_for(Index(0), mesh.edgeCount(), [&](Index e) {
        const Index h = mesh.edgeHalfedge(e);
        const double gi = g[mesh.from(h)], gj = g[mesh.to(h)];
        if (isFront(gi) != isFront(gj))
            crossing[e] = gi / (gi - gj);
    });
    ctx.checkCancelled();
    // Step 5: a face with sign changes on two edges holds one segment.
    std::vector<int> contourFace(mesh.faceCount(), 0);
    tbb::parallel_for(Index(0), mesh.faceCount(), [&](Index f) {
        int n = 0;
        for (int c = 0; c < 3; ++c)
            n += !std::isnan(crossing[mesh.edge(TriangleMesh::halfedge(f, c))]);
        contourFace[f] = n == 2 ? 1 : 0;
    });
    long long crossings = 0, faces = 0;
    for (double t : crossing)
        crossings += !std::isnan(t);
    for (int c : contourFace)
        faces += c;
    s.setField(fields::kZeroCrossing,
               {FieldLocation::Edge, std::move(crossing),
                "t of the zero crossing of g along the edge's stored half-edge, NaN if none"});
    s.setField(fields::kContourFace, {FieldLocation::Face, std::move(contourFace),
                                      "1 if the face holds an interpolated contour segment"});
    s.setCounter(counters::kCrossingEdges, static_cast<double>(crossings));
    s.setCounter(counters::kContourSegments, static_cast<double>(faces));
}

std::vector<InvariantCheck> checkZeroCrossings(const PhaseContext&, const Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<double>& g = *s.field(fields::kG)->scalars();
    const std::vector<double>& crossing = *s.field(fields::kZeroCrossing)->scalars();
    InvariantCheck onEdge{"every crossing lies on its edge (0 <= t <= 1)", 0, ""};
    InvariantCheck zero{"interpolated g vanishes at every crossing", 0, ""};
    InvariantCheck perFace{"every face has zero or two crossing edges", 0, ""};
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const double t = crossing[e];
        if (std::isnan(t))
            continue;
        const Index h = mesh.edgeHalfedge(e);
        const double gi = g[mesh.from(h)], gj = g[mesh.to(h)];
        if (!(t >= 0.0 && t <= 1.0) && onEdge.violations++ == 0)
            onEdge.firstExample = "edge " + std::to_string(e);
        const double value = (1.0 - t) * gi + t * gj;
        if (std::abs(value) > 1e-12 * std::max(std::abs(gi), std::abs(gj)) &&
            zero.violations++ == 0)
            zero.firstExample = "edge " + std::to_string(e);
    }
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        int n = 0;
        for (int c = 0; c < 3; ++c)
            n += !std::isnan(crossing[mesh.edge(TriangleMesh::halfedge(f, c))]);
        if (n != 0 && n != 2 && perFace.violations++ == 0)
            perFace.firstExample = "face " + std::to_string(f);
    }
    return {onEdge, zero, perFace};
}

// Step 6: chain the face segments across shared edges. Nodes are edges, so
// on a closed mesh every chain closes; open chains end on boundary edges.
void chainSegmentsAcrossEdges(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<double>& crossing = *s.field(fields::kZeroCrossing)->scalars();
    const std::vector<int>& contourFace = *s.field(fields::kContourFace)->labels();
    std::vector<ChainSegment> segments;
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        if (!contourFace[f])
            continue;
        Index ends[2];
        int n = 0;
        for (int c = 0; c < 3; ++c) {
            const Index e = mesh.edge(TriangleMesh::halfedge(f, c));
            if (!std::isnan(crossing[e]))
                ends[n++] = e;
        }
        segments.push_back({ends[0], ends[1], f});
    }
    ctx.checkCancelled();
    const std::vector<Chain> chains = chainSegments(segments, mesh.edgeCount());
    std::vector<Polyline> lines;
    for (const Chain& chain : chains) {
        Polyline line;
        line.type = CurveType::Contour;
        line.closed = chain.closed;
        line.source = SegmentSource::Face;
        for (Index e : chain.nodes) {
            const Index h = mesh.edgeHalfedge(e);
            const double t = crossing[e];
            const Vec3& pi = mesh.position(mesh.from(h));
            const Vec3& pj = mesh.position(mesh.to(h));
            line.points.push_back({pi + t * (pj - pi), kInvalidIndex, e, t});
        }
        for (Index seg : chain.segments)
            line.segmentElement.push_back(segments[seg].element);
        lines.push_back(std::move(line));
    }
    publishCurves(s, std::move(lines), ctx.parameters.getBool("include-boundaries"));
}

std::vector<InvariantCheck> checkChains(const PhaseContext&, const Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    InvariantCheck ends{"open chains end on boundary edges", 0, ""};
    for (const Polyline& line : *s.curves) {
        if (line.type != CurveType::Contour || line.closed)
            continue;
        for (const CurvePoint* p : {&line.points.front(), &line.points.back()})
            if (!mesh.isBoundaryEdge(p->edge) && ends.violations++ == 0)
                ends.firstExample = "edge " + std::to_string(p->edge);
    }
    return {ends};
}

} // namespace

Method makeInterpolatedContourMethod() {
    Method m;
    m.name = "interpolated";
    m.label = "Interpolated contours";
    m.description = "Zero set of g = (c - p) · n interpolated linearly from vertex normals "
                    "(tutorial §6.2, Hertzmann & Zorin 2000), on the triangulated cage or on a "
                    "tessellation of its smooth surface with exact limit normals.";
    m.presets = {defaultPreset()};
    // Each phase's parameters are declared before it (Method::addPhase).
    m.parameters = surfaceParameters();
    m.parameters.push_back(
        {"normal-weighting",
         "Vertex normal weights",
         "How face normals are averaged into vertex normals: area (tutorial §6.2.1), angle, or "
         "Max (1999). Only with surface = none; a smooth surface gives exact normals.",
         ParameterType::Choice,
         std::string("area"),
         0,
         0,
         {"area", "angle", "max"}});
    m.addPhase(makeSurfacePhase({[](const ParameterSet& p) {
        return normalWeightingFromName(p.getChoice("normal-weighting"));
    }}));
    m.addPhase({"facing",
                "Vertex normals, g = (c - p) · n at every vertex, and each face's facing.",
                computeVertexFacing, checkVertexFacing});
    m.addPhase({"extraction",
                "Zero crossings of g on edges (t = g_i / (g_i - g_j)); one segment per face "
                "with two crossings.",
                extractZeroCrossings, checkZeroCrossings});
    m.parameters.push_back({"include-boundaries",
                            "Include boundaries",
                            "Also chain the mesh's boundary edges as curves (tutorial §3.2).",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.addPhase({"chaining",
                "Chain segments across shared edges: closed loops on closed meshes, open at "
                "boundaries.",
                chainSegmentsAcrossEdges, checkChains});
    addVisibilityPhase(m, VisibilityFlavor::Interpolated);
    addSimplificationPhase(m);
    return m;
}

} // namespace contour
