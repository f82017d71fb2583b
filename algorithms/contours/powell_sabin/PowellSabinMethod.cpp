// Powell-Sabin contours (Capouellez, Dai, Hertzmann & Zorin 2023), the
// view-independent surface of §5 and its per-view fit: cones and the flat
// metric (§5.1), the cut and layout, the PS-12 macro-patches (§5.2) and the
// thin-plate fit (§5.3) after the view's projective transform (§3). The
// preprocessing phases are cached per cage and parameter values, so a new
// camera re-runs only the fit. Per view the spline's contour follows (§4.1:
// conics per patch, chained across patches; §4.2: cusps, image-space
// crossings and visibility by one ray test per piece of the view graph).
#include "contours/Methods.h"
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/ConeSelection.h"
#include "contours/powell_sabin/ConformalMap.h"
#include "contours/powell_sabin/ContourChains.h"
#include "contours/powell_sabin/PatchAdjacency.h"
#include "contours/powell_sabin/PatchContour.h"
#include "contours/powell_sabin/PatchCusps.h"
#include "contours/powell_sabin/PowellSabinState.h"
#include "contours/powell_sabin/ProjectiveTransform.h"
#include "contours/powell_sabin/Ps12Patch.h"
#include "contours/powell_sabin/SplineTessellation.h"
#include "contours/powell_sabin/SplineViewGraph.h"
#include "contours/powell_sabin/ThinPlateFit.h"
#include "core/SharedResultCache.h"
#include "pipeline/FieldNames.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

using namespace powell_sabin;

constexpr const char* kAuto = "auto";
constexpr const char* kCompute = "compute";
constexpr const char* kTextureCoordinates = "texture-coordinates";

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- The preprocessing cache ------------------------------------------------
// Results of the view-independent stages, keyed by the cage and by the values
// of every parameter the stage and the stages before it read; entries die
// with their cage.
template <typename T, typename Build>
std::pair<std::shared_ptr<const T>, bool>
cachedStage(const std::shared_ptr<const PolygonMesh>& cage, const std::string& key, Build build) {
    static SharedResultCache<PolygonMesh, std::string, void> cache(24);
    auto [value, fromCache] =
        cache.get(cage, key, [&] { return std::shared_ptr<const void>(build()); });
    return {std::static_pointer_cast<const T>(value), fromCache};
}

// ---- Stage results ----------------------------------------------------------
struct ConeStage {
    std::shared_ptr<const TriangleMesh> mesh; // refined around the cones
    std::vector<Index> cones;
    std::vector<Index> cluster; // per vertex of `mesh`
    std::vector<ComponentTopology> components;
    Index split = 0, bisected = 0;
    bool adjacentCones = false;  // the mesh was too coarse to keep cones apart
    std::string textureRejected; // why the texture coordinates were not the layout
    // Set when the cage's texture coordinates are the layout.
    std::shared_ptr<const ConeLayout> textureLayout;
    double seconds = 0.0;
};
struct MapStage {
    ConformalMap map;
    double seconds = 0.0;
};
struct LayoutStage {
    std::shared_ptr<const ConeLayout> layout;
    double seconds = 0.0;
};
struct FactorStage {
    std::shared_ptr<const ThinPlateFit> fit;
    double seconds = 0.0;
};

// The parameters of each stage, as text for the cache keys.
std::string coneKey(const ParameterSet& p) {
    std::ostringstream key;
    key << "cones " << p.getChoice("parameterization") << ' ' << p.getInt("cones-per-component")
        << ' ' << p.getBool("refine-around-cones");
    return key.str();
}
std::string mapKey(const ParameterSet& p) {
    std::ostringstream key;
    key.precision(17);
    key << coneKey(p) << " | map " << p.getDouble("angle-tolerance") << ' '
        << p.getInt("max-newton-iterations") << ' ' << p.getBool("intrinsic-flips");
    return key.str();
}
std::string layoutKey(const ParameterSet& p) {
    return mapKey(p) + " | layout";
}
std::string factorKey(const ParameterSet& p) {
    std::ostringstream key;
    key.precision(17);
    key << layoutKey(p) << " | fit " << p.getDouble("fitting-weight") << ' '
        << p.getBool("thin-plate-in-surface-metric");
    return key.str();
}

bool usesTextureCoordinates(const ParameterSet& p, const PolygonMesh& cage) {
    const std::string& choice = p.getChoice("parameterization");
    if (choice == kTextureCoordinates) {
        if (!cage.hasTextureCoordinates())
            throw std::invalid_argument(
                "parameterization = texture-coordinates, but the mesh has no texture "
                "coordinate on every face corner (OBJ 'vt' and f v/vt)");
        return true;
    }
    return choice == kAuto && cage.hasTextureCoordinates();
}

// The uv of each triangle corner from the cage's texture coordinates.
std::vector<std::array<Vec2, 3>> cornerUvFromCage(const PolygonMesh& cage,
                                                  const TriangleMesh& mesh) {
    std::vector<std::array<Vec2, 3>> uv(mesh.faceCount());
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Index polygon = mesh.sourcePolygon(f);
        const std::span<const Index> corners = cage.face(polygon);
        for (int c = 0; c < 3; ++c) {
            const Index v = mesh.triangle(f)[c];
            size_t k = 0;
            while (k < corners.size() && corners[k] != v)
                ++k;
            if (k == corners.size())
                throw std::logic_error("a triangle corner is not a corner of its polygon");
            uv[f][c] = cage.textureCoordinates[cage.cornerTexture[cage.offsets[polygon] + k]];
        }
    }
    return uv;
}

std::shared_ptr<const ConeStage> coneStage(const PhaseContext& ctx, const Snapshot& input,
                                           bool* fromCache = nullptr) {
    const ParameterSet& p = ctx.parameters;
    if (!input.cage)
        throw std::invalid_argument("the Powell-Sabin method needs the loaded mesh (no cage)");
    const std::shared_ptr<const TriangleMesh> triangulated = input.mesh;
    const std::shared_ptr<const PolygonMesh> cage = input.cage;
    auto [stage, cached] = cachedStage<ConeStage>(cage, coneKey(p), [&] {
        const auto start = std::chrono::steady_clock::now();
        auto out = std::make_shared<ConeStage>();
        out->components = meshComponents(*triangulated);
        if (usesTextureCoordinates(p, *cage)) {
            try {
                out->textureLayout = std::make_shared<const ConeLayout>(
                    layoutFromCornerUv(*triangulated, cornerUvFromCage(*cage, *triangulated)));
            } catch (const std::invalid_argument& e) {
                // auto: a texture atlas is not a cone parameterization (its
                // cut edges need not match); compute one instead, and say so.
                if (p.getChoice("parameterization") != kAuto)
                    throw std::invalid_argument(
                        std::string("the texture coordinates are not a cone parameterization: ") +
                        e.what());
                out->textureRejected = e.what();
            }
        }
        if (out->textureLayout) {
            out->mesh = triangulated;
            for (Index v = 0; v < triangulated->vertexCount(); ++v)
                if (out->textureLayout->isCone[v])
                    out->cones.push_back(v);
            out->cluster.assign(triangulated->vertexCount(), kInvalidIndex);
        } else {
            ConeOptions options;
            options.conesPerComponent = p.getInt("cones-per-component");
            Cones cones;
            try {
                cones = selectCones(*triangulated, options);
            } catch (const std::invalid_argument&) {
                // A mesh too coarse to keep its cones apart (a cube with 8
                // cones): adjacent cones still give a flat metric.
                options.requireNonAdjacent = false;
                cones = selectCones(*triangulated, options);
                out->adjacentCones = true;
            }
            out->components = cones.components;
            if (p.getBool("refine-around-cones") && !cones.vertices.empty()) {
                ConeRefinement refined = refineAroundCones(*triangulated, cones.vertices);
                out->cones = refined.cones;
                out->split = refined.splitTriangles;
                out->bisected = refined.bisectedTriangles;
                // New vertices join the cluster of their parent face's first corner.
                out->cluster.assign(refined.mesh.vertexCount(), kInvalidIndex);
                for (Index f = 0; f < refined.mesh.faceCount(); ++f) {
                    const Index parentCorner = triangulated->triangle(refined.parentFace[f])[0];
                    for (Index v : refined.mesh.triangle(f))
                        if (v >= triangulated->vertexCount())
                            out->cluster[v] = cones.cluster[parentCorner];
                }
                std::copy(cones.cluster.begin(), cones.cluster.end(), out->cluster.begin());
                out->mesh = std::make_shared<const TriangleMesh>(std::move(refined.mesh));
            } else {
                out->cones = cones.vertices;
                out->cluster = cones.cluster;
                out->mesh = triangulated;
            }
        }
        out->seconds = secondsSince(start);
        return std::shared_ptr<const ConeStage>(out);
    });
    if (fromCache)
        *fromCache = cached;
    return stage;
}

