// Consistent contours (Bénard, Hertzmann & Kass 2014): a per-view triangle
// mesh of the smooth surface whose mesh contour generator should be
// topologically equivalent to the smooth one. This file holds the phases
// implemented so far: initialization (§6.1, Fig. 15a-c) and contour vertex
// insertion (§6.2 e, Fig. 15d-f), then chaining of the contour generator
// (edges between an F-VBO and a B-VBO face). Cusp detection (§6.2 d),
// radialization (§6.3) and optimization (§6.4) are not implemented yet.
#include "camera/Facing.h"
#include "contours/EdgePolylines.h"
#include "contours/Methods.h"
#include "contours/SurfacePhase.h"
#include "contours/consistent/ConsistentMesh.h"
#include "contours/consistent/VertexBasedOrientation.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"
#include "surface/SurfaceTessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace contour {

namespace {

using namespace consistent;

constexpr const char* kStatusNote =
    "consistent contours, partial implementation: of the ten sub-phases of issue 4 only "
    "initialization (with the sign-crossing search) and contour vertex insertion (with "
    "snapping to shiftable vertices) are implemented; cusp detection and insertion, radial "
    "edge insertion, edge flipping, radial edge extension, optimization flips, vertex "
    "wiggling, edge splitting and the normal wiggle are NOT implemented yet, so inconsistent "
    "faces remain (radialization, §6.3, is what makes them consistent)";

// ---------------------------------------------------------------- surface

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

// The snapshot is the only state passed between phases: the editable mesh
// is rebuilt from the published mesh and fields.
ConsistentMesh reload(const PhaseContext& ctx, const Snapshot& s) {
    ConsistentMesh m(surfaceFor(ctx, s), ctx.camera, ctx.parameters.getDouble("chart-tolerance"));
    const auto* face = s.field(fields::kPreimageFace);
    const auto* uv = s.field(fields::kPreimageUv);
    const auto* label = s.field(fields::kLabel);
    const auto* prov = s.field(fields::kProvenance);
    const auto* vphase = s.field(fields::kVertexChangedByPhase);
    const auto* fphase = s.field(fields::kChangedByPhase);
    if (!face || !uv || !label || !prov || !vphase || !fphase)
        throw std::logic_error("consistent contours: the previous phase published no mesh");
    const TriangleMesh& mesh = *s.mesh;
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3& p = (*uv->vectors())[v];
        MeshVertex mv = m.evaluate({(*face->labels())[v], p.x(), p.y()});
        mv.label = static_cast<VertexLabel>((*label->labels())[v]);
        mv.provenance = static_cast<Provenance>((*prov->labels())[v]);
        mv.phase = (*vphase->labels())[v];
        m.addVertex(mv);
    }
    for (Index f = 0; f < mesh.faceCount(); ++f)
        m.addFace(mesh.triangle(f), (*fphase->labels())[f]);
    return m;
}

// "face f: v (face u v provenance phase), ..." for the inspector.
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

struct Analysis {
    std::vector<int> facing, vbo, consistent;
    long long inconsistent = 0, undefinedVbo = 0, fbEdges = 0, degenerate = 0, contourVertices = 0;
    std::string firstFb, firstUndefined, firstDegenerate;
};

Analysis analyse(const ConsistentMesh& m) {
    Analysis a;
    const Index nf = m.faceCount();
    a.facing.resize(nf);
    a.vbo.resize(nf);
    a.consistent.resize(nf);
    for (Index f = 0; f < nf; ++f) {
        const Triangle& t = m.face(f);
        const Facing facing = triangleFacing(m.camera(), m.vertex(t[0]).position,
                                             m.vertex(t[1]).position, m.vertex(t[2]).position);
        const Vbo vbo = vertexBasedOrientation(m.vertex(t[0]).label, m.vertex(t[1]).label,
                                               m.vertex(t[2]).label);
        a.facing[f] = static_cast<int>(facing);
        a.vbo[f] = static_cast<int>(vbo);
        a.consistent[f] = isConsistent(vbo, facing) ? 1 : 0;
        a.inconsistent += a.consistent[f] == 0;
        if (vbo == Vbo::Undefined && a.undefinedVbo++ == 0)
            a.firstUndefined = "face " + std::to_string(f);
    }
    for (const auto& [u, v] : m.edges()) {
        const VertexLabel lu = m.vertex(u).label, lv = m.vertex(v).label;
        if (static_cast<int>(lu) * static_cast<int>(lv) < 0 && a.fbEdges++ == 0)
            a.firstFb = "edge " + std::to_string(u) + "-" + std::to_string(v);
        const Index f0 = m.faceOfHalfedge(u, v), f1 = m.faceOfHalfedge(v, u);
        if (f0 != kInvalidIndex && f1 != kInvalidIndex &&
            isDegenerateEdge(lu, lv, static_cast<Vbo>(a.vbo[f0]), static_cast<Vbo>(a.vbo[f1])) &&
            a.degenerate++ == 0)
            a.firstDegenerate = "edge " + std::to_string(u) + "-" + std::to_string(v) +
                                " between " + describeFace(m, f0) + " and " + describeFace(m, f1);
    }
    for (Index v = 0; v < m.vertexCount(); ++v)
        a.contourVertices += m.vertex(v).label == VertexLabel::Contour;
    return a;
}

