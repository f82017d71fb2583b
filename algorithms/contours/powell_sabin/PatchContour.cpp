// The contour generator of one quadratic patch (Capouellez et al. 2023
// §4.1, Table 1), with the errata of the reading notes (A.3.3): the conic's
// center is -A^-1 b; the form keeps its 1/2, so k_i = sqrt(2 c^ / |sigma_i|)
// and the parallel lines solve 1/2 sigma_1 z^2 + b^_1 z + c = 0; the
// parabola divides by b^_2; the hyperbola's z_1 is the axis of negative
// sigma; the ellipse's point at t = infinity is kept out of the domain.
// Conventions and degenerate cases are documented in PatchContour.h.
#include "contours/powell_sabin/PatchContour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace contour::powell_sabin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double cross2(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// The domain in s = (r - origin) / h: side j (corner j -> j + 1) is
// L_j(s) = normal_j . s + offset_j >= 0 inside, a signed distance in s.
struct Frame {
    Vec2 origin = Vec2::Zero();
    double h = 1.0;
    std::array<Vec2, 3> normal;
    std::array<double, 3> offset{};

    double side(int j, const Vec2& s) const { return normal[j].dot(s) + offset[j]; }
};

Frame makeFrame(const std::array<Vec2, 3>& domain, const char* caller) {
    for (const Vec2& v : domain)
        if (!v.allFinite())
            throw std::invalid_argument(std::string(caller) + ": non-finite domain corner");
    if (cross2(domain[1] - domain[0], domain[2] - domain[0]) <= 0.0)
        throw std::invalid_argument(std::string(caller) +
                                    ": the domain triangle is clockwise or degenerate");
    Frame f;
    f.origin = (domain[0] + domain[1] + domain[2]) / 3.0;
    f.h = std::max({(domain[1] - domain[0]).norm(), (domain[2] - domain[1]).norm(),
                    (domain[0] - domain[2]).norm()});
    std::array<Vec2, 3> s;
    for (int i = 0; i < 3; ++i)
        s[i] = (domain[i] - f.origin) / f.h;
    for (int j = 0; j < 3; ++j) {
        const Vec2 e = s[(j + 1) % 3] - s[j];
        f.normal[j] = Vec2(-e.y(), e.x()) / e.norm();
        f.offset[j] = -f.normal[j].dot(s[j]);
    }
    return f;
}

void checkTolerance(const PatchContourOptions& options, const char* caller) {
    if (!std::isfinite(options.zeroTolerance) || options.zeroTolerance < 0.0)
        throw std::invalid_argument(std::string(caller) +
                                    ": zeroTolerance must be finite and non-negative");
}

// f(s) = 1/2 s^T A s + b^T s + c in the frame's s.
struct LocalForm {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Vec2 b = Vec2::Zero();
    double c = 0.0;
};

// Divides by the scale |A|_F + |b| + |c|; false for the zero form.
bool normalize(LocalForm& f) {
    const double scale = f.A.norm() + f.b.norm() + std::abs(f.c);
    if (!(scale > 0.0))
        return false;
    f.A /= scale;
    f.b /= scale;
    f.c /= scale;
    return true;
}

LocalForm localOf(const QuadraticForm2& form, const Frame& fr) {
    if (!form.A.allFinite() || !form.b.allFinite() || !std::isfinite(form.c))
        throw std::invalid_argument("conicContours: non-finite form coefficients");
    const Eigen::Matrix2d A = 0.5 * (form.A + form.A.transpose());
    LocalForm f;
    f.A = fr.h * fr.h * A;
    f.b = fr.h * (A * fr.origin + form.b);
    f.c = 0.5 * fr.origin.dot(A * fr.origin) + form.b.dot(fr.origin) + form.c;
    return f;
}

// tau . (p_u x p_v) about the point o of face uv, in d = r - o:
// 1/2 d^T H d + g^T d + c0. p_u, p_v are linear in d with the constant
// second derivatives, so n is their cross product expanded term by term.
struct Expansion {
    Eigen::Matrix2d H;
    Vec2 g;
    double c0;
};