std::shared_ptr<const MapStage> mapStage(const PhaseContext& ctx, const Snapshot& input,
                                         bool* fromCache = nullptr) {
    const ParameterSet& p = ctx.parameters;
    const auto cones = coneStage(ctx, input);
    auto [stage, cached] = cachedStage<MapStage>(input.cage, mapKey(p), [&] {
        const auto start = std::chrono::steady_clock::now();
        auto out = std::make_shared<MapStage>();
        ConformalMapOptions options;
        options.angleTolerance = p.getDouble("angle-tolerance");
        options.maxNewtonIterations = p.getInt("max-newton-iterations");
        options.intrinsicFlips = p.getBool("intrinsic-flips");
        options.checkCancelled = [&ctx] {
            ctx.checkCancelled();
        };
        out->map = computeConformalMap(*cones->mesh, cones->cones, options);
        out->seconds = secondsSince(start);
        return std::shared_ptr<const MapStage>(out);
    });
    if (fromCache)
        *fromCache = cached;
    return stage;
}

std::shared_ptr<const LayoutStage> layoutStage(const PhaseContext& ctx, const Snapshot& input,
                                               bool* fromCache = nullptr) {
    const auto cones = coneStage(ctx, input);
    if (cones->textureLayout) {
        auto out = std::make_shared<LayoutStage>();
        out->layout = cones->textureLayout;
        if (fromCache)
            *fromCache = true;
        return out;
    }
    const auto map = mapStage(ctx, input);
    auto [stage, cached] = cachedStage<LayoutStage>(input.cage, layoutKey(ctx.parameters), [&] {
        const auto start = std::chrono::steady_clock::now();
        auto out = std::make_shared<LayoutStage>();
        ConeLayout layout = layoutConformalMap(cones->mesh->positions(), map->map, cones->cones);
        // The thin-plate term of eq. 8 scales as 1/s^2 when the uv does by s,
        // and the paper leaves the uv's scale (and A_i) open. The uv is
        // scaled to a mean side length of 1 (and A_i is relative to the mean
        // vertex area, ThinPlateFit.h), so w = 1 smooths at the scale of one
        // edge whatever the mesh's size and resolution.
        double sideSum = 0.0;
        for (const auto& uv : layout.cornerUv)
            for (int c = 0; c < 3; ++c)
                sideSum += (uv[(c + 1) % 3] - uv[c]).norm();
        const double meanSide = sideSum / (3.0 * static_cast<double>(layout.cornerUv.size()));
        if (meanSide > 0.0)
            for (auto& uv : layout.cornerUv)
                for (Vec2& p : uv)
                    p /= meanSide;
        // The uv's scale is arbitrary: the distortion is measured against
        // the layout's mean, log(uv area / 3D area) - log(total uv / total 3D).
        double uvTotal = 0.0, surfaceTotal = 0.0;
        std::vector<double> uvArea(layout.cornerUv.size()), surfaceArea(layout.cornerUv.size());
        for (size_t f = 0; f < uvArea.size(); ++f) {
            const auto& uv = layout.cornerUv[f];
            const Vec2 a = uv[1] - uv[0], b = uv[2] - uv[0];
            uvArea[f] = 0.5 * (a.x() * b.y() - a.y() * b.x());
            surfaceArea[f] = 0.5 * layout.mesh.faceAreaNormal(static_cast<Index>(f)).norm();
            uvTotal += uvArea[f];
            surfaceTotal += surfaceArea[f];
        }
        const double mean = std::log(uvTotal / surfaceTotal);
        layout.minLogAreaRatio = std::numeric_limits<double>::infinity();
        layout.maxLogAreaRatio = -std::numeric_limits<double>::infinity();
        for (size_t f = 0; f < uvArea.size(); ++f) {
            const double r = uvArea[f] > 0.0 && surfaceArea[f] > 0.0
                                 ? std::log(uvArea[f] / surfaceArea[f]) - mean
                                 : -std::numeric_limits<double>::infinity();
            layout.logAreaRatio[f] = r;
            layout.minLogAreaRatio = std::min(layout.minLogAreaRatio, r);
            layout.maxLogAreaRatio = std::max(layout.maxLogAreaRatio, r);
        }
        out->layout = std::make_shared<const ConeLayout>(std::move(layout));
        out->seconds = secondsSince(start);
        return std::shared_ptr<const LayoutStage>(out);
    });
    if (fromCache)
        *fromCache = cached;
    return stage;
}

std::shared_ptr<const FactorStage> factorStage(const PhaseContext& ctx, const Snapshot& input,
                                               bool* fromCache = nullptr) {
    const auto layout = layoutStage(ctx, input);
    auto [stage, cached] = cachedStage<FactorStage>(input.cage, factorKey(ctx.parameters), [&] {
        const auto start = std::chrono::steady_clock::now();
        auto out = std::make_shared<FactorStage>();
        ThinPlateFitOptions options;
        options.fittingWeight = ctx.parameters.getDouble("fitting-weight");
        options.surfaceMetric = ctx.parameters.getBool("thin-plate-in-surface-metric");
        out->fit = std::make_shared<const ThinPlateFit>(*layout->layout, options);
        out->seconds = secondsSince(start);
        return std::shared_ptr<const FactorStage>(out);
    });
    if (fromCache)
        *fromCache = cached;
    return stage;
}

std::shared_ptr<PowellSabinState> copyState(const Snapshot& s) {
    const auto state = std::dynamic_pointer_cast<const PowellSabinState>(s.methodState);
    return state ? std::make_shared<PowellSabinState>(*state)
                 : std::make_shared<PowellSabinState>();
}

// The per-view state of a phase after the fit, or an error naming what is
// missing (the runner always hands the previous phase's snapshot).
const PowellSabinState& viewState(const Snapshot& s) {
    const auto* state = dynamic_cast<const PowellSabinState*>(s.methodState.get());
    if (!state || !state->spline)
        throw std::logic_error("the Powell-Sabin phases after the fit need the fit's spline");
    return *state;
}

Snapshot stageInput(const Snapshot& s) {
    Snapshot input;
    input.cage = s.cage;
    const auto state = std::dynamic_pointer_cast<const PowellSabinState>(s.methodState);
    input.mesh = state ? state->triangulatedCage
                       : std::make_shared<const TriangleMesh>(s.cage->triangulate());
    return input;
}

void setMeshCounters(Snapshot& s) {
    s.setCounter(counters::kFaces, s.mesh->faceCount());
    s.setCounter(counters::kVertices, s.mesh->vertexCount());
    s.setCounter(counters::kEdges, s.mesh->edgeCount());
    s.setCounter(counters::kBoundaryEdges, s.mesh->boundaryEdgeCount());
}

std::vector<int> coneLabels(Index vertexCount, std::span<const Index> cones) {
    std::vector<int> label(vertexCount, 0);
    for (Index c : cones)
        label[c] = 1;
    return label;
}

// ---- Phases -------------------------------------------------------------------

