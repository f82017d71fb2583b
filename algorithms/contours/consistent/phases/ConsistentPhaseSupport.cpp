#include "contours/consistent/phases/ConsistentPhaseSupport.h"

#include "contours/common/SurfacePhase.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour::consistent {

std::shared_ptr<const SmoothSurface> surfaceFor(const PhaseContext& ctx, const Snapshot& s) {
    if (!s.cage)
        throw std::invalid_argument("consistent contours need the control cage, and the input "
                                    "snapshot has none");
    const std::optional<SurfaceKind> kind = selectedSurfaceKind(ctx.parameters, *s.cage);
    if (!kind)
        throw std::invalid_argument("consistent contours need a smooth surface");
    return cachedSmoothSurface(s.cage, *kind).surface;
}

double sceneScale(const ConsistentMesh& m) {
    BoundingBox box;
    for (Index v = 0; v < m.vertexCount(); ++v)
        box.extend(m.vertex(v).position);
    const double d = box.diagonal();
    return d > 0.0 ? d : 1.0;
}

// ------------------------------------------------------ snapshot round trip

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
    ConsistentMesh m(surfaceFor(ctx, s), ctx.camera, ctx.parameters.getDouble("chart-tolerance"));
    m.setVertexRingCharts(ctx.parameters.getBool("chart-vertex-rings"));
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
        ConsistentMesh fresh(m.surfacePtr(), m.camera(),
                             ctx.parameters.getDouble("chart-tolerance"));
        fresh.setVertexRingCharts(ctx.parameters.getBool("chart-vertex-rings"));
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
        ConsistentMesh fresh(m.surfacePtr(), m.camera(),
                             ctx.parameters.getDouble("chart-tolerance"));
        fresh.setVertexRingCharts(ctx.parameters.getBool("chart-vertex-rings"));
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

std::string describeFace(const ConsistentMesh& m, Index f) {
    std::string out = "face " + std::to_string(f) + ":";
    for (Index v : m.face(f)) {
        const MeshVertex& x = m.vertex(v);
        out += " v" + std::to_string(v) + " (domain face " + std::to_string(x.preimage.face) +
               " u " + std::to_string(x.preimage.u) + " v " + std::to_string(x.preimage.v) +
               ", label " + std::to_string(static_cast<int>(x.label)) + ", provenance " +
               std::to_string(static_cast<int>(x.provenance)) + ", phase " +
               std::to_string(x.phase) + ")";
    }
    return out;
}

// ------------------------------------------------------- classification

Vbo faceVbo(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    return vertexBasedOrientation(m.vertex(t[0]).label, m.vertex(t[1]).label, m.vertex(t[2]).label);
}

Facing faceFacing(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    return triangleFacing(m.camera(), m.vertex(t[0]).position, m.vertex(t[1]).position,
                          m.vertex(t[2]).position);
}

bool faceIsConsistent(const ConsistentMesh& m, Index f) {
    return isConsistent(faceVbo(m, f), faceFacing(m, f));
}

Index faceDomainFace(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    const std::optional<Preimage> mid =
        m.interpolate(m.vertex(t[0]).preimage, m.vertex(t[1]).preimage, 0.5);
    if (!mid)
        return kInvalidIndex;
    const std::optional<Preimage> centroid =
        m.interpolate(*mid, m.vertex(t[2]).preimage, 1.0 / 3.0);
    return centroid ? centroid->face : kInvalidIndex;
}

