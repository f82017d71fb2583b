#include "contours/consistent/phases/SnapshotRoundTrip.h"

#include "contours/common/SurfacePhase.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour::consistent {

ChartOptions ChartOptions::read(const ParameterSet& p) {
    ChartOptions o;
    o.tolerance = p.getDouble("chart-tolerance");
    o.vertexRings = p.getBool("chart-vertex-rings");
    return o;
}

std::shared_ptr<const SmoothSurface> surfaceFor(const PhaseContext& ctx, const Snapshot& s) {
    if (!s.cage)
        throw std::invalid_argument("consistent contours need the control cage, and the input "
                                    "snapshot has none");
    const std::optional<SurfaceKind> kind = selectedSurfaceKind(ctx.parameters, *s.cage);
    if (!kind)
        throw std::invalid_argument("consistent contours need a smooth surface");
    return cachedSmoothSurface(s.cage, *kind).surface;
}

namespace {

template <typename T> const std::vector<T>* optionalValues(const Snapshot& s, const char* name) {
    const Field* f = s.field(name);
    return f ? std::get_if<std::vector<T>>(&f->values) : nullptr;
}

// What publish() leaves in Snapshot::methodState: the evaluated vertices
// (f(u), n(u), g and the radial curvature at every preimage) and the
// half-edge table, so that the next phase and the post-conditions need not
// evaluate the surface again nor rehash every edge (most of a phase's time
// on large meshes). Tied to the mesh and preimage fields it was published
// with (held, so their addresses cannot be reused).
struct PublishedVertices final : MethodState {
    std::shared_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const Field> preimageFace, preimageUv;
    std::vector<MeshVertex> vertices;
    std::shared_ptr<const HalfedgeMap> halfedges; // shared with the publishing mesh
    std::shared_ptr<const ConsistentMesh::VertexPreimages> preimages; // null if never built
    // Per face: parameter orientation and centroid's domain face, so that a
    // phase recomputes them only for the faces it edits.
    ConsistentMesh::FaceCaches faceCaches;
    // analyse() of the published mesh without the per-face fields publish()
    // moved into the snapshot (facing, vbo, consistent): what the
    // post-conditions read (phaseChecks()), a function of the mesh only.
    std::shared_ptr<const Analysis> analysis;
};

std::shared_ptr<const Field> fieldPtr(const Snapshot& s, const char* name) {
    const auto it = s.fields.find(name);
    return it == s.fields.end() ? nullptr : it->second;
}

const PublishedVertices* publishedVertices(const Snapshot& s) {
    const auto* p = dynamic_cast<const PublishedVertices*>(s.methodState.get());
    if (!p || p->mesh != s.mesh || p->preimageFace != fieldPtr(s, fields::kPreimageFace) ||
        p->preimageUv != fieldPtr(s, fields::kPreimageUv) ||
        static_cast<Index>(p->vertices.size()) != s.mesh->vertexCount())
        return nullptr;
    return p;
}

#ifdef CONTOUR_CHECK_INVARIANTS
bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool sameBits(const Vec3& a, const Vec3& b) {
    return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}
#endif

} // namespace