void runCones(const PhaseContext& ctx, Snapshot& s) {
    auto state = std::make_shared<PowellSabinState>();
    state->triangulatedCage = s.mesh;
    Snapshot input;
    input.cage = s.cage;
    input.mesh = s.mesh;
    bool cached = false;
    const auto stage = coneStage(ctx, input, &cached);
    s.methodState = state;
    s.mesh = stage->mesh;
    setMeshCounters(s);
    s.setField(fields::kCone,
               {FieldLocation::Vertex, coneLabels(s.mesh->vertexCount(), stage->cones),
                "1 at a cone of the flat metric (§5.1)"});
    s.setField(fields::kConeCluster,
               {FieldLocation::Vertex,
                std::vector<int>(stage->cluster.begin(), stage->cluster.end()),
                "the cone cluster of the vertex (-1: no cones in its component)"});
    int genus = 0, open = 0;
    for (const ComponentTopology& c : stage->components) {
        genus += c.genus;
        open += c.boundaryLoops > 0;
    }
    s.setCounter(counters::kComponents, static_cast<double>(stage->components.size()));
    s.setCounter(counters::kGenus, genus);
    s.setCounter(counters::kCones, static_cast<double>(stage->cones.size()));
    s.setCounter(counters::kConeTrianglesSplit, stage->split);
    s.setCounter(counters::kConeTrianglesBisected, stage->bisected);
    s.setCounter(counters::kPreprocessingCached, cached ? 1.0 : 0.0);
    s.setCounter(counters::kStageSeconds, stage->seconds);
    if (stage->textureLayout)
        s.notes.push_back(
            "the layout is the mesh's texture coordinates: " + std::to_string(stage->cones.size()) +
            " cones found where the uv angle sum is not 2 pi");
    if (!stage->textureRejected.empty())
        s.notes.push_back("the mesh's texture coordinates are not a cone parameterization (" +
                          stage->textureRejected + "): the layout is computed");
    if (stage->adjacentCones)
        s.notes.push_back("the mesh is too coarse to keep every cone away from the others: some "
                          "cones are neighbours");
    if (open > 0)
        s.notes.push_back(std::to_string(open) +
                          " components have a boundary: they get no cones, and their boundary "
                          "vertices keep scale factor 1 and absorb the curvature");
}

std::vector<InvariantCheck> checkCones(const PhaseContext& ctx, const Snapshot& s) {
    const auto stage = coneStage(ctx, stageInput(s));
    InvariantCheck count{"each closed component has the paper's cone count (8 for genus 0, "
                         "4(g-1) for genus > 1, none for a torus)",
                         0, ""};
    if (!stage->textureLayout && ctx.parameters.getInt("cones-per-component") < 0) {
        long long expected = 0;
        for (const ComponentTopology& c : stage->components)
            if (c.boundaryLoops == 0)
                expected += c.genus == 0 ? 8 : c.genus == 1 ? 0 : 4 * (c.genus - 1);
        if (expected != static_cast<long long>(stage->cones.size())) {
            count.violations = 1;
            count.firstExample = std::to_string(stage->cones.size()) + " cones, expected " +
                                 std::to_string(expected);
        }
    }
    InvariantCheck boundary{"no cone lies on a boundary", 0, ""};
    for (Index c : stage->cones)
        if (s.mesh->isBoundaryVertex(c) && boundary.violations++ == 0)
            boundary.firstExample = "vertex " + std::to_string(c);
    return {count, boundary};
}

void runConformalMap(const PhaseContext& ctx, Snapshot& s) {
    const Snapshot input = stageInput(s);
    const auto cones = coneStage(ctx, input);
    if (cones->textureLayout) {
        s.notes.push_back("no conformal map computed: the texture coordinates are the layout");
        s.setCounter(counters::kNewtonIterations, 0);
        s.setCounter(counters::kIntrinsicFlips, 0);
        s.setCounter(counters::kStageSeconds, 0);
        return;
    }
    bool cached = false;
    std::shared_ptr<const MapStage> stage;
    try {
        stage = mapStage(ctx, input, &cached);
    } catch (const ConformalMapError& e) {
        throw std::runtime_error(std::string("conformal map failed: ") + e.what());
    }
    const ConformalMap& map = stage->map;
    std::vector<double> defect(map.angleSum.size());
    for (size_t v = 0; v < defect.size(); ++v)
        defect[v] = 2.0 * std::numbers::pi - map.angleSum[v];
    s.setField(fields::kLogScale, {FieldLocation::Vertex, map.logScale,
                                   "conformal log scale factor u (l = e^((ui+uj)/2) l0)"});
    s.setField(fields::kAngleDefectFlat,
               {FieldLocation::Vertex, std::move(defect),
                "2 pi minus the angle sum in the flat metric (the cone angles)"});
    s.setCounter(counters::kNewtonIterations, map.newtonIterations);
    s.setCounter(counters::kIntrinsicFlips, map.flips);
    s.setCounter(counters::kMaxAngleSumError, map.maxAngleError);
    s.setCounter(counters::kPreprocessingCached, cached ? 1.0 : 0.0);
    s.setCounter(counters::kStageSeconds, stage->seconds);
    if (map.flips > 0)
        s.notes.push_back(std::to_string(map.flips) +
                          " intrinsic flips: the layout's triangles differ from the mesh's there");
}

std::vector<InvariantCheck> checkConformalMap(const PhaseContext& ctx, const Snapshot& s) {
    const Snapshot input = stageInput(s);
    if (coneStage(ctx, input)->textureLayout)
        return {};
    const ConformalMap& map = mapStage(ctx, input)->map;
    const double tolerance = ctx.parameters.getDouble("angle-tolerance");
    InvariantCheck flat{"every vertex that is not a cone or on a boundary has angle sum 2 pi", 0,
                        ""};
    InvariantCheck fixedScale{"cones and boundary vertices keep scale factor 1 (u = 0)", 0, ""};
    for (size_t v = 0; v < map.angleSum.size(); ++v) {
        if (map.fixedScale[v]) {
            if (map.logScale[v] != 0.0 && fixedScale.violations++ == 0)
                fixedScale.firstExample = "vertex " + std::to_string(v);
        } else if (!(std::abs(map.angleSum[v] - 2.0 * std::numbers::pi) <= tolerance) &&
                   flat.violations++ == 0) {
            flat.firstExample = "vertex " + std::to_string(v);
        }
    }
    return {flat, fixedScale};
}

void runLayout(const PhaseContext& ctx, Snapshot& s) {
    bool cached = false;
    const auto stage = layoutStage(ctx, stageInput(s), &cached);
    const ConeLayout& layout = *stage->layout;
    s.mesh = std::shared_ptr<const TriangleMesh>(stage->layout, &stage->layout->mesh);
    setMeshCounters(s);
    for (int c = 0; c < 3; ++c) {
        std::vector<Vec3> uv(layout.cornerUv.size());
        for (size_t f = 0; f < uv.size(); ++f)
            uv[f] = Vec3(layout.cornerUv[f][c].x(), layout.cornerUv[f][c].y(), 0.0);
        const char* name = c == 0   ? fields::kCornerUv0
                           : c == 1 ? fields::kCornerUv1
                                    : fields::kCornerUv2;
        s.setField(name, {FieldLocation::Face, std::move(uv),
                          "(u, v, 0) of the face's corner in the layout"});
    }
    std::vector<int> cut(layout.cutEdge.begin(), layout.cutEdge.end());
    long long cutEdges = 0;
    for (int c : cut)
        cutEdges += c != 0;
    s.setField(fields::kCutEdge, {FieldLocation::Edge, std::move(cut), "1 on an edge of the cut"});
    s.setField(fields::kLogAreaRatio,
               {FieldLocation::Face, layout.logAreaRatio,
                "log(uv area / 3D area) against the layout's mean: its area distortion"});
    std::vector<int> cone(layout.isCone.begin(), layout.isCone.end());
    s.setField(fields::kCone,
               {FieldLocation::Vertex, std::move(cone), "1 at a cone of the flat metric (§5.1)"});
    s.fields.erase(fields::kConeCluster);
    s.setCounter(counters::kCutEdges, static_cast<double>(cutEdges));
    s.setCounter(counters::kLayoutAngleSumError, layout.maxAngleSumError);
    s.setCounter(counters::kCutLengthMismatch, layout.maxCutLengthMismatch);
    s.setCounter(counters::kSideLengthError, layout.maxSideLengthError);
    s.setCounter(counters::kFlippedUvTriangles, layout.flippedTriangles);
    s.setCounter(counters::kMinLogAreaRatio, layout.minLogAreaRatio);
    s.setCounter(counters::kMaxLogAreaRatio, layout.maxLogAreaRatio);
    s.setCounter(counters::kPreprocessingCached, cached ? 1.0 : 0.0);
    s.setCounter(counters::kStageSeconds, stage->seconds);
}

