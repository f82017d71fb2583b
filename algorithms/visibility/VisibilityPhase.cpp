// The "visibility" phase: the view graph of the snapshot's curves (tutorial
// §4.5–4.7; Bénard 2014 §8) and the QI of every chain.
//   - Mesh contours: exact mesh visibility (tutorial ch. 4, app. B–C).
//   - Consistent contours: the same graph on the consistent mesh, curtain
//     folds by the near-face test (Bénard 2014 §8.1), then §8.4's votes and
//     ambiguity rules (ConsistentVisibility.h).
//   - Interpolated contours: heuristic votes (tutorial §6.2.4,
//     InterpolatedVisibility.h).
#include "visibility/VisibilityPhase.h"

#include "pipeline/FieldNames.h"
#include "visibility/ConsistentVisibility.h"
#include "visibility/InterpolatedVisibility.h"
#include "visibility/QiPropagation.h"
#include "visibility/RayCaster.h"
#include "visibility/SurfaceIntersections.h"
#include "visibility/ViewGraphBuilder.h"

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tbb/parallel_invoke.h>

namespace contour {

namespace {

constexpr const char* kVisibility = "visibility";
constexpr const char* kCheckRays = "visibility-check-rays";
constexpr const char* kNearFaceEpsilon = "near-face-epsilon";
constexpr const char* kShortChain = "ambiguity-short-chain";
constexpr const char* kCuspFolds = "curtain-folds-from-cusps";
constexpr const char* kKeepPropagation = "visibility-keep-clean-propagation";
constexpr const char* kMinLoop = "t-junction-min-loop";
constexpr const char* kSurfaceIntersections = "surface-intersections";
constexpr const char* kVotes = "visibility-votes";
constexpr const char* kIgnoredFaces = "visibility-ignored-faces";

// Surface intersections depend on the mesh only: the mesh and interpolated
// methods share one mesh between views (and the tessellation is cached), so
// the last result is kept for the mesh it was computed on.
struct IntersectionCache {
    std::mutex mutex;
    std::weak_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const SurfaceIntersectionCurves> curves;
};

std::shared_ptr<const SurfaceIntersectionCurves>
cachedSurfaceIntersections(const std::shared_ptr<const TriangleMesh>& mesh, bool* fromCache) {
    static IntersectionCache cache;
    {
        std::lock_guard<std::mutex> lock(cache.mutex);
        if (cache.curves && cache.mesh.lock() == mesh) {
            *fromCache = true;
            return cache.curves;
        }
    }
    auto curves =
        std::make_shared<const SurfaceIntersectionCurves>(surfaceIntersectionCurves(*mesh));
    std::lock_guard<std::mutex> lock(cache.mutex);
    cache.mesh = mesh;
    cache.curves = curves;
    *fromCache = false;
    return curves;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::uint8_t> byteField(const Snapshot& s, const char* name, bool invert, size_t size) {
    std::vector<std::uint8_t> out(size, 0);
    const Field* field = s.field(name);
    if (!field || !field->labels())
        return out;
    const std::vector<int>& values = *field->labels();
    for (size_t i = 0; i < size && i < values.size(); ++i)
        out[i] = static_cast<std::uint8_t>(invert ? values[i] == 0 : values[i] != 0);
    return out;
}

// The phase's parameters, read once per run (each flavour declares its own).
struct VisibilityOptions {
    bool enabled = false;              // visibility
    bool surfaceIntersections = false; // surface-intersections
    bool checkRays = false;            // visibility-check-rays
    double nearFaceEpsilon = 0.0;      // consistent: near-face-epsilon
    double shortChainPixels = 0.0;     // consistent: ambiguity-short-chain
    bool smoothCuspFolds = false;      // consistent: curtain-folds-from-cusps
    bool keepCleanPropagation = false; // consistent: visibility-keep-clean-propagation
    double minLoopPixels = 0.0;        // consistent: t-junction-min-loop
    int votes = 0;                     // interpolated: visibility-votes
    std::string ignoredFaces;          // interpolated: visibility-ignored-faces
    static VisibilityOptions read(VisibilityFlavor flavor, const ParameterSet& p) {
        VisibilityOptions o;
        o.enabled = p.getBool(kVisibility);
        o.surfaceIntersections = p.getBool(kSurfaceIntersections);
        o.checkRays = p.getBool(kCheckRays);
        if (flavor == VisibilityFlavor::Consistent) {
            o.nearFaceEpsilon = p.getDouble(kNearFaceEpsilon);
            o.shortChainPixels = p.getDouble(kShortChain);
            o.smoothCuspFolds = p.getBool(kCuspFolds);
            o.keepCleanPropagation = p.getBool(kKeepPropagation);
            o.minLoopPixels = p.getDouble(kMinLoop);
        }
        if (flavor == VisibilityFlavor::Interpolated) {
            o.votes = p.getInt(kVotes);
            o.ignoredFaces = p.getChoice(kIgnoredFaces);
        }
        return o;
    }
};

void runVisibility(VisibilityFlavor flavor, const PhaseContext& ctx, Snapshot& s) {
    const VisibilityOptions parameters = VisibilityOptions::read(flavor, ctx.parameters);
    if (!parameters.enabled) {
        s.viewGraph.reset();
        s.notes.push_back("visibility is off (--visibility true to turn it on): no view graph, "
                          "the curves are passed through unchanged");
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const TriangleMesh& mesh = *s.mesh;
    std::vector<Polyline> curves = s.curves ? *s.curves : std::vector<Polyline>{};
    std::vector<std::vector<Index>> secondFaces(curves.size());

    // Tutorial §4.2/§4.4, Bénard 2014 §8.1: surface–surface intersections
    // are a third curve type; they join the snapshot's curves.
    double intersectionSeconds = 0.0;
    long long intersectionCurves = 0;
    // The ray caster's scene depends on the mesh only (see below).
    std::unique_ptr<const RayCaster> rayCaster;
    double sceneSeconds = 0.0;
    auto buildScene = [&] {
        const auto t0 = std::chrono::steady_clock::now();
        rayCaster = std::make_unique<const RayCaster>(mesh);
        sceneSeconds = secondsSince(t0);
    };
    // The graph needs the surface intersections (they are curves of the
    // graph) but no ray. The intersections run first on every core (a
    // parallel loop); the graph build is mostly serial, so the Embree scene
    // is built beside it (the two tasks share no written data; each is
    // deterministic on its own, so the result does not depend on the
    // scheduling). Measured on controlmesh, 8 views: 218 -> 190 ms.
    // (Starting the scene before the intersections instead, as a task of
    // its own, measured no better on the loaded VM: 379 vs 385 ms, means
    // of 3 runs.)
    ViewGraphBuildStats built;
    std::shared_ptr<ViewGraph> graph;
    // Consistent contours: cusp vertices and inconsistent faces (the
    // consistent mesh's fields), for the curtain folds and §8.4.
    const std::vector<std::uint8_t> cuspVertex =
        flavor == VisibilityFlavor::Consistent
            ? byteField(s, fields::kCusp, false, static_cast<size_t>(mesh.vertexCount()))
            : std::vector<std::uint8_t>{};
    const std::vector<std::uint8_t> singularCusp =
        flavor == VisibilityFlavor::Consistent
            ? byteField(s, fields::kSingularCusp, false, static_cast<size_t>(mesh.vertexCount()))
            : std::vector<std::uint8_t>{};
    const std::vector<std::uint8_t> faceInconsistent =
        flavor == VisibilityFlavor::Consistent
            ? byteField(s, fields::kConsistent, true, static_cast<size_t>(mesh.faceCount()))
            : std::vector<std::uint8_t>{};
    double buildSeconds = 0.0;
    auto intersections = [&] {
        if (parameters.surfaceIntersections) {
            bool cached = false;
            const auto t0 = std::chrono::steady_clock::now();
            const std::shared_ptr<const SurfaceIntersectionCurves> found =
                cachedSurfaceIntersections(s.mesh, &cached);
            intersectionSeconds = secondsSince(t0);
            s.setCounter(counters::kSurfaceIntersectionsCached, cached ? 1.0 : 0.0);
            intersectionCurves = static_cast<long long>(found->curves.size());
            for (size_t i = 0; i < found->curves.size(); ++i) {
                curves.push_back(found->curves[i]);
                secondFaces.push_back(i < found->secondFaces.size() ? found->secondFaces[i]
                                                                    : std::vector<Index>{});
            }
            if (intersectionCurves > 0)
                s.notes.push_back(std::to_string(intersectionCurves) +
                                  " surface-intersection curves added to the curves");
        }
    };
    auto graphOnly = [&] {
        // Face orientation: the exact facing (mesh, interpolated) or the VBO
        // (consistent: the contour generator separates F-VBO from B-VBO faces).
        const char* orientationField =
            flavor == VisibilityFlavor::Consistent ? fields::kVbo : fields::kFacing;
        const Field* orientation = s.field(orientationField);
        if (!orientation || !orientation->labels())
            throw std::runtime_error(std::string("visibility: the snapshot has no '") +
                                     orientationField + "' face field");

        ViewGraphOptions options;
        options.foldTest = flavor == VisibilityFlavor::Mesh ? CurtainFoldTest::Convexity
                           : flavor == VisibilityFlavor::Consistent
                               ? (parameters.smoothCuspFolds ? CurtainFoldTest::SmoothCusps
                                                             : CurtainFoldTest::NearFace)
                               : CurtainFoldTest::None;
        if (flavor == VisibilityFlavor::Consistent) {
            options.nearFaceEpsilon = parameters.nearFaceEpsilon;
            options.smallLoopPixels = parameters.minLoopPixels;
        }
        // Exact mesh visibility needs every fold of the mesh as an occluder
        // (see ViewGraphOptions); interpolated contours keep the tutorial's
        // simpler model where the curves themselves occlude.
        options.meshFoldOccluders = flavor != VisibilityFlavor::Interpolated;
        options.concaveLowerBound = intersectionCurves == 0;
        if (intersectionCurves > 0 && flavor == VisibilityFlavor::Mesh)
            s.notes.push_back("the mesh intersects itself: concave contours may be visible there "
                              "(tutorial theorem B.0.1 assumes no self-intersection), so they get "
                              "no lower bound and are decided by propagation and rays");
        const Field* facing = s.field(fields::kFacing);
        ViewGraphInput input;
        input.mesh = &mesh;
        input.curves = &curves;
        input.secondFaces = &secondFaces;
        input.faceOrientation = orientation->labels();
        input.facing = facing && facing->labels() ? facing->labels() : orientation->labels();
        if (options.foldTest == CurtainFoldTest::SmoothCusps) {
            const std::vector<double>* kappa = fieldValues<double>(
                s, fields::kRadialCurvature, FieldLocation::Vertex, mesh.vertexCount());
            if (!kappa)
                throw std::runtime_error("visibility: smooth-cusp curtain folds need the "
                                         "per-vertex radial_curvature field");
            input.radialCurvature = kappa;
            input.cuspVertex = &cuspVertex;
            input.singularCusp = &singularCusp;
            input.faceInconsistent = &faceInconsistent;
        }
        const auto tBuild = std::chrono::steady_clock::now();
        graph = std::make_shared<ViewGraph>(buildViewGraph(input, ctx.camera, options, &built));
        buildSeconds = secondsSince(tBuild);
    };
    intersections();
    ctx.checkCancelled();
    tbb::parallel_invoke(graphOnly, buildScene);
    ctx.checkCancelled();

    const RayCaster& rays = *rayCaster;
    const bool checkRays = parameters.checkRays;
    QiPropagationStats propagated;
    // Consistent contours: the rays of propagation and of the check from
    // each chain's middle segment are the ones §8.4 votes with there; they
    // are kept and cast once.
    std::vector<RayResult> middleRays;
    std::vector<RayResult>* keepRays =
        flavor == VisibilityFlavor::Consistent ? &middleRays : nullptr;
    double qiSeconds = 0.0, checkSeconds = 0.0, consistentSeconds = 0.0;
    ConsistentVisibilityStats resolved;
    const auto tQi = std::chrono::steady_clock::now();
    if (flavor == VisibilityFlavor::Interpolated) {
        // Tutorial §6.2.4: interpolated contours lie inside faces, not on the
        // mesh's folds, so the +2/+1 propagation rules do not hold for them;
        // the heuristic vote decides, and the check rays say where it
        // disagrees with a single ray.
        const std::optional<IgnoredFaces> ignored = ignoredFacesFromString(parameters.ignoredFaces);
        if (!ignored)
            throw std::invalid_argument("unknown " + std::string(kIgnoredFaces) + " '" +
                                        parameters.ignoredFaces + "'");
        voteInterpolatedVisibility(*graph, mesh, ctx.camera, rays, parameters.votes, *ignored);
        qiSeconds = secondsSince(tQi);
        if (checkRays) {
            const auto tCheck = std::chrono::steady_clock::now();
            checkChainsWithRays(*graph, mesh, ctx.camera, rays, "the heuristic vote", &propagated);
            checkSeconds = secondsSince(tCheck);
        }
    } else {
        propagateQi(*graph, mesh, ctx.camera, rays, &propagated, keepRays);
        qiSeconds = secondsSince(tQi);
        if (checkRays) {
            const auto tCheck = std::chrono::steady_clock::now();
            checkChainsWithRays(*graph, mesh, ctx.camera, rays, "propagation", &propagated,
                                keepRays);
            checkSeconds = secondsSince(tCheck);
        }
    }
    ctx.checkCancelled();

    if (flavor == VisibilityFlavor::Consistent) {
        ConsistentVisibilityOptions consistent;
        consistent.nearFaceEpsilon = parameters.nearFaceEpsilon;
        consistent.shortChainPixels = parameters.shortChainPixels;
        // Propagation is exact only through the surface's own cusps.
        consistent.keepCleanPropagation =
            parameters.keepCleanPropagation && parameters.smoothCuspFolds;
        const auto tConsistent = std::chrono::steady_clock::now();
        resolveConsistentVisibility(*graph, mesh, ctx.camera, rays, faceInconsistent, cuspVertex,
                                    consistent, keepRays, &resolved);
        consistentSeconds = secondsSince(tConsistent);
    }
    const double raySeconds = sceneSeconds + secondsSince(tQi);

    // Counters.
    long long visible = 0, concave = 0;
    for (const ViewChain& c : graph->chains) {
        visible += c.visible();
        concave += c.concave;
    }
    std::map<ViewNodeType, long long> perType;
    long long unreliable = 0;
    for (const ViewNode& n : graph->nodes) {
        ++perType[n.type];
        unreliable += n.unreliable;
    }
    s.setCounter(counters::kChains, static_cast<double>(graph->chains.size()));
    s.setCounter(counters::kVisibleChains, static_cast<double>(visible));
    s.setCounter(counters::kConcaveContourChains, static_cast<double>(concave));
    s.setCounter(counters::kNodes, static_cast<double>(graph->nodes.size()));
    // "nodes: " + toString(type), in this order.
    for (const auto& [t, name] :
         {std::pair{ViewNodeType::CurtainFold, counters::kNodesCurtainFold},
          std::pair{ViewNodeType::BoundaryCurtainFold, counters::kNodesBoundaryCurtainFold},
          std::pair{ViewNodeType::ImageIntersection, counters::kNodesImageIntersection},
          std::pair{ViewNodeType::ContourBoundaryJunction, counters::kNodesContourBoundaryJunction},
          std::pair{ViewNodeType::Bifurcation, counters::kNodesBifurcation},
          std::pair{ViewNodeType::SurfaceIntersectionEnd, counters::kNodesSurfaceIntersectionEnd},
          std::pair{ViewNodeType::CurveEnd, counters::kNodesCurveEnd},
          std::pair{ViewNodeType::HiddenFoldCrossing, counters::kNodesHiddenFoldCrossing}})
        s.setCounter(name, static_cast<double>(perType[t]));
    s.setCounter(counters::kTJunctions,
                 static_cast<double>(perType[ViewNodeType::ImageIntersection]));
    s.setCounter(counters::kCurtainFolds, static_cast<double>(perType[ViewNodeType::CurtainFold]));
    s.setCounter(counters::kSurfaceIntersectionCurves, static_cast<double>(intersectionCurves));
    s.setCounter(counters::kConnectedComponents, static_cast<double>(propagated.components));
    s.setCounter(counters::kRayTests, static_cast<double>(graph->rayTests));
    s.setCounter(counters::kConflicts, static_cast<double>(graph->conflicts.size()));
    s.setCounter(counters::kRayCheckConflicts, static_cast<double>(propagated.rayConflicts));
    s.setCounter(counters::kRootRayCheckConflicts, static_cast<double>(propagated.rootConflicts));
    s.setCounter(counters::kCheckRaysRecountedExactly,
                 static_cast<double>(propagated.exactRecounts));
    s.setCounter(counters::kCheckRaysCorrectedByTheExactRecount,
                 static_cast<double>(propagated.correctedRays));
    s.setCounter(counters::kPropagationCycleDisagreements,
                 static_cast<double>(propagated.cycleDisagreements));
    s.setCounter(counters::kChainsPropagatedBelowTheirBound,
                 static_cast<double>(propagated.belowLowerBound));
    s.setCounter(counters::kVisibleLengthPx, graph->visibleLengthPixels());
    s.setCounter(counters::kHiddenLengthPx, graph->hiddenLengthPixels());
    s.setCounter(counters::kImageSegments, static_cast<double>(built.segments));
    s.setCounter(counters::kImageSegmentsSwept, static_cast<double>(built.sweptSegments));
    s.setCounter(counters::kImageCrossings, static_cast<double>(built.imageCrossings));
    s.setCounter(counters::kLogicalCrossingsIgnored, static_cast<double>(built.logicalCrossings));
    s.setCounter(counters::kEndpointTouchesIgnored, static_cast<double>(built.endpointTouches));
    s.setCounter(counters::kOverlappingSegmentPairs, static_cast<double>(built.overlaps));
    s.setCounter(counters::kCrossingsBehindNonFoldEdges, static_cast<double>(built.nonFoldNear));
    s.setCounter(counters::kFoldEdgesOffTheCurves, static_cast<double>(built.foldOccluderEdges));
    s.setCounter(counters::kCurtainFoldsByTheOneRingTestAlone,
                 static_cast<double>(built.localOnlyFolds));
    s.setCounter(counters::kCurtainFoldsWithoutALocalStep,
                 static_cast<double>(built.foldsWithoutStep));
    s.setCounter(counters::kCurtainFoldsOccludingTheConvexSide,
                 static_cast<double>(built.convexFarFolds));
    s.setCounter(counters::kMixedConvexityChains, static_cast<double>(built.mixedConvexityChains));
    if (flavor == VisibilityFlavor::Consistent) {
        s.setCounter(counters::kUnreliableNearFaceNodes, static_cast<double>(unreliable));
        s.setCounter(counters::kSmallLoopCrossings, static_cast<double>(built.smallLoopCrossings));
        if (parameters.keepCleanPropagation && parameters.smoothCuspFolds) {
            s.setCounter(counters::kChainsKeptFromPropagation,
                         static_cast<double>(resolved.keptFromPropagation));
            s.setCounter(counters::kChainsDecidedByVotes, static_cast<double>(resolved.voted));
        }
        if (parameters.smoothCuspFolds) {
            s.setCounter(counters::kCurtainFoldsAtCusps,
                         static_cast<double>(built.smoothCuspFolds));
            s.setCounter(counters::kCurtainFoldsAtSingularPoints,
                         static_cast<double>(built.singularCuspFolds));
            s.setCounter(counters::kCuspFoldsSidedByCurvature,
                         static_cast<double>(built.cuspFoldsSidedByCurvature));
            s.setCounter(counters::kCurtainFoldsByTheNearFaceFallback,
                         static_cast<double>(built.fallbackFolds));
            s.setCounter(counters::kZigZagVerticesIgnored,
                         static_cast<double>(built.zigZagsIgnored));
        }
    }
    s.setCounter(counters::kSurfaceIntersectionsSeconds, intersectionSeconds);
    s.setCounter(counters::kViewGraphSeconds, buildSeconds);
    s.setCounter(counters::kSweepSeconds, built.sweepSeconds);
    // Built while the surface intersections and the graph are computed (on
    // the other core when there is one): this time overlaps "surface
    // intersections seconds" and "view graph seconds".
    s.setCounter(counters::kRaySceneSeconds, sceneSeconds);
    s.setCounter(counters::kRayAndQISeconds, raySeconds);
    // Its parts: propagation with one ray per component (or the heuristic
    // votes), the optional check rays, Bénard 2014 §8.4.
    s.setCounter(flavor == VisibilityFlavor::Interpolated ? counters::kVoteSeconds
                                                          : counters::kPropagationSeconds,
                 qiSeconds);
    s.setCounter(counters::kCheckRaysSeconds, checkSeconds);
    if (flavor == VisibilityFlavor::Consistent)
        s.setCounter(counters::kConsistentVisibilitySeconds, consistentSeconds);
    s.setCounter(counters::kVisibilitySeconds, secondsSince(start));

    // Notes: what a user should know about this result.
    std::ostringstream note;
    note << graph->chains.size() << " chains (" << visible << " visible), " << graph->nodes.size()
         << " nodes (" << perType[ViewNodeType::ImageIntersection] << " T-junctions, "
         << perType[ViewNodeType::CurtainFold] << " curtain folds";
    if (perType[ViewNodeType::HiddenFoldCrossing] > 0)
        note << ", " << perType[ViewNodeType::HiddenFoldCrossing]
             << " crossings behind mesh folds off the drawn curves";
    if (flavor == VisibilityFlavor::Consistent && parameters.smoothCuspFolds) {
        note << ": " << built.smoothCuspFolds << " at the surface's cusps, ";
        if (built.singularCuspFolds > 0)
            note << built.singularCuspFolds
                 << " at cusps on singular points of the surface (stepped by the one-ring "
                    "test), ";
        note << built.fallbackFolds << " by the near-face test next to inconsistent faces";
    }
    note << "), " << graph->rayTests << " ray tests";
    s.notes.push_back(note.str());
    if (!graph->conflicts.empty())
        s.notes.push_back(std::to_string(graph->conflicts.size()) +
                          " visibility conflicts (a ray test or a bound disagrees with the "
                          "decided QI); both values are kept on the chain");
    if (propagated.cycleDisagreements > 0)
        s.notes.push_back(std::to_string(propagated.cycleDisagreements) +
                          " propagation links disagree with the QI reached another way");
    if (built.endpointTouches + built.overlaps + built.equalDepthCrossings > 0)
        s.notes.push_back(
            std::to_string(built.endpointTouches + built.overlaps + built.equalDepthCrossings) +
            " degenerate image crossings (endpoint touches, overlaps, equal "
            "depths) were not split");
    if (built.foldsWithoutStep > 0)
        s.notes.push_back(std::to_string(built.foldsWithoutStep) +
                          " curtain folds have no one-ring face over either edge (tutorial §4.7 "
                          "expects at least one): QI is carried across them unchanged");
    if (flavor == VisibilityFlavor::Consistent && unreliable > 0)
        s.notes.push_back(std::to_string(unreliable) +
                          " nodes rest on a near-face test below near-face-epsilon (Bénard 2014 "
                          "footnote 3; the paper's threshold 1 flags most of them)");
    if (flavor == VisibilityFlavor::Interpolated)
        s.notes.push_back("interpolated contours: visibility is a vote of ray tests per chain "
                          "ignoring the contour's " +
                          parameters.ignoredFaces +
                          " (tutorial §6.2.4), approximate by design: expect gaps and halos");
    s.viewGraph = std::move(graph);
    s.curves = std::make_shared<const std::vector<Polyline>>(std::move(curves));
}

std::vector<InvariantCheck> checkVisibility(VisibilityFlavor flavor, const PhaseContext&,
                                            const Snapshot& s) {
    InvariantCheck negative{"QI is never negative", 0, {}};
    InvariantCheck decided{"every chain has a decided QI", 0, {}};
    InvariantCheck concave{
        "concave contour chains are never visible (unless the mesh intersects itself)", 0, {}};
    InvariantCheck nodes{"every chain end is a node that lists the chain", 0, {}};
    std::vector<InvariantCheck> out;
    if (!s.viewGraph) {
        out = {negative, decided, nodes};
        if (flavor == VisibilityFlavor::Mesh)
            out.push_back(concave);
        return out;
    }
    const ViewGraph& g = *s.viewGraph;
    // Theorem B.0.1 needs a mesh without self-intersections.
    const bool selfIntersecting = s.counter(counters::kSurfaceIntersectionCurves, 0.0) > 0.0;
    auto violate = [](InvariantCheck& c, const std::string& example) {
        if (c.violations++ == 0)
            c.firstExample = example;
    };
    for (size_t i = 0; i < g.chains.size(); ++i) {
        const ViewChain& c = g.chains[i];
        const std::string name = "chain " + std::to_string(i);
        if (c.qi < 0 && c.decidedBy != VisibilityRule::Unknown)
            violate(negative, name + " qi " + std::to_string(c.qi));
        if (c.qi < 0 || c.decidedBy == VisibilityRule::Unknown)
            violate(decided, name);
        if (flavor == VisibilityFlavor::Mesh && c.type == CurveType::Contour && c.concave &&
            c.visible() && !selfIntersecting)
            violate(concave, name);
        for (Index end : {c.startNode, c.endNode}) {
            if (end == kInvalidIndex)
                continue;
            const std::vector<Index>& at = g.nodes[end].chains;
            if (std::find(at.begin(), at.end(), static_cast<Index>(i)) == at.end())
                violate(nodes, name + " at node " + std::to_string(end));
        }
        if (!c.closed && (c.startNode == kInvalidIndex || c.endNode == kInvalidIndex))
            violate(nodes, name + " (open, no end node)");
    }
    out = {negative, decided, nodes};
    if (flavor == VisibilityFlavor::Mesh)
        out.push_back(concave);
    return out;
}

} // namespace

void addVisibilityPhase(Method& m, VisibilityFlavor flavor) {
    m.parameters.push_back({kVisibility,
                            "Visibility",
                            "Build the view graph and decide each chain's quantitative "
                            "invisibility (tutorial ch. 4; Bénard 2014 §8). Off: the phase "
                            "passes the curves through.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.parameters.push_back({kCheckRays,
                            "Check QI with rays",
                            "Also ray-test every chain and record each disagreement with the "
                            "propagated QI as a conflict (tutorial §4.6, debugging invariants). "
                            "Off: one ray per connected component only.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.parameters.push_back({kSurfaceIntersections,
                            "Surface intersections",
                            "Find the curves where the mesh intersects itself (tutorial §4.2) "
                            "and add them to the view graph.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    if (flavor == VisibilityFlavor::Consistent) {
        m.parameters.push_back(
            {kNearFaceEpsilon,
             "Near-face epsilon",
             "Bénard 2014 footnote 3: the near-face test of a contour edge is unreliable "
             "when |v · (w1 − w2)| is below this. Default 1, the paper's value as printed; "
             "since |v · (w1 − w2)| ≤ 2, most tests are flagged and it may have lost an "
             "exponent: treat it as tunable.",
             ParameterType::Double,
             1.0,
             0.0,
             2.0,
             {}});
        m.parameters.push_back(
            {kCuspFolds,
             "Curtain folds from cusps",
             "Curtain folds only at the surface's cusps (the cusp vertices of §6.2 d), sided by "
             "the one-ring test, step 1 (at a singular point of the surface, the one-ring's "
             "step); the near-face test (§8.1) only next to inconsistent faces. Off: §8.1 at "
             "every contour vertex. Not in the paper.",
             ParameterType::Bool,
             true,
             0,
             0,
             {}});
        m.parameters.push_back(
            {kKeepPropagation,
             "Keep clean propagation",
             "With curtain folds from cusps on: a propagation component with no inconsistent face, "
             "no near-face fold and no disagreement keeps its propagated QI; the §8.4 votes "
             "decide the others. Off: the votes decide every chain (§8.4). Not in the paper.",
             ParameterType::Bool,
             true,
             0,
             0,
             {}});
        m.parameters.push_back(
            {kMinLoop,
             "T-junction smallest loop (px)",
             "Crossings bounding a loop of contour with less than this image arc (two crossings "
             "of two branches, or a branch around a cusp) are zig-zags of the polyline: their "
             "T-junctions keep their QI steps but are flagged and counted apart. 0 flags none. "
             "Not in the paper.",
             ParameterType::Double,
             1.0,
             0.0,
             100.0,
             {}});
        m.parameters.push_back({kShortChain,
                                "Short chain (px)",
                                "Bénard 2014 §8.4 rule (b): an ambiguous chain between two "
                                "T-junctions shorter than this, whose mates are visible, becomes "
                                "visible. The paper gives no value.",
                                ParameterType::Double,
                                5.0,
                                0.0,
                                1000.0,
                                {}});
    }
    if (flavor == VisibilityFlavor::Interpolated) {
        m.parameters.push_back({kVotes,
                                "Ray votes per chain",
                                "Tutorial §6.2.4: ray tests spread along each chain; the majority "
                                "decides.",
                                ParameterType::Int,
                                5,
                                1,
                                101,
                                {}});
        m.parameters.push_back(
            {kIgnoredFaces,
             "Ignored faces",
             "Tutorial §6.2.4: the faces a ray test ignores so that the contour's own "
             "surface does not occlude it: face, edge-neighbours or vertex-neighbours (every "
             "face sharing a vertex with it). Wider rings reduce self-occlusion and widen "
             "halos; vertex-neighbours keeps a sphere's outline visible.",
             ParameterType::Choice,
             std::string(toString(IgnoredFaces::VertexNeighbours)),
             0,
             0,
             {toString(IgnoredFaces::Face), toString(IgnoredFaces::EdgeNeighbours),
              toString(IgnoredFaces::VertexNeighbours)}});
    }
    const char* description =
        flavor == VisibilityFlavor::Mesh
            ? "View graph (tutorial §4.5): curtain folds, Y junctions, bifurcations, "
              "T-junctions (CGAL sweep line); one ray test per connected piece and QI "
              "propagation (§4.7)."
        : flavor == VisibilityFlavor::Consistent
            ? "View graph on the consistent mesh (Bénard 2014 §8.1–8.3, near-face curtain "
              "folds), QI propagation, then §8.4: per-segment ray tests, ambiguity, majority "
              "vote and the ambiguity rules."
            : "View graph of the interpolated contours (T-junctions, Y junctions), then "
              "heuristic visibility: a vote of ray tests per chain (tutorial §6.2.4).";
    m.addPhase({"visibility", description,
                [flavor](const PhaseContext& ctx, Snapshot& s) { runVisibility(flavor, ctx, s); },
                [flavor](const PhaseContext& ctx, const Snapshot& s) {
                    return checkVisibility(flavor, ctx, s);
                }});
}

} // namespace contour