ConsistentMesh reload(const PhaseContext& ctx, const Snapshot& s) {
    const ChartOptions charts = ChartOptions::read(ctx.parameters);
    ConsistentMesh m(surfaceFor(ctx, s), ctx.camera, charts.tolerance);
    m.setVertexRingCharts(charts.vertexRings);
    const auto* face = optionalValues<int>(s, fields::kPreimageFace);
    const auto* uv = optionalValues<Vec3>(s, fields::kPreimageUv);
    const auto* label = optionalValues<int>(s, fields::kLabel);
    const auto* prov = optionalValues<int>(s, fields::kProvenance);
    const auto* vphase = optionalValues<int>(s, fields::kVertexChangedByPhase);
    const auto* fphase = optionalValues<int>(s, fields::kChangedByPhase);
    if (!face || !uv || !label || !prov || !vphase || !fphase)
        throw std::logic_error("consistent contours: the previous phase published no mesh");
    const auto* cusp = optionalValues<int>(s, fields::kCusp);
    const auto* offset = optionalValues<double>(s, fields::kNormalOffset);
    const TriangleMesh& mesh = *s.mesh;
    const PublishedVertices* published = publishedVertices(s);
    std::vector<MeshVertex> vertices(static_cast<size_t>(mesh.vertexCount()));
    tbb::parallel_for(Index(0), mesh.vertexCount(), [&](Index v) {
        const Vec3& p = (*uv)[v];
        const Preimage preimage{(*face)[v], p.x(), p.y()};
        const double off = offset ? (*offset)[v] : 0.0;
        MeshVertex mv;
        if (published && off == 0.0) {
            // The published record's surface values at this same preimage
            // (a vertex off the surface is evaluated again: its published
            // position was computed with the offset).
            const MeshVertex& x = published->vertices[v];
            mv.preimage = preimage;
            mv.position = x.position;
            mv.normal = x.normal;
            mv.g = x.g;
            mv.radialCurvature = x.radialCurvature;
#ifdef CONTOUR_CHECK_INVARIANTS
            const MeshVertex e = m.evaluate(preimage);
            if (!sameBits(e.position, x.position) || !sameBits(e.normal, x.normal) ||
                !sameBits(e.g, x.g) || !sameBits(e.radialCurvature, x.radialCurvature))
                throw std::logic_error("consistent contours: the published vertex " +
                                       std::to_string(v) +
                                       " differs from the surface at its preimage");
#endif
        } else {
            mv = m.evaluate(preimage);
        }
        mv.label = static_cast<VertexLabel>((*label)[v]);
        mv.provenance = static_cast<Provenance>((*prov)[v]);
        mv.phase = (*vphase)[v];
        mv.cusp = cusp && (*cusp)[v] != 0;
        if (offset && off != 0.0) {
            mv.normalOffset = off;
            mv.position += mv.normalOffset * mv.normal;
        }
        vertices[static_cast<size_t>(v)] = mv;
    });
    m.assignShared(std::move(vertices),
                   std::vector<Triangle>(mesh.triangles().begin(), mesh.triangles().end()), *fphase,
                   published ? published->halfedges : nullptr);
    if (published) {
        m.adoptVertexPreimages(published->preimages);
        m.adoptFaceCaches(published->faceCaches);
    }
#ifdef CONTOUR_CHECK_INVARIANTS
    if (published && m.currentVertexPreimages()) {
        ConsistentMesh fresh(m.surfacePtr(), m.camera(), charts.tolerance);
        fresh.setVertexRingCharts(charts.vertexRings);
        fresh.assign(m.vertices(), {}, {}, nullptr);
        const auto& a = *fresh.vertexPreimages();
        const auto& b = *m.currentVertexPreimages();
        bool sameTable = a.offsets == b.offsets && a.reps.size() == b.reps.size();
        for (size_t i = 0; sameTable && i < a.reps.size(); ++i)
            sameTable = a.reps[i].face == b.reps[i].face && sameBits(a.reps[i].u, b.reps[i].u) &&
                        sameBits(a.reps[i].v, b.reps[i].v);
        if (!sameTable)
            throw std::logic_error("consistent contours: the published vertex preimages do not "
                                   "match the snapshot's vertices");
    }
    if (published) {
        // The adopted per-face caches against a fresh computation.
        ConsistentMesh fresh(m.surfacePtr(), m.camera(), charts.tolerance);
        fresh.setVertexRingCharts(charts.vertexRings);
        fresh.assign(m.vertices(),
                     std::vector<Triangle>(mesh.triangles().begin(), mesh.triangles().end()),
                     *fphase, nullptr);
        if (fresh.parameterOrientations() != m.parameterOrientations() ||
            fresh.centroidDomainFaces() != m.centroidDomainFaces())
            throw std::logic_error("consistent contours: the published face orientations or "
                                   "centroid domain faces do not match the snapshot's faces");
        bool same = m.halfedges().size() == 3 * static_cast<size_t>(m.faceCount());
        for (Index f = 0; same && f < m.faceCount(); ++f)
            for (int i = 0; i < 3; ++i)
                same = same && m.faceOfHalfedge(m.face(f)[i], m.face(f)[(i + 1) % 3]) == f;
        if (!same)
            throw std::logic_error("consistent contours: the published half-edge table does not "
                                   "match the snapshot's faces");
    }
#endif
    for (const auto& [name, tag] :
         {std::pair{fields::kCuspEdge, kCuspEdge}, std::pair{fields::kRadialEdge, kRadialEdge}}) {
        const auto* values = optionalValues<int>(s, name);
        if (!values)
            continue;
        for (Index e = 0; e < mesh.edgeCount(); ++e)
            if ((*values)[e] != 0) {
                const Index h = mesh.edgeHalfedge(e);
                m.addEdgeTag(mesh.from(h), mesh.to(h), tag);
            }
    }
    return m;
}