void publish(Snapshot& s, const ConsistentMesh& m) {
    s.mesh = m.toTriangleMesh();
    const Index nv = m.vertexCount();
    std::vector<int> face(nv), label(nv), prov(nv), vphase(nv);
    std::vector<Vec3> uv(nv), normal(nv);
    std::vector<double> g(nv), kr(nv);
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
    }
    std::vector<int> fphase(m.faceCount());
    for (Index f = 0; f < m.faceCount(); ++f)
        fphase[f] = m.facePhase(f);
    Analysis a = analyse(m);
    using L = FieldLocation;
    s.fields.erase(fields::kDomainFace);
    s.setField(fields::kPreimageFace,
               {L::Vertex, std::move(face), "domain face of the vertex's preimage"});
    s.setField(fields::kPreimageUv, {L::Vertex, std::move(uv), "(u, v, 0) in that domain face"});
    s.setField(fields::kVertexNormal, {L::Vertex, std::move(normal), "limit normal n(u)"});
    s.setField(fields::kG, {L::Vertex, std::move(g), "g(u) = (c - f(u)) · n(u), > 0 front"});
    s.setField(fields::kRadialCurvature,
               {L::Vertex, std::move(kr), "radial curvature at the preimage (< 0 exterior)"});
    s.setField(fields::kLabel, {L::Vertex, std::move(label), "R_S label: +1 F, -1 B, 0 C"});
    s.setField(fields::kProvenance,
               {L::Vertex, std::move(prov), "0 initial, 1 inserted, 2 shifted"});
    s.setField(fields::kVertexChangedByPhase,
               {L::Vertex, std::move(vphase), "phase that created or last changed the vertex"});
    s.setField(fields::kChangedByPhase,
               {L::Face, std::move(fphase), "phase that created or last changed the face"});
    s.setField(fields::kFacing,
               {L::Face, std::move(a.facing), "+1 front, -1 back, 0 edge-on (exact)"});
    s.setField(fields::kVbo, {L::Face, std::move(a.vbo),
                              "VBO (Definition 1): +1 F, -1 B, 0 "
                              "undefined"});
    s.setField(fields::kConsistent, {L::Face, std::move(a.consistent),
                                     "1 contour-consistent (Definition 2), 0 inconsistent"});
    s.setCounter("faces", m.faceCount());
    s.setCounter("vertices", nv);
    s.setCounter("inconsistent faces", static_cast<double>(a.inconsistent));
    s.setCounter("undefined VBOs", static_cast<double>(a.undefinedVbo));
    s.setCounter("FB edges left", static_cast<double>(a.fbEdges));
    s.setCounter("degenerate CC edges", static_cast<double>(a.degenerate));
    s.setCounter("contour vertices", static_cast<double>(a.contourVertices));
    s.notes.push_back(kStatusNote);
}

// ------------------------------------------------------------ invariants

InvariantCheck check(const std::string& name) {
    return {name, 0, ""};
}

void violate(InvariantCheck& c, const std::string& example) {
    if (c.violations++ == 0)
        c.firstExample = example;
}

