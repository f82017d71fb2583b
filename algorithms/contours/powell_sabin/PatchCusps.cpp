// Interior and boundary cusps of a quadratic patch's contour (Capouellez et
// al. 2023 §4.2, eq. 5-6), computed over the patch's reference triangle so
// that the conics handed to the pencil solver are well scaled.
#include "contours/powell_sabin/PatchCusps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace contour::powell_sabin {
namespace {

// A linear function a0 + a1 s1 + a2 s2 (scalar or vector valued).
template <typename T> using Linear = std::array<T, 3>;
// A quadratic in monomial order [1, s1, s2, s1^2, s1 s2, s2^2].
template <typename T> using Quadratic = std::array<T, 6>;

template <typename T> Quadratic<T> times(const Linear<T>& a, const Linear<double>& b) {
    return {T(a[0] * b[0]), T(a[0] * b[1] + a[1] * b[0]), T(a[0] * b[2] + a[2] * b[0]),
            T(a[1] * b[1]), T(a[1] * b[2] + a[2] * b[1]), T(a[2] * b[2])};
}

Quadratic<Vec3> cross(const Linear<Vec3>& a, const Linear<Vec3>& b) {
    return {
        a[0].cross(b[0]), a[0].cross(b[1]) + a[1].cross(b[0]), a[0].cross(b[2]) + a[2].cross(b[0]),
        a[1].cross(b[1]), a[1].cross(b[2]) + a[2].cross(b[1]), a[2].cross(b[2])};
}

template <typename T> T at(const Quadratic<T>& q, const Vec2& s) {
    return T(q[0] + q[1] * s.x() + q[2] * s.y() + q[3] * s.x() * s.x() + q[4] * s.x() * s.y() +
             q[5] * s.y() * s.y());
}

template <typename T> T at(const Linear<T>& l, const Vec2& s) {
    return T(l[0] + l[1] * s.x() + l[2] * s.y());
}

// Partial derivatives of a quadratic, as linear functions.
template <typename T> Linear<T> d1(const Quadratic<T>& q) {
    return {q[1], T(2.0 * q[3]), q[4]};
}
template <typename T> Linear<T> d2(const Quadratic<T>& q) {
    return {q[2], q[4], T(2.0 * q[5])};
}

Eigen::Matrix3d conicOf(const Quadratic<double>& q) {
    return conicMatrix(q[3], q[4], q[5], q[1], q[2], q[0]);
}

void requireFinite(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const char* who) {
    bool ok = tau.allFinite();
    for (const Vec3& c : patch.control)
        ok = ok && c.allFinite();
    for (const Vec2& d : patch.domain)
        ok = ok && d.allFinite();
    if (!ok)
        throw std::invalid_argument(std::string(who) + ": the patch or tau is not finite");
}

} // namespace

void viewFrame(const Vec3& tau, Vec3& tau1, Vec3& tau2) {
    const double norm = tau.norm();
    if (!tau.allFinite() || norm == 0.0)
        throw std::invalid_argument("viewFrame: tau is zero or not finite");
    const Vec3 t = tau / norm;
    const Vec3 y = Vec3::UnitY().cross(t);
    if (y.norm() > 0.5) {
        tau1 = y.normalized();
        tau2 = t.cross(tau1);
    } else {
        tau2 = t.cross(Vec3::UnitX()).normalized();
        tau1 = tau2.cross(t);
    }
}

std::array<Vec3, 6> monomialCoefficients(const QuadraticBezier<Vec3>& patch) {
    // Expand sum w_i^2 b_i + 2 w_i w_j b_ij with w0 = 1 - s1 - s2.
    const std::array<Vec3, 6>& b = patch.control; // [b0, b1, b2, b01, b12, b20]
    return {b[0],
            2.0 * (b[3] - b[0]),
            2.0 * (b[5] - b[0]),
            b[0] + b[1] - 2.0 * b[3],
            2.0 * (b[0] - b[3] + b[4] - b[5]),
            b[0] + b[2] - 2.0 * b[5]};
}