Expansion expandAt(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const Vec2& o,
                   const char* caller) {
    if (!tau.allFinite() || tau.squaredNorm() == 0.0)
        throw std::invalid_argument(std::string(caller) + ": tau must be finite and non-zero");
    for (const Vec3& p : patch.control)
        if (!p.allFinite())
            throw std::invalid_argument(std::string(caller) + ": non-finite control point");
    Vec3 pu, pv, duu, duv, dvv;
    uvDerivatives(patch, barycentricOf(patch.domain, o), pu, pv);
    uvSecondDerivatives(patch, duu, duv, dvv);
    Expansion e;
    e.c0 = tau.dot(pu.cross(pv));
    e.g = Vec2(tau.dot(pu.cross(duv) + duu.cross(pv)), tau.dot(pu.cross(dvv) + duv.cross(pv)));
    const double huv = tau.dot(duu.cross(dvv)); // duv x duv = 0
    e.H << 2.0 * tau.dot(duu.cross(duv)), huv, huv, 2.0 * tau.dot(duv.cross(dvv));
    return e;
}

// Up to two conic pieces in s: r_s(t) = (X, Y) / W on the open interval
// (lo, hi); `trim` false for an ellipse inside the domain (two halves).
struct Pieces {
    ConicKind kind = ConicKind::Empty;
    int count = 0;
    bool trim = true;
    std::array<Eigen::Matrix3d, 2> curve;
    double lo = -kInf, hi = kInf;
};

// The curve s = origin + z1 e1 + z2 e2 with z_i = Z_i / W (coefficient rows).
Eigen::Matrix3d inFrame(const Vec2& origin, const Vec2& e1, const Vec2& e2,
                        const Eigen::RowVector3d& z1, const Eigen::RowVector3d& z2,
                        const Eigen::RowVector3d& w) {
    Eigen::Matrix3d m;
    m.row(0) = origin.x() * w + e1.x() * z1 + e2.x() * z2;
    m.row(1) = origin.y() * w + e1.y() * z1 + e2.y() * z2;
    m.row(2) = w;
    return m;
}

Eigen::Matrix3d line(const Vec2& point, const Vec2& direction) {
    Eigen::Matrix3d m;
    m << point.x(), direction.x(), 0.0, point.y(), direction.y(), 0.0, 1.0, 0.0, 0.0;
    return m;
}