// Notes §6.1 items 1 and 2 (embedding pos = f(u), no folds in parameter
// space) and 4 (no degenerate CC edge).
std::vector<InvariantCheck> commonChecks(const PhaseContext& ctx, const Snapshot& s,
                                         const ConsistentMesh& m, const Analysis& a) {
    InvariantCheck embedding = check("every vertex lies at f(u) of its preimage");
    InvariantCheck folds = check("every face keeps the domain's orientation in parameter space");
    InvariantCheck charts = check("every face's corners have a common chart (appendix B)");
    InvariantCheck degenerate = check("no degenerate CC edge (Definition 3)");
    const double tol = ctx.parameters.getDouble("embedding-tolerance") * sceneScale(m);
    const TriangleMesh& mesh = *s.mesh;
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (!((mesh.position(v) - m.surface().evaluate(m.vertex(v).preimage).position).norm() <=
              tol))
            violate(embedding, "vertex " + std::to_string(v));
    for (Index f = 0; f < m.faceCount(); ++f) {
        const std::optional<int> o = m.parameterOrientation(f);
        if (!o)
            violate(charts, "face " + std::to_string(f));
        else if (*o <= 0)
            violate(folds, describeFace(m, f));
    }
    degenerate.violations = a.degenerate;
    degenerate.firstExample = a.firstDegenerate;
    return {embedding, folds, charts, degenerate};
}

std::vector<InvariantCheck> checkInitialization(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    const Analysis a = analyse(m);
    std::vector<InvariantCheck> out = commonChecks(ctx, s, m, a);
    InvariantCheck labels = check("every vertex's label is sign(g) at its preimage");
    for (Index v = 0; v < m.vertexCount(); ++v)
        if (m.vertex(v).label != labelFromG(m.vertex(v).g))
            violate(labels, "vertex " + std::to_string(v));
    out.push_back(labels);
    return out;
}

// Notes §6.1 item 3 (after contour insertion).
std::vector<InvariantCheck> checkContourInsertion(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    const Analysis a = analyse(m);
    std::vector<InvariantCheck> out = commonChecks(ctx, s, m, a);
    InvariantCheck fb = check("no FB edge remains");
    fb.violations = a.fbEdges;
    fb.firstExample = a.firstFb;
    InvariantCheck undefined = check("every face has a defined VBO");
    undefined.violations = a.undefinedVbo;
    undefined.firstExample = a.firstUndefined;
    InvariantCheck root = check("every C vertex has |g| <= root tolerance");
    const double tol = ctx.parameters.getDouble("root-tolerance") * sceneScale(m);
    for (Index v = 0; v < m.vertexCount(); ++v)
        if (m.vertex(v).label == VertexLabel::Contour && !(std::abs(m.vertex(v).g) <= tol))
            violate(root, "vertex " + std::to_string(v));
    out.push_back(fb);
    out.push_back(undefined);
    out.push_back(root);
    return out;
}

// --------------------------------------------------------- initialization

// §6.1 (Fig. 15a-c, notes §2.1): the domain (for Catmull-Clark the cage
// subdivided once, all quads) tessellated at level 1, each quad split into
// two triangles, vertices at their limit positions and labelled by sign(g);
// then the sign-crossing search on FF and BB edges.
void runInitialization(const PhaseContext& ctx, Snapshot& s) {
    const std::shared_ptr<const SmoothSurface> surface = surfaceFor(ctx, s);
    ConsistentMesh m(surface, ctx.camera, ctx.parameters.getDouble("chart-tolerance"));
    const int phase = s.phaseIndex;
    // Step 1-3: subdivide once (the Catmull-Clark domain already is), split
    // quads, move to the limit (SurfaceTessellation at level 1).
    const SurfaceTessellation t = tessellate(*surface, 1);
    for (const Preimage& p : t.preimages) {
        MeshVertex v = m.evaluate(p);
        v.phase = phase;
        m.addVertex(v);
    }
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
    for (size_t i = 0; i < edges.size(); ++i) {
        if (i % 4096 == 0)
            ctx.checkCancelled();
        const auto [a, b] = edges[i];
        const VertexLabel la = m.vertex(a).label;
        if (la == VertexLabel::Contour || la != m.vertex(b).label)
            continue;
        for (int k = 1; k <= samples; ++k) {
            const double tk = static_cast<double>(k) / (samples + 1);
            const std::optional<Preimage> p =
                m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, tk);
            if (!p) {
                ++cancelled;
                break;
            }
            MeshVertex v = m.evaluate(*p);
            if (v.label == la)
                continue;
            v.provenance = Provenance::Inserted;
            m.splitEdge(a, b, v, phase);
            ++splits;
            break;
        }
    }
    publish(s, m);
    s.setCounter("sign-crossing splits", static_cast<double>(splits));
    s.setCounter("cancelled interpolations", static_cast<double>(cancelled));
    if (cancelled > 0)
        s.notes.push_back(std::to_string(cancelled) +
                          " edges were not searched for sign crossings: their endpoints' "
                          "preimages have no common chart (appendix B)");
}

