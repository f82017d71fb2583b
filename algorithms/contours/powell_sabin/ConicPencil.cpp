// Two conics meet where a degenerate member of their pencil meets either of
// them (Ogaki & Tokuyoshi 2011; Capouellez et al. 2023 §4.2): the member is
// found from a real root of the cubic det(M1 + lambda M2), split into lines
// from its eigen-decomposition, and each line is intersected with a conic.
#include "contours/powell_sabin/ConicPencil.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

namespace contour::powell_sabin {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector3d lifted(const Vec2& p) {
    return Vector3d(p.x(), p.y(), 1.0);
}

double residual(const Matrix3d& m, const Vec2& p) {
    const Vector3d x = lifted(p);
    return std::abs(x.dot(m * x)) / x.squaredNorm();
}

// The cofactor matrix transposed: adj(M) M = det(M) I.
Matrix3d adjugate(const Matrix3d& m) {
    Matrix3d a;
    a.col(0) = m.col(1).cross(m.col(2));
    a.col(1) = m.col(2).cross(m.col(0));
    a.col(2) = m.col(0).cross(m.col(1));
    return a.transpose();
}

// The lines of a degenerate (rank <= 2) symmetric member, from its
// eigen-decomposition D = e_i v_i v_i^T + e_j v_j v_j^T (the third eigenvalue
// is round-off): opposite signs give the real pair sqrt|e_i| v_i +-
// sqrt|e_j| v_j, a negligible e_j the double line v_i, equal signs a complex
// pair whose only real point is the null vector.
struct Split {
    std::vector<Vector3d> lines;
    bool complexPair = false;
    Vector3d vertex = Vector3d::Zero();
    double nullRatio = 0.0; // |smallest eigenvalue| / |largest|
};

Split splitDegenerate(const Matrix3d& d, double tol) {
    const Eigen::SelfAdjointEigenSolver<Matrix3d> es(d);
    const Vector3d e = es.eigenvalues();
    std::array<int, 3> order = {0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return std::abs(e[a]) > std::abs(e[b]); });
    const int i = order[0], j = order[1], k = order[2];
    Split s;
    s.nullRatio = std::abs(e[i]) > 0.0 ? std::abs(e[k]) / std::abs(e[i]) : 0.0;
    if (std::abs(e[j]) <= tol * std::abs(e[i])) {
        s.lines.push_back(es.eigenvectors().col(i));
    } else if (e[i] * e[j] < 0.0) {
        const Vector3d a = std::sqrt(std::abs(e[i])) * es.eigenvectors().col(i);
        const Vector3d b = std::sqrt(std::abs(e[j])) * es.eigenvectors().col(j);
        s.lines.push_back((a + b).normalized());
        s.lines.push_back((a - b).normalized());
    } else {
        s.complexPair = true;
        s.vertex = es.eigenvectors().col(k);
    }
    return s;
}

bool isLineAtInfinity(const Vector3d& l, double tol) {
    return std::hypot(l.x(), l.y()) <= tol * l.norm();
}

// Homogeneous points where line l meets conic c (unit norm). Returns false
// when the line lies in the conic.
bool intersectLine(const Vector3d& l, const Matrix3d& c, double tol, std::vector<Vector3d>& out) {
    // Two orthonormal points spanning the line: x = alpha q1 + beta q2.
    int k = 0;
    l.cwiseAbs().minCoeff(&k);
    const Vector3d ln = l.normalized();
    const Vector3d q1 = ln.cross(Vector3d::Unit(k)).normalized();
    const Vector3d q2 = ln.cross(q1);
    const double a = q1.dot(c * q1), b = q1.dot(c * q2), cc = q2.dot(c * q2);
    const double scale = std::max({std::abs(a), std::abs(b), std::abs(cc)});
    if (scale <= tol)
        return false;
    // a alpha^2 + 2 b alpha beta + cc beta^2 = 0; a discriminant within
    // round-off of zero is a tangency.
    double disc = b * b - a * cc;
    if (disc < -tol * scale * scale)
        return true;
    disc = std::max(disc, 0.0);
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (std::abs(q) <= tol * scale) {
        // b and the discriminant vanish, so a or cc does: one double root.
        out.push_back(std::abs(a) <= std::abs(cc) ? q1 : q2);
        return true;
    }
    // Roots alpha / beta = q / a and cc / q without cancellation.
    out.push_back(q * q1 + a * q2);
    out.push_back(cc * q1 + q * q2);
    return true;
}

// Newton steps on the pair of conics, each kept only if it helps.
Vec2 polish(const Matrix3d& n1, const Matrix3d& n2, Vec2 p, int steps) {
    double best = std::max(residual(n1, p), residual(n2, p));
    for (int s = 0; s < steps && best > 0.0; ++s) {
        const Vector3d x = lifted(p);
        Eigen::Matrix2d j;
        j.row(0) = 2.0 * (n1 * x).head<2>().transpose();
        j.row(1) = 2.0 * (n2 * x).head<2>().transpose();
        const double det = j.determinant();
        if (!std::isfinite(det) || det == 0.0)
            break;
        const Vec2 f(x.dot(n1 * x), x.dot(n2 * x));
        const Vec2 q = p - j.inverse() * f;
        if (!q.allFinite())
            break;
        const double r = std::max(residual(n1, q), residual(n2, q));
        if (!(r < best))
            break;
        p = q;
        best = r;
    }
    return p;
}