// The layout's checks recomputed from the corner uv (not from the layout's
// own statistics), so a slip in either shows.
std::vector<InvariantCheck> checkLayout(const PhaseContext& ctx, const Snapshot& s) {
    const auto stage = layoutStage(ctx, stageInput(s));
    const ConeLayout& layout = *stage->layout;
    const TriangleMesh& mesh = layout.mesh;
    InvariantCheck flipped{"no uv triangle is flipped or degenerate", 0, ""};
    InvariantCheck cutLength{"the two uv images of every cut edge have equal length", 0, ""};
    InvariantCheck angles{"uv angle sums are 2 pi at interior vertices that are not cones", 0, ""};
    constexpr double kLengthTolerance = 1e-9;
    constexpr double kAngleTolerance = 1e-7;
    std::vector<double> angleSum(mesh.vertexCount(), 0.0);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto& uv = layout.cornerUv[f];
        const Vec2 a = uv[1] - uv[0], b = uv[2] - uv[0];
        if (!(a.x() * b.y() - a.y() * b.x() > 0.0) && flipped.violations++ == 0)
            flipped.firstExample = "face " + std::to_string(f);
        for (int c = 0; c < 3; ++c) {
            const Vec2 e1 = uv[(c + 1) % 3] - uv[c], e2 = uv[(c + 2) % 3] - uv[c];
            angleSum[mesh.triangle(f)[c]] +=
                std::atan2(std::abs(e1.x() * e2.y() - e1.y() * e2.x()), e1.dot(e2));
        }
    }
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const Index h = mesh.edgeHalfedge(e);
        const Index o = mesh.opposite(h);
        if (o == kInvalidIndex || !layout.cutEdge[e])
            continue;
        const auto side = [&](Index half) {
            const auto& uv = layout.cornerUv[TriangleMesh::face(half)];
            return (uv[(half % 3 + 1) % 3] - uv[half % 3]).norm();
        };
        const double l1 = side(h), l2 = side(o);
        if (!(std::abs(l1 - l2) <= kLengthTolerance * std::max(l1, l2)) &&
            cutLength.violations++ == 0)
            cutLength.firstExample = "edge " + std::to_string(e);
    }
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (!layout.isCone[v] && !mesh.isBoundaryVertex(v) &&
            !(std::abs(angleSum[v] - 2.0 * std::numbers::pi) <= kAngleTolerance) &&
            angles.violations++ == 0)
            angles.firstExample = "vertex " + std::to_string(v);
    return {flipped, cutLength, angles};
}

// A quadratic of the face's uv scale, to test each macro-patch's basis.
struct TestQuadratic {
    Vec2 origin;
    double scale;
    double value(const Vec2& p) const {
        const Vec2 q = (p - origin) / scale;
        return 1.0 + q.x() - 2.0 * q.y() + 0.5 * q.x() * q.x() - q.x() * q.y() +
               2.0 * q.y() * q.y();
    }
    Vec2 gradient(const Vec2& p) const {
        const Vec2 q = (p - origin) / scale;
        return Vec2(1.0 + q.x() - q.y(), -2.0 - q.x() + 4.0 * q.y()) / scale;
    }
};

// Largest |patch - quadratic| over the 12 patches' centroids and corners,
// for DOFs sampled from a quadratic (Powell & Sabin's quadratic precision).
double quadraticPrecisionError(const std::array<Vec2, 3>& uv) {
    const double scale =
        std::max({(uv[1] - uv[0]).norm(), (uv[2] - uv[1]).norm(), (uv[0] - uv[2]).norm()});
    const TestQuadratic f{uv[0], scale};
    Eigen::Matrix<double, kPs12LocalDofs, 1> dofs;
    for (int c = 0; c < 3; ++c) {
        const Vec2 g = f.gradient(uv[c]);
        dofs.segment<3>(3 * c) << f.value(uv[c]), g.x(), g.y();
    }
    for (int side = 0; side < 3; ++side) {
        const Vec2 a = uv[side], b = uv[(side + 1) % 3];
        const Vec2 d = (b - a).normalized();
        const Vec2 inward(-d.y(), d.x()); // left of a -> b in a counter-clockwise triangle
        dofs[9 + side] = f.gradient(0.5 * (a + b)).dot(inward);
    }
    const Ps12Matrix matrix = ps12BezierMatrix(uv);
    const Eigen::Matrix<double, 6 * kPs12Patches, 1> control = matrix * dofs;
    const auto sub = ps12SubTriangles(uv);
    double worst = 0.0;
    for (int l = 0; l < kPs12Patches; ++l) {
        QuadraticBezier<double> patch;
        patch.domain = sub[l];
        for (int c = 0; c < 6; ++c)
            patch.control[c] = control[6 * l + c];
        for (const Vec3& b :
             {Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3), Vec3(1, 0, 0), Vec3(0.2, 0.5, 0.3)}) {
            const Vec2 p = b[0] * sub[l][0] + b[1] * sub[l][1] + b[2] * sub[l][2];
            worst = std::max(worst, std::abs(evaluate(patch, b) - f.value(p)));
        }
    }
    return worst;
}

struct PatchStage {
    double worstPrecision = 0.0;
    Index worstFace = kInvalidIndex;
    long long conePatches = 0;
    long long impreciseFaces = 0;
    double seconds = 0.0;
};
constexpr double kPrecisionTolerance = 1e-9;

std::shared_ptr<const PatchStage> patchStage(const PhaseContext& ctx, const Snapshot& input,
                                             bool* fromCache = nullptr) {
    const auto layoutResult = layoutStage(ctx, input);
    auto [stage, cached] =
        cachedStage<PatchStage>(input.cage, layoutKey(ctx.parameters) + " | patches", [&] {
            const auto start = std::chrono::steady_clock::now();
            auto out = std::make_shared<PatchStage>();
            const ConeLayout& layout = *layoutResult->layout;
            for (Index f = 0; f < layout.mesh.faceCount(); ++f) {
                const double error = quadraticPrecisionError(layout.cornerUv[f]);
                if (!(error <= kPrecisionTolerance))
                    ++out->impreciseFaces;
                if (!(error <= out->worstPrecision)) {
                    out->worstPrecision = error;
                    out->worstFace = f;
                }
                for (Index v : layout.mesh.triangle(f))
                    if (layout.isCone[v]) {
                        // The patches with a corner at the cone: 4 of the 12 per face corner.
                        out->conePatches += 4;
                        break;
                    }
            }
            out->seconds = secondsSince(start);
            return std::shared_ptr<const PatchStage>(out);
        });
    if (fromCache)
        *fromCache = cached;
    return stage;
}

void runPatches(const PhaseContext& ctx, Snapshot& s) {
    bool cached = false;
    const auto stage = patchStage(ctx, stageInput(s), &cached);
    s.setCounter(counters::kMacroPatches, s.mesh->faceCount());
    s.setCounter(counters::kPatches, static_cast<double>(kPs12Patches) * s.mesh->faceCount());
    s.setCounter(counters::kQuadraticPrecisionError, stage->worstPrecision);
    s.setCounter(counters::kPreprocessingCached, cached ? 1.0 : 0.0);
    s.setCounter(counters::kStageSeconds, stage->seconds);
}

std::vector<InvariantCheck> checkPatches(const PhaseContext& ctx, const Snapshot& s) {
    const auto stage = patchStage(ctx, stageInput(s));
    InvariantCheck precise{
        "every macro-patch reproduces a quadratic (1e-9, relative to its values)",
        stage->impreciseFaces, ""};
    if (stage->impreciseFaces > 0)
        precise.firstExample = "face " + std::to_string(stage->worstFace);
    return {precise};
}

// The drawing tessellation of one layout and level with its view-independent
// fields, shared by every view's snapshot.
struct DrawingTessellation {
    std::shared_ptr<const SplineTessellation> welded;
    std::map<std::string, std::shared_ptr<const Field>> fields;
};

