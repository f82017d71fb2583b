// The thin-plate fit of the Powell-Sabin spline (contours/powell_sabin/
// ThinPlateFit.h, Capouellez et al. 2023 §5.2-§5.3) on hand-built layouts of
// known flat metrics: a plane is reproduced exactly; H is symmetric positive
// definite and the solve is accurate; the spline is C1 across patches, mesh
// edges and cut edges of a cube (8 cones) and of a flat torus; the Bezier
// points do not depend on the charts; bad input throws.
#include "PowellSabinLayouts.h"
#include "contours/powell_sabin/ThinPlateFit.h"

#include <Eigen/Dense>
#include <QElapsedTimer>
#include <QtTest>
#include <cmath>
#include <limits>
#include <map>
#include <random>

using namespace contour;
using namespace contour::powell_sabin;
using namespace contour::testing;

namespace {

// A jittered planar grid, uv = its coordinates in the plane spanned by the
// orthonormal a, b through o (an isometric layout without cuts or cones).
struct Planar {
    ConeLayout layout;
    Vec3 o, a, b;
};

Planar planarGrid(int n, double jitter, unsigned seed = 1) {
    Planar p;
    p.o = Vec3(0.3, -0.2, 0.5);
    p.a = Vec3(1, 2, 2).normalized();
    p.b = Vec3(2, -1, 0).normalized();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-jitter, jitter);
    std::vector<Vec2> uv;
    std::vector<Vec3> pos;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            Vec2 q(double(i) / n, double(j) / n);
            if (i > 0 && i < n && j > 0 && j < n)
                q += Vec2(u(rng), u(rng)) / n;
            uv.push_back(q);
            pos.push_back(p.o + q.x() * p.a + q.y() * p.b);
        }
    std::vector<Triangle> tris;
    auto id = [n](int i, int j) {
        return Index(j * (n + 1) + i);
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    p.layout.mesh = TriangleMesh(pos, tris);
    for (const Triangle& t : tris)
        p.layout.cornerUv.push_back({uv[t[0]], uv[t[1]], uv[t[2]]});
    p.layout.cutEdge.assign(p.layout.mesh.edgeCount(), 0);
    p.layout.isCone.assign(p.layout.mesh.vertexCount(), 0);
    return p;
}

// A torus (radii 2, 0.7) over the flat n x m grid.
ConeLayout torusLayout(int n, int m, double aspect) {
    return flatTorusLayout(n, m, aspect, [](double s, double t) {
        return Vec3((2.0 + 0.7 * std::cos(t)) * std::cos(s),
                    (2.0 + 0.7 * std::cos(t)) * std::sin(s), 0.7 * std::sin(t));
    });
}

// Genus 2 with a known flat metric: the regular octagon with opposite sides
// glued by translations, its 8 corners one cone of angle 6 pi, every other
// vertex flat. Each of the 8 sectors (centre, c_j, c_j+1) is split into a
// k x k triangle grid; the sides are the cut. The surface is not embedded:
// positions are the canonical uv of each vertex plus a random height, which
// is all a C1 test needs.
ConeLayout octagonGenus2(int k, unsigned seed) {
    std::array<Vec2, 8> c;
    for (int j = 0; j < 8; ++j)
        c[j] = Vec2(std::cos(M_PI / 8 + j * M_PI / 4), std::sin(M_PI / 8 + j * M_PI / 4));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> height(-0.2, 0.2);
    std::map<std::array<long, 2>, Index> ids;
    std::vector<Vec3> pos;
    // The vertex of octagon point x: sides j >= 4 are translated onto side j - 4
    // (parameter t on side j is 1 - t on side j + 4), all corners are one vertex.
    auto vertexOf = [&](const Vec2& x, int side, int along) {
        Vec2 canonical = x;
        if (along == 0 || along == k)
            canonical = c[0];
        else if (side >= 4)
            canonical = c[side - 4] + (1.0 - double(along) / k) * (c[side - 3] - c[side - 4]);
        const std::array<long, 2> key = {std::lround(canonical.x() * 1e9),
                                         std::lround(canonical.y() * 1e9)};
        auto [it, fresh] = ids.emplace(key, Index(pos.size()));
        if (fresh)
            pos.emplace_back(canonical.x(), canonical.y(), height(rng));
        return it->second;
    };
    std::vector<Triangle> tris;
    std::vector<std::array<Vec2, 3>> uvs;
    for (int j = 0; j < 8; ++j) {
        const Vec2 a = c[j], b = c[(j + 1) % 8];
        // Grid point (r, s): r steps from the centre towards the side, s along it.
        auto point = [&](int r, int t) {
            return (double(r - t) / k) * a + (double(t) / k) * b;
        };
        auto vertex = [&](int r, int t) {
            return r == k ? vertexOf(point(r, t), j, t) : vertexOf(point(r, t), -1, -1);
        };
        for (int r = 0; r < k; ++r)
            for (int t = 0; t <= r; ++t) {
                tris.push_back({vertex(r, t), vertex(r + 1, t), vertex(r + 1, t + 1)});
                uvs.push_back({point(r, t), point(r + 1, t), point(r + 1, t + 1)});
                if (t < r) {
                    tris.push_back({vertex(r, t), vertex(r + 1, t + 1), vertex(r, t + 1)});
                    uvs.push_back({point(r, t), point(r + 1, t + 1), point(r, t + 1)});
                }
            }
    }
    ConeLayout l = layoutWithCuts(pos, tris, uvs);
    l.isCone[ids.at({std::lround(c[0].x() * 1e9), std::lround(c[0].y() * 1e9)})] = 1;
    return l;
}

