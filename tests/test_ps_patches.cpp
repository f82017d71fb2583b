// The Powell-Sabin 12-split macro-patch (contours/powell_sabin/Ps12Patch.h,
// Capouellez et al. 2023 §5.2): the closed-form Bezier matrix against a dense
// solve of all C1 and interpolation conditions, quadratic precision,
// interpolation of the DOFs, C1 inside the macro-patch and across a shared
// (also rigidly moved) mesh edge, the piecewise linear cross-boundary
// derivative, invariance under similarity, and the spline's evaluation.
#include "contours/powell_sabin/PowellSabinSpline.h"
#include "contours/powell_sabin/Ps12Patch.h"

#include <Eigen/Dense>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

using Triangle2 = std::array<Vec2, 3>;
using Dofs = Eigen::Matrix<double, kPs12LocalDofs, 1>;
using Patches = std::array<QuadraticBezier<double>, kPs12Patches>;

// Portable uniform numbers: mt19937_64's output is fixed by the standard,
// std::uniform_real_distribution's is not.
struct Rng {
    std::mt19937_64 engine{20230805};
    double uniform(double a, double b) {
        return a + (b - a) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
    }
    Vec2 point(double r) { return Vec2(uniform(-r, r), uniform(-r, r)); }
};

double cross2(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

Vec2 rotate(const Vec2& v, double angle) {
    return Vec2(std::cos(angle) * v.x() - std::sin(angle) * v.y(),
                std::sin(angle) * v.x() + std::cos(angle) * v.y());
}

// Inward unit normal of side s (V_s -> V_{s+1}) of a CCW triangle.
Vec2 inwardNormal(const Triangle2& t, int s) {
    const Vec2 e = t[(s + 1) % 3] - t[s];
    return Vec2(-e.y(), e.x()) / e.norm();
}

// Fixed shapes (equilateral, right, obtuse up to 170 degrees, thin up to
// 1:200, needle) and random ones with random offsets, scales and rotations.
std::vector<Triangle2> testTriangles() {
    std::vector<Triangle2> t = {
        {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2)},
        {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)},
        {Vec2(0, 0), Vec2(2, 0),
         Vec2(1.0 + std::cos(std::numbers::pi * 5 / 6) * 0.3,
              std::sin(std::numbers::pi * 5 / 6) * 0.3)},
        {Vec2(0, 0), Vec2(1, 0), Vec2(-0.9, 0.15)},                 // 170-degree corner
        {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 0.01)},                  // thin, 1:100
        {Vec2(0, 0), Vec2(1, 0), Vec2(0.97, 0.005)},                // thin and obtuse
        {Vec2(3, -2), Vec2(3.004, -2.001), Vec2(2.0, 5.0)},         // needle
        {Vec2(100, 50), Vec2(100.02, 50.0), Vec2(100.01, 50.0001)}, // tiny, far, 1:200
    };
    Rng rng;
    while (t.size() < 40) {
        const double scale = std::pow(10.0, rng.uniform(-2, 1));
        const Vec2 offset = rng.point(20);
        Triangle2 tri = {offset + scale * rng.point(1), offset + scale * rng.point(1),
                         offset + scale * rng.point(1)};
        const double area2 = cross2(tri[1] - tri[0], tri[2] - tri[0]);
        const double diam = std::max(
            {(tri[1] - tri[0]).norm(), (tri[2] - tri[1]).norm(), (tri[0] - tri[2]).norm()});
        if (std::abs(area2) < 1e-3 * diam * diam)
            continue;
        if (area2 < 0)
            std::swap(tri[1], tri[2]);
        t.push_back(tri);
    }
    return t;
}

double diameter(const Triangle2& t) {
    return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
}

// Rounding of absolute uv coordinates: a triangle far from the origin
// compared to its size loses that ratio in relative precision.
double conditioning(const Triangle2& t) {
    const double far = std::max({t[0].norm(), t[1].norm(), t[2].norm()});
    return std::max(1.0, far / diameter(t));
}