DrawingTessellation drawingTessellation(SplineTessellation t, const ConeLayout& layout) {
    DrawingTessellation d;
    const auto add = [&](const char* name, Field field) {
        d.fields[name] = std::make_shared<const Field>(std::move(field));
    };
    std::array<std::vector<Vec3>, 3> cornerUv;
    for (auto& uv : cornerUv)
        uv.resize(t.cornerBarycentric.size());
    tbb::parallel_for(size_t(0), t.cornerBarycentric.size(), [&](size_t f) {
        const auto& faceUv = layout.cornerUv[t.macroPatch[f]];
        for (int c = 0; c < 3; ++c) {
            const Vec3& b = t.cornerBarycentric[f][c];
            const Vec2 uv = b[0] * faceUv[0] + b[1] * faceUv[1] + b[2] * faceUv[2];
            cornerUv[c][f] = Vec3(uv.x(), uv.y(), 0.0);
        }
    });
    for (int c = 0; c < 3; ++c)
        add(c == 0   ? fields::kCornerUv0
            : c == 1 ? fields::kCornerUv1
                     : fields::kCornerUv2,
            {FieldLocation::Face, std::move(cornerUv[c]),
             "(u, v, 0) of the triangle's corner in the layout"});
    std::vector<int> cone(static_cast<size_t>(t.mesh.vertexCount()), 0);
    for (Index v = 0; v < t.mesh.vertexCount(); ++v) {
        const Triangle& corners = layout.mesh.triangle(t.vertexMacroPatch[v]);
        for (int c = 0; c < 3; ++c)
            if (t.barycentric[v][c] == 1.0 && layout.isCone[corners[c]])
                cone[v] = 1;
    }
    add(fields::kCone, {FieldLocation::Vertex, std::move(cone), "1 at a cone"});
    add(fields::kPatch,
        {FieldLocation::Face, t.patch, "the quadratic patch 12 f + l of the triangle"});
    add(fields::kMacroPatch,
        {FieldLocation::Face, t.macroPatch, "the macro-patch (layout face) of the triangle"});
    add(fields::kPatchEdge,
        {FieldLocation::Edge, t.patchEdge,
         "1 patch boundary, 2 macro-patch boundary, 3 cut edge, 0 inside a patch"});
    d.welded = std::make_shared<const SplineTessellation>(std::move(t));
    return d;
}

// The drawing tessellation of the current layout and tessellation level,
// built once per mesh in the preprocessing: the welding needs only the
// layout, so it is made with the spline fitted to the mesh itself (no view
// transform) and each view evaluates its own spline at the vertices.
std::shared_ptr<const DrawingTessellation> drawingStage(const PhaseContext& ctx,
                                                        const Snapshot& input, bool* built) {
    const auto layoutResult = layoutStage(ctx, input);
    const int level = ctx.parameters.getInt("tessellation-level");
    return cachedStage<DrawingTessellation>(
               input.cage, layoutKey(ctx.parameters) + " | tessellation " + std::to_string(level),
               [&] {
                   if (built)
                       *built = true;
                   const ConeLayout& layout = *layoutResult->layout;
                   const ThinPlateFit& fit = *factorStage(ctx, input)->fit;
                   std::vector<Vec3> targets(layout.mesh.positions().begin(),
                                             layout.mesh.positions().end());
                   const PowellSabinSpline spline = fit.splineOf(fit.solveDofs(targets));
                   return std::make_shared<const DrawingTessellation>(
                       drawingTessellation(tessellateSpline(spline, layout, level), layout));
               })
        .first;
}

void runFactorization(const PhaseContext& ctx, Snapshot& s) {
    bool cached = false;
    const auto stage = factorStage(ctx, stageInput(s), &cached);
    s.setCounter(counters::kScalarDofs, stage->fit->dofCount());
    const Eigen::SparseMatrix<double>& hs = stage->fit->smoothingHessian();
    s.setCounter(counters::kHessianNonzeros, static_cast<double>(hs.nonZeros()));
    const auto weldStart = std::chrono::steady_clock::now();
    bool welded = false;
    const auto drawing = drawingStage(ctx, stageInput(s), &welded);
    s.setCounter(counters::kTessellationFaces, drawing->welded->mesh.faceCount());
    s.setCounter(counters::kWeldingSeconds, welded ? secondsSince(weldStart) : 0.0);
    s.setCounter(counters::kPreprocessingCached, cached && !welded ? 1.0 : 0.0);
    s.setCounter(counters::kStageSeconds, stage->seconds);
}

std::vector<InvariantCheck> checkFactorization(const PhaseContext& ctx, const Snapshot& s) {
    const auto stage = factorStage(ctx, stageInput(s));
    const Eigen::SparseMatrix<double>& hs = stage->fit->smoothingHessian();
    const Eigen::SparseMatrix<double> asymmetry = hs - Eigen::SparseMatrix<double>(hs.transpose());
    InvariantCheck symmetric{"the thin-plate Hessian is symmetric", 0, ""};
    const double norm = hs.norm();
    if (!(asymmetry.norm() <= 1e-12 * std::max(norm, 1.0))) {
        symmetric.violations = 1;
        symmetric.firstExample = "|Hs - Hs^T| = " + std::to_string(asymmetry.norm());
    }
    return {symmetric};
}

// The spline's value at a layout vertex: the corner control point of a
// patch with a corner there (a Bezier patch interpolates its corners).
Vec3 vertexValue(const PowellSabinSpline& spline, const ConeLayout& layout, Index v) {
    const Index h = layout.mesh.vertexHalfedge(v);
    const Index f = TriangleMesh::face(h);
    const Vec2& uv = layout.cornerUv[f][h % 3];
    for (int l = 0; l < kPs12Patches; ++l) {
        const QuadraticBezier<Vec3>& patch = spline.patches[kPs12Patches * f + l];
        for (int c = 0; c < 3; ++c)
            if ((patch.domain[c] - uv).norm() <= 1e-12 * (1.0 + uv.norm()))
                return patch.control[c];
    }
    throw std::logic_error("no patch has a corner at a vertex of its face");
}

void runFit(const PhaseContext& ctx, Snapshot& s) {
    const Snapshot input = stageInput(s);
    const auto layoutResult = layoutStage(ctx, input);
    const auto factor = factorStage(ctx, input);
    const ConeLayout& layout = *layoutResult->layout;
    const ThinPlateFit& fit = *factor->fit;
    const auto start = std::chrono::steady_clock::now();
    const ProjectiveTransform transform(ctx.camera);
    std::vector<Vec3> targets(layout.mesh.vertexCount());
    for (Index v = 0; v < layout.mesh.vertexCount(); ++v)
        targets[v] = transform.apply(layout.mesh.position(v));
    const Eigen::MatrixX3d dofs = fit.solveDofs(targets);
    const auto splinePtr = std::make_shared<const PowellSabinSpline>(fit.splineOf(dofs));
    const PowellSabinSpline& spline = *splinePtr;
    // What the paper's per-view fit does: the transform, the back-substitution
    // and the patches' Bezier points (the tessellation is for drawing only).
    const double fitSeconds = secondsSince(start);
    ctx.checkCancelled();

    const double residual = fit.backwardError(dofs, targets);

    // Distance of the spline's vertex values to the input vertices, in world units.
    const double diagonal = layout.mesh.boundingBox().diagonal();
    double worst = 0.0, sumSquares = 0.0;
    for (Index v = 0; v < layout.mesh.vertexCount(); ++v) {
        const Vec3 value = vertexValue(spline, layout, v);
        const double d = (transform.invert(value) - layout.mesh.position(v)).norm();
        worst = std::max(worst, d);
        sumSquares += d * d;
    }
    const double rms = std::sqrt(sumSquares / std::max<Index>(layout.mesh.vertexCount(), 1));

    SplineToWorld toWorld;
    toWorld.point = [&transform](const Vec3& p) {
        return transform.invert(p);
    };
    toWorld.jacobian = [&transform](const Vec3& p) {
        return transform.inverseJacobian(p);
    };
    const auto tessellationStart = std::chrono::steady_clock::now();
    const int level = ctx.parameters.getInt("tessellation-level");
    const auto drawing = drawingStage(ctx, input, nullptr);
    const SplineTessellation& t = *drawing->welded;
    TessellationPoints points = evaluateTessellationPoints(t, spline, toWorld);
    std::vector<double> offset(t.mesh.vertexCount());
    tbb::parallel_for(Index(0), t.mesh.vertexCount(), [&](Index v) {
        const Triangle& corners = layout.mesh.triangle(t.vertexMacroPatch[v]);
        const Vec3& b = t.barycentric[v];
        const Vec3 flat = b[0] * layout.mesh.position(corners[0]) +
                          b[1] * layout.mesh.position(corners[1]) +
                          b[2] * layout.mesh.position(corners[2]);
        offset[v] = (points.positions[v] - flat).norm();
    });
    s.mesh =
        std::make_shared<const TriangleMesh>(t.mesh.withPositions(std::move(points.positions)));
    setMeshCounters(s);
    s.fields.clear();
    for (const auto& [name, field] : drawing->fields)
        s.fields[name] = field;
    s.setField(fields::kVertexNormal, {FieldLocation::Vertex, std::move(points.normals),
                                       "unit normal of the fitted spline (zero at cones)"});
    s.setField(fields::kFitOffset,
               {FieldLocation::Vertex, std::move(offset),
                "distance from the spline to the input triangle at the same parameter"});
    s.setCounter(counters::kTessellationFaces, s.mesh->faceCount());
    s.setCounter(counters::kTessellationSeconds, secondsSince(tessellationStart));
    s.setCounter(counters::kStageSeconds, fitSeconds);
    s.setCounter(counters::kFitResidual, residual);
    s.setCounter(counters::kFitMaxDistance, diagonal > 0.0 ? worst / diagonal : 0.0);
    s.setCounter(counters::kFitRmsDistance, diagonal > 0.0 ? rms / diagonal : 0.0);
    auto state = copyState(s);
    state->layout = layoutResult->layout;
    state->spline = splinePtr;
    state->tessellationLevel = level;
    s.methodState = state;
    s.notes.push_back(transform.isPerspective()
                          ? "fitted after the projective transform [x/z, y/z, -1/z] (§3): the "
                            "surface drawn is that fit mapped back"
                          : "orthographic view: fitted in camera coordinates");
}