// Table 1 on the normalized local form; `build` false only classifies.
Pieces conicPieces(const LocalForm& f, const Frame& fr, double eps, bool build) {
    Pieces out;
    const double a = f.A(0, 0), d = f.A(1, 1), off = f.A(0, 1);
    // A = U^T diag(sigma_1, sigma_2) U with |sigma_1| >= |sigma_2|; the small
    // eigenvalue from the determinant, which keeps its relative accuracy.
    const double mean = 0.5 * (a + d);
    const double radius = std::sqrt(0.25 * (a - d) * (a - d) + off * off);
    const double s1 = mean >= 0.0 ? mean + radius : mean - radius;
    const double s2 = s1 != 0.0 ? (a * d - off * off) / s1 : 0.0;
    const Vec2 v1(off, s1 - a), v2(s1 - d, off);
    Vec2 e1 = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    e1 = e1.squaredNorm() > 0.0 ? Vec2(e1.normalized()) : Vec2(1.0, 0.0);
    const Vec2 e2(-e1.y(), e1.x());
    const double bh1 = e1.dot(f.b), bh2 = e2.dot(f.b);
    const Eigen::RowVector3d one(1.0, 0.0, 0.0);

    if (std::abs(s1) < eps) {
        // A = 0 within eps: f is linear, the parabola with sigma_1 = 0.
        const double nb = f.b.norm();
        if (nb < eps)
            return out;
        out.kind = ConicKind::Parabola;
        if (build) {
            out.count = 1;
            out.curve[0] = line(-f.c * f.b / (nb * nb), Vec2(-f.b.y(), f.b.x()) / nb);
        }
        return out;
    }
    if (std::abs(s2) < eps) {
        // Singular A, eq. (4) with z = U s: 1/2 s1 z1^2 + b^.z + c = 0.
        if (std::abs(bh2) >= eps) {
            out.kind = ConicKind::Parabola;
            if (build) {
                out.count = 1;
                const Eigen::RowVector3d z1(0.0, 1.0, 0.0);
                const Eigen::RowVector3d z2(-f.c / bh2, -bh1 / bh2, -0.5 * s1 / bh2);
                out.curve[0] = inFrame(Vec2::Zero(), e1, e2, z1, z2, one);
            }
            return out;
        }
        const double disc = bh1 * bh1 - 2.0 * s1 * f.c;
        if (disc <= eps)
            return out; // a double line or no real line: no stable contour
        out.kind = ConicKind::ParallelLines;
        if (build) {
            out.count = 2;
            const double q = -0.5 * (bh1 + std::copysign(std::sqrt(disc), bh1));
            const std::array<double, 2> roots = {q / (0.5 * s1), f.c / q};
            for (int i = 0; i < 2; ++i)
                out.curve[i] = line(roots[i] * e1, e2);
        }
        return out;
    }

    // Nonsingular A, eq. (3): z = U (s - s0), s0 = -A^-1 b.
    const Vec2 s0 = -(bh1 / s1) * e1 - (bh2 / s2) * e2;
    double ch = f.c - 0.5 * (bh1 * bh1 / s1 + bh2 * bh2 / s2);
    const double sign = ch < 0.0 ? -1.0 : 1.0;
    ch *= sign;
    const double p1 = sign * s1, p2 = sign * s2;
    if (ch < eps) {
        if (p1 * p2 >= 0.0)
            return out; // an isolated zero
        out.kind = ConicKind::IntersectingLines;
        if (build) {
            // Table 1's z = t (1, +-sqrt(-sigma_1 / sigma_2)) are the zero lines
            // of sqrt|sigma_1| z_1 -+ sqrt|sigma_2| z_2, with z_i = e_i . s +
            // b^_i / sigma_i. Built from these linear forms rather than
            // through s0, which is far away when A is nearly singular.
            out.count = 2;
            const double r1 = std::sqrt(std::abs(s1)), r2 = std::sqrt(std::abs(s2));
            for (int i = 0; i < 2; ++i) {
                const double pm = i == 0 ? 1.0 : -1.0;
                const Vec2 m = r1 * e1 + pm * r2 * e2;
                const double kappa = r1 * bh1 / s1 + pm * r2 * bh2 / s2;
                const double mm = m.squaredNorm();
                out.curve[i] = line(-kappa * m / mm, Vec2(-m.y(), m.x()) / std::sqrt(mm));
            }
        }
        return out;
    }
    if (p1 > 0.0 && p2 > 0.0)
        return out; // sigma_1, sigma_2, c^ > 0: f has no zero
    // The conic's two vertices on the axis through s0 along e_axis (of
    // eigenvalue sa; the other axis e_other, so): the roots of f on that
    // line, computed from the line's own quadratic so that they stay
    // accurate when s0 is far (nearly singular A, a center at |b| / sigma_2).
    struct Vertices {
        Vec2 v[2];
        Vec2 out[2]; // unit, from the center through v[i]
    };
    auto vertices = [&](const Vec2& ea, double sa, double ba, const Vec2& eo, double so,
                        double bo) {
        const double cLine = f.c - 0.5 * bo * bo / so; // f at the axis' foot
        const double disc = std::max(0.0, ba * ba - 2.0 * sa * cLine);
        const double q = -(ba + std::copysign(std::sqrt(disc), ba));
        const double ya = q / sa, yb = q != 0.0 ? 2.0 * cLine / q : ya;
        const Vec2 foot = -(bo / so) * eo;
        Vertices vs;
        vs.v[0] = foot + ya * ea;
        vs.v[1] = foot + yb * ea;
        vs.out[0] = ya >= yb ? ea : Vec2(-ea);
        vs.out[1] = -vs.out[0];
        return vs;
    };
    if (p1 < 0.0 && p2 < 0.0) {
        out.kind = ConicKind::Ellipse;
        if (!build)
            return out;
        const double k1 = std::sqrt(2.0 * ch / -p1), k2 = std::sqrt(2.0 * ch / -p2);
        const Eigen::RowVector3d w(1.0, 0.0, 1.0);
        // Anchored at the vertex of the major axis (e2) nearer the domain:
        // s = V + (2 k1 t e1 + 2 k2 t^2 u) / (1 + t^2), u towards the center;
        // t = infinity is the opposite vertex. Used when that vertex is
        // outside the domain, so that the trimmed pieces have finite t.
        const Vertices vs = vertices(e2, s2, bh2, e1, s1, bh1);
        const int near = vs.v[0].squaredNorm() <= vs.v[1].squaredNorm() ? 0 : 1;
        const Vec2 far = vs.v[1 - near];
        double farSide = kInf;
        for (int j = 0; j < 3; ++j)
            farSide = std::min(farSide, fr.side(j, far));
        if (farSide < -eps) {
            out.count = 1;
            out.curve[0] = inFrame(vs.v[near], e1, -vs.out[near], Eigen::RowVector3d(0, 2 * k1, 0),
                                   Eigen::RowVector3d(0, 0, 2 * k2), w);
            return out;
        }
        // A small ellipse (the center is near): z = (k1 cos(phi0 + theta),
        // k2 sin(phi0 + theta)), t = tan(theta / 2), whose t = infinity is the
        // point of angle phi0 + pi. Put it where the ellipse is farthest
        // outside a side.
        double worst = kInf, c0 = 1.0, sn0 = 0.0;
        for (int j = 0; j < 3; ++j) {
            const double al = fr.normal[j].dot(e1) * k1, be = fr.normal[j].dot(e2) * k2;
            const double rho = std::sqrt(al * al + be * be);
            const double lowest = fr.side(j, s0) - rho;
            if (lowest < worst) {
                worst = lowest;
                c0 = al / rho;
                sn0 = be / rho;
            }
        }
        auto ellipse = [&](double c, double sn) {
            return inFrame(s0, e1, e2, k1 * Eigen::RowVector3d(c, -2.0 * sn, -c),
                           k2 * Eigen::RowVector3d(sn, 2.0 * c, -sn), w);
        };
        if (worst < -eps) {
            out.count = 1;
            out.curve[0] = ellipse(c0, sn0);
        } else {
            // Inside the domain: the halves phi0 = 0 and phi0 = pi (t -> -1/t),
            // each on t in [-1, 1]; the first ends where the second starts.
            out.count = 2;
            out.trim = false;
            out.lo = -1.0;
            out.hi = 1.0;
            out.curve[0] = ellipse(1.0, 0.0);
            out.curve[1] = ellipse(-1.0, 0.0);
        }
        return out;
    }
    out.kind = ConicKind::Hyperbola;
    if (!build)
        return out;
    // Table 1 with z1 along the transverse axis (negative sigma after the
    // sign normalization), each branch anchored at its vertex V:
    // s = V + (2 k1 t^2 u + 2 k2 t e_c) / (1 - t^2), u outwards, t in (-1, 1);
    // the poles t = +-1 separate the branches (Table 1's formula maps the
    // branch z1 <= -k1 to |t| < 1 and z1 >= k1 to |t| > 1; here each is its
    // own curve on |t| < 1).
    const bool firstNegative = p1 < 0.0;
    const Vec2 et = firstNegative ? e1 : e2, ec = firstNegative ? e2 : e1;
    const double st = firstNegative ? s1 : s2, sc = firstNegative ? s2 : s1;
    const double bt = firstNegative ? bh1 : bh2, bc = firstNegative ? bh2 : bh1;
    const double pt = firstNegative ? p1 : p2, pc = firstNegative ? p2 : p1;
    const double k1 = std::sqrt(2.0 * ch / -pt), k2 = std::sqrt(2.0 * ch / pc);
    const Vertices vs = vertices(et, st, bt, ec, sc, bc);
    const Eigen::RowVector3d w(1.0, 0.0, -1.0);
    out.count = 2;
    out.lo = -1.0;
    out.hi = 1.0;
    for (int i = 0; i < 2; ++i)
        out.curve[i] = inFrame(vs.v[i], vs.out[i], ec, Eigen::RowVector3d(0, 0, 2 * k1),
                               Eigen::RowVector3d(0, 2 * k2, 0), w);
    return out;
}

