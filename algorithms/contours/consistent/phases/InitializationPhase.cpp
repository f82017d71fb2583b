// Initialization (Bénard 2014 §6.1, Fig. 15a-c).
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/Initialization.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "surface/SurfaceTessellation.h"

#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>

namespace contour::consistent {

CrossingSearchOptions CrossingSearchOptions::read(const ParameterSet& p) {
    CrossingSearchOptions o;
    o.samples = p.getInt("crossing-samples");
    o.rounds = p.getInt("crossing-search-rounds");
    return o;
}

namespace {

// The phase's parameters, read once per run.
struct InitializationOptions {
    ChartOptions charts;
    int crossingSamples = 0;   // crossing-samples
    int crossingRounds = 0;    // crossing-search-rounds
    bool deepestFirst = false; // crossing-split-deepest
    static InitializationOptions read(const ParameterSet& p) {
        InitializationOptions o;
        o.charts = ChartOptions::read(p);
        const CrossingSearchOptions crossing = CrossingSearchOptions::read(p);
        o.crossingSamples = crossing.samples;
        o.crossingRounds = crossing.rounds;
        o.deepestFirst = p.getBool("crossing-split-deepest");
        return o;
    }
};

// §6.1 (Fig. 15a-c): the domain (for Catmull-Clark the cage
// subdivided once, all quads) tessellated at level 1, each quad split into
// two triangles, vertices at their limit positions and labelled by sign(g);
// then the sign-crossing search on FF and BB edges.
void runInitialization(const PhaseContext& ctx, Snapshot& s) {
    const InitializationOptions options = InitializationOptions::read(ctx.parameters);
    const std::shared_ptr<const SmoothSurface> surface = surfaceFor(ctx, s);
    ConsistentMesh m(surface, ctx.camera, options.charts.tolerance);
    m.setVertexRingCharts(options.charts.vertexRings);
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
    s.setCounter(counters::kInitialFaces, m.faceCount());
    ctx.checkCancelled();
    // Step 4: sign-crossing detection with `crossing-samples` samples of
    // R_S per FF or BB edge, along the interpolated preimage (appendix B);
    // the edge is split at the first sample whose label differs (which one
    // to use is unspecified in the paper), into two FB edges (Fig. 16a).
    const int samples = options.crossingSamples;
    const int rounds = options.crossingRounds;
    const bool deepestFirst = options.deepestFirst;
    long long splits = 0, cancelled = 0, laterSplits = 0;
    std::vector<double> tk(static_cast<size_t>(samples));
    for (int k = 1; k <= samples; ++k)
        tk[static_cast<size_t>(k - 1)] = static_cast<double>(k) / (samples + 1);
    // A split leaves the other edges' endpoints as they were, so every
    // edge's search only reads vertices that exist before the round:
    // searched in parallel, applied in edge order. Returns the new vertices.
    enum class Found : char { None, Split, Cancelled };
    // Later rounds: the split vertex (each edge's first end) can lie very
    // close to g = 0 (the first sample of the other label), so g = 0 can
    // pass right next to it (spot view 31: two crossings at 0.3 % and 7 % of
    // the edge from it): samples at 2^-k of the edge from it too, merged;
    // and the split takes the deepest sample of the run (the first one would
    // put the new vertex next to g = 0 again, and the rounds would chase it).
    std::vector<double> tNear = tk;
    for (int k = 2; k <= 12; ++k)
        tNear.push_back(std::ldexp(1.0, -k));
    std::sort(tNear.begin(), tNear.end());
    tNear.erase(std::unique(tNear.begin(), tNear.end()), tNear.end());
    const auto searchAndSplit = [&](const std::vector<std::array<Index, 2>>& edges,
                                    const std::vector<double>& ts, bool deepest,
                                    long long& splitCount) {
        std::vector<Found> found(edges.size(), Found::None);
        std::vector<MeshVertex> at(edges.size());
        tbb::parallel_for(size_t(0), edges.size(), [&](size_t i) {
            if (i % 4096 == 0)
                ctx.checkCancelled();
            const auto [a, b] = edges[i];
            const VertexLabel la = m.vertex(a).label;
            if (la == VertexLabel::Contour || la != m.vertex(b).label)
                return;
            std::vector<std::optional<Preimage>> along(ts.size());
            m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, ts, along);
            std::optional<Preimage> split;
            double depth = 0.0;
            for (const std::optional<Preimage>& p : along) {
                if (!p) {
                    found[i] = Found::Cancelled;
                    return;
                }
                // The label decides; the radial curvature only for the split.
                const MeshVertex v = m.evaluateWithoutCurvature(*p);
                if (v.label == la) {
                    if (split)
                        break; // the end of the first run of the other label
                    continue;
                }
                if (!split || (deepest && std::abs(v.g) > depth)) {
                    split = p;
                    depth = std::abs(v.g);
                }
                if (!deepest)
                    break;
            }
            if (!split)
                return;
            at[i] = m.evaluate(*split);
            at[i].provenance = Provenance::Inserted;
            found[i] = Found::Split;
        });
        ctx.checkCancelled();
        std::vector<Index> created;
        for (size_t i = 0; i < edges.size(); ++i) {
            if (found[i] == Found::Cancelled)
                ++cancelled;
            if (found[i] != Found::Split)
                continue;
            created.push_back(m.splitEdge(edges[i][0], edges[i][1], at[i], phase));
            ++splitCount;
        }
        return created;
    };
    std::vector<Index> created = searchAndSplit(m.edges(), tk, deepestFirst, splits);
    // The FF and BB edges at the given split vertices, each once.
    const auto edgesAt = [&](std::vector<Index> vertices) {
        std::sort(vertices.begin(), vertices.end());
        std::vector<std::array<Index, 2>> out;
        for (const Index v : vertices)
            for (const Index w : m.neighbours(v))
                if (m.vertex(v).label == m.vertex(w).label &&
                    (v < w || !std::binary_search(vertices.begin(), vertices.end(), w)))
                    out.push_back({v, w});
        return out;
    };
    // crossing-search-rounds: a split vertex has the other label, so its new
    // edges to the two opposite corners can be FF or BB edges that the paper's
    // single pass never searched (spot view 2: a contour loop joined to its
    // neighbour and a cusp lost across such an edge). Search the edges at the
    // vertices of the last round, as many rounds as allowed.
    for (int round = 1; round < rounds && !created.empty(); ++round)
        created = searchAndSplit(edgesAt(created), tNear, true, laterSplits);
    const size_t unsearched = edgesAt(created).size();
    publish(s, m);
    s.setCounter(counters::kSignCrossingSplits, static_cast<double>(splits));
    s.setCounter(counters::kSignCrossingSplitsOnNewEdges, static_cast<double>(laterSplits));
    if (unsearched > 0)
        s.notes.push_back(std::to_string(unsearched) +
                          " FF or BB edges made by the last round's sign-crossing splits were not "
                          "searched (crossing-search-rounds)");
    s.setCounter(counters::kCancelledInterpolations, static_cast<double>(cancelled));
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
    m.parameters.push_back(
        {"crossing-search-rounds",
         "Sign-crossing search rounds",
         "Rounds of the sign-crossing search (§6.1). 1: the paper's single pass. n > 1 "
         "(not in the paper): each further round searches the FF and BB edges the "
         "previous round's splits created, with finer samples near the split vertex, "
         "splitting at the deepest sample.",
         ParameterType::Int,
         4,
         1,
         100,
         {}});
    m.parameters.push_back(
        {"crossing-split-deepest",
         "Split at the deepest crossing sample",
         "Which sample of the sign-crossing search (§6.1, which leaves it open) becomes "
         "the split vertex. Off: the first sample of the other label. On (not in the "
         "paper): the sample of that run where |g| is largest, away from the contour. "
         "First pass only; later rounds take the deepest.",
         ParameterType::Bool,
         false,
         0,
         0,
         {}});
    m.addPhase(
        {"initialization",
         "§6.1 (Fig. 15a-c): the smooth surface's domain (Catmull-Clark: cage subdivided once) "
         "triangulated, vertices at the limit and labelled by sign(g); sign-crossing search "
         "on FF and BB edges with crossing-samples samples, splitting at the first crossing; "
         "then crossing-search-rounds - 1 rounds on the FF and BB edges the splits created.",
         runInitialization, checkInitialization});
}

} // namespace contour::consistent