std::vector<Vec3> noisyPositions(const TriangleMesh& mesh, double amount, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, amount);
    std::vector<Vec3> t(mesh.positions().begin(), mesh.positions().end());
    for (Vec3& p : t)
        p += Vec3(g(rng), g(rng), g(rng));
    return t;
}

// Patch of face f containing uv (a point inside or on the face).
int patchAt(const PowellSabinSpline& s, Index f, const Vec2& uv, Vec3& bary) {
    int best = -1;
    double bestMin = -1e300;
    for (int l = 0; l < kPs12Patches; ++l) {
        const Vec3 b = barycentricOf(s.patches[f * kPs12Patches + l].domain, uv);
        if (b.minCoeff() > bestMin) {
            bestMin = b.minCoeff();
            best = l;
            bary = b;
        }
    }
    return best;
}

struct Jet {
    Vec3 p;
    Eigen::Matrix<double, 3, 2> j; // [p_u p_v]
};

Jet jetAt(const PowellSabinSpline& s, Index f, const Vec2& uv) {
    Vec3 b;
    const int l = patchAt(s, f, uv, b);
    const QuadraticBezier<Vec3>& q = s.patches[f * kPs12Patches + l];
    Jet jet;
    jet.p = evaluate(q, b);
    Vec3 du, dv;
    uvDerivatives(q, b, du, dv);
    jet.j.col(0) = du;
    jet.j.col(1) = dv;
    return jet;
}

// Largest C1 defects of the spline over `layout`: positions (absolute) and
// normals (1 - n1.n2 of unit normals, where both are well defined) between
// the sub-patches of every face and across every interior mesh edge, and the
// chart-consistent Jacobian mismatch ||J_f - J_g Q|| (Q the rigid map from
// f's uv to g's uv along the edge).
struct Defects {
    double position = 0.0;
    double normal = 0.0;
    double jacobian = 0.0;
    int samples = 0;
};

