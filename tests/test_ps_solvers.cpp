// The small polynomial solvers of §4.2 of Capouellez et al. 2023
// (contours/powell_sabin/ConicPencil.h, PatchCusps.h, PatchRayTest.h): conic
// pairs with known intersections (through four chosen points, tangencies, no
// real point, lines, shared components); cusps of hand-made patches with a
// known cusp and of a fitted torus seen at a grazing angle, against dense
// sampling of the contour's image tangent, with the QI rule checked by ray
// counts; ray tests against dense sampling plus Newton.
#include "PowellSabinLayouts.h"
#include "contours/powell_sabin/ConicPencil.h"
#include "contours/powell_sabin/PatchCusps.h"
#include "contours/powell_sabin/PatchRayTest.h"
#include "contours/powell_sabin/ThinPlateFit.h"

#include <Eigen/Dense>
#include <QElapsedTimer>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Portable uniform numbers: mt19937_64's output is fixed by the standard.
struct Rng {
    std::mt19937_64 engine{20230805};
    double uniform(double a, double b) {
        return a + (b - a) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
    }
    Vec2 point(double r) { return Vec2(uniform(-r, r), uniform(-r, r)); }
};

Vector3d lineThrough(const Vec2& a, const Vec2& b) {
    return Vector3d(a.x(), a.y(), 1.0).cross(Vector3d(b.x(), b.y(), 1.0));
}

// The degenerate conic l m^T + m l^T (the line pair l, m).
Matrix3d linePair(const Vector3d& l, const Vector3d& m) {
    return l * m.transpose() + m * l.transpose();
}

// The conic M moved by the affine map x -> H x (homogeneous H).
Matrix3d moved(const Matrix3d& m, const Matrix3d& h) {
    const Matrix3d hi = h.inverse();
    Matrix3d r = hi.transpose() * m * hi;
    return 0.5 * (r + r.transpose());
}

Vec2 apply(const Matrix3d& h, const Vec2& p) {
    const Vector3d x = h * Vector3d(p.x(), p.y(), 1.0);
    return x.head<2>() / x.z();
}

Matrix3d randomAffine(Rng& rng) {
    const double a = rng.uniform(0, 2 * M_PI), s = rng.uniform(0.5, 2.0);
    Matrix3d h = Matrix3d::Identity();
    h.topLeftCorner<2, 2>() << s * std::cos(a), -s * std::sin(a), s * std::sin(a), s * std::cos(a);
    h(0, 1) += rng.uniform(-0.3, 0.3);
    h.topRightCorner<2, 1>() = rng.point(1.0);
    return h;
}

// Each expected point matched by exactly one returned point within tol.
bool samePoints(const std::vector<Vec2>& got, const std::vector<Vec2>& want, double tol) {
    if (got.size() != want.size())
        return false;
    for (const Vec2& w : want)
        if (std::count_if(got.begin(), got.end(),
                          [&](const Vec2& g) { return (g - w).norm() <= tol; }) != 1)
            return false;
    return true;
}

QString describe(const std::vector<Vec2>& pts) {
    QString s;
    for (const Vec2& p : pts)
        s += QString("(%1, %2) ").arg(p.x(), 0, 'g', 17).arg(p.y(), 0, 'g', 17);
    return s;
}

// A quadratic patch p(uv) = g(uv) over `domain`, from g's values:
// b_i = g(V_i), b_ij = 2 g(m_ij) - (g(V_i) + g(V_j)) / 2.
template <typename G> QuadraticBezier<Vec3> patchOf(const std::array<Vec2, 3>& domain, G g) {
    QuadraticBezier<Vec3> p;
    p.domain = domain;
    for (int i = 0; i < 3; ++i)
        p.control[i] = g(domain[i]);
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        p.control[3 + i] =
            2.0 * g(0.5 * (domain[i] + domain[j])) - 0.5 * (g(domain[i]) + g(domain[j]));
    }
    return p;
}

// Dense, independent evaluation of a patch's contour (through Ps12Patch's
// evaluate / uvDerivatives and finite differences, not the solvers' algebra).
struct Probe {
    const QuadraticBezier<Vec3>& patch;
    Vec3 tau = Vec3::UnitZ();
    double f(const Vec2& uv) const {
        Vec3 du, dv;
        uvDerivatives(patch, barycentricOf(patch.domain, uv), du, dv);
        return tau.dot(du.cross(dv));
    }
    double size() const {
        return std::max((patch.domain[1] - patch.domain[0]).norm(),
                        (patch.domain[2] - patch.domain[0]).norm());
    }
    // The contour's domain tangent [-f_v, f_u] and 3D tangent (eq. 5).
    Vec3 tangent(const Vec2& uv, Vec2* domainTangent = nullptr) const {
        const double h = 1e-6 * size();
        const double fu = (f(uv + Vec2(h, 0)) - f(uv - Vec2(h, 0))) / (2 * h);
        const double fv = (f(uv + Vec2(0, h)) - f(uv - Vec2(0, h))) / (2 * h);
        Vec3 du, dv;
        uvDerivatives(patch, barycentricOf(patch.domain, uv), du, dv);
        if (domainTangent)
            *domainTangent = Vec2(-fv, fu);
        return -du * fv + dv * fu;
    }
    // |image tangent| / |3D tangent|: zero exactly at cusps.
    double imageRatio(const Vec2& uv) const {
        const Vec3 t = tangent(uv);
        return t.head<2>().norm() / t.norm();
    }
    Vec3 normal(const Vec2& uv) const {
        Vec3 du, dv;
        uvDerivatives(patch, barycentricOf(patch.domain, uv), du, dv);
        return du.cross(dv);
    }
    // Points of the contour from uv0 (on it) along sigma * [-f_v, f_u], in
    // steps of `fraction` / steps of the patch size, each projected back
    // onto f = 0 by Newton along grad f; stops at the domain's boundary.
    std::vector<Vec2> traceContour(const Vec2& uv0, double sigma, double fraction,
                                   int steps) const {
        std::vector<Vec2> out;
        Vec2 uv = uv0;
        const double h = fraction * size() / steps;
        for (int k = 0; k < steps; ++k) {
            Vec2 dir;
            tangent(uv, &dir);
            uv += sigma * h * dir.normalized();
            for (int it = 0; it < 3; ++it) {
                tangent(uv, &dir);
                const Vec2 g(dir.y(), -dir.x()); // grad f from T = (-f_v, f_u)
                uv -= f(uv) / g.squaredNorm() * g;
            }
            if (barycentricOf(patch.domain, uv).minCoeff() < 0.0)
                break;
            out.push_back(uv);
        }
        return out;
    }
    Vec3 position(const Vec2& uv) const { return evaluate(patch, barycentricOf(patch.domain, uv)); }
};

