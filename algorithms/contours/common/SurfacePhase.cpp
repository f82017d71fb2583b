#include "contours/common/SurfacePhase.h"

#include "contours/common/VertexNormalCache.h"
#include "core/SharedResultCache.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"
#include "surface/SurfaceFields.h"
#include "surface/SurfaceTessellation.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

constexpr const char* kNone = "none";
constexpr const char* kAuto = "auto";

// The view-independent part of a tessellated surface, shared by every view.
struct TessellationEntry {
    std::shared_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const Field> normals, preimageFace, preimageUv, domainFace;
    std::shared_ptr<const Field> gaussian, mean;
    std::vector<ShapeOperator> shape; // per vertex, for the radial curvature of each view
    Index domainFaces = 0;
    Index domainBoundaryEdges = 0;
    double seconds = 0.0;
};

std::shared_ptr<const TessellationEntry>
buildEntry(const std::shared_ptr<const SmoothSurface>& surfacePtr, int level) {
    const auto start = std::chrono::steady_clock::now();
    const SmoothSurface& surface = *surfacePtr;
    // The tessellation itself is the one the consistent method's
    // initialization uses (sharedTessellation), so a session builds it once;
    // this entry adds the view-independent fields and statistics.
    const SurfaceTessellation& t = *sharedTessellation(surfacePtr, level);
    auto e = std::make_shared<TessellationEntry>();
    const size_t n = t.preimages.size();
    std::vector<int> face(n);
    std::vector<Vec3> uv(n);
    for (size_t v = 0; v < n; ++v) {
        face[v] = t.preimages[v].face;
        uv[v] = Vec3(t.preimages[v].u, t.preimages[v].v, 0.0);
    }
    e->shape = shapeOperators(t.points);
    std::vector<double> gaussian(n), mean(n);
    tbb::parallel_for(size_t(0), n, [&](size_t v) {
        gaussian[v] = e->shape[v].gaussian();
        mean[v] = e->shape[v].mean();
    });
    const auto field = [](FieldLocation location, auto values, const char* description) {
        return std::make_shared<const Field>(Field{location, std::move(values), description});
    };
    e->mesh = t.mesh;
    e->normals = field(FieldLocation::Vertex, t.normals,
                       "unit normal of the smooth surface at the vertex (exact limit normal)");
    e->preimageFace = field(FieldLocation::Vertex, std::move(face),
                            "domain face of the vertex's preimage on the smooth surface");
    e->preimageUv = field(FieldLocation::Vertex, std::move(uv),
                          "(u, v, 0): the vertex's preimage coordinates in its domain face");
    e->domainFace =
        field(FieldLocation::Face, std::vector<int>(t.sourceFace.begin(), t.sourceFace.end()),
              "domain face of the smooth surface the triangle lies in");
    e->gaussian = field(FieldLocation::Vertex, std::move(gaussian),
                        "Gaussian curvature of the smooth surface (> 0 elliptic, < 0 hyperbolic)");
    e->mean = field(FieldLocation::Vertex, std::move(mean),
                    "mean curvature of the smooth surface (outward normal: -1/R on a sphere)");
    e->domainFaces = surface.domain().faceCount();
    for (Index f = 0; f < e->domainFaces; ++f)
        for (int k = 0; k < static_cast<int>(surface.domain().face(f).size()); ++k)
            e->domainBoundaryEdges += surface.neighbor(f, k).face == kInvalidIndex;
    e->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return e;
}

// Tessellations of the last few (surface, level) pairs, so that a session or
// a 26-view batch tessellates once. Entries die with their surface.
// Thread-safe; concurrent requests for one key build once.
struct CachedEntry {
    std::shared_ptr<const TessellationEntry> entry;
    bool fromCache = false;
};

CachedEntry cachedTessellation(const std::shared_ptr<const SmoothSurface>& surface, int level) {
    static SharedResultCache<SmoothSurface, int, TessellationEntry> cache(4);
    auto [entry, fromCache] = cache.get(surface, level, [&] { return buildEntry(surface, level); });
    return {entry, fromCache};
}