Vec2 evalCurve(const Eigen::Matrix3d& m, double t) {
    const Eigen::Vector3d p = m.col(0) + t * (m.col(1) + t * m.col(2));
    return Vec2(p.x() / p.z(), p.y() / p.z());
}

// Real roots of a t^2 + b t + c, stable for any magnitudes; a double root
// once (it bounds no piece).
int quadraticRoots(double a, double b, double c, std::array<double, 2>& roots) {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0 || (a == 0.0 && b == 0.0))
        return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    int n = 0;
    if (a != 0.0)
        roots[n++] = q / a;
    if (q != 0.0 && (n == 0 || c / q != roots[0]))
        roots[n++] = c / q;
    return n;
}

// Face uv of a curve given in s: r = origin + h s.
RationalQuadratic toFaceUv(const Eigen::Matrix3d& m, const Frame& fr) {
    RationalQuadratic r;
    r.coefficients.row(0) = fr.origin.x() * m.row(2) + fr.h * m.row(0);
    r.coefficients.row(1) = fr.origin.y() * m.row(2) + fr.h * m.row(1);
    r.coefficients.row(2) = m.row(2);
    return r;
}

void emit(const Eigen::Matrix3d& m, double t0, double t1, int startSide, int endSide,
          ConicKind kind, Index patchId, const Frame& fr, std::vector<ContourSegment>& out) {
    ContourSegment s;
    s.patch = patchId;
    s.kind = kind;
    s.curve = toFaceUv(m, fr);
    s.t0 = t0;
    s.t1 = t1;
    s.startSide = startSide;
    s.endSide = endSide;
    out.push_back(s);
}