// Marching triangles over an n x n split of the domain: the contour's
// crossings of every small edge (refined by bisection) joined per small
// triangle; a piece whose ends have opposed image tangents holds a cusp.
struct ContourSample {
    std::vector<Vec2> points;    // crossings
    std::vector<Vec2> reversals; // midpoints of pieces with reversed image tangent
};

ContourSample sampleContour(const Probe& probe, int n) {
    const std::array<Vec2, 3>& d = probe.patch.domain;
    auto uvOf = [&](int i, int j) {
        return Vec2(d[0] + (double(i) / n) * (d[1] - d[0]) + (double(j) / n) * (d[2] - d[0]));
    };
    std::vector<double> fv;
    auto id = [n](int i, int j) {
        return j * (n + 1) + i;
    };
    fv.assign(std::size_t((n + 1) * (n + 1)), 0.0);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i + j <= n; ++i)
            fv[std::size_t(id(i, j))] = probe.f(uvOf(i, j));
    auto crossing = [&](Vec2 a, Vec2 b, double fa) {
        for (int it = 0; it < 50; ++it) {
            const Vec2 m = 0.5 * (a + b);
            const double fm = probe.f(m);
            if ((fm > 0) == (fa > 0)) {
                a = m;
                fa = fm;
            } else {
                b = m;
            }
        }
        return Vec2(0.5 * (a + b));
    };
    ContourSample s;
    auto triangle = [&](std::array<std::array<int, 2>, 3> c) {
        std::vector<Vec2> ends;
        for (int e = 0; e < 3; ++e) {
            const auto& a = c[e];
            const auto& b = c[(e + 1) % 3];
            const double fa = fv[std::size_t(id(a[0], a[1]))], fb = fv[std::size_t(id(b[0], b[1]))];
            if ((fa > 0) != (fb > 0))
                ends.push_back(crossing(uvOf(a[0], a[1]), uvOf(b[0], b[1]), fa));
        }
        if (ends.size() != 2)
            return;
        s.points.push_back(ends[0]);
        const Vec3 t0 = probe.tangent(ends[0]), t1 = probe.tangent(ends[1]);
        if (t0.head<2>().dot(t1.head<2>()) < 0.0)
            s.reversals.push_back(0.5 * (ends[0] + ends[1]));
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i) {
            triangle({{{i, j}, {i + 1, j}, {i, j + 1}}});
            if (i + j + 1 < n)
                triangle({{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}});
        }
    return s;
}

// All points of the patch on the ray through x (tau = z), by Newton from
// every small triangle of an n x n split whose image contains x.
std::vector<double> bruteForceDepths(const QuadraticBezier<Vec3>& patch, const Vec2& x, int n,
                                     bool& nearFold) {
    const std::array<Vec2, 3>& d = patch.domain;
    auto uvOf = [&](double i, double j) {
        return Vec2(d[0] + (i / n) * (d[1] - d[0]) + (j / n) * (d[2] - d[0]));
    };
    auto image = [&](const Vec2& uv) {
        return Vec2(evaluate(patch, barycentricOf(d, uv)).head<2>());
    };
    std::vector<Vec2> roots;
    nearFold = false;
    auto tryTriangle = [&](const std::array<Vec2, 3>& t) {
        const Vec2 a = image(t[0]), b = image(t[1]), c = image(t[2]);
        Eigen::Matrix2d m;
        m.col(0) = b - a;
        m.col(1) = c - a;
        if (std::abs(m.determinant()) < 1e-300)
            return;
        const Vec2 l = m.inverse() * (x - a);
        if (l.minCoeff() < -0.05 || l.sum() > 1.05)
            return;
        Vec2 uv = t[0] + l.x() * (t[1] - t[0]) + l.y() * (t[2] - t[0]);
        for (int it = 0; it < 40; ++it) {
            Vec3 du, dv;
            uvDerivatives(patch, barycentricOf(d, uv), du, dv);
            Eigen::Matrix2d j;
            j.col(0) = du.head<2>();
            j.col(1) = dv.head<2>();
            uv -= j.inverse() * (image(uv) - x);
        }
        Vec3 du, dv;
        uvDerivatives(patch, barycentricOf(d, uv), du, dv);
        if ((image(uv) - x).norm() > 1e-13 || barycentricOf(d, uv).minCoeff() < -1e-10)
            return;
        if (std::abs(du.cross(dv).normalized().z()) < 1e-3)
            nearFold = true;
        for (const Vec2& r : roots)
            if ((r - uv).norm() < 1e-7)
                return;
        roots.push_back(uv);
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i) {
            tryTriangle({uvOf(i, j), uvOf(i + 1, j), uvOf(i, j + 1)});
            if (i + j + 1 < n)
                tryTriangle({uvOf(i + 1, j), uvOf(i + 1, j + 1), uvOf(i, j + 1)});
        }
    std::vector<double> depths;
    for (const Vec2& r : roots)
        depths.push_back(evaluate(patch, barycentricOf(d, r)).z());
    std::sort(depths.begin(), depths.end());
    return depths;
}