void setMeshCounters(Snapshot& s) {
    s.setCounter(counters::kFaces, s.mesh->faceCount());
    s.setCounter(counters::kVertices, s.mesh->vertexCount());
    s.setCounter(counters::kEdges, s.mesh->edgeCount());
    s.setCounter(counters::kBoundaryEdges, s.mesh->boundaryEdgeCount());
}

std::optional<SurfaceKind> kindOrThrow(const ParameterSet& parameters, const Snapshot& s) {
    if (parameters.getChoice("surface") == kNone)
        return std::nullopt;
    if (!s.cage)
        throw std::invalid_argument("a smooth surface needs the control cage, and the input "
                                    "snapshot has none");
    return selectedSurfaceKind(parameters, *s.cage);
}

// The phase's parameters, read once per run.
struct SurfacePhaseOptions {
    int tessellationLevel = 0; // tessellation-level
    // The weighting of the vertex normals published with surface = none.
    std::optional<NormalWeighting> noneWeighting;
    static SurfacePhaseOptions read(const ParameterSet& p, const NoneSurfaceNormals& noneNormals) {
        SurfacePhaseOptions o;
        o.tessellationLevel = p.getInt("tessellation-level");
        if (noneNormals.weighting)
            o.noneWeighting = noneNormals.weighting(p);
        return o;
    }
};

void runSurfacePhase(const PhaseContext& ctx, Snapshot& s, const NoneSurfaceNormals& noneNormals) {
    const SurfacePhaseOptions options = SurfacePhaseOptions::read(ctx.parameters, noneNormals);
    const std::optional<SurfaceKind> kind = kindOrThrow(ctx.parameters, s);
    if (!kind) {
        // The triangulated cage stays the working mesh.
        s.setCounter(counters::kDomainFaces, s.cage ? s.cage->faceCount() : s.mesh->faceCount());
        s.setCounter(counters::kTessellationFaces, s.mesh->faceCount());
        s.setCounter(counters::kSurfaceSetupSeconds, 0.0);
        if (options.noneWeighting)
            s.fields[fields::kVertexNormal] = cachedVertexNormals(s.mesh, *options.noneWeighting);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const CachedSmoothSurface surface = cachedSmoothSurface(s.cage, *kind);
    s.setCounter(counters::kSurfaceSetupSeconds,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    s.setCounter(counters::kSurfaceBuildSeconds, surface.buildSeconds);
    s.setCounter(counters::kSurfaceCached, surface.fromCache ? 1.0 : 0.0);
    ctx.checkCancelled();
    ctx.reportProgress(0.5);
    applySmoothSurface(s, surface.surface, options.tessellationLevel, ctx.camera);
    if (options.noneWeighting)
        s.notes.push_back("vertex normals are the smooth surface's exact normals; the "
                          "normal-weighting parameter applies only with surface = none");
}

std::vector<InvariantCheck> checkSurfacePhase(const PhaseContext& ctx, const Snapshot& s) {
    const std::optional<SurfaceKind> kind = kindOrThrow(ctx.parameters, s);
    if (!kind)
        return {};
    const TriangleMesh& mesh = *s.mesh;
    InvariantCheck unit{"every vertex has a unit limit normal", 0, ""};
    InvariantCheck inside{"every vertex's preimage lies in its domain face", 0, ""};
    InvariantCheck closed{"the tessellation has L boundary edges per domain boundary edge", 0, ""};
    const auto& normals = *s.field(fields::kVertexNormal)->vectors();
    const auto& face = *s.field(fields::kPreimageFace)->labels();
    const auto& uv = *s.field(fields::kPreimageUv)->vectors();
    const CachedSmoothSurface surface = cachedSmoothSurface(s.cage, *kind);
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
        if (!(std::abs(normals[v].norm() - 1.0) <= 1e-9) && unit.violations++ == 0)
            unit.firstExample = "vertex " + std::to_string(v);
        if (!surface.surface->contains({face[v], uv[v].x(), uv[v].y()}) && inside.violations++ == 0)
            inside.firstExample = "vertex " + std::to_string(v);
    }
    const Index domainBoundary = static_cast<Index>(s.counter(counters::kDomainBoundaryEdges));
    if (mesh.boundaryEdgeCount() !=
        domainBoundary * static_cast<Index>(s.counter(counters::kTessellationLevel))) {
        closed.violations = 1;
        closed.firstExample = std::to_string(mesh.boundaryEdgeCount()) + " boundary edges for " +
                              std::to_string(domainBoundary) + " domain boundary edges";
    }
    return {unit, inside, closed};
}

} // namespace