// f = c0 + c1 u + c2 v + c3 u^2 + c4 u v + c5 v^2 around `center`.
struct Quadratic {
    std::array<double, 6> c{};
    Vec2 center = Vec2::Zero();
    double value(const Vec2& x) const {
        const Vec2 d = x - center;
        return c[0] + c[1] * d.x() + c[2] * d.y() + c[3] * d.x() * d.x() + c[4] * d.x() * d.y() +
               c[5] * d.y() * d.y();
    }
    Vec2 gradient(const Vec2& x) const {
        const Vec2 d = x - center;
        return Vec2(c[1] + 2 * c[3] * d.x() + c[4] * d.y(), c[2] + c[4] * d.x() + 2 * c[5] * d.y());
    }
};

Dofs dofsOf(const Quadratic& f, const Triangle2& t) {
    Dofs q;
    for (int i = 0; i < 3; ++i) {
        q(3 * i) = f.value(t[i]);
        q.segment<2>(3 * i + 1) = f.gradient(t[i]);
        q(9 + i) = f.gradient(0.5 * (t[i] + t[(i + 1) % 3])).dot(inwardNormal(t, i));
    }
    return q;
}

Dofs randomDofs(Rng& rng) {
    Dofs q;
    for (int k = 0; k < kPs12LocalDofs; ++k)
        q(k) = rng.uniform(-1, 1);
    return q;
}

Patches patchesOf(const Triangle2& t, const Dofs& q) {
    const Ps12Matrix b = ps12BezierMatrix(t);
    const auto sub = ps12SubTriangles(t);
    const Eigen::Matrix<double, 6 * kPs12Patches, 1> ordinates = b * q;
    Patches p;
    for (int l = 0; l < kPs12Patches; ++l) {
        p[l].domain = sub[l];
        for (int c = 0; c < 6; ++c)
            p[l].control[c] = ordinates(6 * l + c);
    }
    return p;
}

Vec3 randomBarycentric(Rng& rng) {
    double a = rng.uniform(0, 1);
    double b = rng.uniform(0, 1);
    if (a + b > 1) {
        a = 1 - a;
        b = 1 - b;
    }
    return Vec3(1 - a - b, a, b);
}

struct Sample {
    double value = 0;
    Vec2 gradient = Vec2::Zero();
};

Sample sampleOf(const QuadraticBezier<double>& p, const Vec3& w) {
    Sample s;
    s.value = evaluate(p, w);
    uvDerivatives(p, w, s.gradient.x(), s.gradient.y());
    return s;
}

// The macro-patch at a uv point of its triangle: the sub-triangle that
// contains it best (largest smallest barycentric coordinate).
Sample sampleAt(const Patches& p, const Vec2& uv) {
    int best = 0;
    double bestMin = -1e300;
    Vec3 bestW;
    for (int l = 0; l < kPs12Patches; ++l) {
        const Vec3 w = barycentricOf(p[l].domain, uv);
        if (w.minCoeff() > bestMin) {
            bestMin = w.minCoeff();
            best = l;
            bestW = w;
        }
    }
    return sampleOf(p[best], bestW);
}

// Largest magnitude of the ordinates and of the derivative scale
// (ordinates over the smallest sub-triangle height): tolerances are relative
// to what the patches can produce.
struct Scales {
    double value = 0;
    double derivative = 0;
    double second = 0;
};

Scales scalesOf(const Patches& p) {
    Scales s;
    double minHeight = 1e300;
    for (const auto& patch : p) {
        for (double b : patch.control)
            s.value = std::max(s.value, std::abs(b));
        const Triangle2& d = patch.domain;
        const double area2 = cross2(d[1] - d[0], d[2] - d[0]);
        minHeight = std::min(minHeight, area2 / diameter(d));
    }
    s.value = std::max(s.value, 1e-300);
    s.derivative = s.value / minHeight;
    s.second = s.derivative / minHeight;
    return s;
}

// The worst error of a check over many samples, relative to its tolerance,
// with the triangle it happened on.
struct Worst {
    double ratio = 0;
    double error = 0;
    int triangle = -1;
    void add(double error_, double tolerance, int triangle_) {
        const double r = error_ / tolerance;
        if (!(r <= ratio)) { // also catches NaN
            ratio = std::isnan(r) ? 1e300 : r;
            error = error_;
            triangle = triangle_;
        }
    }
    bool ok() const { return ratio <= 1.0; }
    QString message(const char* what) const {
        return QString("%1: worst error %2 on triangle %3, %4 times the tolerance")
            .arg(what)
            .arg(error, 0, 'g', 3)
            .arg(triangle)
            .arg(ratio, 0, 'g', 3);
    }
};
#define CHECK_WORST(w, what)                                                                       \
    do {                                                                                           \
        qInfo("%s", qPrintable((w).message(what)));                                                \
        QVERIFY2((w).ok(), qPrintable((w).message(what)));                                         \
    } while (false)