// ------------------------------------------------------ contour insertion

// Appendix C (notes §2.5): may vertex `v` move to preimage `p` and become a
// C vertex? Checks rules 1-4: no fold in parameter space, no CCC triangle,
// no "X" (at most two zero crossings on the one-ring's outer boundary), and
// interpolation to every neighbour still possible; and, beyond appendix C,
// that the shift creates no degenerate CC edge (notes §6.1 item 4).
bool shiftable(const ConsistentMesh& m, Index v, const Preimage& p) {
    if (m.vertex(v).label == VertexLabel::Contour)
        return false;
    int crossings = 0;
    std::set<Index> ringContour;
    for (Index f : m.vertexFaces(v)) {
        Triangle t = m.face(f);
        while (t[0] != v)
            std::rotate(t.begin(), t.begin() + 1, t.end());
        const VertexLabel l1 = m.vertex(t[1]).label, l2 = m.vertex(t[2]).label;
        // Rule 2: no CCC triangle once v is C.
        if (l1 == VertexLabel::Contour && l2 == VertexLabel::Contour)
            return false;
        // Notes §6.1 item 4 (Definition 3): no degenerate CC edge, ever. Once
        // v is C, edge v-t1 with t1 C is degenerate when the vertices
        // opposite it on both sides carry the same label (an isolated F or B
        // vertex inside a tiny loop would otherwise be snapped flat).
        if (l1 == VertexLabel::Contour) {
            const Index g = m.faceOfHalfedge(t[1], v);
            if (g != kInvalidIndex) {
                const Triangle& o = m.face(g);
                for (Index b : o)
                    if (b != v && b != t[1] && m.vertex(b).label == l2)
                        return false;
            }
        }
        // Rule 3: zero crossings on the outer boundary edge t1-t2.
        crossings += static_cast<int>(l1) * static_cast<int>(l2) < 0;
        for (Index w : {t[1], t[2]})
            if (m.vertex(w).label == VertexLabel::Contour)
                ringContour.insert(w);
        // Rule 4: the edges to the neighbours can still be interpolated.
        for (Index w : {t[1], t[2]})
            if (!m.interpolate(p, m.vertex(w).preimage, 0.5))
                return false;
        // Rule 1: no fold in parameter space.
        const std::optional<int> o =
            m.parameterOrientation({p, m.vertex(t[1]).preimage, m.vertex(t[2]).preimage});
        if (!o || *o <= 0)
            return false;
    }
    return crossings + static_cast<int>(ringContour.size()) <= 2;
}