// The pleat g(u, v) = (u + alpha v^2, u v, +-v + ...) rotated in the image:
// its contour u = 2 alpha v^2 has a single cusp at uv = 0, image
// (3 alpha v^2, 2 alpha v^3) before rotation.
struct Pleat {
    double alpha = 0.8, angle = 0.7, depthSign = 1.0;
    Vec2 shift = Vec2(0.2, -0.1);
    Vec3 operator()(const Vec2& uv) const {
        const double u = uv.x(), v = uv.y();
        const Vec2 xy(u + alpha * v * v, u * v);
        const Eigen::Rotation2Dd r(angle);
        const Vec2 im = r * xy + shift;
        return Vec3(im.x(), im.y(), depthSign * v + 0.3 * u * u - 0.2 * u * v + 0.1);
    }
};

const std::array<Vec2, 3> kPleatDomain = {Vec2(-0.6, -0.5), Vec2(0.7, -0.4), Vec2(-0.1, 0.8)};

// A torus (radii 1, 0.4) from a grid of n x m quads, its flat metric the
// rectangle [0, n] x [0, m aspect], cut along two loops, rotated by `tilt`
// about x so that the view along z grazes the inner side.
ConeLayout tiltedTorus(int n, int m, double aspect, double tilt) {
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(tilt, Vec3::UnitX()).toRotationMatrix();
    return contour::testing::flatTorusLayout(n, m, aspect, [&rot](double s, double t) {
        return Vec3(rot * Vec3((1.0 + 0.4 * std::cos(t)) * std::cos(s),
                               (1.0 + 0.4 * std::cos(t)) * std::sin(s), 0.4 * std::sin(t)));
    });
}

// Fitted splines of the tilted torus, built once per tilt.
const PowellSabinSpline& torusSpline(double tilt = 1.25) {
    static std::map<double, PowellSabinSpline> cache;
    auto it = cache.find(tilt);
    if (it == cache.end()) {
        const ConeLayout layout = tiltedTorus(16, 8, 0.8, tilt);
        const ThinPlateFit fit(layout);
        it = cache.emplace(tilt, fit.fit(layout.mesh.positions())).first;
    }
    return it->second;
}

} // namespace