bool sameSplitPoint(const Vec2& a, const Vec2& b) {
    return a == b;
}

// --- The reference: all 72 ordinates as unknowns, solved densely. ---------

// The uv gradient at corner k of patch l as two linear forms on the 72
// ordinates: grad . (X - P_k) = 2 (b_kX - b_k) along both sides from P_k.
Eigen::Matrix<double, 2, 72> cornerGradient(const std::array<Triangle2, 12>& sub, int l, int k) {
    const int k1 = (k + 1) % 3;
    const int k2 = (k + 2) % 3;
    const int edge1 = 3 + k;  // side k -> k1
    const int edge2 = 3 + k2; // side k2 -> k
    Eigen::Matrix2d dirs;
    dirs.row(0) = (sub[l][k1] - sub[l][k]).transpose();
    dirs.row(1) = (sub[l][k2] - sub[l][k]).transpose();
    Eigen::Matrix<double, 2, 72> along = Eigen::Matrix<double, 2, 72>::Zero();
    along(0, 6 * l + edge1) = 2;
    along(0, 6 * l + k) = -2;
    along(1, 6 * l + edge2) = 2;
    along(1, 6 * l + k) = -2;
    return dirs.inverse() * along;
}

// Index of the ordinate of patch l at the domain point between corners a
// and b of its domain (a == b: the corner).
int ordinateIndex(int l, int a, int b) {
    if (a == b)
        return 6 * l + a;
    if (b == (a + 1) % 3)
        return 6 * l + 3 + a;
    return 6 * l + 3 + b;
}

int cornerAt(const Triangle2& t, const Vec2& x) {
    for (int k = 0; k < 3; ++k)
        if (sameSplitPoint(t[k], x))
            return k;
    return -1;
}

struct ReferenceSolve {
    Eigen::MatrixXd ordinates; // 72 x 12
    Eigen::Index rank = 0;
    double residual = 0;
    int interiorEdges = 0;
    int identicalPatches = 0;
};

ReferenceSolve referenceSolve(const Triangle2& t) {
    const auto sub = ps12SubTriangles(t);
    std::vector<Eigen::RowVectorXd> rows;
    std::vector<Eigen::RowVectorXd> rhs;
    auto add = [&](const Eigen::RowVectorXd& row, const Eigen::RowVectorXd& r) {
        rows.push_back(row);
        rhs.push_back(r);
    };
    const Eigen::RowVectorXd zero = Eigen::RowVectorXd::Zero(12);
    ReferenceSolve out;
    // Shared ordinates and C1 across shared sub-edges.
    for (int l = 0; l < 12; ++l)
        for (int n = l + 1; n < 12; ++n) {
            std::array<int, 3> inN{};
            int shared = 0;
            for (int k = 0; k < 3; ++k) {
                inN[k] = cornerAt(sub[n], sub[l][k]);
                if (inN[k] >= 0) {
                    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(72);
                    row(6 * l + k) = 1;
                    row(6 * n + inN[k]) = -1;
                    add(row, zero);
                    ++shared;
                }
            }
            if (shared < 2)
                continue;
            if (shared == 3) {
                ++out.identicalPatches;
                continue;
            }
            ++out.interiorEdges;
            int x = 0;
            while (inN[x] < 0)
                ++x;
            int y = x + 1;
            while (inN[y] < 0)
                ++y;
            const int z = 3 - x - y;
            const int w = 3 - inN[x] - inN[y]; // apex of patch n
            Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(72);
            row(ordinateIndex(n, inN[x], inN[y])) = 1;
            row(ordinateIndex(l, x, y)) = -1;
            add(row, zero);
            // C1: with lambda the barycentrics of n's apex in l, both
            // ordinates of n next to the edge are the affine images of l's.
            const Vec3 lambda = barycentricOf(sub[l], sub[n][w]);
            for (int end : {x, y}) {
                const int other = end == x ? y : x;
                Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(72);
                c(ordinateIndex(n, inN[end], w)) = 1;
                c(ordinateIndex(l, end, end)) -= lambda(end);
                c(ordinateIndex(l, end, other)) -= lambda(other);
                c(ordinateIndex(l, end, z)) -= lambda(z);
                add(c, zero);
            }
        }
    // Interpolation at every patch that touches a vertex or edge midpoint.
    for (int l = 0; l < 12; ++l)
        for (int i = 0; i < 3; ++i) {
            const int k = cornerAt(sub[l], t[i]);
            if (k >= 0) {
                Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(72);
                row(6 * l + k) = 1;
                Eigen::RowVectorXd r = zero;
                r(3 * i) = 1;
                add(row, r);
                const Eigen::Matrix<double, 2, 72> g = cornerGradient(sub, l, k);
                for (int a = 0; a < 2; ++a) {
                    Eigen::RowVectorXd ra = zero;
                    ra(3 * i + 1 + a) = 1;
                    add(g.row(a), ra);
                }
            }
            const int km = cornerAt(sub[l], 0.5 * (t[i] + t[(i + 1) % 3]));
            if (km >= 0) {
                const Eigen::Matrix<double, 2, 72> g = cornerGradient(sub, l, km);
                const Vec2 nrm = inwardNormal(t, i);
                Eigen::RowVectorXd r = zero;
                r(9 + i) = 1;
                add(nrm.x() * g.row(0) + nrm.y() * g.row(1), r);
            }
        }
    Eigen::MatrixXd a(rows.size(), 72);
    Eigen::MatrixXd b(rows.size(), 12);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        a.row(static_cast<Eigen::Index>(r)) = rows[r];
        b.row(static_cast<Eigen::Index>(r)) = rhs[r];
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    out.rank = qr.rank();
    out.ordinates = qr.solve(b);
    out.residual = (a * out.ordinates - b).norm() / std::max(1.0, b.norm());
    return out;
}

} // namespace

