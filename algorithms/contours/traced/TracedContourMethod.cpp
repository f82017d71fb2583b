// Traced contours (Summers 2016): the contour generator g = 0 traced on the
// Catmull-Clark or Loop limit surface itself, from seeds on the domain edges
// and inside faces, by predictor-corrector steps, then the cusps and the
// common view graph. Summers works in orthographic projection only; g =
// (c - f) · n here covers perspective too (SurfaceFields.h).
#include "contours/Methods.h"
#include "contours/common/EdgePolylines.h"
#include "contours/common/FacingPhase.h"
#include "contours/common/SurfacePhase.h"
#include "contours/traced/CurveTracer.h"
#include "contours/traced/EdgePolynomials.h"
#include "contours/traced/EdgeSeeds.h"
#include "contours/traced/InteriorSeeds.h"
#include "contours/traced/TracedCusps.h"
#include "contours/traced/TracedState.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"
#include "surface/SurfaceTessellation.h"
#include "visibility/SimplificationPhase.h"
#include "visibility/VisibilityPhase.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace contour {

namespace {

using namespace traced;

constexpr const char* kToleranceGroup = "tolerances";

std::shared_ptr<const SmoothSurface> surfaceOf(const PhaseContext& ctx, const Snapshot& s) {
    const std::optional<SurfaceKind> kind = selectedSurfaceKind(ctx.parameters, *s.cage);
    if (!kind || (*kind != SurfaceKind::CatmullClark && *kind != SurfaceKind::Loop))
        throw std::invalid_argument("traced contours need a Catmull-Clark or Loop surface");
    return cachedSmoothSurface(s.cage, *kind).surface;
}

double diagonal(const Snapshot& s) {
    return std::max(s.mesh->boundingBox().diagonal(), 1e-300);
}

double gTolerance(const PhaseContext& ctx, const Snapshot& s) {
    return ctx.parameters.getDouble("g-tolerance") * diagonal(s);
}

EdgePolynomialOptions polynomialOptions(const ParameterSet& p) {
    EdgePolynomialOptions o;
    o.fitTolerance = p.getDouble("fit-tolerance");
    o.fallbackSamples = p.getInt("fallback-samples");
    return o;
}

TracerOptions tracerOptions(const PhaseContext& ctx, const Snapshot& s) {
    TracerOptions o;
    o.maxStep = ctx.parameters.getDouble("max-step");
    o.minStep = ctx.parameters.getDouble("min-step");
    o.maxDeviation = ctx.parameters.getDouble("max-deviation");
    o.maxTurn = ctx.parameters.getDouble("max-turn");
    o.gTolerance = gTolerance(ctx, s);
    // grad g is a length per unit of parameter (about the diagonal): far below
    // it two branches of g = 0 touch or cross (Summers 2016 Fig. 13).
    o.singularGradient = 1e-5 * diagonal(s);
    return o;
}

// The state so far, with every missing piece up to `upTo` rebuilt.
enum class Stage { EdgeSeeds, InteriorSeeds, Curves, Cusps };
std::shared_ptr<TracedState> ensureState(const PhaseContext& ctx, const Snapshot& s, Stage upTo) {
    auto state = std::make_shared<TracedState>();
    if (const auto* previous = dynamic_cast<const TracedState*>(s.methodState.get()))
        *state = *previous;
    if (!state->surface)
        state->surface = surfaceOf(ctx, s);
    const SmoothSurface& surface = *state->surface;
    if (!state->edgeSeeds) {
        state->polynomials =
            sharedEdgePolynomials(state->surface, polynomialOptions(ctx.parameters));
        EdgeSeedOptions o;
        o.maxDepth = ctx.parameters.getInt("root-depth");
        o.gTolerance = gTolerance(ctx, s);
        state->edgeSeeds = std::make_shared<const EdgeSeeds>(
            findEdgeSeeds(surface, *state->polynomials, ctx.camera, o));
    }
    if (upTo >= Stage::InteriorSeeds && !state->interiorSeeds) {
        InteriorSeedOptions o;
        o.raysPerExtremum = ctx.parameters.getInt("interior-rays");
        o.gTolerance = gTolerance(ctx, s);
        const auto lattice =
            sharedFaceLattice(state->surface, ctx.parameters.getInt("interior-grid"));
        state->interiorSeeds = std::make_shared<const InteriorSeeds>(
            findInteriorSeeds(surface, *lattice, ctx.camera, o));
    }
    if (upTo >= Stage::Curves && !state->curves)
        state->curves = std::make_shared<const std::vector<TracedCurve>>(
            traceContours(surface, ctx.camera, *state->edgeSeeds, *state->interiorSeeds,
                          tracerOptions(ctx, s), nullptr));
    if (upTo >= Stage::Cusps && !state->cusps) {
        CuspOptions o;
        o.samplesPerSegment = ctx.parameters.getInt("cusp-samples");
        o.gTolerance = gTolerance(ctx, s);
        o.jumpCurvature = 1e-4 / diagonal(s);
        state->cusps = std::make_shared<const std::vector<TracedCusp>>(
            findTracedCusps(surface, ctx.camera, *state->curves, o));
    }
    return state;
}

void runEdgeSeeds(const PhaseContext& ctx, Snapshot& s) {
    auto state = std::make_shared<TracedState>();
    state->surface = surfaceOf(ctx, s);
    const auto t0 = std::chrono::steady_clock::now();
    state->polynomials = sharedEdgePolynomials(state->surface, polynomialOptions(ctx.parameters));
    s.setCounter(counters::kEdgeSetupSeconds,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    ctx.checkCancelled();
    s.methodState = state;
    state = ensureState(ctx, s, Stage::EdgeSeeds);
    const EdgeSeeds& seeds = *state->edgeSeeds;
    s.setCounter(counters::kEdgeRoots, static_cast<double>(seeds.roots.size()));
    s.setCounter(counters::kCertifiedEdges, static_cast<double>(seeds.certifiedEdges));
    s.setCounter(counters::kSampledEdges, static_cast<double>(seeds.sampledEdges));
    s.setCounter(counters::kUnresolvedRootClusters, static_cast<double>(seeds.unresolvedClusters));
    s.setCounter(counters::kVanishingEdges, static_cast<double>(seeds.vanishingEdges));
    s.setCounter(counters::kTangentRoots, static_cast<double>(seeds.tangentRoots));
    if (seeds.vanishingEdges > 0)
        s.notes.push_back(
            "degenerate view: g vanishes along " + std::to_string(seeds.vanishingEdges) +
            " whole domain edges (the contour runs along patch edges, Summers 2016 §3.4.2.2); "
            "those edges give no seeds and the contour there is not traced");
    if (seeds.unresolvedClusters > 0)
        s.notes.push_back(std::to_string(seeds.unresolvedClusters) +
                          " root clusters on edges were not isolated (a contour tangent to an "
                          "edge or roots closer than 2^-root-depth)");
    s.methodState = state;
}

std::vector<InvariantCheck> checkEdgeSeeds(const PhaseContext& ctx, const Snapshot& s) {
    InvariantCheck small{"|g| at every polished edge root is within the tolerance", 0, ""};
    const auto* state = dynamic_cast<const TracedState*>(s.methodState.get());
    if (!state || !state->edgeSeeds)
        return {small};
    const double tol = gTolerance(ctx, s);
    for (size_t i = 0; i < state->edgeSeeds->roots.size(); ++i)
        if (!(std::abs(state->edgeSeeds->roots[i].g) <= tol) && small.violations++ == 0)
            small.firstExample = "root " + std::to_string(i);
    return {small};
}

void runInteriorSeeds(const PhaseContext& ctx, Snapshot& s) {
    const auto state = ensureState(ctx, s, Stage::InteriorSeeds);
    const InteriorSeeds& seeds = *state->interiorSeeds;
    s.setCounter(counters::kCriticalPointCandidates, static_cast<double>(seeds.candidates));
    s.setCounter(counters::kCriticalPoints, static_cast<double>(seeds.criticalPoints));
    s.setCounter(counters::kCriticalExtrema, static_cast<double>(seeds.extrema));
    s.setCounter(counters::kCriticalSaddles, static_cast<double>(seeds.saddles));
    s.setCounter(counters::kInteriorSeeds, static_cast<double>(seeds.seeds.size()));
    s.methodState = state;
}

// Per domain face, the tessellation triangles over it (for segmentElement).
struct FaceTriangles {
    std::vector<std::vector<Index>> ofFace;
};

Index triangleAt(const SurfaceTessellation& t, const FaceTriangles& index, const Preimage& p) {
    Index best = kInvalidIndex;
    double bestOutside = std::numeric_limits<double>::infinity();
    const Vec2 x(p.u, p.v);
    for (Index f : index.ofFace[static_cast<size_t>(p.face)]) {
        const auto& c = t.cornerUv[static_cast<size_t>(f)];
        double outside = 0.0;
        for (int k = 0; k < 3; ++k) {
            const Vec2 a = c[static_cast<size_t>(k)], b = c[static_cast<size_t>((k + 1) % 3)];
            const Vec2 d = b - a;
            // Counter-clockwise triangles: outside is to the right of an edge.
            outside = std::max(outside, (d.y() * (x - a).x() - d.x() * (x - a).y()) /
                                            std::max(d.norm(), 1e-300));
        }
        if (outside < bestOutside) {
            bestOutside = outside;
            best = f;
        }
    }
    return best;
}

void runTracing(const PhaseContext& ctx, Snapshot& s) {
    auto state = ensureState(ctx, s, Stage::InteriorSeeds);
    TracerStats stats;
    state->curves = std::make_shared<const std::vector<TracedCurve>>(
        traceContours(*state->surface, ctx.camera, *state->edgeSeeds, *state->interiorSeeds,
                      tracerOptions(ctx, s), &stats));
    ctx.checkCancelled();
    const std::vector<TracedCurve>& curves = *state->curves;
    const auto tessellation =
        sharedTessellation(state->surface, ctx.parameters.getInt("tessellation-level"));
    FaceTriangles index;
    index.ofFace.resize(static_cast<size_t>(state->surface->domain().faceCount()));
    for (size_t f = 0; f < tessellation->sourceFace.size(); ++f)
        index.ofFace[static_cast<size_t>(tessellation->sourceFace[f])].push_back(
            static_cast<Index>(f));
    std::vector<Polyline> lines;
    long long loops = 0, open = 0, interiorLoops = 0;
    for (const TracedCurve& c : curves) {
        Polyline line;
        line.type = CurveType::Contour;
        line.closed = c.closed;
        line.source = SegmentSource::Face;
        line.offMesh = true;
        for (const TracedPoint& p : c.points)
            line.points.push_back({p.position, kInvalidIndex, kInvalidIndex, 0.0});
        for (const TracedSegment& seg : c.segments)
            line.segmentElement.push_back(triangleAt(
                *tessellation, index,
                {seg.face, 0.5 * (seg.a.x() + seg.b.x()), 0.5 * (seg.a.y() + seg.b.y())}));
        (c.closed ? loops : open)++;
        interiorLoops += c.interior;
        lines.push_back(std::move(line));
    }
    const EdgeSeeds& edgeSeeds = *state->edgeSeeds;
    s.setCounter(counters::kTracedSeeds,
                 static_cast<double>(edgeSeeds.roots.size() + state->interiorSeeds->seeds.size()));
    s.setCounter(counters::kLoops, static_cast<double>(loops));
    s.setCounter(counters::kOpenCurves, static_cast<double>(open));
    s.setCounter(counters::kInteriorLoops, static_cast<double>(interiorLoops));
    s.setCounter(counters::kTracingSteps, static_cast<double>(stats.steps));
    s.setCounter(counters::kRejectedSteps, static_cast<double>(stats.rejectedSteps));
    s.setCounter(counters::kStalls, static_cast<double>(stats.stalls));
    s.setCounter(counters::kRecoveredStalls, static_cast<double>(stats.recoveredStalls));
    s.setCounter(counters::kCollisions, static_cast<double>(stats.collisions));
    s.setCounter(counters::kSingularPoints, static_cast<double>(stats.singularPoints));
    s.setCounter(counters::kJoinedPieces, static_cast<double>(stats.joinedPieces));
    s.setCounter(counters::kUnreachedRoots, static_cast<double>(stats.unreachedRoots));
    s.setCounter(counters::kRootlessCrossings, static_cast<double>(stats.rootlessCrossings));
    if (stats.rootlessCrossings > 0)
        s.notes.push_back(std::to_string(stats.rootlessCrossings) +
                          " times a curve crossed a domain edge where the edge has no root of g: "
                          "the contour touches the edge or runs along it (a view not in general "
                          "position); the tracer crossed without a seed there");
    s.setCounter(counters::kInteriorSeedsOnCurves,
                 static_cast<double>(stats.interiorSeedsOnCurves));
    s.setCounter(counters::kInteriorSeedsLeavingFace,
                 static_cast<double>(stats.interiorSeedsLeavingFace));
    s.setCounter(counters::kMaxAbsG, stats.maxAbsG / diagonal(s));
    if (open > 0) {
        std::string ends;
        for (const TracedCurve& c : curves)
            if (!c.closed)
                ends += std::string(ends.empty() ? "" : ", ") + toString(c.end);
        s.notes.push_back(std::to_string(open) + " traced curves stay open (" + ends + ")");
    }
    if (stats.singularPoints > 0)
        s.notes.push_back("grad g vanishes on the contour at " +
                          std::to_string(stats.singularPoints) +
                          " points: the view is degenerate there (curves touch or cross, Summers "
                          "2016 Fig. 13); tracing stops at them");
    publishCurves(s, std::move(lines), ctx.parameters.getBool("include-boundaries"));
    s.methodState = state;
}

std::vector<InvariantCheck> checkTracing(const PhaseContext& ctx, const Snapshot& s) {
    InvariantCheck onCurve{"|g| at every traced point is within the tolerance", 0, ""};
    InvariantCheck segments{"every curve has one segment per point (closed) or one fewer", 0, ""};
    const auto* state = dynamic_cast<const TracedState*>(s.methodState.get());
    if (!state || !state->curves)
        return {onCurve, segments};
    const double tol = gTolerance(ctx, s);
    for (size_t c = 0; c < state->curves->size(); ++c) {
        const TracedCurve& curve = (*state->curves)[c];
        for (const TracedPoint& p : curve.points)
            if (!(std::abs(p.g) <= tol) && onCurve.violations++ == 0)
                onCurve.firstExample = "curve " + std::to_string(c);
        const size_t expected = curve.closed ? curve.points.size() : curve.points.size() - 1;
        if (curve.segments.size() != expected && segments.violations++ == 0)
            segments.firstExample = "curve " + std::to_string(c);
    }
    return {onCurve, segments};
}

void runCusps(const PhaseContext& ctx, Snapshot& s) {
    auto state = ensureState(ctx, s, Stage::Curves);
    CuspOptions o;
    o.samplesPerSegment = ctx.parameters.getInt("cusp-samples");
    o.gTolerance = gTolerance(ctx, s);
    o.jumpCurvature = 1e-4 / diagonal(s);
    long long samples = 0;
    state->cusps = std::make_shared<const std::vector<TracedCusp>>(
        findTracedCusps(*state->surface, ctx.camera, *state->curves, o, &samples));
    long long jumps = 0;
    for (const TracedCusp& c : *state->cusps)
        jumps += c.jump;
    s.setCounter(counters::kCusps, static_cast<double>(state->cusps->size()));
    s.setCounter(counters::kCuspsAtJumps, static_cast<double>(jumps));
    if (jumps > 0)
        s.notes.push_back(std::to_string(jumps) +
                          " cusps are jumps of the radial curvature over 0 where the evaluator's "
                          "patches meet next to extraordinary vertices (end caps), not roots");
    s.setCounter(counters::kCuspSamples, static_cast<double>(samples));
    // The cusps on the published curves (one polyline per traced curve,
    // one segment per traced segment): the view graph's curtain folds.
    if (s.curves) {
        auto curves = std::make_shared<std::vector<Polyline>>(*s.curves);
        for (const TracedCusp& c : *state->cusps) {
            if (c.curve < 0 || static_cast<size_t>(c.curve) >= curves->size())
                continue;
            (*curves)[static_cast<size_t>(c.curve)].cusps.push_back(
                {static_cast<Index>(c.segment), c.fraction, c.krBefore, c.krAfter});
        }
        for (Polyline& line : *curves)
            std::sort(line.cusps.begin(), line.cusps.end(), [](const auto& x, const auto& y) {
                return x.segment != y.segment ? x.segment < y.segment : x.tau < y.tau;
            });
        s.curves = std::move(curves);
    }
    s.methodState = state;
}

ParameterSpec parameter(const char* name, const char* label, const char* help, ParameterType type,
                        ParameterValue value, double minimum, double maximum,
                        std::string group = {}) {
    return {name, label, help, type, std::move(value), minimum, maximum, {}, std::move(group)};
}

} // namespace

Method makeTracedContourMethod() {
    Method m;
    m.name = "traced";
    m.label = "Traced curves (Summers 2016)";
    m.description =
        "The contour generator g = 0 traced on the Catmull-Clark or Loop limit surface itself "
        "(Summers 2016): seeds where g changes sign on domain edges (Descartes' rule on "
        "Bernstein coefficients where an edge is one polynomial patch) and inside faces (from "
        "critical points of g), predictor-corrector tracing across faces, cusps where the "
        "radial curvature changes sign, then the common view graph. Perspective and "
        "orthographic.";
    m.presets = {defaultPreset()};
    std::vector<ParameterSpec> surface = surfaceParameters();
    for (ParameterSpec& p : surface)
        if (p.name == "surface") {
            p.help = "The limit surface the contour is traced on (OpenSubdiv): Catmull-Clark or "
                     "Loop. auto: Catmull-Clark, or Loop for an all-triangle cage.";
            p.defaultValue = std::string("auto");
            p.choices = {"auto", toString(SurfaceKind::CatmullClark), toString(SurfaceKind::Loop)};
        } else if (p.name == "tessellation-level") {
            p.help = "Each domain quad becomes an L x L grid of quads (domain triangles: L^2 "
                     "triangles): the mesh the view graph's rays are cast against and the "
                     "workbench draws; the contour itself is traced on the limit surface.";
        }
    m.parameters = surface;
    m.addPhase(makeSurfacePhase({}));
    m.addPhase(makeFacingPhase());
    m.parameters.push_back(parameter(
        "g-tolerance", "g tolerance",
        "Largest |g| = |(c - f) · n| accepted on the traced curve and at the seeds, times the "
        "bounding-box diagonal (Summers 2016 §3.4.2.1 uses 1e-8 in its own units).",
        ParameterType::Double, 1e-10, 1e-14, 1e-4, kToleranceGroup));
    m.parameters.push_back(parameter(
        "fit-tolerance", "Polynomial fit tolerance",
        "An edge's Bernstein fit of g's parts must match the surface at check points to this "
        "relative error to be isolated by Descartes' rule; otherwise the edge is sampled. Not in "
        "the paper.",
        ParameterType::Double, 1e-9, 1e-14, 1e-2));
    m.parameters.push_back(parameter(
        "fallback-samples", "Samples per sampled edge",
        "Samples of g along an edge that is not one polynomial patch (extraordinary vertices, "
        "end caps); each sign change is bisected. Not in the paper.",
        ParameterType::Int, 16, 2, 1024));
    m.parameters.push_back(parameter(
        "root-depth", "Root isolation depth",
        "Subdivision depth of Descartes' rule (Summers 2016 §3.4.2.2, Vincent's theorem) before "
        "a cluster of roots (a contour tangent to an edge) is reported and seeded once.",
        ParameterType::Int, 40, 4, 60));
    m.addPhase({"edge-seeds",
                "Seeds where g changes sign on domain edges (Summers 2016 §3.4.2.2): Descartes' "
                "rule and bisection on Bernstein coefficients, dense sampling where an edge is "
                "not one polynomial.",
                runEdgeSeeds, checkEdgeSeeds});
    m.parameters.push_back(parameter(
        "interior-grid", "Critical point lattice",
        "Lattice steps per face side whose discrete extrema of g start Newton's method for the "
        "critical points that seed loops inside one face (Summers 2016 §3.3 uses the "
        "Morse-Smale complex instead).",
        ParameterType::Int, 8, 2, 64));
    m.parameters.push_back(parameter(
        "interior-rays", "Rays per extremum",
        "Rays cast from each extremum of g to the first sign change of g: seeds of the loops "
        "around it. Not in the paper.",
        ParameterType::Int, 8, 1, 64));
    m.addPhase({"interior-seeds",
                "Critical points of g inside faces (Newton from a lattice's discrete extrema) "
                "and seeds of the loops around the extrema (Summers 2016 §3.3).",
                runInteriorSeeds,
                {}});
    m.parameters.push_back(parameter(
        "max-step", "Largest step",
        "Largest predictor step in domain parameters (Summers 2016 §3.4.2.1: a fixed 0.1, about "
        "10 steps per patch); steps shrink where the curve bends or leaves g = 0.",
        ParameterType::Double, 0.1, 1e-4, 1.0));
    m.parameters.push_back(parameter(
        "min-step", "Smallest step",
        "Below this step (domain parameters) the tracer stalls and tries to close the curve on "
        "the next root; a curve that stays open is counted. Not in the paper.",
        ParameterType::Double, 1e-6, 1e-12, 1e-2));
    m.parameters.push_back(parameter(
        "max-deviation", "Largest chord deviation",
        "Bound on the distance of each chord's midpoint to g = 0, |g| / |grad g| in domain "
        "parameters; a step beyond it is halved. Not in the paper.",
        ParameterType::Double, 1e-3, 1e-8, 0.1));
    m.parameters.push_back(parameter(
        "max-turn", "Largest turn per step",
        "Largest angle (radians) between the tangents at the two ends of a step. Not in the "
        "paper.",
        ParameterType::Double, 0.3, 0.01, 1.5));
    m.parameters.push_back(
        parameter("include-boundaries", "Include boundaries",
                  "Also chain the tessellation's boundary edges as curves (tutorial §3.2).",
                  ParameterType::Bool, true, 0, 0));
    m.addPhase({"tracing",
                "Predictor-corrector tracing of g = 0 across faces from every seed, through the "
                "edge roots, with loop closure and duplicate suppression (Summers 2016 "
                "§3.4.2.1).",
                runTracing, checkTracing});
    m.parameters.push_back(parameter(
        "cusp-samples", "Curvature samples per segment",
        "Radial curvature samples per traced segment (points pulled onto g = 0) whose sign "
        "changes are bisected into cusps. Not in the paper.",
        ParameterType::Int, 16, 1, 64));
    m.addPhase({"cusps",
                "Cusps where the radial curvature changes sign along the traced curves, "
                "bisected on the curve.",
                runCusps,
                {}});
    addVisibilityPhase(m, VisibilityFlavor::Interpolated);
    addSimplificationPhase(m);
    return m;
}

} // namespace contour