// §4.1 "Trimming": the crossings of r(t) with the three side lines are the
// roots of the quadratics L_j(X, Y) W; consecutive crossings bound a piece,
// kept when its midpoint is inside. Pieces with an infinite end leave the
// bounded domain, so only intervals between crossings count.
void trimPiece(const Eigen::Matrix3d& m, double lo, double hi, const LocalForm& f, const Frame& fr,
               double eps, ConicKind kind, Index patchId, std::vector<ContourSegment>& out) {
    struct Crossing {
        double t;
        int side;
    };
    std::array<Crossing, 6> x{};
    int n = 0;
    const double curveScale = m.cwiseAbs().sum();
    for (int j = 0; j < 3; ++j) {
        const Eigen::RowVector3d q =
            fr.normal[j].x() * m.row(0) + fr.normal[j].y() * m.row(1) + fr.offset[j] * m.row(2);
        if (q.cwiseAbs().sum() <= eps * curveScale)
            continue; // the curve lies along this side: the other sides bound it
        std::array<double, 2> roots{};
        const int k = quadraticRoots(q[2], q[1], q[0], roots);
        for (int i = 0; i < k; ++i)
            if (std::isfinite(roots[i]) && roots[i] > lo && roots[i] < hi)
                x[n++] = {roots[i], j};
    }
    for (int i = 1; i < n; ++i) // at most six: insertion sort
        for (int j = i; j > 0 && x[j].t < x[j - 1].t; --j)
            std::swap(x[j], x[j - 1]);
    for (int i = 0; i + 1 < n; ++i) {
        const double ta = x[i].t, tb = x[i + 1].t;
        if (!(tb > ta) || (evalCurve(m, tb) - evalCurve(m, ta)).norm() < eps)
            continue; // through a corner: a piece of zero length
        const Vec2 mid = evalCurve(m, 0.5 * (ta + tb));
        int nearest = 0;
        double lowest = kInf;
        for (int j = 0; j < 3; ++j) {
            const double l = fr.side(j, mid);
            if (l < lowest) {
                lowest = l;
                nearest = j;
            }
        }
        if (!(lowest >= -eps))
            continue;
        // Along a side: owned by the patch into which grad f points, so the
        // neighbour across the side (same f, opposite normal) drops it.
        if (lowest <= eps && !(fr.normal[nearest].dot(f.A * mid + f.b) > 0.0))
            continue;
        emit(m, ta, tb, x[i].side, x[i + 1].side, kind, patchId, fr, out);
    }
}