Defects c1Defects(const ConeLayout& layout, const PowellSabinSpline& s) {
    Defects d;
    const TriangleMesh& mesh = layout.mesh;
    const std::array<double, 5> ts = {0.07, 0.21, 0.38, 0.66, 0.89};
    auto compare = [&](const Jet& a, const Jet& b, const Eigen::Matrix2d& q) {
        d.position = std::max(d.position, (a.p - b.p).norm());
        d.jacobian = std::max(d.jacobian, (a.j - b.j * q).norm());
        const Vec3 na = a.j.col(0).cross(a.j.col(1)), nb = b.j.col(0).cross(b.j.col(1));
        if (na.norm() > 1e-8 && nb.norm() > 1e-8)
            d.normal = std::max(d.normal, 1.0 - na.normalized().dot(nb.normalized()));
        ++d.samples;
    };
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        // Inside the macro-patch: every pair of sub-triangles sharing an edge.
        for (int l = 0; l < kPs12Patches; ++l)
            for (int k = l + 1; k < kPs12Patches; ++k) {
                const auto& a = s.patches[f * kPs12Patches + l];
                const auto& b = s.patches[f * kPs12Patches + k];
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const Vec2 a0 = a.domain[i], a1 = a.domain[(i + 1) % 3];
                        if ((a0 - b.domain[(j + 1) % 3]).norm() > 1e-12 ||
                            (a1 - b.domain[j]).norm() > 1e-12)
                            continue;
                        for (double t : ts) {
                            const Vec2 x = a0 + t * (a1 - a0);
                            Jet ja, jb;
                            Vec3 w;
                            ja.p = evaluate(a, barycentricOf(a.domain, x));
                            jb.p = evaluate(b, barycentricOf(b.domain, x));
                            Vec3 du, dv;
                            uvDerivatives(a, barycentricOf(a.domain, x), du, dv);
                            ja.j << du, dv;
                            uvDerivatives(b, barycentricOf(b.domain, x), du, dv);
                            jb.j << du, dv;
                            compare(ja, jb, Eigen::Matrix2d::Identity());
                        }
                    }
            }
        // Across mesh edges, cut or not.
        for (int i = 0; i < 3; ++i) {
            const Index h = TriangleMesh::halfedge(f, i);
            const Index o = mesh.opposite(h);
            if (o == kInvalidIndex || o < h)
                continue;
            const Index g = TriangleMesh::face(o);
            const auto& uf = layout.cornerUv[f];
            const auto& ug = layout.cornerUv[g];
            const Vec2 f0 = uf[i], f1 = uf[(i + 1) % 3];
            const Vec2 g0 = ug[(o % 3 + 1) % 3], g1 = ug[o % 3]; // same ends, from(h) first
            const Vec2 ef = f1 - f0, eg = g1 - g0;
            Eigen::Matrix2d q; // f's uv directions to g's
            const double c = ef.dot(eg) / (ef.norm() * eg.norm());
            const double sn = (ef.x() * eg.y() - ef.y() * eg.x()) / (ef.norm() * eg.norm());
            q << c, -sn, sn, c;
            for (double t : ts)
                compare(jetAt(s, f, f0 + t * ef), jetAt(s, g, g0 + t * eg), q);
        }
    }
    return d;
}

double bboxDiagonal(const TriangleMesh& mesh) {
    return mesh.boundingBox().diagonal();
}

double maxControlDifference(const PowellSabinSpline& a, const PowellSabinSpline& b) {
    double d = 0.0;
    for (std::size_t p = 0; p < a.patches.size(); ++p)
        for (int c = 0; c < 6; ++c)
            d = std::max(d, (a.patches[p].control[c] - b.patches[p].control[c]).norm());
    return d;
}

} // namespace