bool clipLineToReferenceTriangle(const Eigen::Vector3d& l, double pad, Vec2& a, Vec2& b) {
    const Vec2 nrm(l.x(), l.y());
    const double n2 = nrm.squaredNorm();
    if (!(n2 > 0.0))
        return false;
    const Vec2 p0 = -l.z() / n2 * nrm;
    const Vec2 d(-nrm.y(), nrm.x());
    // Half-planes g . s >= c: s1 >= -pad, s2 >= -pad, -s1 - s2 >= -1 - pad.
    const std::array<Vec2, 3> g = {Vec2(1, 0), Vec2(0, 1), Vec2(-1, -1)};
    const std::array<double, 3> c = {-pad, -pad, -1.0 - pad};
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        const double gd = g[i].dot(d), slack = c[i] - g[i].dot(p0);
        if (gd == 0.0) {
            if (slack > 0.0)
                return false;
        } else if (gd > 0.0) {
            lo = std::max(lo, slack / gd);
        } else {
            hi = std::min(hi, slack / gd);
        }
    }
    if (!(lo <= hi))
        return false;
    a = p0 + lo * d;
    b = p0 + hi * d;
    return true;
}

PatchCuspResult patchCusps(const QuadraticBezier<Vec3>& patch, const Vec3& tau,
                           const PatchCuspOptions& options) {
    requireFinite(patch, tau, "patchCusps");
    Vec3 tau1, tau2;
    viewFrame(tau, tau1, tau2);
    const Vec3 view = tau.normalized();
    // Face uv of s: uv = V0 + J s.
    Eigen::Matrix2d jac;
    jac.col(0) = patch.domain[1] - patch.domain[0];
    jac.col(1) = patch.domain[2] - patch.domain[0];
    const double detJ = jac.determinant();
    if (!(std::abs(detJ) > 0.0))
        throw std::invalid_argument("patchCusps: the patch's domain triangle is degenerate");
    const double scaleBack = 1.0 / (detJ * detJ);

    const std::array<Vec3, 6> p = monomialCoefficients(patch);
    const Linear<Vec3> p1 = d1(p), p2 = d2(p);
    const Quadratic<Vec3> n = cross(p1, p2);
    Quadratic<double> f;
    double nScale = 0.0;
    for (int k = 0; k < 6; ++k) {
        f[k] = view.dot(n[k]);
        nScale += n[k].squaredNorm();
    }
    nScale = std::sqrt(nScale);
    const Linear<double> f1 = d1(f), f2 = d2(f);

    PatchCuspResult result;
    const double gradScale =
        std::sqrt(f[1] * f[1] + f[2] * f[2] + f[3] * f[3] + f[4] * f[4] + f[5] * f[5]);
    if (gradScale <= options.gradientTolerance * nScale) {
        // f is constant: no contour, or (f = 0) the whole patch is on it.
        result.degenerate = std::abs(f[0]) <= options.zeroTolerance * nScale;
        return result;
    }

    // No contour in the domain when f's Bernstein coefficients (which bound
    // it there) share a strict sign: skip the solve.
    {
        auto value = [&](double a, double b) {
            return at(f, Vec2(a, b));
        };
        const double b0 = value(0, 0), b1 = value(1, 0), b2 = value(0, 1);
        const std::array<double, 6> bern = {b0,
                                            b1,
                                            b2,
                                            2.0 * value(0.5, 0) - 0.5 * (b0 + b1),
                                            2.0 * value(0.5, 0.5) - 0.5 * (b1 + b2),
                                            2.0 * value(0, 0.5) - 0.5 * (b2 + b0)};
        const double eps = options.zeroTolerance * nScale;
        if (*std::min_element(bern.begin(), bern.end()) > eps ||
            *std::max_element(bern.begin(), bern.end()) < -eps)
            return result;
    }

    // Eq. 5 with T = (-f_2, f_1), then eq. 6.
    Quadratic<Vec3> t = times(p2, f1);
    const Quadratic<Vec3> minus = times(p1, f2);
    Quadratic<double> q1, q2;
    for (int k = 0; k < 6; ++k) {
        t[k] -= minus[k];
        q1[k] = tau1.dot(t[k]);
        q2[k] = tau2.dot(t[k]);
    }
    const ConicIntersection roots = intersectConics(conicOf(q1), conicOf(q2), options.pencil);

    auto gradient = [&](const Vec2& s) {
        return Vec2(at(f1, s), at(f2, s));
    };
    auto regular = [&](const Vec2& s) {
        return gradient(s).norm() > options.gradientTolerance * nScale;
    };
    if (roots.sharedConic)
        result.degenerate = true;
    for (const Eigen::Vector3d& l : roots.sharedLines) {
        // A shared line is harmless where t = 0 on it (f's critical line of a
        // cylinder-like patch); elsewhere t is parallel to tau along it.
        Vec2 a, b;
        if (!clipLineToReferenceTriangle(l, options.domainTolerance, a, b))
            continue;
        for (int i = 0; i <= 4; ++i)
            if (regular(a + 0.25 * i * (b - a)))
                result.degenerate = true;
    }

    for (const Vec2& s : roots.points) {
        const Vec3 w(1.0 - s.x() - s.y(), s.x(), s.y());
        if (w.minCoeff() < -options.domainTolerance)
            continue;
        if (std::abs(at(f, s)) > options.zeroTolerance * nScale || !regular(s))
            continue;
        const Vec2 grad = gradient(s);
        const Vec2 T(-grad.y(), grad.x());
        const Vec3 tangent = at(t, s);
        PatchCusp c;
        c.barycentric = w;
        c.uv = patch.domain[0] + jac * s;
        c.position = at(p, s);
        // Back to face uv: t_s = det(J)^2 t_uv and J T_s = det(J)^2 T_uv.
        c.domainTangent = scaleBack * (jac * T);
        c.tangent = scaleBack * tangent;
        const double depthRate = view.dot(tangent);
        c.qiIncreasesAlongDomainTangent = depthRate > 0.0;

        // Image expansion about the cusp along the flow ds/dsigma = T.
        const Linear<Vec3> dt1 = d1(t), dt2 = d2(t);
        const Vec3 dtT = at(dt1, s) * T.x() + at(dt2, s) * T.y();
        const Eigen::Matrix2d dT = (Eigen::Matrix2d() << -f2[1], -f2[2], f1[1], f1[2]).finished();
        const Vec2 dTT = dT * T;
        const Vec3 ddt = 2.0 * t[3] * T.x() * T.x() + 2.0 * t[4] * T.x() * T.y() +
                         2.0 * t[5] * T.y() * T.y() + at(dt1, s) * dTT.x() + at(dt2, s) * dTT.y();
        const Vec2 a(tau1.dot(dtT), tau2.dot(dtT));
        const Vec2 bb(tau1.dot(ddt), tau2.dot(ddt));
        const double an = a.norm();
        if (an > options.gradientTolerance * tangent.norm() * T.norm()) {
            c.imageAxis = a / an;
            const Vec2 perp = bb - bb.dot(c.imageAxis) * c.imageAxis;
            if (perp.norm() > options.gradientTolerance * bb.norm())
                c.farSide = (depthRate > 0.0 ? 1.0 : -1.0) * perp.normalized();
        }
        result.cusps.push_back(c);
    }
    return result;
}

bool isBoundaryCusp(const Vec3& normal, const Vec3& t, const Vec3& tPrime, const Vec3& tau,
                    const PatchCuspOptions& options) {
    if (!normal.allFinite() || !t.allFinite() || !tPrime.allFinite() || !tau.allFinite())
        throw std::invalid_argument("isBoundaryCusp: an input vector is not finite");
    if (tau.norm() == 0.0)
        throw std::invalid_argument("isBoundaryCusp: tau is zero");
    const Vec3 view = tau.normalized();
    const double a = view.dot(normal.cross(t));
    const double b = view.dot(normal.cross(tPrime));
    const double ea = options.zeroTolerance * normal.norm() * t.norm();
    const double eb = options.zeroTolerance * normal.norm() * tPrime.norm();
    if (std::abs(a) <= ea || std::abs(b) <= eb)
        return false;
    return (a > 0.0) != (b > 0.0);
}

} // namespace contour::powell_sabin