std::vector<ContourSegment> contoursOfLocal(LocalForm f, const Frame& fr, Index patchId,
                                            double eps) {
    std::vector<ContourSegment> out;
    if (!normalize(f))
        return out;
    const Pieces p = conicPieces(f, fr, eps, true);
    for (int i = 0; i < p.count; ++i) {
        if (p.trim)
            trimPiece(p.curve[i], p.lo, p.hi, f, fr, eps, p.kind, patchId, out);
        else
            emit(p.curve[i], p.lo, p.hi, -1, -1, p.kind, patchId, fr, out);
    }
    return out;
}

} // namespace

const char* toString(ConicKind kind) {
    switch (kind) {
    case ConicKind::Empty:
        return "empty";
    case ConicKind::Ellipse:
        return "ellipse";
    case ConicKind::Hyperbola:
        return "hyperbola";
    case ConicKind::IntersectingLines:
        return "intersecting lines";
    case ConicKind::Parabola:
        return "parabola";
    case ConicKind::ParallelLines:
        return "parallel lines";
    }
    return "unknown";
}

Vec2 RationalQuadratic::at(double t) const {
    return evalCurve(coefficients, t);
}

Vec2 RationalQuadratic::derivative(double t) const {
    const Eigen::Matrix3d& m = coefficients;
    const Eigen::Vector3d p = m.col(0) + t * (m.col(1) + t * m.col(2));
    const Eigen::Vector3d dp = m.col(1) + 2.0 * t * m.col(2);
    const double w2 = p.z() * p.z();
    return Vec2((dp.x() * p.z() - p.x() * dp.z()) / w2, (dp.y() * p.z() - p.y() * dp.z()) / w2);
}

QuadraticForm2 contourFunction(const QuadraticBezier<Vec3>& patch, const Vec3& tau) {
    makeFrame(patch.domain, "contourFunction");
    // Expanded about the domain's first corner, then moved to face uv.
    const Vec2 o = patch.domain[0];
    const Expansion e = expandAt(patch, tau, o, "contourFunction");
    QuadraticForm2 f;
    f.A = e.H;
    f.b = e.g - e.H * o;
    f.c = e.c0 - e.g.dot(o) + 0.5 * o.dot(e.H * o);
    return f;
}

std::vector<ContourSegment> patchContours(const QuadraticBezier<Vec3>& patch, Index patchId,
                                          const Vec3& tau, const PatchContourOptions& options) {
    checkTolerance(options, "patchContours");
    const Frame fr = makeFrame(patch.domain, "patchContours");
    // Expanded about the frame's origin: the local form directly, without
    // the cancellation of a round trip through face uv.
    const Expansion e = expandAt(patch, tau, fr.origin, "patchContours");
    LocalForm f;
    f.A = fr.h * fr.h * e.H;
    f.b = fr.h * e.g;
    f.c = e.c0;
    return contoursOfLocal(f, fr, patchId, options.zeroTolerance);
}

std::vector<ContourSegment> conicContours(const QuadraticForm2& form,
                                          const std::array<Vec2, 3>& domain, Index patchId,
                                          const PatchContourOptions& options) {
    checkTolerance(options, "conicContours");
    const Frame fr = makeFrame(domain, "conicContours");
    return contoursOfLocal(localOf(form, fr), fr, patchId, options.zeroTolerance);
}

ConicKind classifyConic(const QuadraticForm2& form, const std::array<Vec2, 3>& domain,
                        const PatchContourOptions& options) {
    checkTolerance(options, "classifyConic");
    const Frame fr = makeFrame(domain, "classifyConic");
    LocalForm f = localOf(form, fr);
    if (!normalize(f))
        return ConicKind::Empty;
    return conicPieces(f, fr, options.zeroTolerance, false).kind;
}

} // namespace contour::powell_sabin