std::shared_ptr<const Analysis> publishedAnalysis(const Snapshot& s) {
    const PublishedVertices* published = publishedVertices(s);
    return published ? published->analysis : nullptr;
}

void publish(Snapshot& s, ConsistentMesh& m) {
    m.compact();
    const double foldedBefore = s.counter(counters::kFoldedFaces, 0.0);
    s.mesh = m.toTriangleMesh();
    const TriangleMesh& mesh = *s.mesh;
    const Index nv = m.vertexCount();
    std::vector<int> face(nv), label(nv), prov(nv), vphase(nv), cusp(nv), singular(nv, 0);
    const double scale = sceneScale(m);
    std::vector<Vec3> uv(nv), normal(nv);
    std::vector<double> g(nv), kr(nv), offset(nv);
    for (Index v = 0; v < nv; ++v) {
        const MeshVertex& x = m.vertex(v);
        face[v] = x.preimage.face;
        uv[v] = Vec3(x.preimage.u, x.preimage.v, 0.0);
        normal[v] = x.normal;
        g[v] = x.g;
        kr[v] = x.radialCurvature;
        label[v] = static_cast<int>(x.label);
        prov[v] = static_cast<int>(x.provenance);
        vphase[v] = x.phase;
        cusp[v] = x.cusp ? 1 : 0;
        singular[v] = x.cusp && atSingularPoint(m, v, scale) ? 1 : 0;
        offset[v] = x.normalOffset;
    }
    std::vector<int> fphase(m.faceCount());
    for (Index f = 0; f < m.faceCount(); ++f)
        fphase[f] = m.facePhase(f);
    // faceDomainFace() of every face, at once.
    std::vector<int> domainFace = m.centroidDomainFaces();
    // The tagged edges (a few hundred) located through their half-edges,
    // which toTriangleMesh() numbers 3 f + corner as the faces are here.
    std::vector<int> radialEdge(mesh.edgeCount(), 0), cuspEdge(mesh.edgeCount(), 0);
    for (const auto& [k, tag] : m.edgeTags()) {
        const auto [x, y] = ConsistentMesh::edgeFromKey(k);
        for (const auto& [a, b] : {std::pair{x, y}, std::pair{y, x}}) {
            const Index f = m.faceOfHalfedge(a, b);
            if (f == kInvalidIndex)
                continue;
            int corner = 0;
            while (m.face(f)[corner] != a)
                ++corner;
            const Index e = mesh.edge(TriangleMesh::halfedge(f, corner));
            radialEdge[e] = (tag & kRadialEdge) ? 1 : 0;
            cuspEdge[e] = (tag & kCuspEdge) ? 1 : 0;
            break;
        }
    }
    const long long radialEdges = std::count(radialEdge.begin(), radialEdge.end(), 1);
    Analysis a = analyse(m, &mesh);
    // The per-face facing, VBO and consistency go into the fields; the rest
    // of the analysis is kept for the next phase's reload.
    std::vector<int> facing = std::move(a.facing);
    std::vector<int> vbo = std::move(a.vbo);
    std::vector<int> consistent = std::move(a.consistent);
    a.facing.clear();
    a.vbo.clear();
    a.consistent.clear();
    auto kept = std::make_shared<Analysis>(a);
    RadialClassification radial = classifyRadialFaces(m);
    const long long radialFaces = std::count(radial.radial.begin(), radial.radial.end(), 1);
    const long long standardFaces = std::count(radial.standard.begin(), radial.standard.end(), 1);
    using L = FieldLocation;
    s.setField(fields::kDomainFace,
               {L::Face, std::move(domainFace),
                "domain face holding the triangle's centroid (-1: no common chart)"});
    s.setField(fields::kPreimageFace,
               {L::Vertex, std::move(face), "domain face of the vertex's preimage"});
    s.setField(fields::kPreimageUv, {L::Vertex, std::move(uv), "(u, v, 0) in that domain face"});
    s.setField(fields::kVertexNormal, {L::Vertex, std::move(normal), "limit normal n(u)"});
    s.setField(fields::kG, {L::Vertex, std::move(g), "g(u) = (c - f(u)) · n(u), > 0 front"});
    s.setField(fields::kRadialCurvature,
               {L::Vertex, std::move(kr), "radial curvature at the preimage (< 0 exterior)"});
    s.setField(fields::kLabel, {L::Vertex, std::move(label), "R_S label: +1 F, -1 B, 0 C"});
    s.setField(fields::kProvenance,
               {L::Vertex, std::move(prov), "0 initial, 1 inserted, 2 shifted, 3 wiggled"});
    s.setField(fields::kVertexChangedByPhase,
               {L::Vertex, std::move(vphase), "phase that created or last changed the vertex"});
    s.setField(fields::kCusp, {L::Vertex, std::move(cusp), "1 at a cusp vertex"});
    s.setField(fields::kSingularCusp, {L::Vertex, std::move(singular),
                                       "1 at a cusp vertex where the surface is singular"});
    s.setField(fields::kNormalOffset,
               {L::Vertex, std::move(offset), "offset along n(u) of the normal wiggle"});
    s.setField(fields::kChangedByPhase,
               {L::Face, std::move(fphase), "phase that created or last changed the face"});
    s.setField(fields::kFacing,
               {L::Face, std::move(facing), "+1 front, -1 back, 0 edge-on (exact)"});
    s.setField(fields::kVbo, {L::Face, std::move(vbo),
                              "VBO (Definition 1): +1 F, -1 B, 0 "
                              "undefined"});
    s.setField(fields::kConsistent, {L::Face, std::move(consistent),
                                     "1 contour-consistent (Definition 2), 0 inconsistent"});
    s.setField(fields::kFolded,
               {L::Face, std::move(a.folded), "1 folded in parameter space (against the domain)"});
    s.setField(fields::kRadial,
               {L::Face, std::move(radial.radial), "1 radial triangle (Definition 5)"});
    s.setField(fields::kStandardRadial,
               {L::Face, std::move(radial.standard), "1 standard radial triangle (§6.3)"});
    s.setField(fields::kRadialEdge,
               {L::Edge, std::move(radialEdge), "1 radial edge p-r (Definition 5)"});
    s.setField(fields::kCuspEdge,
               {L::Edge, std::move(cuspEdge), "1 FB edge holding a cusp, inserted last"});
    s.setCounter(counters::kFaces, m.faceCount());
    s.setCounter(counters::kVertices, nv);
    s.setCounter(counters::kInconsistentFaces, static_cast<double>(a.inconsistent));
    s.setCounter(counters::kUndefinedVBOs, static_cast<double>(a.undefinedVbo));
    s.setCounter(counters::kFBEdgesLeft, static_cast<double>(a.fbEdges));
    s.setCounter(counters::kDegenerateCCEdges, static_cast<double>(a.degenerate));
    s.setCounter(counters::kContourVertices, static_cast<double>(a.contourVertices));
    s.setCounter(counters::kCusps, static_cast<double>(a.cusps));
    s.setCounter(counters::kFoldedFaces, static_cast<double>(a.foldedFaces));
    s.setCounter(counters::kFoldsIntroduced,
                 std::max(0.0, static_cast<double>(a.foldedFaces) - foldedBefore));
    s.setCounter(counters::kRadialEdges, static_cast<double>(radialEdges));
    s.setCounter(counters::kRadialFaces, static_cast<double>(radialFaces));
    s.setCounter(counters::kStandardRadialFaces, static_cast<double>(standardFaces));
    auto published = std::make_shared<PublishedVertices>();
    published->mesh = s.mesh;
    published->preimageFace = fieldPtr(s, fields::kPreimageFace);
    published->preimageUv = fieldPtr(s, fields::kPreimageUv);
    published->vertices = m.vertices();
    published->halfedges = m.shareHalfedges();
    published->preimages = m.currentVertexPreimages();
    published->faceCaches = m.faceCaches();
    published->analysis = std::move(kept);
    s.methodState = std::move(published);
}

} // namespace contour::consistent