// Real roots of c3 l^3 + c2 l^2 + c1 l + c0 (c3 != 0) from the eigenvalues of
// the companion matrix (§4.2), each polished by Newton on the cubic.
std::vector<double> cubicRealRoots(double c0, double c1, double c2, double c3,
                                   double realTolerance) {
    Matrix3d comp = Matrix3d::Zero();
    comp(1, 0) = 1.0;
    comp(2, 1) = 1.0;
    comp(0, 2) = -c0 / c3;
    comp(1, 2) = -c1 / c3;
    comp(2, 2) = -c2 / c3;
    const Eigen::EigenSolver<Matrix3d> es(comp, false);
    std::vector<double> roots;
    for (int i = 0; i < 3; ++i) {
        const std::complex<double> z = es.eigenvalues()[i];
        // A double real root may come out as a pair with a tiny imaginary part.
        if (std::abs(z.imag()) > realTolerance * (1.0 + std::abs(z.real())))
            continue;
        double x = z.real();
        for (int it = 0; it < 3; ++it) {
            const double f = ((c3 * x + c2) * x + c1) * x + c0;
            const double df = (3.0 * c3 * x + 2.0 * c2) * x + c1;
            if (df == 0.0)
                break;
            const double y = x - f / df;
            const double fy = ((c3 * y + c2) * y + c1) * y + c0;
            if (!(std::abs(fy) < std::abs(f)))
                break;
            x = y;
        }
        roots.push_back(x);
    }
    return roots;
}

} // namespace

Eigen::Matrix3d conicMatrix(double a, double b, double c, double d, double e, double f) {
    Matrix3d m;
    m << a, 0.5 * b, 0.5 * d, 0.5 * b, c, 0.5 * e, 0.5 * d, 0.5 * e, f;
    return m;
}

ConicIntersection intersectConics(const Eigen::Matrix3d& m1, const Eigen::Matrix3d& m2,
                                  const ConicPencilOptions& options) {
    for (const Matrix3d* m : {&m1, &m2}) {
        if (!m->allFinite())
            throw std::invalid_argument("intersectConics: a conic matrix is not finite");
        if ((*m - m->transpose()).norm() > options.symmetryTolerance * m->norm())
            throw std::invalid_argument("intersectConics: a conic matrix is not symmetric");
    }
    const double tol = options.zeroTolerance;
    ConicIntersection result;
    const double s1 = m1.norm(), s2 = m2.norm();
    if (s1 == 0.0 || s2 == 0.0) {
        result.sharedConic = true;
        return result;
    }
    const Matrix3d n1 = m1 / s1, n2 = m2 / s2;
    if (std::min((n1 - n2).norm(), (n1 + n2).norm()) <= tol) {
        result.sharedConic = true;
        return result;
    }

    // The split of a degenerate member and the conic `other` it is
    // intersected with.
    Matrix3d other;
    Split split;
    const double det1 = n1.determinant(), det2 = n2.determinant();
    if (std::abs(det1) <= tol || std::abs(det2) <= tol) {
        // One conic is degenerate already (lines, or conics sharing a line,
        // where every member is degenerate).
        const bool first = std::abs(det1) <= std::abs(det2);
        other = first ? n2 : n1;
        split = splitDegenerate(first ? n1 : n2, tol);
    } else {
        // det(p + lambda q) with |det q| >= |det p|, so the cubic's leading
        // coefficient is not small.
        const bool swap = std::abs(det1) > std::abs(det2);
        const Matrix3d& p = swap ? n2 : n1;
        const Matrix3d& q = swap ? n1 : n2;
        const double c0 = p.determinant(), c3 = q.determinant();
        const double c1 = (adjugate(p) * q).trace(), c2 = (p * adjugate(q)).trace();
        const std::vector<double> roots = cubicRealRoots(c0, c1, c2, c3, options.realRootTolerance);
        if (roots.empty())
            throw std::runtime_error("intersectConics: the pencil's cubic has no real root");
        // Every real root works in exact arithmetic; prefer a member that
        // splits into real lines, then the most clearly degenerate one.
        double bestScore = std::numeric_limits<double>::infinity();
        for (double lambda : roots) {
            Matrix3d m = p + lambda * q;
            m /= m.norm();
            const Split s = splitDegenerate(m, tol);
            const double score = s.nullRatio + (s.complexPair ? 1.0 : 0.0);
            if (score < bestScore) {
                bestScore = score;
                split = s;
                // The member meets q where p and q meet; when it is close
                // to q (large lambda), meet p instead.
                other = std::abs(lambda) <= 1.0 ? q : p;
            }
        }
    }

    std::vector<Vector3d> homogeneous;
    if (split.complexPair)
        homogeneous.push_back(split.vertex);
    for (const Vector3d& l : split.lines)
        if (!intersectLine(l, other, tol, homogeneous) && !isLineAtInfinity(l, tol))
            result.sharedLines.push_back(l.normalized());

    struct Candidate {
        Vec2 p;
        double r;
    };
    std::vector<Candidate> candidates;
    for (const Vector3d& x : homogeneous) {
        if (std::abs(x.z()) <= options.infinityTolerance * x.norm())
            continue; // a common point at infinity
        const Vec2 p = polish(n1, n2, Vec2(x.x() / x.z(), x.y() / x.z()), options.newtonSteps);
        const double r = std::max(residual(n1, p), residual(n2, p));
        if (p.allFinite() && r <= options.residualTolerance)
            candidates.push_back({p, r});
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.r < b.r; });
    for (const Candidate& c : candidates) {
        const bool known =
            std::any_of(result.points.begin(), result.points.end(), [&](const Vec2& q) {
                return (q - c.p).norm() <= options.mergeDistance * std::max(1.0, c.p.norm());
            });
        if (!known && result.points.size() < 4)
            result.points.push_back(c.p);
    }
    return result;
}

} // namespace contour::powell_sabin
