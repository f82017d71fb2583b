#include "contours/consistent/edits/RadialTriangles.h"

#include "contours/consistent/phases/ConsistentPhaseSupport.h"

#include <cmath>
#include <limits>

namespace contour::consistent {

double radialPlaneDistance(const Camera& camera, const MeshVertex& p, const Vec3& q) {
    const Vec3 axis = p.normal.cross(camera.toCamera(p.position));
    const double norm = axis.norm();
    if (!(norm > 0.0))
        return std::numeric_limits<double>::quiet_NaN();
    return axis.dot(q - p.position) / norm;
}

bool isRadialEdge(const ConsistentMesh& m, Index a, Index b) {
    return (m.edgeTag(a, b) & kRadialEdge) != 0;
}

bool onOtherRadialEdge(const ConsistentMesh& m, Index v, Index a, Index b) {
    for (Index w : m.neighbours(v))
        if (isRadialEdge(m, v, w) && !((v == a && w == b) || (v == b && w == a)))
            return true;
    return false;
}

bool onRadialEdge(const ConsistentMesh& m, Index v) {
    return onOtherRadialEdge(m, v, kInvalidIndex, kInvalidIndex);
}

int radialEdgesOnSide(const ConsistentMesh& m, Index p, VertexLabel side) {
    int n = 0;
    for (Index w : m.neighbours(p))
        n += isRadialEdge(m, p, w) && m.vertex(w).label == side;
    return n;
}

bool isStandardRadial(const ConsistentMesh& m, const Triangle& t) {
    for (int i = 0; i < 3; ++i) {
        const Index a = t[i], b = t[(i + 1) % 3], q = t[(i + 2) % 3];
        if (!isRadialEdge(m, a, b))
            continue;
        const Index p = m.vertex(a).label == VertexLabel::Contour ? a : b;
        if (m.vertex(p).label == VertexLabel::Contour && m.vertex(q).label == VertexLabel::Contour)
            return true;
        if (onOtherRadialEdge(m, q, a, b))
            return true;
    }
    return false;
}

StandardRadialShare standardRadialShare(const ConsistentMesh& m) {
    StandardRadialShare s;
    for (Index f = 0; f < m.faceCount(); ++f) {
        bool touches = false;
        for (Index v : m.face(f))
            touches = touches || (m.vertex(v).label == VertexLabel::Contour && !m.vertex(v).cusp);
        if (!touches)
            continue;
        ++s.contourFaces;
        s.standard += isStandardRadial(m, m.face(f));
    }
    return s;
}

RadialCoverage radialCoverage(const ConsistentMesh& m) {
    RadialCoverage c;
    for (Index p = 0; p < m.vertexCount(); ++p) {
        const MeshVertex& x = m.vertex(p);
        if (x.label != VertexLabel::Contour || m.vertexFaces(p).empty())
            continue;
        ++c.contourVertices;
        const int front = radialEdgesOnSide(m, p, VertexLabel::Front);
        const int back = radialEdgesOnSide(m, p, VertexLabel::Back);
        // Fig. 18e: a cusp gets two radial edges on its outside region.
        const long long missing = x.cusp ? std::max(0, 2 - front - back)
                                         : static_cast<long long>(front == 0) + (back == 0);
        c.missingSides += missing;
        c.complete += missing == 0;
    }
    return c;
}

InvariantCheck radialEdgeCheck(const PhaseContext& ctx, const ConsistentMesh& m) {
    InvariantCheck c = check("every radial edge joins a C vertex p to an F or B vertex r with "
                             "|h_p(r)| <= radial-root-tolerance (as a distance, §6.3 g)");
    const double tol = ctx.parameters.getDouble("radial-root-tolerance") * sceneScale(m);
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
        if (!(std::abs(d) <= tol))
            violate(c, "edge " + std::to_string(p) + "-" + std::to_string(r) + ": distance " +
                           std::to_string(d) + " to p's radial plane");
    }
    return c;
}

} // namespace contour::consistent