class TestPsFit : public QObject {
    Q_OBJECT
private slots:
    void planeIsReproduced() {
        const Planar p = planarGrid(6, 0.2);
        const ThinPlateFit fit(p.layout);
        const std::vector<Vec3> targets(p.layout.mesh.positions().begin(),
                                        p.layout.mesh.positions().end());
        const Eigen::MatrixX3d q = fit.solveDofs(targets);
        // The plane's own DOFs: p, gradient (a, b), g^m = (a, b) . left normal.
        const TriangleMesh& m = p.layout.mesh;
        Eigen::MatrixX3d exact(fit.dofCount(), 3);
        for (Index v = 0; v < m.vertexCount(); ++v) {
            exact.row(fit.positionDof(v)) = targets[v].transpose();
            exact.row(fit.gradientDof(v)) = p.a.transpose();
            exact.row(fit.gradientDof(v) + 1) = p.b.transpose();
        }
        for (Index e = 0; e < m.edgeCount(); ++e) {
            const Index h = m.edgeHalfedge(e);
            const auto& uv = p.layout.cornerUv[TriangleMesh::face(h)];
            const Vec2 d = (uv[(h % 3 + 1) % 3] - uv[h % 3]).normalized();
            exact.row(fit.edgeDof(e)) = (-d.y() * p.a + d.x() * p.b).transpose();
        }
        const double scale = fit.smoothingHessian().norm();
        const double e0 = (exact.transpose() * fit.smoothingHessian() * exact).trace();
        const double es = (q.transpose() * fit.smoothingHessian() * q).trace();
        const double dq = (q - exact).cwiseAbs().maxCoeff();
        qInfo("plane: |H^s| %.3g, exact q^T H^s q = %.3g, fitted %.3g, max |q - exact| %.3g", scale,
              e0, es, dq);
        // Zero up to rounding: H^s is large (|H^s| ~ 1/h^2), and the solve's
        // forward error is cond(H) * eps.
        QVERIFY2(std::abs(e0) < 1e-12 * scale, qPrintable(QString::number(e0)));
        QVERIFY2(std::abs(es) < 1e-12 * scale, qPrintable(QString::number(es)));
        QVERIFY2(dq < 1e-8, qPrintable(QString::number(dq)));
        const double diag = bboxDiagonal(m);
        const PowellSabinSpline s = fit.splineOf(q);
        QCOMPARE(s.faceCount(), p.layout.mesh.faceCount());
        // Every Bezier point on the plane o + u a + v b of its own domain.
        double worst = 0.0;
        for (const auto& patch : s.patches) {
            const std::array<Vec2, 6> at = {patch.domain[0],
                                            patch.domain[1],
                                            patch.domain[2],
                                            0.5 * (patch.domain[0] + patch.domain[1]),
                                            0.5 * (patch.domain[1] + patch.domain[2]),
                                            0.5 * (patch.domain[2] + patch.domain[0])};
            for (int c = 0; c < 6; ++c)
                worst = std::max(
                    worst, (patch.control[c] - (p.o + at[c].x() * p.a + at[c].y() * p.b)).norm());
        }
        QVERIFY2(worst < 1e-9 * diag, qPrintable(QString::number(worst)));
        // Every vertex on its target.
        double vertexError = 0.0;
        for (Index f = 0; f < m.faceCount(); ++f)
            for (int i = 0; i < 3; ++i)
                vertexError = std::max(
                    vertexError,
                    (jetAt(s, f, p.layout.cornerUv[f][i]).p - targets[m.triangle(f)[i]]).norm());
        QVERIFY2(vertexError < 1e-9 * diag, qPrintable(QString::number(vertexError)));
        QCOMPARE(fit.dofCount(), 3 * m.vertexCount() + m.edgeCount());
        QCOMPARE(fit.fittingWeight(), 1.0);
        // The fit() path gives the same spline.
        QVERIFY(maxControlDifference(fit.fit(targets), s) == 0.0);
    }

    void hessianAndSolve() {
        const ConeLayout cube = cubeLayout(2, {0.3, 1.1, -0.7, 2.0, 0.0, 2.9});
        for (double w : {1.0, 0.01, 100.0}) {
            ThinPlateFitOptions options;
            options.fittingWeight = w;
            const ThinPlateFit fit(cube, options);
            const Eigen::SparseMatrix<double>& hs = fit.smoothingHessian();
            const Eigen::SparseMatrix<double>& hf = fit.fittingHessian();
            const Eigen::MatrixXd hsd(hs), hfd(hf);
            const Eigen::MatrixXd h = hsd + w * hfd;
            QCOMPARE(h.rows(), Eigen::Index(fit.dofCount()));
            // Cones eliminate their gradients: 8 corners x 2 DOFs.
            QCOMPARE(fit.dofCount(), 3 * cube.mesh.vertexCount() - 16 + cube.mesh.edgeCount());
            QVERIFY((hsd - hsd.transpose()).norm() == 0.0);
            QVERIFY((hfd - hfd.transpose()).norm() == 0.0);
            const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(hsd);
            const double scale = es.eigenvalues().cwiseAbs().maxCoeff();
            QVERIFY2(es.eigenvalues().minCoeff() > -1e-12 * scale,
                     qPrintable(QString::number(es.eigenvalues().minCoeff() / scale)));
            const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eh(h);
            QVERIFY(eh.eigenvalues().minCoeff() > 0.0);
            // H^f: 2 A_i on the p slots with A_i relative to the mean vertex
            // area, so they sum to the vertex count.
            QVERIFY(std::abs(hfd.trace() - 2.0 * cube.mesh.vertexCount()) < 1e-9);
            // The barycentric areas themselves: they sum to the cube's area 24.
            ThinPlateFitOptions absolute = options;
            absolute.relativeAreaWeights = false;
            const Eigen::MatrixXd hfAbsolute(ThinPlateFit(cube, absolute).fittingHessian());
            QVERIFY(std::abs(hfAbsolute.trace() - 2.0 * 24.0) < 1e-12);
            const std::vector<Vec3> targets = noisyPositions(cube.mesh, 0.05, 7);
            const Eigen::MatrixX3d q = fit.solveDofs(targets);
            const Eigen::MatrixX3d rhs = w * (hfd * fit.targetDofs(targets));
            const double residual = (h * q - rhs).norm() / rhs.norm();
            QVERIFY2(residual < 1e-10, qPrintable(QString::number(residual)));
        }
    }

