// The Powell-Sabin 12-split macro-patch (Powell & Sabin 1977; Capouellez et
// al. 2023 §5.2). Derivation: docs/methods/powell-sabin-ps12.md.
//
// Split points (indices mod 3): V_i the corners, M_s the midpoint of side s
// (V_s -> V_{s+1}), Q_i = (M_{i-1} + M_i) / 2, which lies on the median from
// V_i halfway to the opposite midpoint M_{i+1}, and C the centroid.
// Sub-triangles, each counter-clockwise, corners in this order:
//   2i      (V_i, M_i, Q_i)          corner region of V_i, along side i
//   2i + 1  (V_i, Q_i, M_{i-1})      corner region of V_i, along side i - 1
//   6 + 2i  (M_i, Q_{i+1}, C)        medial triangle
//   7 + 2i  (Q_{i+1}, M_{i+1}, C)    medial triangle
// Control points per patch [b0, b1, b2, b01, b12, b20] (Ps12Patch.h).
//
// Closed form instead of a linear solve: a C1 piecewise quadratic has, at
// every split point X, one value s(X) and gradient g(X), and the ordinate at
// the middle of a sub-edge XY is s(X) + g(X).(Y - X) / 2 from either end.
// On every straight line of the split (sides, medial sides, medians) the
// spline restricts to a C1 quadratic spline, and these 1D conditions give,
// in turn, s and g at the M_s (from the corners and m_s), s and the median
// derivative at the Q_i (from the M's and V_i), and s at C. The result
// agrees with the dense solve of all interpolation and C1 conditions
// (tests/test_ps_patches.cpp).
#include "contours/powell_sabin/Ps12Patch.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace contour::powell_sabin {
namespace {

// Linear forms on the 12 local DOFs: a value, and a gradient (two rows).
using Form = Eigen::Matrix<double, 1, kPs12LocalDofs>;
using GradForm = Eigen::Matrix<double, 2, kPs12LocalDofs>;

struct Node {
    Form value;
    GradForm grad;
};

constexpr int next(int i) {
    return (i + 1) % 3;
}
constexpr int prev(int i) {
    return (i + 2) % 3;
}

// Split point indices and sub-triangle corners: Ps12Patch.h.
constexpr int kSplitPoints = kPs12SplitPoints;
constexpr int vPoint(int i) {
    return ps12CornerPoint(i);
}
constexpr int mPoint(int s) {
    return ps12MidpointPoint(s);
}
constexpr int qPoint(int i) {
    return ps12MedianPoint(i);
}
constexpr int kCPoint = kPs12CentroidPoint;
using Corners = std::array<int, 3>;
constexpr const std::array<Corners, kPs12Patches>& kSubTriangles = ps12SubTriangleCorners;

constexpr int valueDof(int i) {
    return 3 * i;
}
constexpr int guDof(int i) {
    return 3 * i + 1;
}
constexpr int gvDof(int i) {
    return 3 * i + 2;
}
constexpr int normalDof(int s) {
    return 9 + s;
}

double cross(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// The contract asks for counter-clockwise triangles; a clockwise or
// degenerate one has no well defined inward normal or split orientation.
void requireCounterClockwise(const std::array<Vec2, 3>& uv, const char* caller) {
    const double area2 = cross(uv[1] - uv[0], uv[2] - uv[0]);
    if (!uv[0].allFinite() || !uv[1].allFinite() || !uv[2].allFinite() || !std::isfinite(area2))
        throw std::invalid_argument(std::string(caller) +
                                    ": the uv triangle has non-finite corners");
    if (!(area2 > 0.0)) {
        std::ostringstream message;
        message << caller << ": the uv triangle (" << uv[0].transpose() << "), ("
                << uv[1].transpose() << "), (" << uv[2].transpose() << ") is "
                << (area2 < 0.0 ? "clockwise" : "degenerate") << " (twice its signed area is "
                << area2 << "); it must be counter-clockwise";
        throw std::invalid_argument(message.str());
    }
}

std::array<Vec2, kSplitPoints> splitPoints(const std::array<Vec2, 3>& uv) {
    std::array<Vec2, kSplitPoints> p;
    for (int i = 0; i < 3; ++i) {
        p[vPoint(i)] = uv[i];
        p[mPoint(i)] = 0.5 * (uv[i] + uv[next(i)]);
    }
    for (int i = 0; i < 3; ++i)
        p[qPoint(i)] = 0.5 * (p[mPoint(prev(i))] + p[mPoint(i)]);
    p[kCPoint] = (uv[0] + uv[1] + uv[2]) / 3.0;
    return p;
}

Form along(const GradForm& g, const Vec2& d) {
    return d.x() * g.row(0) + d.y() * g.row(1);
}

// Ordinate at the middle of sub-edge X -> Y: on the tangent plane at X.
Form edgeOrdinate(const Node& x, const Vec2& from, const Vec2& to) {
    return x.value + 0.5 * along(x.grad, to - from);
}

// A C1 quadratic spline on segment [a, b] with a knot at its middle, from
// the value and gradient at both ends: the value at the middle and the
// derivative there along e = b - a.
void midpointOfSegment(const Node& a, const Node& b, const Vec2& e, Form& value, Form& alongE) {
    value = 0.5 * (a.value + b.value) + 0.125 * along(a.grad - b.grad, e);
    alongE = 2.0 * (b.value - a.value) - 0.5 * along(a.grad + b.grad, e);
}

struct BarycentricGradients {
    std::array<Vec2, 3> g; // uv gradient of each barycentric coordinate
};

BarycentricGradients barycentricGradients(const std::array<Vec2, 3>& d) {
    const Vec2 e1 = d[1] - d[0];
    const Vec2 e2 = d[2] - d[0];
    const double det = cross(e1, e2);
    if (!(std::isfinite(det) && det != 0.0))
        throw std::invalid_argument("quadratic Bezier patch: degenerate or non-finite domain");
    BarycentricGradients b;
    b.g[1] = Vec2(e2.y(), -e2.x()) / det;
    b.g[2] = Vec2(-e1.y(), e1.x()) / det;
    b.g[0] = -(b.g[1] + b.g[2]);
    return b;
}

} // namespace

std::array<std::array<Vec2, 3>, kPs12Patches> ps12SubTriangles(const std::array<Vec2, 3>& uv) {
    requireCounterClockwise(uv, "ps12SubTriangles");
    const std::array<Vec2, kSplitPoints> p = splitPoints(uv);
    std::array<std::array<Vec2, 3>, kPs12Patches> out;
    for (int l = 0; l < kPs12Patches; ++l)
        for (int c = 0; c < 3; ++c)
            out[l][c] = p[kSubTriangles[l][c]];
    return out;
}

Ps12Matrix ps12BezierMatrix(const std::array<Vec2, 3>& uv) {
    requireCounterClockwise(uv, "ps12BezierMatrix");
    // The matrix depends on differences only: relative to V_0 they keep
    // their precision for a small triangle far from the origin.
    const std::array<Vec2, 3> local = {Vec2::Zero().eval(), (uv[1] - uv[0]).eval(),
                                       (uv[2] - uv[0]).eval()};
    const std::array<Vec2, kSplitPoints> p = splitPoints(local);
    std::array<Node, 6> node; // V and M

    for (int i = 0; i < 3; ++i) {
        Node& v = node[vPoint(i)];
        v.value.setZero();
        v.grad.setZero();
        v.value(valueDof(i)) = 1.0;
        v.grad(0, guDof(i)) = 1.0;
        v.grad(1, gvDof(i)) = 1.0;
    }
    // M_s: value and tangential derivative from the side's 1D spline, normal
    // derivative the DOF m_s (inward unit normal = left normal, CCW).
    for (int s = 0; s < 3; ++s) {
        const Vec2 e = local[next(s)] - local[s];
        const Vec2 normal = Vec2(-e.y(), e.x()) / e.norm();
        Node& m = node[mPoint(s)];
        Form alongE;
        midpointOfSegment(node[vPoint(s)], node[vPoint(next(s))], e, m.value, alongE);
        Form dn = Form::Zero();
        dn(normalDof(s)) = 1.0;
        m.grad = (e / e.squaredNorm()) * alongE + normal * dn;
    }
    // Q_i: value from the medial side M_{i-1} M_i, whose middle it is, and
    // the derivative along the median d from the half V_i Q_i (Q_i - V_i =
    // d / 2). The only sub-edge that takes its ordinate from Q_i is Q_i C
    // (C - Q_i = d / 6), so the gradient at Q_i is never formed: its solve
    // from the two nearly parallel directions of a needle is ill-conditioned.
    std::array<Form, 3> qValue;
    std::array<Form, 3> qToC; // ordinate at the middle of Q_i C
    for (int i = 0; i < 3; ++i) {
        const Vec2 w = p[mPoint(i)] - p[mPoint(prev(i))];
        const Vec2 d = p[mPoint(next(i))] - p[vPoint(i)];
        Form alongW;
        midpointOfSegment(node[mPoint(prev(i))], node[mPoint(i)], w, qValue[i], alongW);
        const Node& v = node[vPoint(i)];
        const Form alongD = 4.0 * (qValue[i] - v.value) - along(v.grad, d);
        qToC[i] = qValue[i] + alongD / 12.0;
    }
    // C splits Q_i M_{i+1} in the ratio 1 : 2 (at 1/2 and 2/3 of the median);
    // C1 along the median puts s(C) at (2 b(Q_i C) + b(C M_{i+1})) / 3. The
    // three medians agree; their mean keeps the formula symmetric.
    Form cValue = Form::Zero();
    for (int i = 0; i < 3; ++i) {
        const Form bm = edgeOrdinate(node[mPoint(next(i))], p[mPoint(next(i))], p[kCPoint]);
        cValue += (2.0 * qToC[i] + bm) / 9.0;
    }

    auto pointOrdinate = [&](int a) -> Form {
        if (a == kCPoint)
            return cValue;
        if (a >= qPoint(0))
            return qValue[a - qPoint(0)];
        return node[a].value;
    };
    // Each sub-edge takes its ordinate from its lower split point: V or M
    // (with a gradient), or Q for Q C.
    auto edgeOrdinateOf = [&](int a, int b) -> Form {
        const int lo = std::min(a, b);
        const int hi = std::max(a, b);
        if (lo >= qPoint(0))
            return qToC[lo - qPoint(0)];
        return edgeOrdinate(node[lo], p[lo], p[hi]);
    };
    Ps12Matrix m;
    for (int l = 0; l < kPs12Patches; ++l) {
        const Corners& t = kSubTriangles[l];
        for (int c = 0; c < 3; ++c) {
            m.row(6 * l + c) = pointOrdinate(t[c]);
            m.row(6 * l + 3 + c) = edgeOrdinateOf(t[c], t[next(c)]);
        }
    }
    if (!m.allFinite())
        throw std::invalid_argument("ps12BezierMatrix: the uv triangle is too thin for finite "
                                    "Bezier coefficients");
    return m;
}

template <typename T> T evaluate(const QuadraticBezier<T>& patch, const Vec3& w) {
    const std::array<T, 6>& b = patch.control;
    return T(w[0] * w[0] * b[0] + w[1] * w[1] * b[1] + w[2] * w[2] * b[2] +
             2.0 * w[0] * w[1] * b[3] + 2.0 * w[1] * w[2] * b[4] + 2.0 * w[2] * w[0] * b[5]);
}

template <typename T>
void uvDerivatives(const QuadraticBezier<T>& patch, const Vec3& w, T& du, T& dv) {
    const BarycentricGradients bg = barycentricGradients(patch.domain);
    const std::array<T, 6>& b = patch.control;
    // Derivatives along the barycentric coordinates, then the chain rule.
    const T f0 = 2.0 * (w[0] * b[0] + w[1] * b[3] + w[2] * b[5]);
    const T f1 = 2.0 * (w[0] * b[3] + w[1] * b[1] + w[2] * b[4]);
    const T f2 = 2.0 * (w[0] * b[5] + w[1] * b[4] + w[2] * b[2]);
    du = T(f0 * bg.g[0].x() + f1 * bg.g[1].x() + f2 * bg.g[2].x());
    dv = T(f0 * bg.g[0].y() + f1 * bg.g[1].y() + f2 * bg.g[2].y());
}

template <typename T>
void uvSecondDerivatives(const QuadraticBezier<T>& patch, T& duu, T& duv, T& dvv) {
    const BarycentricGradients bg = barycentricGradients(patch.domain);
    const std::array<T, 6>& b = patch.control;
    // The patch is sum_jk B_jk l_j l_k with B = [[b0, b01, b20], [b01, b1,
    // b12], [b20, b12, b2]]; its Hessian in uv is 2 sum_jk B_jk grad l_j grad l_k^T.
    auto second = [&](int p, int q) {
        const std::array<Vec2, 3>& g = bg.g;
        auto pair = [&](int j, int k) {
            return 2.0 * (g[j][p] * g[k][q] + g[k][p] * g[j][q]);
        };
        return T(2.0 * g[0][p] * g[0][q] * b[0] + 2.0 * g[1][p] * g[1][q] * b[1] +
                 2.0 * g[2][p] * g[2][q] * b[2] + pair(0, 1) * b[3] + pair(1, 2) * b[4] +
                 pair(2, 0) * b[5]);
    };
    duu = second(0, 0);
    duv = second(0, 1);
    dvv = second(1, 1);
}

Vec3 barycentricOf(const std::array<Vec2, 3>& domain, const Vec2& uv) {
    const BarycentricGradients bg = barycentricGradients(domain);
    const Vec2 r = uv - domain[0];
    const double l1 = bg.g[1].dot(r);
    const double l2 = bg.g[2].dot(r);
    return Vec3(1.0 - l1 - l2, l1, l2);
}

template double evaluate<double>(const QuadraticBezier<double>&, const Vec3&);
template Vec3 evaluate<Vec3>(const QuadraticBezier<Vec3>&, const Vec3&);
template void uvDerivatives<double>(const QuadraticBezier<double>&, const Vec3&, double&, double&);
template void uvDerivatives<Vec3>(const QuadraticBezier<Vec3>&, const Vec3&, Vec3&, Vec3&);
template void uvSecondDerivatives<double>(const QuadraticBezier<double>&, double&, double&,
                                          double&);
template void uvSecondDerivatives<Vec3>(const QuadraticBezier<Vec3>&, Vec3&, Vec3&, Vec3&);

} // namespace contour::powell_sabin