class TestPsPatches : public QObject {
    Q_OBJECT
private slots:
    void splitGeometry() {
        for (const Triangle2& t : testTriangles()) {
            const auto sub = ps12SubTriangles(t);
            const double area = cross2(t[1] - t[0], t[2] - t[0]);
            double sum = 0;
            for (const Triangle2& s : sub) {
                const double a = cross2(s[1] - s[0], s[2] - s[0]);
                QVERIFY(a > 0); // counter-clockwise
                sum += a;
            }
            QVERIFY(std::abs(sum - area) <= 1e-12 * area);
            // The corner regions take 1/8 each (two halves of a quarter
            // split by the median), the medial ones 1/24 each.
            for (int l = 0; l < 12; ++l) {
                const double a = cross2(sub[l][1] - sub[l][0], sub[l][2] - sub[l][0]);
                QVERIFY(std::abs(a - area / (l < 6 ? 8.0 : 24.0)) <= 1e-9 * area);
            }
            // Corner patches 2i, 2i + 1 start at V_i; the centroid is a corner
            // of exactly the six medial patches.
            const Vec2 c = (t[0] + t[1] + t[2]) / 3.0;
            for (int l = 0; l < 12; ++l) {
                if (l < 6)
                    QVERIFY(sub[l][0] == t[l / 2]);
                QCOMPARE((sub[l][2] - c).norm() <= 1e-12 * diameter(t), l >= 6);
            }
        }
    }