// §6.2 (e), notes §2.2: bisection of g along every FB edge, snap to a
// shiftable endpoint within `snap-fraction` of the edge length, otherwise
// insert a C vertex splitting both faces (Fig. 16c); repeat until no FB edge
// remains. Cusp edges are not treated separately: cusp detection (§6.2 d)
// is not implemented.
void runContourInsertion(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const double tol = ctx.parameters.getDouble("root-tolerance") * sceneScale(m);
    const int maxIterations = ctx.parameters.getInt("root-max-iterations");
    const double snap = ctx.parameters.getDouble("snap-fraction");
    long long inserted = 0, snapped = 0, cancelled = 0, unconverged = 0;
    for (bool progress = true; progress;) {
        progress = false;
        for (const auto& [e0, e1] : m.edges()) {
            ctx.checkCancelled();
            if (static_cast<int>(m.vertex(e0).label) * static_cast<int>(m.vertex(e1).label) >= 0 ||
                (m.faceOfHalfedge(e0, e1) == kInvalidIndex &&
                 m.faceOfHalfedge(e1, e0) == kInvalidIndex))
                continue;
            // x is the F end, y the B end: g(x) > 0 > g(y) along the edge.
            const Index x = m.vertex(e0).label == VertexLabel::Front ? e0 : e1;
            const Index y = x == e0 ? e1 : e0;
            const Preimage px = m.vertex(x).preimage, py = m.vertex(y).preimage;
            double lo = 0.0, hi = 1.0;
            std::optional<MeshVertex> root;
            bool failed = false, converged = false;
            for (int it = 0; it < maxIterations; ++it) {
                const double mid = 0.5 * (lo + hi);
                const std::optional<Preimage> p = m.interpolate(px, py, mid);
                if (!p) {
                    failed = true;
                    break;
                }
                MeshVertex v = m.evaluate(*p);
                if (!root || std::abs(v.g) < std::abs(root->g))
                    root = v;
                if (std::abs(v.g) <= tol) {
                    converged = true;
                    break;
                }
                (v.g > 0.0 ? lo : hi) = mid;
            }
            if (failed || !root) {
                ++cancelled; // appendix B: no common chart, insertion cancelled
                continue;
            }
            unconverged += !converged;
            progress = true;
            root->label = VertexLabel::Contour;
            root->provenance = Provenance::Inserted;
            // Snap rule: shift an endpoint onto the root when it is within
            // snap-fraction of the edge length and shiftable (appendix C).
            const double length = (m.vertex(x).position - m.vertex(y).position).norm();
            const double dx = (root->position - m.vertex(x).position).norm();
            const double dy = (root->position - m.vertex(y).position).norm();
            bool done = false;
            for (Index w : dx <= dy ? std::array{x, y} : std::array{y, x}) {
                const double d = w == x ? dx : dy;
                if (d < snap * length && shiftable(m, w, root->preimage)) {
                    m.shiftVertex(w, root->preimage, VertexLabel::Contour, phase);
                    ++snapped;
                    done = true;
                    break;
                }
            }
            if (!done) {
                m.splitEdge(x, y, *root, phase);
                ++inserted;
            }
        }
    }
    publish(s, m);
    s.setCounter("inserted contour vertices", static_cast<double>(inserted));
    s.setCounter("snapped vertices", static_cast<double>(snapped));
    s.setCounter("cancelled insertions", static_cast<double>(cancelled));
    s.setCounter("unconverged roots", static_cast<double>(unconverged));
    if (unconverged > 0)
        s.notes.push_back(std::to_string(unconverged) +
                          " roots did not reach |g| <= root-tolerance within root-max-iterations "
                          "bisection steps (g is not continuous along the edge there); their C "
                          "vertices are counted by the |g| post-condition");
    if (cancelled > 0)
        s.notes.push_back(std::to_string(cancelled) +
                          " FB edges kept: their endpoints' preimages have no common chart, "
                          "so the insertion was cancelled (appendix B)");
}

// --------------------------------------------------------------- chaining

// The mesh's contour generator on a consistent mesh: the edges between an
// F-VBO face and a B-VBO face (§4), chained through vertices of degree 2.
void runChaining(const PhaseContext& ctx, Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& vbo = *s.field(fields::kVbo)->labels();
    const std::vector<int>& facing = *s.field(fields::kFacing)->labels();
    std::vector<Index> generator;
    long long meshContourEdges = 0;
    std::vector<int> label(mesh.edgeCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const Index h = mesh.edgeHalfedge(e);
        if (mesh.isBoundary(h))
            continue;
        const Index f0 = TriangleMesh::face(h), f1 = TriangleMesh::face(mesh.opposite(h));
        meshContourEdges += (facing[f0] > 0) != (facing[f1] > 0);
        if (vbo[f0] * vbo[f1] < 0) {
            generator.push_back(e);
            label[e] = 1;
        }
    }
    s.setField(fields::kContourEdge,
               {FieldLocation::Edge, std::move(label),
                "1 on the contour generator (an F-VBO face next to a B-VBO face)"});
    s.setCounter("contour generator edges", static_cast<double>(generator.size()));
    s.setCounter("mesh contour edges", static_cast<double>(meshContourEdges));
    publishCurves(ctx, s, edgePolylines(mesh, generator, CurveType::Contour));
    s.notes.push_back(kStatusNote);
}

// Notes §6.1 item 10: contour-generator vertices have degree 2 except on
// boundaries, and every contour-generator edge is a CC edge.
std::vector<InvariantCheck> checkChaining(const PhaseContext&, const Snapshot& s) {
    const TriangleMesh& mesh = *s.mesh;
    const std::vector<int>& edgeLabel = *s.field(fields::kContourEdge)->labels();
    const std::vector<int>& vertexLabel = *s.field(fields::kLabel)->labels();
    InvariantCheck degree = check("every contour-generator vertex has degree 2 (no bifurcation)");
    InvariantCheck cc = check("every contour-generator edge joins two C vertices");
    std::vector<int> count(mesh.vertexCount(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (!edgeLabel[e])
            continue;
        const Index h = mesh.edgeHalfedge(e);
        ++count[mesh.from(h)];
        ++count[mesh.to(h)];
        if ((vertexLabel[mesh.from(h)] != 0 || vertexLabel[mesh.to(h)] != 0))
            violate(cc, "edge " + std::to_string(e));
    }
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (count[v] != 0 && count[v] != 2 && !mesh.isBoundaryVertex(v))
            violate(degree, "vertex " + std::to_string(v));
    return {degree, cc};
}

} // namespace