class TestPsSolvers : public QObject {
    Q_OBJECT
private slots:
    void conicsThroughFourPoints() {
        // Two distinct members of the pencil spanned by the line pairs
        // (P0P1, P2P3) and (P0P2, P1P3) meet exactly in P0..P3.
        Rng rng;
        double worst = 0.0;
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<Vec2> p;
            for (int i = 0; i < 4; ++i)
                p.push_back(rng.point(2.0));
            const Matrix3d a = linePair(lineThrough(p[0], p[1]), lineThrough(p[2], p[3]));
            const Matrix3d b = linePair(lineThrough(p[0], p[2]), lineThrough(p[1], p[3]));
            const double s = rng.uniform(-2, 2), t = rng.uniform(-2, 2);
            const Matrix3d m1 = a + s * b, m2 = a + t * b;
            const ConicIntersection x = intersectConics(m1, m2);
            QVERIFY(!x.sharedConic && x.sharedLines.empty());
            // Nearly collinear triples make the members nearly share a line:
            // still exact to the conditioning, checked loosely there.
            QVERIFY2(samePoints(x.points, p, 1e-6), qPrintable(describe(x.points)));
            for (const Vec2& q : p)
                for (const Vec2& g : x.points)
                    if ((g - q).norm() < 1e-6)
                        worst = std::max(worst, (g - q).norm());
        }
        qInfo("four chosen points, 300 random pairs: worst point error %.3g", worst);
        QVERIFY(worst < 1e-6);
    }

    void randomConicsAgainstNewton() {
        // Random conic pairs of every type against Newton's method started
        // from a grid of seeds: the same real points in the box [-2, 2]^2.
        Rng rng;
        int total = 0;
        for (int trial = 0; trial < 300; ++trial) {
            std::array<Matrix3d, 2> m;
            for (Matrix3d& c : m) {
                c = conicMatrix(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1),
                                rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.5, 0.5));
            }
            auto value = [&](int k, const Vec2& p) {
                const Vector3d x(p.x(), p.y(), 1.0);
                return x.dot(m[k] * x);
            };
            std::vector<Vec2> want;
            bool nearEdge = false;
            for (int i = 0; i <= 30; ++i)
                for (int j = 0; j <= 30; ++j) {
                    Vec2 p(-3.0 + 0.2 * i, -3.0 + 0.2 * j);
                    for (int it = 0; it < 60; ++it) {
                        const Vector3d x(p.x(), p.y(), 1.0);
                        Eigen::Matrix2d jac;
                        jac.row(0) = 2.0 * (m[0] * x).head<2>().transpose();
                        jac.row(1) = 2.0 * (m[1] * x).head<2>().transpose();
                        p -= jac.partialPivLu().solve(Vec2(value(0, p), value(1, p)));
                        if (!p.allFinite() || p.norm() > 100)
                            break;
                    }
                    if (!p.allFinite() || std::abs(value(0, p)) + std::abs(value(1, p)) > 1e-13)
                        continue;
                    if (p.cwiseAbs().maxCoeff() > 2.0) {
                        nearEdge = nearEdge || p.cwiseAbs().maxCoeff() < 2.01;
                        continue;
                    }
                    if (std::none_of(want.begin(), want.end(),
                                     [&](const Vec2& q) { return (q - p).norm() < 1e-8; }))
                        want.push_back(p);
                }
            if (nearEdge)
                continue;
            const ConicIntersection x = intersectConics(m[0], m[1]);
            std::vector<Vec2> got;
            for (const Vec2& p : x.points)
                if (p.cwiseAbs().maxCoeff() <= 2.0)
                    got.push_back(p);
            QVERIFY2(samePoints(got, want, 1e-9),
                     qPrintable(describe(got) + " vs " + describe(want)));
            total += int(want.size());
        }
        qInfo("random conic pairs: %d points in the box matched", total);
        QVERIFY(total > 200);
    }

    void conicsWithComplexPoints() {
        // Pencils through complex conjugate points: members through P0, P1,
        // Q, conj(Q) (two real points) and Q1, Q2 and conjugates (none),
        // built from line pairs whose sums with their conjugates are real.
        Rng rng;
        using C3 = Eigen::Vector3cd;
        auto cpoint = [&](double r) {
            return C3(std::complex<double>(rng.uniform(-r, r), rng.uniform(-r, r)),
                      std::complex<double>(rng.uniform(-r, r), rng.uniform(-r, r)), 1.0);
        };
        auto real = [](const Vec2& p) {
            return C3(p.x(), p.y(), 1.0);
        };
        auto pair = [](const C3& l, const C3& m) -> Eigen::Matrix3cd {
            return l * m.transpose() + m * l.transpose();
        };
        for (int trial = 0; trial < 200; ++trial) {
            const Vec2 p0 = rng.point(2), p1 = rng.point(2);
            const C3 q = cpoint(2), qc = q.conjugate();
            const Matrix3d a = pair(real(p0).cross(real(p1)), q.cross(qc)).imag();
            const Matrix3d b = pair(real(p0).cross(q), real(p1).cross(qc)).real();
            const double s = rng.uniform(-2, 2), t = rng.uniform(-2, 2);
            const ConicIntersection x =
                intersectConics(a / a.norm() + s * b / b.norm(), a / a.norm() + t * b / b.norm());
            QVERIFY2(samePoints(x.points, {p0, p1}, 1e-8), qPrintable(describe(x.points)));

            const C3 q1 = cpoint(2), q2 = cpoint(2);
            const Matrix3d c = pair(q1.cross(q1.conjugate()), q2.cross(q2.conjugate())).real();
            const Matrix3d d = pair(q1.cross(q2), q1.conjugate().cross(q2.conjugate())).real();
            const ConicIntersection y =
                intersectConics(c / c.norm() + s * d / d.norm(), c / c.norm() + t * d / d.norm());
            QVERIFY2(y.points.empty(), qPrintable(describe(y.points)));
        }
    }

    void conicsTwoRealPoints() {
        // Circles meet in two finite points (the other two are the circular
        // points at infinity), here moved by random affine maps.
        Rng rng;
        for (int trial = 0; trial < 50; ++trial) {
            const Matrix3d h = randomAffine(rng);
            const Matrix3d c1 = conicMatrix(1, 0, 1, 0, 0, -1); // unit circle
            const Matrix3d c2 = conicMatrix(1, 0, 1, -4, 0, 0); // (x - 2)^2 + y^2 = 4
            const std::vector<Vec2> want = {apply(h, Vec2(0.25, std::sqrt(15.0) / 4)),
                                            apply(h, Vec2(0.25, -std::sqrt(15.0) / 4))};
            const ConicIntersection x = intersectConics(moved(c1, h), moved(c2, h));
            QVERIFY2(samePoints(x.points, want, 1e-10), qPrintable(describe(x.points)));
        }
    }

    void conicsTangency() {
        Rng rng;
        for (int trial = 0; trial < 50; ++trial) {
            const Matrix3d h = randomAffine(rng);
            // Circles touching externally at (1, 0).
            ConicIntersection x = intersectConics(moved(conicMatrix(1, 0, 1, 0, 0, -1), h),
                                                  moved(conicMatrix(1, 0, 1, -6, 0, 5), h));
            QVERIFY2(samePoints(x.points, {apply(h, Vec2(1, 0))}, 1e-6),
                     qPrintable(describe(x.points)));
            // Circle and parabola y = x^2 - 1: tangent at (0, -1), crossing at (+-1, 0).
            x = intersectConics(moved(conicMatrix(1, 0, 1, 0, 0, -1), h),
                                moved(conicMatrix(1, 0, 0, 0, -1, -1), h));
            QVERIFY2(
                samePoints(x.points,
                           {apply(h, Vec2(0, -1)), apply(h, Vec2(1, 0)), apply(h, Vec2(-1, 0))},
                           1e-6),
                qPrintable(describe(x.points)));
            // Double contact: circle and ellipse x^2 + y^2 / 4 = 1 touch at
            // (+-1, 0); the pencil's degenerate member is the double line y = 0.
            x = intersectConics(moved(conicMatrix(1, 0, 1, 0, 0, -1), h),
                                moved(conicMatrix(1, 0, 0.25, 0, 0, -1), h));
            QVERIFY2(samePoints(x.points, {apply(h, Vec2(1, 0)), apply(h, Vec2(-1, 0))}, 1e-6),
                     qPrintable(describe(x.points)));
            // A line tangent to a circle.
            x = intersectConics(moved(conicMatrix(1, 0, 1, 0, 0, -1), h),
                                moved(conicMatrix(0, 0, 0, 0, 1, -1), h));
            QVERIFY2(samePoints(x.points, {apply(h, Vec2(0, 1))}, 1e-6),
                     qPrintable(describe(x.points)));
        }
    }

    void conicsWithoutRealPoints() {
        Rng rng;
        for (int trial = 0; trial < 50; ++trial) {
            const Matrix3d h = randomAffine(rng);
            // Disjoint circles, nested ellipses, a line missing a circle,
            // parabolas y = x^2 and y = x^2 + 1 and concentric circles (both
            // pairs meet only at infinity).
            const std::array<std::pair<Matrix3d, Matrix3d>, 5> pairs = {
                {{conicMatrix(1, 0, 1, 0, 0, -1), conicMatrix(1, 0, 1, -10, 0, 24)},
                 {conicMatrix(1, 0, 1, 0, 0, -1), conicMatrix(1, 0, 1, 0, 0, -4)},
                 {conicMatrix(1, 0, 1, 0, 0, -4), conicMatrix(0.5, 0, 1, 0, 0, -1)},
                 {conicMatrix(1, 0, 1, 0, 0, -1), conicMatrix(0, 0, 0, 0, 1, -1.5)},
                 {conicMatrix(1, 0, 0, 0, -1, 0), conicMatrix(1, 0, 0, 0, -1, 1)}}};
            for (const auto& [a, b] : pairs) {
                const ConicIntersection x = intersectConics(moved(a, h), moved(b, h));
                QVERIFY2(x.points.empty(), qPrintable(describe(x.points)));
                QVERIFY(!x.sharedConic && x.sharedLines.empty());
            }
        }
    }

    void degenerateConics() {
        // Lines given as conics (zero quadratic part): crossing, parallel, equal.
        ConicIntersection x =
            intersectConics(conicMatrix(0, 0, 0, 1, 1, -1), conicMatrix(0, 0, 0, 1, -1, 0));
        QVERIFY2(samePoints(x.points, {Vec2(0.5, 0.5)}, 1e-12), qPrintable(describe(x.points)));
        QVERIFY(x.sharedLines.empty()); // the line at infinity does not count
        x = intersectConics(conicMatrix(0, 0, 0, 1, 1, -1), conicMatrix(0, 0, 0, 2, 2, 3));
        QVERIFY(x.points.empty() && x.sharedLines.empty() && !x.sharedConic);
        x = intersectConics(conicMatrix(0, 0, 0, 1, 1, -1), conicMatrix(0, 0, 0, -3, -3, 3));
        QVERIFY(x.sharedConic && x.points.empty());
        // A conic and a scaled copy; a zero conic.
        x = intersectConics(conicMatrix(1, 0.3, 2, 0.1, 0, -1),
                            conicMatrix(-2, -0.6, -4, -0.2, 0, 2));
        QVERIFY(x.sharedConic);
        x = intersectConics(Matrix3d::Zero(), conicMatrix(1, 0, 1, 0, 0, -1));
        QVERIFY(x.sharedConic);
        // Line pairs sharing the line y = 0: the shared line and the crossing
        // of the others, (1, 1).
        const Vector3d l(0, 1, 0);
        x = intersectConics(linePair(l, Vector3d(1, 0, -1)), linePair(l, Vector3d(1, -1, 0)));
        QCOMPARE(x.sharedLines.size(), std::size_t(1));
        QVERIFY(std::abs(std::abs(x.sharedLines[0].dot(l)) - 1.0) < 1e-12);
        QVERIFY(std::any_of(x.points.begin(), x.points.end(),
                            [](const Vec2& p) { return (p - Vec2(1, 1)).norm() < 1e-12; }));
        // A line through a circle; a line pair through a circle.
        x = intersectConics(conicMatrix(1, 0, 1, 0, 0, -1), conicMatrix(0, 0, 0, 1, 0, 0));
        QVERIFY(samePoints(x.points, {Vec2(0, 1), Vec2(0, -1)}, 1e-12));
        x = intersectConics(conicMatrix(1, 0, 1, 0, 0, -1), conicMatrix(1, 0, -1, 0, 0, 0));
        const double r = std::sqrt(0.5);
        QVERIFY(samePoints(x.points, {Vec2(r, r), Vec2(r, -r), Vec2(-r, r), Vec2(-r, -r)}, 1e-12));
        // Two double lines u^2 = 0 and v^2 = 0: the single point (0, 0).
        x = intersectConics(conicMatrix(1, 0, 0, 0, 0, 0), conicMatrix(0, 0, 1, 0, 0, 0));
        QVERIFY2(samePoints(x.points, {Vec2(0, 0)}, 1e-12), qPrintable(describe(x.points)));
        // The point conic x^2 + y^2 = 0 with a circle through the origin.
        x = intersectConics(conicMatrix(1, 0, 1, 0, 0, 0), conicMatrix(1, 0, 1, -2, 0, 0));
        QVERIFY2(samePoints(x.points, {Vec2(0, 0)}, 1e-8), qPrintable(describe(x.points)));
        // Bad input.
        Matrix3d bad = conicMatrix(1, 0, 1, 0, 0, -1);
        bad(0, 1) = 3.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, intersectConics(bad, bad.transpose()));
        bad = conicMatrix(1, 0, 1, 0, 0, std::nan(""));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 intersectConics(bad, conicMatrix(1, 0, 0, 0, 0, -1)));
    }

    void pleatCusp() {
        for (const double sign : {1.0, -1.0}) {
            Pleat g;
            g.depthSign = sign;
            const QuadraticBezier<Vec3> patch = patchOf(kPleatDomain, g);
            const PatchCuspResult r = patchCusps(patch, Vec3::UnitZ());
            QVERIFY(!r.degenerate);
            QCOMPARE(r.cusps.size(), std::size_t(1));
            const PatchCusp& c = r.cusps[0];
            QVERIFY2(c.uv.norm() < 1e-12, qPrintable(QString::number(c.uv.norm())));
            QVERIFY((c.position - g(Vec2(0, 0))).norm() < 1e-12);
            QVERIFY((c.barycentric - barycentricOf(kPleatDomain, c.uv)).norm() < 1e-12);
            // t parallel to tau, T = (4 alpha v, 1) = (0, 1) at the cusp.
            QVERIFY(c.tangent.head<2>().norm() < 1e-12 * c.tangent.norm());
            QVERIFY((c.domainTangent.normalized() - Vec2(0, 1)).norm() < 1e-12);
            // Depth +-v grows along T iff sign > 0.
            QCOMPARE(c.qiIncreasesAlongDomainTangent, sign > 0);
            // Image (3 alpha v^2, 2 alpha v^3) rotated: axis along the rotated
            // +x, the far branch (v sign > 0) on the side of rotated +-y.
            const Eigen::Rotation2Dd rot(g.angle);
            QVERIFY((c.imageAxis - rot * Vec2(1, 0)).norm() < 1e-9);
            QVERIFY((c.farSide - sign * (rot * Vec2(0, 1))).norm() < 1e-9);

            // Dense sampling: the image tangent vanishes at the cusp and
            // nowhere else on the contour inside the patch.
            const Probe probe{patch};
            QVERIFY(probe.imageRatio(c.uv) < 1e-8);
            const ContourSample s = sampleContour(probe, 300);
            QVERIFY(s.points.size() > 200);
            double minAway = 1e300;
            for (const Vec2& q : s.points)
                if ((q - c.uv).norm() > 0.02)
                    minAway = std::min(minAway, probe.imageRatio(q));
            QVERIFY2(minAway > 1e-3, qPrintable(QString::number(minAway)));
            QCOMPARE(s.reversals.size(), std::size_t(1));
            QVERIFY((s.reversals[0] - c.uv).norm() < 0.01);

            // QI rule by ray counts within the patch: a contour point on the
            // far branch has one patch sheet in front, one on the near branch
            // none; the far branch lies on the farSide of the axis.
            const Vec2 imageCusp = c.position.head<2>();
            int farCount = 0, nearCount = 0;
            for (const Vec2& q : s.points) {
                const double d = (q - c.uv).norm();
                if (d < 0.05 || d > 0.15)
                    continue;
                const Vec3 x = probe.position(q);
                const bool far =
                    ((q - c.uv).dot(c.domainTangent) > 0) == c.qiIncreasesAlongDomainTangent;
                const int inFront = hitsInFront(patch, Vec3::UnitZ(), x.head<2>(), x.z());
                // The ray touches the surface at the contour point: a hit there.
                const PatchRayHits hits = rayPatchIntersections(patch, Vec3::UnitZ(), x.head<2>());
                QVERIFY(std::any_of(hits.hits.begin(), hits.hits.end(), [&](const RayHit& hit) {
                    return std::abs(hit.depth - x.z()) < 1e-6;
                }));
                QCOMPARE(inFront, far ? 1 : 0);
                QVERIFY(((x.head<2>() - imageCusp).dot(c.farSide) > 0) == far);
                (far ? farCount : nearCount)++;
            }
            QVERIFY(farCount > 5 && nearCount > 5);
        }
    }

    void spuriousCriticalPointIsNoCusp() {
        // p = (u^2, v^2, u + v): tau . n = 4 u v, a crossing of two contour
        // lines at uv = 0 where t = 0 solves eq. 6; it is not a cusp.
        const QuadraticBezier<Vec3> patch =
            patchOf({Vec2(-0.5, -0.4), Vec2(0.6, -0.3), Vec2(0.0, 0.7)}, [](const Vec2& uv) {
                return Vec3(uv.x() * uv.x(), uv.y() * uv.y(), uv.sum());
            });
        const PatchCuspResult r = patchCusps(patch, Vec3::UnitZ());
        QVERIFY(r.cusps.empty());
        QVERIFY(!r.degenerate);
        // A plane: no contour, no cusps; seen edge-on: degenerate.
        const auto plane = [](const Vec2& uv) {
            return Vec3(uv.x(), uv.y(), 0.3 * uv.x());
        };
        QVERIFY(patchCusps(patchOf(kPleatDomain, plane), Vec3::UnitZ()).cusps.empty());
        QVERIFY(!patchCusps(patchOf(kPleatDomain, plane), Vec3::UnitZ()).degenerate);
        const auto edgeOn = [](const Vec2& uv) {
            return Vec3(uv.x(), 0.5 * uv.x(), uv.y());
        };
        QVERIFY(patchCusps(patchOf(kPleatDomain, edgeOn), Vec3::UnitZ()).degenerate);
        // The edge-on plane's image is a line: a ray through it lies in the surface.
        const PatchRayHits h =
            rayPatchIntersections(patchOf(kPleatDomain, edgeOn), Vec3::UnitZ(), Vec2(0.1, 0.05));
        QVERIFY(h.rayInSurface);
        QVERIFY_THROWS_EXCEPTION(
            std::runtime_error,
            hitsInFront(patchOf(kPleatDomain, edgeOn), Vec3::UnitZ(), Vec2(0.1, 0.05), 1.0));
        QVERIFY(rayPatchIntersections(patchOf(kPleatDomain, edgeOn), Vec3::UnitZ(), Vec2(0.1, 0.2))
                    .hits.empty());
        QuadraticBezier<Vec3> bad = patch;
        bad.control[2].x() = std::nan("");
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, patchCusps(bad, Vec3::UnitZ()));
    }

    void boundaryCusp() {
        // At a contour point n is perpendicular to tau; tau . (n x t) is the
        // image tangent's component across the projected normal.
        const Vec3 n(1, 0, 0), tau(0, 0, 1);
        QVERIFY(isBoundaryCusp(n, Vec3(0, 1, 0.3), Vec3(0, -1, 0.3), tau));
        QVERIFY(!isBoundaryCusp(n, Vec3(0, 1, 0.3), Vec3(0, 2, -0.5), tau));
        QVERIFY(!isBoundaryCusp(n, Vec3(0, 0, 1), Vec3(0, -1, 0.3), tau)); // zero: not decided
        // Chart independence of eq. 5's t: the pleat over a rotated and
        // shifted face uv has the same tangent at the same point.
        const Pleat g;
        const QuadraticBezier<Vec3> a = patchOf(kPleatDomain, g);
        const Eigen::Rotation2Dd rot(1.1);
        std::array<Vec2, 3> moved;
        for (int i = 0; i < 3; ++i)
            moved[i] = rot * kPleatDomain[i] + Vec2(3, -2);
        const QuadraticBezier<Vec3> b =
            patchOf(moved, [&](const Vec2& uv) { return g(rot.inverse() * (uv - Vec2(3, -2))); });
        const PatchCuspResult ra = patchCusps(a, tau), rb = patchCusps(b, tau);
        QCOMPARE(rb.cusps.size(), std::size_t(1));
        QVERIFY((ra.cusps[0].tangent - rb.cusps[0].tangent).norm() < 1e-10);
        QVERIFY((ra.cusps[0].position - rb.cusps[0].position).norm() < 1e-12);
    }

    void torusCusps_data() {
        // The view's angle to the torus' axis, and the fewest cusps the view
        // must show (the exact count depends on the fit; it is checked
        // against dense sampling).
        QTest::addColumn<double>("tilt");
        QTest::addColumn<int>("cusps");
        QTest::newRow("tilt 1.00") << 1.0 << 0;
        QTest::newRow("tilt 1.25") << 1.25 << 2;
        QTest::newRow("tilt 1.45") << 1.45 << 2;
    }

    void torusCusps() {
        QFETCH(double, tilt);
        QFETCH(int, cusps);
        const PowellSabinSpline& spline = torusSpline(tilt);
        const Vec3 tau = Vec3::UnitZ();
        // Solve every patch, timed.
        std::vector<PatchCuspResult> results(spline.patches.size());
        QElapsedTimer timer;
        timer.start();
        for (std::size_t i = 0; i < spline.patches.size(); ++i)
            results[i] = patchCusps(spline.patches[i], tau);
        const double ns = double(timer.nsecsElapsed()) / double(spline.patches.size());
        qInfo("patchCusps: %zu patches, %.2f us per patch", spline.patches.size(), ns * 1e-3);

        int found = 0, sampled = 0, boundaryOnly = 0, qiChecked = 0;
        std::vector<std::size_t> withContour;
        double worstRatio = 0.0;
        for (std::size_t i = 0; i < spline.patches.size(); ++i) {
            const QuadraticBezier<Vec3>& patch = spline.patches[i];
            QVERIFY(!results[i].degenerate);
            const Probe probe{patch};
            for (const PatchCusp& c : results[i].cusps) {
                worstRatio = std::max(worstRatio, probe.imageRatio(c.uv));
                QVERIFY(std::abs(probe.f(c.uv)) < 1e-8 * probe.normal(c.uv).norm());
            }
            const ContourSample s = sampleContour(probe, 40);
            if (!s.points.empty())
                withContour.push_back(i);
            found += int(results[i].cusps.size());
            sampled += int(s.reversals.size());
            // Each sampled reversal is near a returned cusp and vice versa,
            // except within a grid step of the patch's boundary.
            const double step = probe.size() / 40;
            auto nearBoundary = [&](const Vec2& uv) {
                const Vec3 w = barycentricOf(patch.domain, uv);
                return w.minCoeff() < 2.0 / 40;
            };
            for (const Vec2& q : s.reversals) {
                const bool matched =
                    std::any_of(results[i].cusps.begin(), results[i].cusps.end(),
                                [&](const PatchCusp& c) { return (c.uv - q).norm() < 2 * step; });
                if (!matched) {
                    QVERIFY2(nearBoundary(q), qPrintable(QString("patch %1").arg(i)));
                    ++boundaryOnly;
                }
            }
            // QI rule on the whole spline: contour points near the cusp on its
            // far branch have one more occluder than those on its near branch,
            // and lie on the farSide of the image axis.
            for (const PatchCusp& c : results[i].cusps) {
                std::array<std::vector<int>, 2> qi; // near, far
                // Stay inside the patch: the cusp's distance to the domain's
                // sides, relative to the patch size.
                double reach = 1e300;
                for (int e = 0; e < 3; ++e) {
                    const Vec2 a = patch.domain[e], b = patch.domain[(e + 1) % 3];
                    const Vec2 d = (b - a).normalized();
                    reach =
                        std::min(reach, std::abs(d.x() * (c.uv - a).y() - d.y() * (c.uv - a).x()));
                }
                reach /= probe.size();
                for (const double sigma : {-1.0, 1.0}) {
                    const bool far = (sigma > 0) == c.qiIncreasesAlongDomainTangent;
                    const std::vector<Vec2> trace =
                        probe.traceContour(c.uv, sigma, std::min(0.1, 0.9 * reach), 10);
                    // The rule is local: farther along, the branches may cross
                    // other contours in the image (QI +-2; one does at tilt
                    // 1.45, confirmed by dense sampling) or meet other cusps.
                    for (std::size_t k = 3; k < std::min<std::size_t>(trace.size(), 5); ++k) {
                        const Vec3 x = probe.position(trace[k]);
                        qi[far].push_back(hitsInFront(spline, tau, x.head<2>(), x.z()));
                        QVERIFY(((x - c.position).head<2>().dot(c.farSide) > 0) == far);
                    }
                }
                if (qi[0].empty() || qi[1].empty())
                    continue;
                for (int v : qi[0])
                    QCOMPARE(v, qi[0][0]);
                for (int v : qi[1])
                    QCOMPARE(v, qi[0][0] + 1);
                ++qiChecked;
            }
            for (const PatchCusp& c : results[i].cusps) {
                const bool matched =
                    std::any_of(s.reversals.begin(), s.reversals.end(),
                                [&](const Vec2& q) { return (c.uv - q).norm() < 2 * step; });
                if (!matched) {
                    QVERIFY2(nearBoundary(c.uv), qPrintable(QString("patch %1").arg(i)));
                    ++boundaryOnly;
                }
            }
        }
        qInfo("torus: %d cusps returned, %d found by dense sampling, %d unmatched within a grid "
              "step of a patch edge, worst |image tangent| / |t| at a cusp %.3g",
              found, sampled, boundaryOnly, worstRatio);
        QVERIFY(found >= cusps);
        qInfo("QI +1 from the near to the far branch checked by spline ray counts at %d of %d "
              "cusps",
              qiChecked, found);
        QVERIFY(qiChecked >= found / 2);
        QVERIFY(std::abs(found - sampled) <= boundaryOnly);
        // The solve proper, on the patches the contour crosses.
        timer.restart();
        std::size_t total = 0;
        for (int rep = 0; rep < 20; ++rep)
            for (std::size_t i : withContour)
                total += patchCusps(spline.patches[i], tau).cusps.size();
        qInfo("patchCusps on the %zu patches with contour: %.2f us per patch", withContour.size(),
              double(timer.nsecsElapsed()) * 1e-3 / double(20 * withContour.size()));
        QCOMPARE(total, std::size_t(20 * found));
        QVERIFY(worstRatio < 1e-6);
    }

    void rayTestAgainstSampling() {
        Rng rng;
        const PowellSabinSpline& spline = torusSpline();
        // Hand-made folded patches and random patches of the torus.
        std::vector<QuadraticBezier<Vec3>> patches = {patchOf(kPleatDomain, Pleat{})};
        for (int i = 0; i < 40; ++i)
            patches.push_back(
                spline.patches[std::size_t(rng.uniform(0, double(spline.patches.size())))]);
        int rays = 0, skipped = 0, withHits = 0;
        double worst = 0.0;
        for (const QuadraticBezier<Vec3>& patch : patches) {
            Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
            for (const Vec3& c : patch.control) {
                lo = lo.cwiseMin(c.head<2>());
                hi = hi.cwiseMax(c.head<2>());
            }
            for (int k = 0; k < 12; ++k) {
                const Vec2 x(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
                bool nearFold = false;
                const std::vector<double> want = bruteForceDepths(patch, x, 60, nearFold);
                if (nearFold) {
                    ++skipped;
                    continue;
                }
                const PatchRayHits got = rayPatchIntersections(patch, Vec3::UnitZ(), x);
                QVERIFY(!got.rayInSurface);
                ++rays;
                QCOMPARE(got.hits.size(), want.size());
                if (want.empty())
                    continue;
                ++withHits;
                const double err = std::abs(got.hits[0].depth - want[0]);
                worst = std::max(worst, err);
                QVERIFY2(err < 1e-9, qPrintable(QString::number(err)));
                for (std::size_t h = 0; h < want.size(); ++h) {
                    QVERIFY(std::abs(got.hits[h].depth - want[h]) < 1e-9);
                    const Vec3 p = evaluate(patch, got.hits[h].barycentric);
                    QVERIFY((p.head<2>() - x).norm() < 1e-12);
                    QVERIFY((got.hits[h].barycentric - barycentricOf(patch.domain, got.hits[h].uv))
                                .norm() < 1e-12);
                }
                // Counting in front of a depth between the hits.
                const double mid = want.size() > 1 ? 0.5 * (want[0] + want[1]) : want[0] + 1.0;
                QCOMPARE(hitsInFront(patch, Vec3::UnitZ(), x, mid), 1);
                QCOMPARE(hitsInFront(patch, Vec3::UnitZ(), x, want[0] - 1e-3), 0);
            }
        }
        qInfo("ray tests: %d rays (%d with hits, %d skipped near a fold), worst closest-depth "
              "error %.3g",
              rays, withHits, skipped, worst);
        QVERIFY(withHits > 100);

        // Timing per patch call, on rays that pass the bounding box.
        std::vector<std::pair<std::size_t, Vec2>> queries;
        for (int k = 0; k < 20000; ++k) {
            const std::size_t i = std::size_t(rng.uniform(0, double(spline.patches.size())));
            const auto& c = spline.patches[i].control;
            const double a = rng.uniform(0, 1), b = rng.uniform(0, 1 - a);
            queries.push_back({i, Vec2(((1 - a - b) * c[0] + a * c[1] + b * c[2]).head<2>())});
        }
        QElapsedTimer timer;
        timer.start();
        std::size_t total = 0;
        for (const auto& [i, x] : queries)
            total += rayPatchIntersections(spline.patches[i], Vec3::UnitZ(), x).hits.size();
        const double ns = double(timer.nsecsElapsed()) / double(queries.size());
        qInfo("rayPatchIntersections: %.2f us per patch (%zu hits over %zu rays)", ns * 1e-3, total,
              queries.size());
        QVERIFY(total > 0);
    }

    void splineQi() {
        // The QI of points of the torus by hitsInFront over the whole spline:
        // a point seen from the front has QI 0 when nothing is in front of it
        // by dense sampling of every patch.
        const PowellSabinSpline& spline = torusSpline();
        Rng rng;
        int checked = 0, occluded = 0;
        for (int k = 0; k < 40; ++k) {
            const std::size_t i = std::size_t(rng.uniform(0, double(spline.patches.size())));
            const Vec3 w(0.3, 0.3, 0.4);
            const Vec3 p = spline.position(Index(i), w);
            int want = 0;
            for (const QuadraticBezier<Vec3>& patch : spline.patches) {
                Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
                for (const Vec3& c : patch.control) {
                    lo = lo.cwiseMin(c.head<2>());
                    hi = hi.cwiseMax(c.head<2>());
                }
                if ((p.head<2>().array() < lo.array() - 1e-9).any() ||
                    (p.head<2>().array() > hi.array() + 1e-9).any())
                    continue;
                bool nearFold = false;
                for (double d : bruteForceDepths(patch, p.head<2>(), 30, nearFold))
                    want += d < p.z() - 1e-7;
            }
            QCOMPARE(hitsInFront(spline, Vec3::UnitZ(), p.head<2>(), p.z()), want);
            ++checked;
            occluded += want > 0;
        }
        QCOMPARE(checked, 40);
        qInfo("spline QI: %d of 40 random surface points occluded", occluded);
        QVERIFY(occluded > 5);
    }
};

QTEST_GUILESS_MAIN(TestPsSolvers)
#include "test_ps_solvers.moc"