    void closedFormMatchesDenseSolve() {
        Worst worst;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const ReferenceSolve ref = referenceSolve(t);
            QCOMPARE(ref.identicalPatches, 0);
            QCOMPARE(ref.interiorEdges, 15);
            QCOMPARE(ref.rank, Eigen::Index(72)); // the ordinates are unique
            QVERIFY2(ref.residual < 1e-9, "the C1 and interpolation conditions are inconsistent");
            const Ps12Matrix b = ps12BezierMatrix(t);
            // Columns of gradient and normal DOFs scale with the triangle.
            Eigen::Matrix<double, 12, 1> colScale = Eigen::Matrix<double, 12, 1>::Constant(1.0);
            const double d = diameter(t);
            for (int k = 0; k < 12; ++k)
                if (k >= 9 || k % 3 != 0)
                    colScale(k) = d;
            const double err =
                ((b - ref.ordinates) * colScale.cwiseInverse().asDiagonal()).cwiseAbs().maxCoeff();
            worst.add(err, 1e-9 * conditioning(t), ti);
        }
        CHECK_WORST(worst, "closed form vs dense solve, per unit DOF");
    }

    void quadraticPrecision() {
        Rng rng;
        Worst value, gradient, second;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const double kappa = conditioning(t);
            Quadratic f;
            const double d = diameter(t);
            f.center =
                t[0] + rng.uniform(-1, 1) * (t[1] - t[0]) + rng.uniform(-1, 1) * (t[2] - t[0]);
            for (int k = 0; k < 6; ++k)
                f.c[k] = rng.uniform(-1, 1) / std::pow(d, k == 0 ? 0 : (k < 3 ? 1 : 2));
            const Patches p = patchesOf(t, dofsOf(f, t));
            const Scales s = scalesOf(p);
            for (int l = 0; l < 12; ++l) {
                for (int n = 0; n < 20; ++n) {
                    const Vec3 w = randomBarycentric(rng);
                    const Vec2 x =
                        w[0] * p[l].domain[0] + w[1] * p[l].domain[1] + w[2] * p[l].domain[2];
                    const Sample got = sampleOf(p[l], w);
                    value.add(std::abs(got.value - f.value(x)), 1e-12 * kappa * s.value, ti);
                    gradient.add((got.gradient - f.gradient(x)).norm(),
                                 1e-12 * kappa * s.derivative, ti);
                }
                double duu = 0, duv = 0, dvv = 0;
                uvSecondDerivatives(p[l], duu, duv, dvv);
                const double err = std::abs(duu - 2 * f.c[3]) + std::abs(duv - f.c[4]) +
                                   std::abs(dvv - 2 * f.c[5]);
                second.add(err, 1e-12 * kappa * s.second, ti);
            }
        }
        CHECK_WORST(value, "value");
        CHECK_WORST(gradient, "gradient");
        CHECK_WORST(second, "second derivatives");
    }

    void interpolatesTheDofs() {
        Rng rng;
        Worst value, gradient, normal;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const double kappa = conditioning(t);
            const Dofs q = randomDofs(rng);
            const Patches p = patchesOf(t, q);
            const Scales s = scalesOf(p);
            int vertexHits = 0;
            int midpointHits = 0;
            for (int l = 0; l < 12; ++l)
                for (int k = 0; k < 3; ++k) {
                    const Sample got = sampleOf(p[l], Vec3::Unit(k));
                    for (int i = 0; i < 3; ++i) {
                        if (p[l].domain[k] == t[i]) {
                            ++vertexHits;
                            value.add(std::abs(got.value - q(3 * i)), 1e-14 * s.value, ti);
                            gradient.add((got.gradient - q.segment<2>(3 * i + 1)).norm(),
                                         1e-12 * kappa * s.derivative, ti);
                        }
                        const Vec2 m = 0.5 * (t[i] + t[(i + 1) % 3]);
                        if ((p[l].domain[k] - m).norm() <= 1e-14 * diameter(t)) {
                            ++midpointHits;
                            normal.add(std::abs(got.gradient.dot(inwardNormal(t, i)) - q(9 + i)),
                                       1e-12 * kappa * s.derivative, ti);
                        }
                    }
                }
            QCOMPARE(vertexHits, 6);    // two patches per vertex
            QCOMPARE(midpointHits, 12); // four patches per edge midpoint
        }
        CHECK_WORST(value, "vertex value");
        CHECK_WORST(gradient, "vertex gradient");
        CHECK_WORST(normal, "midpoint normal derivative");
    }

    void c1InsideTheMacroPatch() {
        Rng rng;
        Worst value, gradient;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const double kappa = conditioning(t);
            const Patches p = patchesOf(t, randomDofs(rng));
            const Scales s = scalesOf(p);
            int edges = 0;
            for (int l = 0; l < 12; ++l)
                for (int n = l + 1; n < 12; ++n)
                    for (int k = 0; k < 3; ++k) {
                        const Vec2& a = p[l].domain[k];
                        const Vec2& b = p[l].domain[(k + 1) % 3];
                        if (cornerAt(p[n].domain, a) < 0 || cornerAt(p[n].domain, b) < 0)
                            continue;
                        ++edges;
                        for (int j = 0; j <= 10; ++j) {
                            const Vec2 x = a + (j / 10.0) * (b - a);
                            const Sample sl = sampleOf(p[l], barycentricOf(p[l].domain, x));
                            const Sample sn = sampleOf(p[n], barycentricOf(p[n].domain, x));
                            value.add(std::abs(sl.value - sn.value), 1e-12 * kappa * s.value, ti);
                            gradient.add((sl.gradient - sn.gradient).norm(),
                                         1e-12 * kappa * s.derivative, ti);
                        }
                    }
            QCOMPARE(edges, 15);
        }
        CHECK_WORST(value, "value across sub-edges");
        CHECK_WORST(gradient, "gradient across sub-edges");
    }

    // Along side s the cross-boundary derivative is linear on each half, the
    // piecewise linear interpolant of g_s . n, m_s, g_{s+1} . n: the kink at
    // the midpoint is what the DOF m_s is for, and only shared DOFs enter.
    void crossDerivativeAlongSides() {
        Rng rng;
        Worst cross;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const double kappa = conditioning(t);
            const Dofs q = randomDofs(rng);
            const Patches p = patchesOf(t, q);
            const Scales s = scalesOf(p);
            for (int side = 0; side < 3; ++side) {
                const Vec2 a = t[side];
                const Vec2 b = t[(side + 1) % 3];
                const Vec2 n = inwardNormal(t, side);
                const double da = Vec2(q(3 * side + 1), q(3 * side + 2)).dot(n);
                const int o = (side + 1) % 3;
                const double db = Vec2(q(3 * o + 1), q(3 * o + 2)).dot(n);
                const double dm = q(9 + side);
                for (int j = 0; j <= 20; ++j) {
                    const double u = j / 20.0;
                    const double expected =
                        u <= 0.5 ? da + (dm - da) * (2 * u) : dm + (db - dm) * (2 * u - 1);
                    const Sample got = sampleAt(p, a + u * (b - a));
                    cross.add(std::abs(got.gradient.dot(n) - expected),
                              1e-12 * kappa * s.derivative, ti);
                }
            }
        }
        CHECK_WORST(cross, "cross-boundary derivative");
    }

    void c1AcrossAMeshEdge() { acrossEdge(false); }
    void c1AcrossARigidlyMovedEdge() { acrossEdge(true); }

    void planarFunctionIsReproduced() {
        Rng rng;
        Worst worst;
        const std::vector<Triangle2> triangles = testTriangles();
        for (int ti = 0; ti < static_cast<int>(triangles.size()); ++ti) {
            const Triangle2& t = triangles[ti];
            const double kappa = conditioning(t);
            Quadratic f;
            f.center = t[0];
            f.c = {rng.uniform(-1, 1),
                   rng.uniform(-1, 1) / diameter(t),
                   rng.uniform(-1, 1) / diameter(t),
                   0,
                   0,
                   0};
            const Patches p = patchesOf(t, dofsOf(f, t));
            // For a linear function every ordinate is its value at the
            // ordinate's domain point.
            double scale = 0;
            for (const auto& patch : p)
                for (const Vec2& x : patch.domain)
                    scale = std::max(scale, std::abs(f.value(x)));
            for (const auto& patch : p)
                for (int c = 0; c < 3; ++c) {
                    const Vec2& x0 = patch.domain[c];
                    const Vec2& x1 = patch.domain[(c + 1) % 3];
                    worst.add(std::abs(patch.control[c] - f.value(x0)), 1e-12 * kappa * scale, ti);
                    worst.add(std::abs(patch.control[3 + c] - f.value(0.5 * (x0 + x1))),
                              1e-12 * kappa * scale, ti);
                }
        }
        CHECK_WORST(worst, "ordinates of a linear function");
    }

    // Under a similarity x' = sigma R x + tau the same ordinates come from the
    // DOFs of the same function in the new coordinates: values unchanged,
    // gradients R g / sigma, normal derivatives m / sigma (the normals turn
    // with the triangle). So B(x') S = B(x), S = diag(1, R / sigma, ..., 1 /
    // sigma). Relabelling the corners cyclically permutes patches and DOFs.
    void similarityInvariance() {
        Rng rng;
        for (const Triangle2& t : testTriangles()) {
            const double angle = rng.uniform(-std::numbers::pi, std::numbers::pi);
            const double sigma = std::pow(10.0, rng.uniform(-3, 3));
            const Vec2 tau = rng.point(100);
            Triangle2 moved;
            for (int i = 0; i < 3; ++i)
                moved[i] = sigma * rotate(t[i], angle) + tau;
            Eigen::Matrix<double, 12, 12> sMat = Eigen::Matrix<double, 12, 12>::Zero();
            const Eigen::Matrix2d r = Eigen::Rotation2Dd(angle).toRotationMatrix();
            for (int i = 0; i < 3; ++i) {
                sMat(3 * i, 3 * i) = 1;
                sMat.block<2, 2>(3 * i + 1, 3 * i + 1) = r / sigma;
                sMat(9 + i, 9 + i) = 1 / sigma;
            }
            const Ps12Matrix b = ps12BezierMatrix(t);
            const Ps12Matrix bMoved = ps12BezierMatrix(moved);
            const double scale = b.cwiseAbs().maxCoeff();
            QVERIFY((bMoved * sMat - b).cwiseAbs().maxCoeff() <= 1e-9 * scale);

            const Triangle2 relabelled = {t[1], t[2], t[0]};
            const Ps12Matrix br = ps12BezierMatrix(relabelled);
            for (int l = 0; l < 12; ++l) {
                // Patch l of the relabelled triangle is patch l + 2 (mod 6 in
                // each group of six) of the original.
                const int lo = l < 6 ? (l + 2) % 6 : 6 + (l - 6 + 2) % 6;
                for (int c = 0; c < 6; ++c)
                    for (int k = 0; k < 12; ++k) {
                        const int ko = k < 9 ? (k + 3) % 9 : 9 + (k - 9 + 1) % 3;
                        QVERIFY(std::abs(br(6 * l + c, k) - b(6 * lo + c, ko)) <= 1e-12 * scale);
                    }
            }
        }
    }

    void vectorSplineEvaluation() {
        Rng rng;
        const Triangle2 t = {Vec2(0.3, -0.2), Vec2(1.4, 0.1), Vec2(0.2, 0.9)};
        const Ps12Matrix b = ps12BezierMatrix(t);
        const auto sub = ps12SubTriangles(t);
        Eigen::Matrix<double, 12, 3> q;
        for (int k = 0; k < 12; ++k)
            for (int c = 0; c < 3; ++c)
                q(k, c) = rng.uniform(-1, 1);
        q.row(1).setZero(); // zero gradient at V_0, as at a cone
        q.row(2).setZero();
        const Eigen::Matrix<double, 72, 3> ordinates = b * q;
        PowellSabinSpline spline;
        spline.patches.resize(12);
        spline.conePatch.assign(12, 0);
        std::array<Patches, 3> scalar;
        for (int c = 0; c < 3; ++c)
            scalar[c] = patchesOf(t, q.col(c));
        for (int l = 0; l < 12; ++l) {
            spline.patches[l].domain = sub[l];
            for (int c = 0; c < 6; ++c)
                spline.patches[l].control[c] = ordinates.row(6 * l + c).transpose();
        }
        QCOMPARE(spline.faceCount(), Index(1));
        for (int l = 0; l < 12; ++l) {
            const Vec3 w = randomBarycentric(rng);
            const Vec3 x = spline.position(l, w);
            Vec3 du, dv;
            spline.derivatives(l, w, du, dv);
            for (int c = 0; c < 3; ++c) {
                const Sample s = sampleOf(scalar[c][l], w);
                QVERIFY(std::abs(x[c] - s.value) <= 1e-13);
                QVERIFY(std::abs(du[c] - s.gradient.x()) <= 1e-12);
                QVERIFY(std::abs(dv[c] - s.gradient.y()) <= 1e-12);
            }
            QVERIFY((spline.normal(l, w) - du.cross(dv)).norm() <= 1e-12);
            Vec3 duu, duv, dvv;
            uvSecondDerivatives(spline.patches[l], duu, duv, dvv);
            for (int c = 0; c < 3; ++c) {
                double suu = 0, suv = 0, svv = 0;
                uvSecondDerivatives(scalar[c][l], suu, suv, svv);
                QVERIFY(std::abs(duu[c] - suu) + std::abs(duv[c] - suv) + std::abs(dvv[c] - svv) <=
                        1e-10);
            }
        }
        // Zero gradient DOFs at V_0: a zero normal there.
        QVERIFY(spline.normal(0, Vec3(1, 0, 0)).norm() <= 1e-14);
        QVERIFY(spline.normal(0, Vec3(0.9, 0.05, 0.05)).norm() > 1e-8);
    }

    void badInputThrows() {
        const Triangle2 clockwise = {Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)};
        const Triangle2 degenerate = {Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)};
        const Triangle2 nan = {Vec2(0, 0), Vec2(1, 0), Vec2(std::nan(""), 1)};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ps12BezierMatrix(clockwise));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ps12BezierMatrix(degenerate));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ps12BezierMatrix(nan));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ps12SubTriangles(clockwise));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, barycentricOf(degenerate, Vec2(0.5, 0.5)));
        QuadraticBezier<double> flat;
        flat.domain = degenerate;
        flat.control = {0, 0, 0, 0, 0, 0};
        double du = 0, dv = 0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, uvDerivatives(flat, Vec3(1, 0, 0), du, dv));
        PowellSabinSpline spline;
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, spline.position(0, Vec3(1, 0, 0)));
    }

