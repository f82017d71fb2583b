#include "contours/consistent/predicates/FoldTest.h"

#include <cmath>
#include <limits>

namespace contour::consistent {

Vec3 projectedBarycentrics(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x) {
    // Signed areas of the sub-triangles measured along the face normal: the
    // projection along the normal does not change them.
    const Vec3 n = (b - a).cross(c - a);
    const double area = n.squaredNorm();
    if (!(area > 0.0))
        return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    return Vec3((c - b).cross(x - b).dot(n) / area, (a - c).cross(x - c).dot(n) / area,
                (b - a).cross(x - a).dot(n) / area);
}

bool insertionFolds(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x) {
    const Vec3 l = projectedBarycentrics(a, b, c, x);
    return !(l.x() > 0.0 && l.y() > 0.0 && l.z() > 0.0);
}

bool turnsOver(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& reference) {
    return !((b - a).cross(c - a).dot(reference) > 0.0);
}

Vec3 faceNormal(const ConsistentMesh& m, Index f) {
    const Triangle& t = m.face(f);
    const Vec3 &a = m.vertex(t[0]).position, &b = m.vertex(t[1]).position,
               &c = m.vertex(t[2]).position;
    return (b - a).cross(c - a);
}

bool keepsParameterOrientation(const ConsistentMesh& m, const std::array<Preimage, 3>& corners) {
    const std::optional<int> o = m.parameterOrientation(corners);
    return o && *o > 0;
}

FlipFold flipFolds(const ConsistentMesh& m, Index a, Index b) {
    FlipFold out;
    const Index f0 = m.faceOfHalfedge(a, b), f1 = m.faceOfHalfedge(b, a);
    const auto [c, d] = m.oppositeVertices(a, b);
    if (f0 == kInvalidIndex || f1 == kInvalidIndex || c == d || c == kInvalidIndex ||
        d == kInvalidIndex || m.faceOfHalfedge(c, d) != kInvalidIndex ||
        m.faceOfHalfedge(d, c) != kInvalidIndex) {
        out.impossible = true;
        return out;
    }
    const Vec3 reference = faceNormal(m, f0) + faceNormal(m, f1);
    const auto& pa = m.vertex(a);
    const auto& pb = m.vertex(b);
    const auto& pc = m.vertex(c);
    const auto& pd = m.vertex(d);
    out.space3d = turnsOver(pa.position, pd.position, pc.position, reference) ||
                  turnsOver(pb.position, pc.position, pd.position, reference);
    out.parameterSpace = !keepsParameterOrientation(m, {pa.preimage, pd.preimage, pc.preimage}) ||
                         !keepsParameterOrientation(m, {pb.preimage, pc.preimage, pd.preimage});
    return out;
}

bool edgeInterpolates(const ConsistentMesh& m, const Preimage& a, const Preimage& b) {
    for (int k = 1; k < 10; ++k)
        if (!m.interpolate(a, b, 0.1 * k))
            return false;
    return true;
}

bool splitKeepsCharts(const ConsistentMesh& m, Index a, Index b, const Preimage& p) {
    const auto [c, d] = m.oppositeVertices(a, b);
    for (Index x : {a, b, c, d})
        if (x != kInvalidIndex && !edgeInterpolates(m, p, m.vertex(x).preimage))
            return false;
    return splitKeepsParameterOrientation(m, a, b, p);
}

bool splitKeepsParameterOrientation(const ConsistentMesh& m, Index a, Index b, const Preimage& p) {
    const auto [c, d] = m.oppositeVertices(a, b);
    const Preimage &pa = m.vertex(a).preimage, &pb = m.vertex(b).preimage;
    for (const auto& [x, y, z] : {std::array{a, b, c}, std::array{b, a, d}}) {
        if (z == kInvalidIndex)
            continue;
        const Preimage &px = x == a ? pa : pb, &py = y == a ? pa : pb;
        const Preimage& pz = m.vertex(z).preimage;
        for (const auto& tri : {std::array{px, p, pz}, std::array{p, py, pz}}) {
            const std::optional<int> o = m.parameterOrientation(tri);
            if (!o || *o <= 0)
                return false;
        }
    }
    return true;
}

bool moveFolds3d(const ConsistentMesh& m, Index v, const Vec3& position) {
    for (Index f : m.vertexFaces(v)) {
        std::array<Vec3, 3> p;
        const Triangle& t = m.face(f);
        for (int i = 0; i < 3; ++i)
            p[i] = t[i] == v ? position : m.vertex(t[i]).position;
        if (turnsOver(p[0], p[1], p[2], faceNormal(m, f)))
            return true;
    }
    return false;
}

bool againstSurfaceNormals(const ConsistentMesh& m, Index f) {
    const Vec3 n = faceNormal(m, f);
    for (Index v : m.face(f))
        if (n.dot(m.vertex(v).normal) > 0.0)
            return false;
    return true;
}

} // namespace contour::consistent
