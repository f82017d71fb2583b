#include "contours/consistent/predicates/RadialTriangles.h"

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

} // namespace contour::consistent