private:
    // Triangles (A, B, C) and (B, A, D) share side A -> B: side 0 of both.
    // They share p, g at A and B and the edge's normal derivative, whose
    // sign flips because each triangle's normal points inside it. Every
    // other DOF is independent. With `moved`, the second triangle's uv is
    // rotated and translated, and its gradient DOFs rotated with it.
    void acrossEdge(bool moved) {
        Rng rng;
        Worst value, cross, gradient;
        int pairs = 0;
        const std::vector<Triangle2> shapes = testTriangles();
        for (const Triangle2& first : shapes) {
            for (const Triangle2& second : {shapes[(pairs * 7 + 3) % shapes.size()], first}) {
                const Vec2 a = first[0];
                const Vec2 b = first[1];
                // Place the second shape's side 0 on B -> A, apex on the other side.
                const Vec2 e = a - b;
                const Vec2 e2 = second[1] - second[0];
                const double scale = e.norm() / e2.norm();
                const double turn = std::atan2(e.y(), e.x()) - std::atan2(e2.y(), e2.x());
                const Vec2 d = b + scale * rotate(second[2] - second[0], turn);
                Triangle2 t1 = first;
                Triangle2 t2 = {b, a, d};
                QVERIFY(cross2(t2[1] - t2[0], t2[2] - t2[0]) > 0);
                ++pairs;

                Dofs q1 = randomDofs(rng);
                Dofs q2 = randomDofs(rng);
                q2.segment<3>(0) = q1.segment<3>(3); // B
                q2.segment<3>(3) = q1.segment<3>(0); // A
                q2(9) = -q1(9);
                double angle = 0;
                Vec2 tau = Vec2::Zero();
                if (moved) {
                    angle = rng.uniform(-std::numbers::pi, std::numbers::pi);
                    tau = rng.point(50);
                    for (Vec2& x : t2)
                        x = rotate(x, angle) + tau;
                    for (int i = 0; i < 3; ++i) {
                        const Vec2 g = rotate(Vec2(q2(3 * i + 1), q2(3 * i + 2)), angle);
                        q2(3 * i + 1) = g.x();
                        q2(3 * i + 2) = g.y();
                    }
                }
                const Patches p1 = patchesOf(t1, q1);
                const Patches p2 = patchesOf(t2, q2);
                const Scales s1 = scalesOf(p1);
                const Scales s2 = scalesOf(p2);
                const double kappa = std::max(conditioning(t1), conditioning(t2));
                const double valueTol = 1e-12 * kappa * std::max(s1.value, s2.value);
                const double derivTol = 1e-12 * kappa * std::max(s1.derivative, s2.derivative);
                const Vec2 n = inwardNormal(t1, 0);
                for (int j = 0; j <= 40; ++j) {
                    const Vec2 x = a + (j / 40.0) * (b - a);
                    const Sample s = sampleAt(p1, x);
                    Sample o = sampleAt(p2, rotate(x, angle) + tau);
                    o.gradient = rotate(o.gradient, -angle); // back to the first uv
                    value.add(std::abs(s.value - o.value), valueTol, pairs - 1);
                    cross.add(std::abs(s.gradient.dot(n) - o.gradient.dot(n)), derivTol, pairs - 1);
                    gradient.add((s.gradient - o.gradient).norm(), derivTol, pairs - 1);
                }
            }
        }
        QVERIFY(pairs >= 40);
        CHECK_WORST(value, "value across the edge");
        CHECK_WORST(cross, "cross derivative across the edge");
        CHECK_WORST(gradient, "gradient across the edge");
    }
};

QTEST_GUILESS_MAIN(TestPsPatches)
#include "test_ps_patches.moc"