    void cubeIsC1AcrossCutsAndCones() {
        const ConeLayout cube = cubeLayout(3, {0.3, 1.1, -0.7, 2.0, 0.0, 2.9});
        const ThinPlateFit fit(cube);
        const std::vector<Vec3> targets = noisyPositions(cube.mesh, 0.03, 3);
        const PowellSabinSpline s = fit.fit(targets);
        const Defects d = c1Defects(cube, s);
        const double diag = bboxDiagonal(cube.mesh);
        qInfo("cube n=3: %d samples, position %.3g, 1-n.n %.3g, jacobian %.3g", d.samples,
              d.position, d.normal, d.jacobian);
        QVERIFY(d.samples > 1000);
        QVERIFY2(d.position < 1e-10 * diag, qPrintable(QString::number(d.position)));
        QVERIFY2(d.normal < 1e-8, qPrintable(QString::number(d.normal)));
        QVERIFY2(d.jacobian < 1e-10 * diag, qPrintable(QString::number(d.jacobian)));
        // Cone patches: the 8 corners touch 2 sub-triangles per incident face.
        int cones = 0, conePatches = 0;
        for (char c : cube.isCone)
            cones += c;
        for (char c : s.conePatch)
            conePatches += c;
        QCOMPARE(cones, 8);
        // Every cone corner of a face touches two of its sub-triangles.
        int coneCorners = 0;
        for (Index f = 0; f < cube.mesh.faceCount(); ++f)
            for (Index v : cube.mesh.triangle(f))
                coneCorners += cube.isCone[v];
        QCOMPARE(coneCorners, 36);
        QCOMPARE(conePatches, 2 * coneCorners);
        // At a cone the spline is singular: both uv derivatives vanish.
        for (Index f = 0; f < cube.mesh.faceCount(); ++f)
            for (int i = 0; i < 3; ++i)
                if (cube.isCone[cube.mesh.triangle(f)[i]]) {
                    const Jet j = jetAt(s, f, cube.cornerUv[f][i]);
                    QVERIFY(j.j.norm() < 1e-12);
                }
    }

    void chartsDoNotMatter() {
        const std::array<double, 6> angles = {0.3, 1.1, -0.7, 2.0, 0.0, 2.9};
        const ConeLayout cube = cubeLayout(2, angles);
        const std::vector<Vec3> targets = noisyPositions(cube.mesh, 0.05, 11);
        const PowellSabinSpline base = ThinPlateFit(cube).fit(targets);
        // Another reference face for every vertex: the last face around it.
        ThinPlateFitOptions options;
        options.chartReferenceFace.assign(cube.mesh.vertexCount(), 0);
        for (Index f = 0; f < cube.mesh.faceCount(); ++f)
            for (Index v : cube.mesh.triangle(f))
                options.chartReferenceFace[v] = f;
        const PowellSabinSpline other = ThinPlateFit(cube, options).fit(targets);
        const double diag = bboxDiagonal(cube.mesh);
        const double d = maxControlDifference(base, other);
        QVERIFY2(d < 1e-9 * diag, qPrintable(QString::number(d)));
        // The charts' DOFs do change (the gradients are stored rotated).
        const ThinPlateFit a(cube), b(cube, options);
        QVERIFY((a.solveDofs(targets) - b.solveDofs(targets)).norm() > 1e-3);
        // Rotating the sides' uv (new frames for every chart and edge) keeps
        // the Bezier points too.
        const ConeLayout turned = cubeLayout(2, {-1.3, 0.4, 2.2, 0.9, 3.0, -2.5});
        const double t = maxControlDifference(base, ThinPlateFit(turned).fit(targets));
        QVERIFY2(t < 1e-9 * diag, qPrintable(QString::number(t)));
        // A uniform uv scale s leaves the patches' shapes unchanged (§5.1) but
        // scales the thin-plate term by 1/s^2: with w / s^2 the optimum is the same.
        ConeLayout scaled = cube;
        for (auto& uv : scaled.cornerUv)
            for (Vec2& x : uv)
                x *= 7.5;
        ThinPlateFitOptions lighter;
        lighter.fittingWeight = 1.0 / (7.5 * 7.5);
        const double u = maxControlDifference(base, ThinPlateFit(scaled, lighter).fit(targets));
        QVERIFY2(u < 1e-9 * diag, qPrintable(QString::number(u)));
    }