std::vector<InvariantCheck> checkFit(const PhaseContext&, const Snapshot& s) {
    InvariantCheck residual{"the fit solves H q = w Hf q0 (backward error below 1e-12)", 0, ""};
    const double r = s.counter(counters::kFitResidual);
    if (!(r <= 1e-12)) {
        residual.violations = 1;
        residual.firstExample = "backward error " + std::to_string(r);
    }
    InvariantCheck finite{"every point of the spline is finite", 0, ""};
    for (Index v = 0; v < s.mesh->vertexCount(); ++v)
        if (!s.mesh->position(v).allFinite() && finite.violations++ == 0)
            finite.firstExample = "vertex " + std::to_string(v);
    return {residual, finite};
}

// ---- Per-view contours (§4) ------------------------------------------------------

// The view direction after the projective transform (§3).
const Vec3 kTau(0.0, 0.0, 1.0);

// World points of a contour segment, `samples` + 1 of them from t0 to t1,
// with the tessellation triangle of each piece.
void sampleSegment(const ContourSegment& segment, const PowellSabinSpline& spline,
                   const ProjectiveTransform& transform, int level, int samples, bool reversed,
                   Polyline& line) {
    const QuadraticBezier<Vec3>& patch = spline.patches[segment.patch];
    const auto pointAt = [&](double t) {
        const Vec3 b = barycentricOf(patch.domain, segment.curve.at(t));
        return std::pair{transform.invert(evaluate(patch, b)), b};
    };
    const bool first = line.points.empty();
    for (int k = first ? 0 : 1; k <= samples; ++k) {
        const double u = static_cast<double>(k) / samples;
        const double t = reversed ? segment.t1 + u * (segment.t0 - segment.t1)
                                  : segment.t0 + u * (segment.t1 - segment.t0);
        CurvePoint point;
        point.position = pointAt(t).first;
        line.points.push_back(point);
        if (k > 0) {
            const double tMid = reversed
                                    ? segment.t1 + (u - 0.5 / samples) * (segment.t0 - segment.t1)
                                    : segment.t0 + (u - 0.5 / samples) * (segment.t1 - segment.t0);
            line.segmentElement.push_back(
                tessellationTriangle(segment.patch, pointAt(tMid).second, level));
        }
    }
}

constexpr int kSamplesPerSegment = 8;

void runPatchContours(const PhaseContext& ctx, Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    const PowellSabinSpline& spline = *view.spline;
    const auto start = std::chrono::steady_clock::now();
    const Index patches = static_cast<Index>(spline.patches.size());
    std::vector<std::vector<ContourSegment>> perPatch(static_cast<size_t>(patches));
    tbb::parallel_for(Index(0), patches, [&](Index p) {
        perPatch[static_cast<size_t>(p)] = patchContours(spline.patches[p], p, kTau);
    });
    auto segments = std::make_shared<std::vector<ContourSegment>>();
    long long withContour = 0;
    std::map<ConicKind, long long> kinds;
    for (auto& list : perPatch) {
        withContour += !list.empty();
        for (ContourSegment& segment : list) {
            ++kinds[segment.kind];
            segments->push_back(std::move(segment));
        }
    }
    const double seconds = secondsSince(start);
    ctx.checkCancelled();
    // One curve per segment until they are chained.
    const ProjectiveTransform transform(ctx.camera);
    auto curves = std::make_shared<std::vector<Polyline>>();
    for (const ContourSegment& segment : *segments) {
        Polyline line;
        line.type = CurveType::Contour;
        line.source = SegmentSource::Face;
        sampleSegment(segment, spline, transform, view.tessellationLevel, kSamplesPerSegment, false,
                      line);
        curves->push_back(std::move(line));
    }
    s.curves = curves;
    auto state = copyState(s);
    state->segments = segments;
    s.methodState = state;
    s.setCounter(counters::kContourSegments, static_cast<double>(segments->size()));
    s.setCounter(counters::kPatchesWithContour, static_cast<double>(withContour));
    s.setCounter(counters::kEllipseSegments, static_cast<double>(kinds[ConicKind::Ellipse]));
    s.setCounter(counters::kHyperbolaSegments, static_cast<double>(kinds[ConicKind::Hyperbola]));
    s.setCounter(counters::kLineSegments, static_cast<double>(kinds[ConicKind::IntersectingLines] +
                                                              kinds[ConicKind::ParallelLines]));
    s.setCounter(counters::kParabolaSegments, static_cast<double>(kinds[ConicKind::Parabola]));
    s.setCounter(counters::kStageSeconds, seconds);
}

// eq. 2 on the segments themselves: tau . n vanishes along each (relative
// to the patch's contour function), and each end lies in the patch.
std::vector<InvariantCheck> checkPatchContours(const PhaseContext&, const Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    InvariantCheck onContour{"tau . n vanishes along every contour segment (1e-8, relative)", 0,
                             ""};
    InvariantCheck inside{"every contour segment lies in its patch's domain", 0, ""};
    for (size_t i = 0; i < view.segments->size(); ++i) {
        const ContourSegment& segment = (*view.segments)[i];
        const QuadraticBezier<Vec3>& patch = view.spline->patches[segment.patch];
        const QuadraticForm2 f = contourFunction(patch, kTau);
        const double scale = f.A.norm() * patch.domain[0].squaredNorm() +
                             f.b.norm() * patch.domain[0].norm() + std::abs(f.c) + f.A.norm() +
                             f.b.norm() + 1e-300;
        for (int k = 0; k <= 4; ++k) {
            const double t = segment.t0 + 0.25 * k * (segment.t1 - segment.t0);
            const Vec2 r = segment.curve.at(t);
            if (!(std::abs(f(r)) <= 1e-8 * scale) && onContour.violations++ == 0)
                onContour.firstExample =
                    "segment " + std::to_string(i) + " of patch " + std::to_string(segment.patch);
            if (!(barycentricOf(patch.domain, r).minCoeff() >= -1e-6) && inside.violations++ == 0)
                inside.firstExample = "segment " + std::to_string(i);
        }
    }
    return {onContour, inside};
}

void runChaining(const PhaseContext& ctx, Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    const auto start = std::chrono::steady_clock::now();
    // The adjacency depends on the layout only: built once per layout.
    const std::shared_ptr<const PatchAdjacency> adjacency =
        cachedStage<PatchAdjacency>(s.cage, layoutKey(ctx.parameters) + " | adjacency", [&] {
            return std::make_shared<const PatchAdjacency>(*view.layout, *view.spline);
        }).first;
    auto chaining = std::make_shared<const ContourChaining>(
        chainContours(*view.segments, *adjacency, *view.spline));
    const double seconds = secondsSince(start);
    const ProjectiveTransform transform(ctx.camera);
    auto curves = std::make_shared<std::vector<Polyline>>();
    for (const ContourChain& chain : chaining->chains) {
        Polyline line;
        line.type = CurveType::Contour;
        line.source = SegmentSource::Face;
        line.closed = chain.closed;
        for (const ChainLink& link : chain.links)
            sampleSegment((*view.segments)[link.segment], *view.spline, transform,
                          view.tessellationLevel, kSamplesPerSegment, link.reversed, line);
        if (chain.closed && line.points.size() > 1) {
            // The last point repeats the first: a closed polyline closes itself.
            line.points.pop_back();
        }
        curves->push_back(std::move(line));
    }
    s.curves = curves;
    auto state = copyState(s);
    state->chaining = chaining;
    s.methodState = state;
    s.setCounter(counters::kContourLoops, chaining->closedLoops);
    s.setCounter(counters::kOpenContourChains, chaining->openChains);
    s.setCounter(counters::kConeChainEnds, chaining->coneEnds);
    s.setCounter(counters::kUnmatchedSegmentEnds, chaining->unmatchedEnds);
    s.setCounter(counters::kStageSeconds, seconds);
    if (chaining->coneEnds > 0)
        s.notes.push_back(std::to_string(chaining->coneEnds) +
                          " chain ends at cones: the contour passes through a cone point there, "
                          "where several loops may meet (§4.2)");
}

