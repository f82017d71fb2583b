#include "contours/consistent/phases/PhaseChecks.h"

#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/RadialTriangles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour::consistent {

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

// Whether C vertex v lies within `tol` (a distance) of the contour, the
// set where g changes sign (§6.2 e): |g| <= tol, or g has the other sign at
// distance tol from v along one of its edges. At a crease of the surface the
// normal, and so g, jumps: the contour runs along the crease and bisection
// ends next to the jump with |g| large, yet on the contour.
bool contourWithin(const ConsistentMesh& m, Index v, double tol) {
    const MeshVertex& x = m.vertex(v);
    if (std::abs(x.g) <= tol)
        return true;
    for (Index w : m.neighbours(v)) {
        const MeshVertex& y = m.vertex(w);
        if (!(x.g * y.g < 0.0))
            continue;
        const double length = (y.position - x.position).norm();
        if (!(length > 0.0))
            continue;
        const std::optional<Preimage> p =
            m.segment(x.preimage, y.preimage).at(std::min(1.0, tol / length));
        if (p && x.g * m.evaluateWithoutCurvature(*p).g <= 0.0)
            return true;
    }
    return false;
}

std::vector<InvariantCheck> contourInsertionChecks(const PhaseContext& ctx, const ConsistentMesh& m,
                                                   const Analysis& a) {
    InvariantCheck fb = check("no FB edge remains");
    fb.violations = a.fbEdges;
    fb.firstExample = a.firstFb;
    InvariantCheck undefined = check("every face has a defined VBO");
    undefined.violations = a.undefinedVbo;
    undefined.firstExample = a.firstUndefined;
    InvariantCheck root = check("every C vertex lies within root tolerance of g = 0 (|g| <= "
                                "root tolerance, or g changes sign that close: a crease)");
    InvariantCheck valence = check("every cusp vertex has valence 4 until radial edges are added "
                                   "around it (Fig. 18d-e)");
    const double tol = ContourRootOptions::read(ctx.parameters).tolerance * sceneScale(m);
    for (Index v = 0; v < m.vertexCount(); ++v) {
        const MeshVertex& x = m.vertex(v);
        // The normal wiggle moves vertices off the surface; g at the
        // preimage is unchanged by it.
        if (x.label == VertexLabel::Contour && !contourWithin(m, v, tol))
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
    const std::shared_ptr<const Analysis> kept = publishedAnalysis(s);
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

InvariantCheck radialEdgeCheck(const PhaseContext& ctx, const ConsistentMesh& m) {
    InvariantCheck c = check("every radial edge joins a C vertex p to an F or B vertex r with "
                             "|h_p(r)| <= radial-root-tolerance (as a distance, §6.3 g)");
    const double tol = RadialEdgeOptions::read(ctx.parameters).rootTolerance * sceneScale(m);
    for (const auto& [k, tag] : m.edgeTags()) {
        if (!(tag & kRadialEdge))
            continue;
        const auto [a, b] = ConsistentMesh::edgeFromKey(k);
        const bool aC = m.vertex(a).label == VertexLabel::Contour;
        const bool bC = m.vertex(b).label == VertexLabel::Contour;
        if (aC == bC) {
            violate(c, "edge " + std::to_string(a) + "-" + std::to_string(b) +
                           (aC ? " joins two C vertices" : " has no C vertex"));
            continue;
        }
        const Index p = aC ? a : b, r = aC ? b : a;
        const double d = radialPlaneDistance(m.camera(), m.vertex(p), m.vertex(r).position);
        if (!(std::abs(d) <= tol)) {
            char what[96];
            std::snprintf(what, sizeof what, ": distance %.3g to p's radial plane (tolerance %.3g)",
                          d, tol);
            violate(c, "edge " + std::to_string(p) + "-" + std::to_string(r) + what);
        }
    }
    return c;
}

} // namespace contour::consistent