    void flatTorusIsC1() {
        const ConeLayout torus = torusLayout(24, 10, 1.3);
        int cuts = 0;
        for (char c : torus.cutEdge)
            cuts += c;
        QCOMPARE(cuts, 24 + 10); // the two seams
        const ThinPlateFit fit(torus);
        QCOMPARE(fit.dofCount(), 3 * torus.mesh.vertexCount() + torus.mesh.edgeCount());
        const std::vector<Vec3> targets(torus.mesh.positions().begin(),
                                        torus.mesh.positions().end());
        const PowellSabinSpline s = fit.fit(targets);
        const Defects d = c1Defects(torus, s);
        const double diag = bboxDiagonal(torus.mesh);
        qInfo("torus: %d samples, position %.3g, 1-n.n %.3g, jacobian %.3g", d.samples, d.position,
              d.normal, d.jacobian);
        QVERIFY2(d.position < 1e-10 * diag, qPrintable(QString::number(d.position)));
        QVERIFY2(d.normal < 1e-8, qPrintable(QString::number(d.normal)));
        QVERIFY2(d.jacobian < 1e-10 * diag, qPrintable(QString::number(d.jacobian)));
        for (char c : s.conePatch)
            QCOMPARE(int(c), 0);
        // The fit approaches the vertices as w grows (eq. 8): the thin-plate
        // term pulls this coarse tube inwards at w = 1.
        const TriangleMesh& m = torus.mesh;
        double previous = 1e300;
        for (double w : {1.0, 100.0, 1e4}) {
            ThinPlateFitOptions options;
            options.fittingWeight = w;
            const PowellSabinSpline sw = ThinPlateFit(torus, options).fit(targets);
            double worst = 0.0;
            for (Index f = 0; f < m.faceCount(); ++f)
                for (int i = 0; i < 3; ++i)
                    worst = std::max(
                        worst,
                        (jetAt(sw, f, torus.cornerUv[f][i]).p - targets[m.triangle(f)[i]]).norm());
            qInfo("torus w=%g: max vertex deviation %.3g", w, worst);
            QVERIFY(worst < previous);
            previous = worst;
        }
    }