Method makeConsistentContourMethod() {
    Method m;
    m.name = "consistent";
    m.label = "Consistent contours (Bénard et al. 2014)";
    m.description =
        "A per-view triangulation of the smooth surface whose contour generator is meant to be "
        "topologically equivalent to the smooth one (Bénard, Hertzmann & Kass 2014). "
        "Implemented: initialization with the sign-crossing search (§6.1) and contour vertex "
        "insertion (§6.2 e), then chaining of the edges between F-VBO and B-VBO faces. NOT yet "
        "implemented: cusp detection (§6.2 d), radialization (§6.3) and optimization (§6.4), so "
        "inconsistent faces remain.";
    m.parameters = {
        {"surface",
         "Smooth surface",
         "The smooth surface whose domain is triangulated (§6.1): Catmull-Clark (the cage "
         "subdivided once), Loop or vertex-normal patches. auto: Catmull-Clark, or Loop for an "
         "all-triangle cage.",
         ParameterType::Choice,
         std::string("auto"),
         0,
         0,
         {"auto", toString(SurfaceKind::CatmullClark), toString(SurfaceKind::Loop),
          toString(SurfaceKind::VertexNormalPatches)}},
        {"crossing-samples",
         "Sign-crossing samples",
         "Samples of sign(g) per FF or BB edge in the sign-crossing search (§6.1; paper: 10).",
         ParameterType::Int,
         10,
         1,
         1000,
         {}},
        {"root-tolerance",
         "Root tolerance",
         "Bisection on FB edges stops when |g| is below this times the bounding-box diagonal "
         "(§6.2 e; the paper does not give its tolerance). Also the bound checked at C "
         "vertices.",
         ParameterType::Double,
         1e-10,
         1e-16,
         1e-2,
         {}},
        {"root-max-iterations",
         "Root iterations",
         "Maximum bisection steps per FB edge (§6.2 e; unspecified in the paper).",
         ParameterType::Int,
         100,
         1,
         1000,
         {}},
        {"snap-fraction",
         "Snap fraction",
         "A root closer than this fraction of the edge length to an endpoint shifts that "
         "endpoint onto the root when it is shiftable (appendix C) instead of inserting a "
         "vertex (§6.2 e; paper: 0.2).",
         ParameterType::Double,
         0.2,
         0.0,
         0.5,
         {}},
        {"chart-tolerance",
         "Chart tolerance",
         "How close (in domain parameters) a preimage must be to a domain edge to also belong "
         "to the neighbouring face, and how far outside a face an interpolated preimage may "
         "land (appendix B; not in the paper).",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-3,
         {}},
        {"embedding-tolerance",
         "Embedding tolerance",
         "Post-condition pos = f(u) (notes §6.1 item 2) holds within this times the "
         "bounding-box diagonal.",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-2,
         {}},
        {"include-boundaries",
         "Include boundaries",
         "Also chain the mesh's boundary edges as curves.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}},
    };
    m.phases = {
        {"initialization",
         "§6.1 (Fig. 15a-c): the smooth surface's domain (Catmull-Clark: cage subdivided once) "
         "triangulated, vertices at the limit and labelled by sign(g); sign-crossing search "
         "on FF and BB edges with crossing-samples samples, splitting at the first crossing.",
         runInitialization, checkInitialization},
        {"contour-insertion",
         "§6.2 e (Fig. 15d-f): bisection root of g on every FB edge; shift a shiftable endpoint "
         "within snap-fraction of the edge length onto it (appendix C), otherwise insert a C "
         "vertex splitting both faces; until no FB edge remains. Cusp detection is not "
         "implemented.",
         runContourInsertion, checkContourInsertion},
        {"chaining",
         "The contour generator (edges between an F-VBO and a B-VBO face) chained into "
         "polylines, and the boundaries.",
         runChaining, checkChaining},
    };
    return m;
}

} // namespace contour