std::vector<InvariantCheck> checkChaining(const PhaseContext&, const Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    InvariantCheck matched{"every segment end meets another, a cone or the boundary", 0, ""};
    matched.violations = view.chaining->unmatchedEnds;
    matched.firstExample = view.chaining->firstUnmatched;
    InvariantCheck once{"every segment is in exactly one chain", 0, ""};
    std::vector<int> uses(view.segments->size(), 0);
    for (const ContourChain& chain : view.chaining->chains)
        for (const ChainLink& link : chain.links)
            ++uses[static_cast<size_t>(link.segment)];
    for (size_t i = 0; i < uses.size(); ++i)
        if (uses[i] != 1 && once.violations++ == 0)
            once.firstExample = "segment " + std::to_string(i);
    return {matched, once};
}

void runCusps(const PhaseContext& ctx, Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    const auto start = std::chrono::steady_clock::now();
    // Only patches with a contour can hold a cusp.
    std::vector<Index> patches;
    for (const ContourSegment& segment : *view.segments)
        if (patches.empty() || patches.back() != segment.patch)
            patches.push_back(segment.patch);
    std::vector<PatchCuspResult> found(patches.size());
    tbb::parallel_for(size_t(0), patches.size(), [&](size_t i) {
        found[i] = patchCusps(view.spline->patches[patches[i]], kTau);
    });
    auto cusps = std::make_shared<std::vector<PatchCusp>>();
    long long degenerate = 0;
    // A cusp on a side shared by two patches is found by both: one is kept
    // (positions within 1e-9 of the patches' size apart).
    const double merge = 1e-9 * view.layout->mesh.boundingBox().diagonal();
    for (const PatchCuspResult& r : found) {
        degenerate += r.degenerate;
        for (const PatchCusp& cusp : r.cusps) {
            bool seen = false;
            for (const PatchCusp& kept : *cusps)
                seen = seen || (kept.position - cusp.position).norm() <= merge;
            if (!seen)
                cusps->push_back(cusp);
        }
    }
    // Boundary cusps (§4.2): at every join across a patch side, the sign
    // test on the two segments' tangents.
    long long boundary = 0;
    for (const ContourChain& chain : view.chaining->chains)
        for (size_t k = 0; k + 1 < chain.links.size() + (chain.closed ? 1 : 0); ++k) {
            const ChainLink& a = chain.links[k];
            const ChainLink& b = chain.links[(k + 1) % chain.links.size()];
            const ContourSegment& sa = (*view.segments)[a.segment];
            const ContourSegment& sb = (*view.segments)[b.segment];
            if (sa.patch == sb.patch)
                continue;
            const double ta = a.reversed ? sa.t0 : sa.t1, tb = b.reversed ? sb.t1 : sb.t0;
            const QuadraticBezier<Vec3>& pa = view.spline->patches[sa.patch];
            const QuadraticBezier<Vec3>& pb = view.spline->patches[sb.patch];
            const auto tangent = [](const QuadraticBezier<Vec3>& patch, const ContourSegment& seg,
                                    double t, bool reversed) {
                const Vec3 at = barycentricOf(patch.domain, seg.curve.at(t));
                Vec3 du, dv;
                uvDerivatives(patch, at, du, dv);
                const Vec2 d = seg.curve.derivative(t) * (reversed ? -1.0 : 1.0);
                return std::pair{Vec3(du * d.x() + dv * d.y()), Vec3(du.cross(dv))};
            };
            const auto [t1, n1] = tangent(pa, sa, ta, a.reversed);
            const auto [t2, n2] = tangent(pb, sb, tb, b.reversed);
            boundary += isBoundaryCusp(n1, t1, t2, kTau);
        }
    auto state = copyState(s);
    state->cusps = cusps;
    s.methodState = state;
    s.setCounter(counters::kInteriorCusps, static_cast<double>(cusps->size()));
    s.setCounter(counters::kBoundaryCusps, static_cast<double>(boundary));
    s.setCounter(counters::kDegenerateCuspPatches, static_cast<double>(degenerate));
    s.setCounter(counters::kStageSeconds, secondsSince(start));
    ctx.checkCancelled();
    if (degenerate > 0)
        s.notes.push_back(std::to_string(degenerate) +
                          " patches have a non-generic view (the contour's image tangent "
                          "vanishes along a curve): their cusps are not listed");
}

void runVisibility(const PhaseContext& ctx, Snapshot& s) {
    const PowellSabinState& view = viewState(s);
    const ProjectiveTransform transform(ctx.camera);
    SplineViewGraphOptions options;
    options.minRayChainPixels = ctx.parameters.getDouble("min-ray-chain-pixels");
    SplineViewGraph built = buildSplineViewGraph(*view.spline, *view.segments, *view.chaining,
                                                 ctx.camera, transform, options);
    ctx.checkCancelled();
    const ViewGraph& graph = built.graph;
    const SplineViewGraphStats& stats = built.stats;
    long long visible = 0;
    for (const ViewChain& chain : graph.chains)
        visible += chain.visible();
    long long folds = 0;
    for (const ViewNode& node : graph.nodes)
        folds += node.type == ViewNodeType::CurtainFold;
    s.setCounter(counters::kChains, static_cast<double>(graph.chains.size()));
    s.setCounter(counters::kVisibleChains, static_cast<double>(visible));
    s.setCounter(counters::kNodes, static_cast<double>(graph.nodes.size()));
    s.setCounter(counters::kTJunctions, stats.tJunctions);
    s.setCounter(counters::kCurtainFolds, static_cast<double>(folds));
    s.setCounter(counters::kInteriorCusps, stats.interiorCusps);
    s.setCounter(counters::kBoundaryCusps, stats.boundaryCusps);
    s.setCounter(counters::kUnreliableBoundaryCusps, stats.unreliableCusps);
    s.setCounter(counters::kUncheckedCuspSteps, stats.uncheckedCuspSteps);
    s.setCounter(counters::kPropagatedChains, stats.propagatedChains);
    s.setCounter(counters::kChordOnlyCrossings, static_cast<double>(stats.chordOnlyCrossings));
    s.setCounter(counters::kTouchingCrossings, static_cast<double>(stats.touchingCrossings));
    s.setCounter(counters::kCuspPlacementSeconds, stats.secondsCusps);
    s.setCounter(counters::kSamplingSeconds, stats.secondsSampling);
    s.setCounter(counters::kIntersectionSeconds, stats.secondsIntersections);
    s.setCounter(counters::kChainCuttingSeconds, stats.secondsChains);
    s.setCounter(counters::kRayTestSeconds, stats.secondsRays);
    s.setCounter(counters::kRuleCheckSeconds, stats.secondsChecks);
    s.setCounter(counters::kRayTests, static_cast<double>(stats.rays));
    s.setCounter(counters::kConflicts, static_cast<double>(graph.conflicts.size()));
    s.setCounter(counters::kVisibleLengthPx, graph.visibleLengthPixels());
    s.setCounter(counters::kHiddenLengthPx, graph.hiddenLengthPixels());
    s.setCounter(counters::kStageSeconds, stats.secondsTotal);
    s.viewGraph = std::make_shared<const ViewGraph>(std::move(built.graph));
    if (stats.conePoints > 0)
        s.notes.push_back(std::to_string(stats.conePoints) +
                          " cone points on the contour: chains meet there and no QI is "
                          "propagated through them (§4.2)");
    if (!graph.conflicts.empty())
        s.notes.push_back(std::to_string(graph.conflicts.size()) +
                          " chains whose ray test disagrees with the propagation rules at a node "
                          "(listed in the JSON report and the inspector)");
    s.notes.push_back("T-junctions come from the exact crossings of the densely sampled rational "
                      "curves (0.25 px chords), not from Bezier clipping");
}