    void genusTwoIsC1() {
        const ConeLayout g2 = octagonGenus2(4, 9);
        const TriangleMesh& m = g2.mesh;
        // Closed, genus 2: V - E + F = -2.
        QCOMPARE(m.boundaryEdgeCount(), 0);
        QCOMPARE(m.vertexCount() - m.edgeCount() + m.faceCount(), -2);
        const ThinPlateFit fit(g2);
        const std::vector<Vec3> targets(m.positions().begin(), m.positions().end());
        const PowellSabinSpline s = fit.fit(targets);
        const Defects d = c1Defects(g2, s);
        const double diag = bboxDiagonal(m);
        qInfo("genus 2: %d samples, position %.3g, 1-n.n %.3g, jacobian %.3g", d.samples,
              d.position, d.normal, d.jacobian);
        QVERIFY2(d.position < 1e-10 * diag, qPrintable(QString::number(d.position)));
        QVERIFY2(d.normal < 1e-8, qPrintable(QString::number(d.normal)));
        QVERIFY2(d.jacobian < 1e-10 * diag, qPrintable(QString::number(d.jacobian)));
        // The cone (valence 16, 6 pi) touches two sub-triangles of each face there.
        int conePatches = 0;
        for (char c : s.conePatch)
            conePatches += c;
        QCOMPARE(conePatches, 2 * 16);
        // Unflagged, the 6 pi corner is refused.
        ConeLayout noCone = g2;
        noCone.isCone.assign(noCone.isCone.size(), 0);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit{noCone});
    }

    // The same cube through layoutFromCornerUv (ConeLayout.h): it finds the
    // hand-made cuts and cones, and the fit is the same.
    void layoutFromCornerUvAgrees() {
        const ConeLayout cube = cubeLayout(2, {0.3, 1.1, -0.7, 2.0, 0.0, 2.9});
        const ConeLayout found = layoutFromCornerUv(cube.mesh, cube.cornerUv);
        QVERIFY(found.cutEdge == cube.cutEdge);
        QVERIFY(found.isCone == cube.isCone);
        const std::vector<Vec3> targets = noisyPositions(cube.mesh, 0.05, 5);
        const double d =
            maxControlDifference(ThinPlateFit(cube).fit(targets), ThinPlateFit(found).fit(targets));
        QVERIFY(d == 0.0);
    }

    void badInputThrows() {
        const ConeLayout cube = cubeLayout(1, {0, 0, 0, 0, 0, 0});
        // A corner that is not flagged a cone: its charts do not close.
        ConeLayout noCone = cube;
        noCone.isCone.assign(noCone.isCone.size(), 0);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit{noCone});
        // Zero 3D area: no fitting term, H singular.
        ConeLayout flat = planarGrid(2, 0.0).layout;
        flat.mesh = TriangleMesh(
            std::vector<Vec3>(flat.mesh.vertexCount(), Vec3::Zero()),
            std::vector<Triangle>(flat.mesh.triangles().begin(), flat.mesh.triangles().end()));
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, ThinPlateFit{flat});
        // Flipped uv triangle.
        ConeLayout flipped = planarGrid(2, 0.0).layout;
        std::swap(flipped.cornerUv[0][1], flipped.cornerUv[0][2]);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit{flipped});
        // Size mismatches and options.
        ConeLayout missing = cube;
        missing.cutEdge.pop_back();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit{missing});
        ThinPlateFitOptions zero;
        zero.fittingWeight = 0.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit(cube, zero));
        const ConeLayout grid = planarGrid(3, 0.0).layout;
        ThinPlateFitOptions wrongFace;
        wrongFace.chartReferenceFace.assign(grid.mesh.vertexCount(), 0);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ThinPlateFit(grid, wrongFace));
        const ThinPlateFit fit(cube);
        const std::vector<Vec3> few(3, Vec3::Zero());
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, fit.solveDofs(few));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, fit.splineOf(Eigen::MatrixX3d(2, 3)));
    }

    // Figures for the report (no assertion on time): a 100 x 100 planar grid,
    // 20000 faces, bumped out of its plane.
    void timing() {
        const Planar p = planarGrid(100, 0.2);
        QElapsedTimer timer;
        timer.start();
        const ThinPlateFit fit(p.layout);
        const qint64 build = timer.nsecsElapsed();
        std::vector<Vec3> targets(p.layout.mesh.positions().begin(),
                                  p.layout.mesh.positions().end());
        for (Vec3& t : targets)
            t += 0.05 * std::sin(9.0 * t.x()) * std::cos(7.0 * t.y()) * p.a.cross(p.b);
        // Per view: the best of 5 solves (the machine is shared).
        qint64 solve = std::numeric_limits<qint64>::max();
        Eigen::MatrixX3d q;
        for (int k = 0; k < 5; ++k) {
            timer.restart();
            q = fit.solveDofs(targets);
            solve = std::min(solve, timer.nsecsElapsed());
        }
        timer.restart();
        const PowellSabinSpline s = fit.splineOf(q);
        const qint64 spline = timer.nsecsElapsed();
        qInfo("%d faces, %d DOFs: assembly+factor %.1f ms, solveDofs %.2f ms, splineOf %.1f ms",
              int(p.layout.mesh.faceCount()), int(fit.dofCount()), build * 1e-6, solve * 1e-6,
              spline * 1e-6);
        QCOMPARE(s.faceCount(), p.layout.mesh.faceCount());
    }
};

QTEST_GUILESS_MAIN(TestPsFit)
#include "test_ps_fit.moc"