std::vector<ParameterSpec> surfaceParameters() {
    return {
        {"surface",
         "Smooth surface",
         "The surface the contours are computed on: none (the triangulated cage), the "
         "Catmull-Clark or Loop limit surface (OpenSubdiv) or vertex-normal patches, "
         "tessellated uniformly with exact limit positions and normals (Hertzmann & Zorin "
         "2000). auto: Catmull-Clark, or Loop for an all-triangle cage.",
         ParameterType::Choice,
         std::string(kNone),
         0,
         0,
         {kNone, kAuto, toString(SurfaceKind::CatmullClark), toString(SurfaceKind::Loop),
          toString(SurfaceKind::VertexNormalPatches)}},
        {"tessellation-level",
         "Tessellation level",
         "Each domain quad of the smooth surface becomes an L x L grid of quads (two triangles "
         "each), each domain triangle L^2 triangles. Ignored with surface = none.",
         ParameterType::Int,
         4,
         1,
         16,
         {}},
    };
}

std::optional<SurfaceKind> selectedSurfaceKind(const ParameterSet& parameters,
                                               const PolygonMesh& cage) {
    const std::string& name = parameters.getChoice("surface");
    if (name == kNone)
        return std::nullopt;
    if (name == kAuto)
        return automaticSurfaceKind(cage);
    if (const auto kind = surfaceKindFromName(name))
        return kind;
    throw std::invalid_argument("surface: unknown surface \"" + name + "\"");
}

void applySmoothSurface(Snapshot& s, const std::shared_ptr<const SmoothSurface>& surface, int level,
                        const Camera& camera) {
    const CachedEntry cached = cachedTessellation(surface, level);
    const TessellationEntry& e = *cached.entry;
    s.mesh = e.mesh;
    s.fields[fields::kVertexNormal] = e.normals;
    s.fields[fields::kPreimageFace] = e.preimageFace;
    s.fields[fields::kPreimageUv] = e.preimageUv;
    s.fields[fields::kDomainFace] = e.domainFace;
    s.fields[fields::kGaussianCurvature] = e.gaussian;
    s.fields[fields::kMeanCurvature] = e.mean;
    std::vector<double> radial(e.shape.size());
    tbb::parallel_for(size_t(0), e.shape.size(), [&](size_t v) {
        radial[v] = radialCurvature(e.shape[v], e.mesh->position(static_cast<Index>(v)), camera);
    });
    long long undefined = 0;
    for (double k : radial)
        undefined += std::isnan(k);
    s.setField(fields::kRadialCurvature,
               {FieldLocation::Vertex, std::move(radial),
                "radial curvature: normal curvature along the view vector projected onto the "
                "tangent plane; < 0 at an ordinary exterior contour; NaN where undefined"});
    setMeshCounters(s);
    s.setCounter(counters::kDomainFaces, e.domainFaces);
    s.setCounter(counters::kTessellationFaces, e.mesh->faceCount());
    s.setCounter(counters::kDomainBoundaryEdges, e.domainBoundaryEdges);
    s.setCounter(counters::kTessellationLevel, level);
    s.setCounter(counters::kTessellationSeconds, cached.fromCache ? 0.0 : e.seconds);
    s.setCounter(counters::kTessellationCached, cached.fromCache ? 1.0 : 0.0);
    s.notes.push_back(surface->description());
    if (undefined > 0)
        s.notes.push_back(std::to_string(undefined) +
                          " vertices see the camera along their normal: radial curvature is "
                          "undefined there (NaN)");
}

Phase makeSurfacePhase(NoneSurfaceNormals noneNormals) {
    return {"surface",
            "Tessellate the smooth surface (none: keep the triangulated cage): exact limit "
            "positions and normals at every vertex, preimages, curvature fields.",
            [noneNormals](const PhaseContext& ctx, Snapshot& s) {
                runSurfacePhase(ctx, s, noneNormals);
            },
            checkSurfacePhase};
}

} // namespace contour
