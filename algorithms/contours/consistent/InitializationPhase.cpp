// Initialization (Bénard 2014 §6.1, Fig. 15a-c; notes §2.1).
#include "contours/consistent/ConsistentPhaseSupport.h"
#include "contours/consistent/ConsistentPhases.h"
#include "surface/SurfaceTessellation.h"

#include <tbb/parallel_for.h>

namespace contour::consistent {

namespace {

// §6.1 (Fig. 15a-c, notes §2.1): the domain (for Catmull-Clark the cage
// subdivided once, all quads) tessellated at level 1, each quad split into
// two triangles, vertices at their limit positions and labelled by sign(g);
// then the sign-crossing search on FF and BB edges.
void runInitialization(const PhaseContext& ctx, Snapshot& s) {
    const std::shared_ptr<const SmoothSurface> surface = surfaceFor(ctx, s);
    ConsistentMesh m(surface, ctx.camera, ctx.parameters.getDouble("chart-tolerance"));
    m.setVertexRingCharts(ctx.parameters.getBool("chart-vertex-rings"));
    const int phase = s.phaseIndex;
    // Step 1-3: subdivide once (the Catmull-Clark domain already is), split
    // quads, move to the limit (SurfaceTessellation at level 1).
    // The tessellation (and its surface points, f and derivatives at every
    // vertex) depends on the surface only: shared by every view.
    const std::shared_ptr<const SurfaceTessellation> tessellation = sharedTessellation(surface, 1);
    const SurfaceTessellation& t = *tessellation;
    std::vector<MeshVertex> initial(t.preimages.size());
    tbb::parallel_for(size_t(0), t.preimages.size(), [&](size_t i) {
        initial[i] = m.evaluated(t.preimages[i], t.points[i]);
        initial[i].phase = phase;
    });
    m.reserve(static_cast<Index>(initial.size()), t.mesh->faceCount());
    for (const MeshVertex& v : initial)
        m.addVertex(v);
    for (Index f = 0; f < t.mesh->faceCount(); ++f)
        m.addFace(t.mesh->triangle(f), phase);
    s.setCounter("initial faces", m.faceCount());
    ctx.checkCancelled();
    // Step 4: sign-crossing detection with `crossing-samples` samples of
    // R_S per FF or BB edge, along the interpolated preimage (appendix B);
    // the edge is split at the first sample whose label differs (which one
    // to use is unspecified in the paper), into two FB edges (Fig. 16a).
    const int samples = ctx.parameters.getInt("crossing-samples");
    long long splits = 0, cancelled = 0;
    const auto edges = m.edges();
    // A split leaves the other edges' endpoints as they were, so every
    // edge's search only reads the initial vertices: searched in parallel,
    // applied in edge order.
    enum class Found : char { None, Split, Cancelled };
    std::vector<Found> found(edges.size(), Found::None);
    std::vector<MeshVertex> at(edges.size());
    std::vector<double> tk(static_cast<size_t>(samples));
    for (int k = 1; k <= samples; ++k)
        tk[static_cast<size_t>(k - 1)] = static_cast<double>(k) / (samples + 1);
    tbb::parallel_for(size_t(0), edges.size(), [&](size_t i) {
        if (i % 4096 == 0)
            ctx.checkCancelled();
        const auto [a, b] = edges[i];
        const VertexLabel la = m.vertex(a).label;
        if (la == VertexLabel::Contour || la != m.vertex(b).label)
            return;
        std::vector<std::optional<Preimage>> along(tk.size());
        m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, tk, along);
        for (const std::optional<Preimage>& p : along) {
            if (!p) {
                found[i] = Found::Cancelled;
                return;
            }
            // The label decides; the radial curvature only for the split.
            if (m.evaluateWithoutCurvature(*p).label == la)
                continue;
            MeshVertex v = m.evaluate(*p);
            v.provenance = Provenance::Inserted;
            at[i] = v;
            found[i] = Found::Split;
            return;
        }
    });
    ctx.checkCancelled();
    for (size_t i = 0; i < edges.size(); ++i) {
        if (found[i] == Found::Cancelled)
            ++cancelled;
        if (found[i] != Found::Split)
            continue;
        m.splitEdge(edges[i][0], edges[i][1], at[i], phase);
        ++splits;
    }
    publish(s, m);
    s.setCounter("sign-crossing splits", static_cast<double>(splits));
    s.setCounter("cancelled interpolations", static_cast<double>(cancelled));
    if (cancelled > 0)
        s.notes.push_back(std::to_string(cancelled) +
                          " edges were not searched for sign crossings: their endpoints' "
                          "preimages have no common chart (appendix B)");
}

std::vector<InvariantCheck> checkInitialization(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, false);
    out.push_back(labelsFollowG(m));
    return out;
}

} // namespace

void addInitializationPhase(Method& m) {
    m.parameters.push_back(
        {"crossing-samples",
         "Sign-crossing samples",
         "Samples of sign(g) per FF or BB edge in the sign-crossing search (§6.1; paper: 10).",
         ParameterType::Int,
         10,
         1,
         1000,
         {}});
    m.phases.push_back(
        {"initialization",
         "§6.1 (Fig. 15a-c): the smooth surface's domain (Catmull-Clark: cage subdivided once) "
         "triangulated, vertices at the limit and labelled by sign(g); sign-crossing search "
         "on FF and BB edges with crossing-samples samples, splitting at the first crossing.",
         runInitialization, checkInitialization});
}

} // namespace contour::consistent