std::vector<InvariantCheck> checkVisibility(const PhaseContext& ctx, const Snapshot& s) {
    InvariantCheck decided{"every chain has a QI, from its ray or by propagation", 0, ""};
    InvariantCheck rays{"every chain of at least min-ray-chain-pixels has its own ray", 0, ""};
    const double minRay = ctx.parameters.getDouble("min-ray-chain-pixels");
    if (s.viewGraph)
        for (size_t c = 0; c < s.viewGraph->chains.size(); ++c) {
            const ViewChain& chain = s.viewGraph->chains[c];
            if (chain.qi < 0 && decided.violations++ == 0)
                decided.firstExample = "chain " + std::to_string(c);
            if ((chain.closed || chain.lengthPixels >= minRay) &&
                chain.decidedBy != VisibilityRule::RayTest && rays.violations++ == 0)
                rays.firstExample = "chain " + std::to_string(c);
        }
    // §4.2 T-junctions are crossings of the curves, not of their chords.
    InvariantCheck crossings{"every T-junction lies on both curves (1e-5 px apart at most)", 0, ""};
    if (s.viewGraph)
        for (size_t n = 0; n < s.viewGraph->nodes.size(); ++n) {
            const ViewNode& node = s.viewGraph->nodes[n];
            if (node.type != ViewNodeType::ImageIntersection)
                continue;
            const double apart =
                (ctx.camera.project(node.position).pixel - ctx.camera.project(node.nearPoint).pixel)
                    .norm();
            if (!(apart <= 1e-5) && crossings.violations++ == 0)
                crossings.firstExample =
                    "node " + std::to_string(n) + ": " + std::to_string(apart) + " px apart";
        }
    return {decided, rays, crossings};
}

} // namespace

Method makePowellSabinMethod() {
    Method m;
    m.name = "powell-sabin";
    m.label = "Powell-Sabin contours (Capouellez et al. 2023)";
    m.description =
        "A G1 piecewise-quadratic surface fitted to the mesh (Capouellez et al. 2023 §5): cones, "
        "a discrete conformal map, a cut and uv layout, 12 Powell-Sabin patches per triangle and "
        "a thin-plate fit factored once per mesh, solved per view after the projective transform "
        "(§3). Quads are split along the shorter diagonal, polygons as fans; an OBJ whose texture "
        "coordinates are a cone parameterization is used as it is. Per view: each patch's contour "
        "conic (§4.1), chains, cusps, T-junctions and visibility (§4.2).";
    // Capouellez et al. 2023 as written: the parameters whose help says "not
    // in the paper" off.
    m.presets = {defaultPreset(),
                 {"paper",
                  "Capouellez et al. 2023 as written: the thin-plate energy of eq. 8 in uv, w = 1.",
                  {{"thin-plate-in-surface-metric", false}}}};
    m.parameters = {
        {"parameterization",
         "Parameterization",
         "Where the layout comes from: compute (cones, conformal map, layout, §5.1), "
         "texture-coordinates (the OBJ's vt, as the paper's code reads them) or auto (the vt "
         "when they form a cone parameterization, else computed, with a note).",
         ParameterType::Choice,
         std::string(kAuto),
         0,
         0,
         {kAuto, kCompute, kTextureCoordinates}},
        {"cones-per-component",
         "Cones per component",
         "Cones per closed component; -1: the paper's count, 8 for genus 0 and 4(g-1) for genus "
         "g > 1 (§5.1). Components with a boundary get none.",
         ParameterType::Int,
         -1,
         -1,
         64,
         {}},
        {"refine-around-cones",
         "Refine around cones",
         "One Loop subdivision step on the triangles incident to the cones (§5.1: to reduce "
         "artifacts).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}},
    };
    m.addPhase({"cones",
                "Cones of the flat metric: per closed component 8 for genus 0, 4(g-1) for g > 1, "
                "at the smallest discrete curvature of clusters of close size; then one Loop "
                "step on their incident triangles (§5.1).",
                runCones, checkCones});
    m.parameters.push_back({"angle-tolerance",
                            "Angle tolerance",
                            "Newton stops when every free vertex's angle sum is within this of "
                            "2 pi (radians).",
                            ParameterType::Double,
                            1e-9,
                            1e-14,
                            1e-3,
                            {}});
    m.parameters.push_back({"max-newton-iterations",
                            "Newton iterations",
                            "At most this many Newton steps; the phase fails with the residual "
                            "reached beyond it.",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.parameters.push_back({"intrinsic-flips",
                            "Intrinsic flips",
                            "Keep the triangulation intrinsically Delaunay in the current metric "
                            "(Ptolemy flips, Gillespie et al. 2021), so no triangle inequality "
                            "breaks.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.addPhase({"conformal-map",
                "Discrete conformal map with the cones' scale factors fixed (Springborn et al. "
                "2008 energy, Newton with line search, CHOLMOD) and intrinsic Delaunay flips.",
                runConformalMap, checkConformalMap});
    m.addPhase({"layout",
                "Cut to a disk through the cones and greedy layout of the flat metric to uv per "
                "corner; angle sums, cut-edge lengths, flipped triangles and distortion checked.",
                runLayout, checkLayout});
    m.addPhase({"patches",
                "Powell-Sabin 12-split: 12 quadratic Bezier patches per triangle from 12 DOFs "
                "(§5.2), each macro-patch checked for quadratic precision.",
                runPatches, checkPatches});
    m.parameters.push_back({"fitting-weight",
                            "Fitting weight",
                            "w of eq. 8: the weight of the fit to the vertices against the "
                            "thin-plate energy (the paper uses 1).",
                            ParameterType::Double,
                            1.0,
                            1e-6,
                            1e6,
                            {}});
    m.parameters.push_back({"thin-plate-in-surface-metric",
                            "Thin plate in the surface metric",
                            "Not in the paper: each face's thin-plate term weighted by its uv "
                            "over its 3D area, so the smoothing does not follow the conformal "
                            "scale (which shrinks protrusions exponentially). Off: eq. 8 as "
                            "written.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.addPhase({"factorization",
                "Thin-plate and fitting Hessians assembled (eq. 8-10) and H factored once per "
                "mesh (sparse Cholesky, CHOLMOD); the drawing tessellation welded once per "
                "layout.",
                runFactorization, checkFactorization});
    m.parameters.push_back({"tessellation-level",
                            "Tessellation level",
                            "Each quadratic patch is drawn as k x k triangles.",
                            ParameterType::Int,
                            2,
                            1,
                            8,
                            {}});
    m.addPhase({"fit",
                "Per view: the projective transform of the vertices (§3), one back-substitution "
                "per coordinate, the spline's patches and their tessellation.",
                runFit, checkFit});
    m.addPhase({"patch-contours",
                "Per patch, tau . n = 0 as a conic in closed form (§4.1, Table 1 with the reading "
                "notes' errata), parameterized rationally and trimmed to the patch.",
                runPatchContours, checkPatchContours});
    m.addPhase({"chaining",
                "The segments joined across patch sides into loops; chains end at cone points, "
                "where several loops may meet (§4.2).",
                runChaining, checkChaining});
    m.addPhase({"cusps",
                "Interior cusps from eq. 5-6 (two conics, pencil method, cubic roots as companion "
                "eigenvalues) and boundary cusps by the sign test at patch sides (§4.2).",
                runCusps,
                {}});
    m.parameters.push_back(
        {"min-ray-chain-pixels",
         "Shortest ray-tested chain (px)",
         "Shorter chains take their QI from their neighbours, not from a ray: next to a cusp "
         "the sheet covering a sub-pixel chain is closer to it in depth than a ray test "
         "resolves. 0: a ray on every chain. The paper casts rays only where propagation "
         "leaves a chain without a QI.",
         ParameterType::Double,
         1.0,
         0.0,
         64.0,
         {}});
    m.addPhase({"visibility",
                "The view graph (§4.2): the chains sampled densely, cut at cusps, cone points and "
                "image-space crossings (T-junctions); one ray test per piece against the patches "
                "(two conics each, a grid over their boxes); the propagation rules checked at "
                "every node, disagreements kept as conflicts.",
                runVisibility, checkVisibility});
    return m;
}

} // namespace contour