std::vector<Index> facesAround(const ConsistentMesh& m, const std::vector<Index>& vertices) {
    std::vector<Index> faces;
    for (Index v : vertices)
        faces.insert(faces.end(), m.vertexFaces(v).begin(), m.vertexFaces(v).end());
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

int inconsistentFacesAround(const ConsistentMesh& m, const std::vector<Index>& vertices) {
    int n = 0;
    for (Index f : facesAround(m, vertices))
        n += !faceIsConsistent(m, f);
    return n;
}

RadialClassification classifyRadialFaces(const ConsistentMesh& m) {
    RadialClassification c;
    c.radial.assign(m.faceCount(), 0);
    c.standard.assign(m.faceCount(), 0);
    // The faces on both sides of every radial edge (visiting the few tagged
    // edges, not every face's three edges).
    const auto isContour = [&](Index v) {
        return m.vertex(v).label == VertexLabel::Contour;
    };
    for (const auto& [k, tag] : m.edgeTags()) {
        if (!(tag & kRadialEdge))
            continue;
        const auto [a, b] = ConsistentMesh::edgeFromKey(k);
        for (const Index f : {m.faceOfHalfedge(a, b), m.faceOfHalfedge(b, a)}) {
            if (f == kInvalidIndex)
                continue;
            c.radial[f] = 1;
            Index q = kInvalidIndex;
            for (Index w : m.face(f))
                if (w != a && w != b)
                    q = w;
            // A CC edge: q and the edge's C end p.
            const bool ccEdge = isContour(q) && (isContour(a) || isContour(b));
            // q on another radial edge (q is not on a-b).
            bool otherRadial = false;
            for (Index w : ccEdge ? std::vector<Index>{} : m.neighbours(q))
                otherRadial = otherRadial || (m.edgeTag(q, w) & kRadialEdge);
            if (ccEdge || otherRadial)
                c.standard[f] = 1;
        }
    }
    return c;
}

namespace {

// analyse(); `published`, when given, is m.toTriangleMesh() (the same faces
// in the same order), whose opposite half-edges replace the hash look-ups.
Analysis analyseMesh(const ConsistentMesh& m, const TriangleMesh* published) {
    Analysis a;
    const Index nf = m.faceCount();
    a.facing.resize(nf);
    a.vbo.resize(nf);
    a.consistent.resize(nf);
    a.folded.resize(nf);
    a.noChart.resize(nf);
    const std::vector<std::optional<int>> orientation = m.parameterOrientations();
    // Per face in parallel (each writes its own slots), counted in order.
    tbb::parallel_for(Index(0), nf, [&](Index f) {
        const Facing facing = faceFacing(m, f);
        const Vbo vbo = faceVbo(m, f);
        a.facing[f] = static_cast<int>(facing);
        a.vbo[f] = static_cast<int>(vbo);
        a.consistent[f] = isConsistent(vbo, facing) ? 1 : 0;
        const std::optional<int>& o = orientation[static_cast<size_t>(f)];
        a.folded[f] = o && *o <= 0 ? 1 : 0;
        a.noChart[f] = o ? 0 : 1;
    });
    for (Index f = 0; f < nf; ++f) {
        a.inconsistent += a.consistent[f] == 0;
        if (static_cast<Vbo>(a.vbo[f]) == Vbo::Undefined && a.undefinedVbo++ == 0)
            a.firstUndefined = describeFace(m, f);
        if (a.folded[f] && a.foldedFaces++ == 0)
            a.firstFolded = describeFace(m, f);
    }
    // The edges in m.edges() order (faces in order, each edge at its a < b
    // half-edge or its only one), with the face across each half-edge
    // looked up in parallel.
    std::vector<Index> across(3 * static_cast<size_t>(nf));
    tbb::parallel_for(Index(0), nf, [&](Index f) {
        const Triangle& t = m.face(f);
        for (int i = 0; i < 3; ++i) {
            Index g = kInvalidIndex;
            if (published) {
                const Index o = published->opposite(TriangleMesh::halfedge(f, i));
                g = o == kInvalidIndex ? kInvalidIndex : o / 3;
            } else {
                g = m.faceOfHalfedge(t[(i + 1) % 3], t[i]);
            }
            across[3 * static_cast<size_t>(f) + i] = g;
        }
    });
    for (Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i) {
            const Index u = m.face(f)[i], v = m.face(f)[(i + 1) % 3];
            const Index f0 = f, f1 = across[3 * static_cast<size_t>(f) + i];
            if (!(u < v || f1 == kInvalidIndex))
                continue;
            const VertexLabel lu = m.vertex(u).label, lv = m.vertex(v).label;
            if (static_cast<int>(lu) * static_cast<int>(lv) < 0 && a.fbEdges++ == 0)
                a.firstFb = "edge " + std::to_string(u) + "-" + std::to_string(v);
            if (f0 != kInvalidIndex && f1 != kInvalidIndex &&
                isDegenerateEdge(lu, lv, static_cast<Vbo>(a.vbo[f0]),
                                 static_cast<Vbo>(a.vbo[f1])) &&
                a.degenerate++ == 0)
                a.firstDegenerate = "edge " + std::to_string(u) + "-" + std::to_string(v) +
                                    " between " + describeFace(m, f0) + " and " +
                                    describeFace(m, f1);
        }
    for (Index v = 0; v < m.vertexCount(); ++v) {
        a.contourVertices += m.vertex(v).label == VertexLabel::Contour;
        a.cusps += m.vertex(v).cusp;
    }
    return a;
}

} // namespace

Analysis analyse(const ConsistentMesh& m) {
    return analyseMesh(m, nullptr);
}

void publish(Snapshot& s, ConsistentMesh& m) {
    m.compact();
    const double foldedBefore = s.counter("folded faces", 0.0);
    s.mesh = m.toTriangleMesh();
    const TriangleMesh& mesh = *s.mesh;
    const Index nv = m.vertexCount();
    std::vector<int> face(nv), label(nv), prov(nv), vphase(nv), cusp(nv);
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
    Analysis a = analyseMesh(m, &mesh);
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
    s.setCounter("faces", m.faceCount());
    s.setCounter("vertices", nv);
    s.setCounter("inconsistent faces", static_cast<double>(a.inconsistent));
    s.setCounter("undefined VBOs", static_cast<double>(a.undefinedVbo));
    s.setCounter("FB edges left", static_cast<double>(a.fbEdges));
    s.setCounter("degenerate CC edges", static_cast<double>(a.degenerate));
    s.setCounter("contour vertices", static_cast<double>(a.contourVertices));
    s.setCounter("cusps", static_cast<double>(a.cusps));
    s.setCounter("folded faces", static_cast<double>(a.foldedFaces));
    s.setCounter("folds introduced",
                 std::max(0.0, static_cast<double>(a.foldedFaces) - foldedBefore));
    s.setCounter("radial edges", static_cast<double>(radialEdges));
    s.setCounter("radial faces", static_cast<double>(radialFaces));
    s.setCounter("standard radial faces", static_cast<double>(standardFaces));
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

// ------------------------------------------------------------ invariants

InvariantCheck check(const std::string& name) {
    return {name, 0, ""};
}

void violate(InvariantCheck& c, const std::string& example) {
    if (c.violations++ == 0)
        c.firstExample = example;
}

std::vector<InvariantCheck> commonChecks(const PhaseContext& ctx, const Snapshot& s,
                                         const ConsistentMesh& m, const Analysis& a) {
    InvariantCheck embedding =
        check("every vertex lies at f(u) + offset n(u) of its preimage (offset 0 before the "
              "normal wiggle)");
    InvariantCheck folds = check("every face keeps the domain's orientation in parameter space");
    InvariantCheck charts = check("every face's corners have a common chart (appendix B)");
    InvariantCheck degenerate = check("no degenerate CC edge (Definition 3)");
    const double tol = ctx.parameters.getDouble("embedding-tolerance") * sceneScale(m);
    const TriangleMesh& mesh = *s.mesh;
    // The surface evaluated afresh at every preimage (not the published
    // values reload() reuses), in parallel, reported in order.
    std::vector<char> off(static_cast<size_t>(mesh.vertexCount()));
    tbb::parallel_for(Index(0), mesh.vertexCount(), [&](Index v) {
        const MeshVertex& x = m.vertex(v);
        const SurfacePoint sp = m.surface().evaluateFirstOrder(x.preimage);
        const Vec3 expected = sp.position + x.normalOffset * sp.normal();
        off[static_cast<size_t>(v)] = !((mesh.position(v) - expected).norm() <= tol);
    });
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (off[static_cast<size_t>(v)])
            violate(embedding, "vertex " + std::to_string(v));
    for (Index f = 0; f < m.faceCount(); ++f) {
        const bool noChart = a.noChart.size() == static_cast<size_t>(m.faceCount())
                                 ? a.noChart[f] != 0
                                 : !m.parameterOrientation(f);
        if (noChart)
            violate(charts, "face " + std::to_string(f));
        else if (a.folded[f])
            violate(folds, describeFace(m, f));
    }
    degenerate.violations = a.degenerate;
    degenerate.firstExample = a.firstDegenerate;
    return {embedding, folds, charts, degenerate};
}

std::vector<InvariantCheck> contourInsertionChecks(const PhaseContext& ctx, const ConsistentMesh& m,
                                                   const Analysis& a) {
    InvariantCheck fb = check("no FB edge remains");
    fb.violations = a.fbEdges;
    fb.firstExample = a.firstFb;
    InvariantCheck undefined = check("every face has a defined VBO");
    undefined.violations = a.undefinedVbo;
    undefined.firstExample = a.firstUndefined;
    InvariantCheck root = check("every C vertex has |g| <= root tolerance");
    InvariantCheck valence = check("every cusp vertex has valence 4 until radial edges are added "
                                   "around it (Fig. 18d-e)");
    const double tol = ctx.parameters.getDouble("root-tolerance") * sceneScale(m);
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const MeshVertex& x = m.vertex(v);
        // The normal wiggle moves vertices off the surface; g at the
        // preimage is unchanged by it.
        if (x.label == VertexLabel::Contour && !(std::abs(x.g) <= tol))
            violate(root, "vertex " + std::to_string(v) + " g " + std::to_string(x.g));
        bool radial = false;
        for (Index w : x.cusp ? m.neighbours(v) : std::vector<Index>{})
            radial = radial || (m.edgeTag(v, w) & kRadialEdge);
        if (x.cusp && !radial && m.neighbours(v).size() != 4)
            violate(valence, "vertex " + std::to_string(v) + " valence " +
                                 std::to_string(m.neighbours(v).size()));
    }
    return {fb, undefined, root, valence};
}

std::vector<InvariantCheck> phaseChecks(const PhaseContext& ctx, const Snapshot& s,
                                        const ConsistentMesh& m, bool afterContourInsertion) {
    // The analysis publish() made of this very mesh (m is s reloaded), else
    // a fresh one; Debug builds compare the two.
    const PublishedVertices* published = publishedVertices(s);
    const std::shared_ptr<const Analysis> kept = published ? published->analysis : nullptr;
    const Analysis fresh = kept ? Analysis{} : analyse(m);
#ifdef CONTOUR_CHECK_INVARIANTS
    if (kept) {
        const Analysis b = analyse(m);
        if (b.folded != kept->folded || b.noChart != kept->noChart ||
            b.inconsistent != kept->inconsistent || b.undefinedVbo != kept->undefinedVbo ||
            b.fbEdges != kept->fbEdges || b.degenerate != kept->degenerate ||
            b.contourVertices != kept->contourVertices || b.cusps != kept->cusps ||
            b.foldedFaces != kept->foldedFaces || b.firstFb != kept->firstFb ||
            b.firstUndefined != kept->firstUndefined ||
            b.firstDegenerate != kept->firstDegenerate || b.firstFolded != kept->firstFolded)
            throw std::logic_error("consistent contours: the published analysis differs from "
                                   "the reloaded mesh's");
    }
#endif
    const Analysis& a = kept ? *kept : fresh;
    std::vector<InvariantCheck> out = commonChecks(ctx, s, m, a);
    if (afterContourInsertion)
        for (InvariantCheck& c : contourInsertionChecks(ctx, m, a))
            out.push_back(std::move(c));
    return out;
}

InvariantCheck labelsFollowG(const ConsistentMesh& m) {
    InvariantCheck labels = check("every vertex's label is sign(g) at its preimage");
    for (Index v = 0; v < m.vertexCount(); ++v)
        if (m.vertex(v).label != labelFromG(m.vertex(v).g))
            violate(labels, "vertex " + std::to_string(v));
    return labels;
}

int cuspEdgesOf(const ConsistentMesh& m, const Triangle& t) {
    int n = 0;
    for (int i = 0; i < 3; ++i)
        n += (m.edgeTag(t[i], t[(i + 1) % 3]) & kCuspEdge) != 0;
    return n;
}

std::vector<InvariantCheck> cuspEdgeChecks(const ConsistentMesh& m) {
    InvariantCheck edges = check("every cusp edge is an interior FB edge (§6.2 d, Fig. 18b)");
    for (const auto& [k, tag] : m.edgeTags()) {
        if (!(tag & kCuspEdge))
            continue;
        const auto [x, y] = ConsistentMesh::edgeFromKey(k);
        if (static_cast<int>(m.vertex(x).label) * static_cast<int>(m.vertex(y).label) >= 0 ||
            m.faceOfHalfedge(x, y) == kInvalidIndex || m.faceOfHalfedge(y, x) == kInvalidIndex)
            violate(edges, "edge " + std::to_string(x) + "-" + std::to_string(y));
    }
    InvariantCheck apart = check("no face has two cusp edges (each cusp vertex gets valence 4)");
    for (Index f = 0; f < m.faceCount(); ++f)
        if (cuspEdgesOf(m, m.face(f)) > 1)
            violate(apart, describeFace(m, f));
    return {edges, apart};
}

std::vector<InvariantCheck> cuspPhaseChecks(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, false);
    out.push_back(labelsFollowG(m));
    for (InvariantCheck& c : cuspEdgeChecks(m))
        out.push_back(std::move(c));
    return out;
}

} // namespace contour::consistent
