// Vertex-normal patches (van Overveld & Wyvill): the §2.4 edge control points
// and their constraints, crack-free shared edges on meshes of triangles,
// quads and n-gons, planar input staying planar, the output counts of the
// recursive filter, exact derivatives against finite differences, the apex
// parameter λ, border normals (§2.8), and accuracy on a sphere.
#include "mesh/ProceduralShapes.h"
#include "surface/VertexNormalPatches.h"

#include <QElapsedTimer>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

using namespace contour;

namespace {

constexpr double kPi = std::numbers::pi;

// A convex polyhedron from its vertices (all on a sphere, faces planar):
// every plane through three vertices with all others on one side is a face;
// its vertices sorted counter-clockwise seen from outside.
PolygonMesh convexPolyhedron(const std::vector<Vec3>& points) {
    PolygonMesh mesh;
    mesh.positions = points;
    const int n = static_cast<int>(points.size());
    std::vector<std::vector<Index>> faces;
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            for (int c = b + 1; c < n; ++c) {
                Vec3 normal = (points[b] - points[a]).cross(points[c] - points[a]);
                if (normal.norm() < 1e-9)
                    continue;
                normal.normalize();
                int above = 0, below = 0;
                std::vector<Index> on;
                for (int i = 0; i < n; ++i) {
                    const double d = normal.dot(points[i] - points[a]);
                    if (d > 1e-9)
                        ++above;
                    else if (d < -1e-9)
                        ++below;
                    else
                        on.push_back(i);
                }
                if (above && below)
                    continue;
                if (above)
                    normal = -normal;
                if (std::find(faces.begin(), faces.end(), on) != faces.end())
                    continue;
                faces.push_back(on);
                Vec3 centre = Vec3::Zero();
                for (Index i : on)
                    centre += points[i];
                centre /= static_cast<double>(on.size());
                const Vec3 e1 = (points[on[0]] - centre).normalized(), e2 = normal.cross(e1);
                std::vector<Index> sorted = on;
                std::sort(sorted.begin(), sorted.end(), [&](Index i, Index j) {
                    const Vec3 p = points[i] - centre, q = points[j] - centre;
                    return std::atan2(p.dot(e2), p.dot(e1)) < std::atan2(q.dot(e2), q.dot(e1));
                });
                mesh.addFace(std::span<const Index>(sorted));
            }
    return mesh;
}

// Regular dodecahedron inscribed in the unit sphere: 12 pentagons.
PolygonMesh dodecahedron() {
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> v;
    for (int x : {-1, 1})
        for (int y : {-1, 1})
            for (int z : {-1, 1})
                v.emplace_back(x, y, z);
    for (int a : {-1, 1})
        for (int b : {-1, 1}) {
            v.emplace_back(0, a / phi, b * phi);
            v.emplace_back(a / phi, b * phi, 0);
            v.emplace_back(a * phi, 0, b / phi);
        }
    for (Vec3& p : v)
        p.normalize();
    return convexPolyhedron(v);
}

// Regular icosahedron (20 triangles) and cube (6 quads) in the unit sphere.
PolygonMesh icosahedron() {
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> v;
    for (int a : {-1, 1})
        for (int b : {-1, 1}) {
            v.emplace_back(0, a, b * phi);
            v.emplace_back(a, b * phi, 0);
            v.emplace_back(a * phi, 0, b);
        }
    for (Vec3& p : v)
        p.normalize();
    return convexPolyhedron(v);
}
PolygonMesh cube() {
    std::vector<Vec3> v;
    for (int x : {-1, 1})
        for (int y : {-1, 1})
            for (int z : {-1, 1})
                v.push_back(Vec3(x, y, z).normalized());
    return convexPolyhedron(v);
}

// Prism over a regular n-gon of circumradius 1, height h (two n-gon caps).
PolygonMesh prism(int n, double h) {
    std::vector<Vec3> v;
    for (double z : {0.0, h})
        for (int k = 0; k < n; ++k)
            v.emplace_back(std::cos(2 * kPi * k / n), std::sin(2 * kPi * k / n), z);
    return convexPolyhedron(v);
}

// A hexagonal prism whose top is a hexagonal pyramid: one hexagon, six quads
// and six triangles, so triangles meet quads and quads meet the hexagon.
PolygonMesh hexagonHouse() {
    PolygonMesh m;
    for (double z : {0.0, 1.0})
        for (int k = 0; k < 6; ++k)
            m.positions.emplace_back(std::cos(kPi * k / 3), std::sin(kPi * k / 3), z);
    m.positions.emplace_back(0.1, -0.05, 1.7);
    m.addFace({5, 4, 3, 2, 1, 0});
    for (Index k = 0; k < 6; ++k) {
        const Index k1 = (k + 1) % 6;
        m.addFace({k, k1, 6 + k1, 6 + k});
        m.addFace({6 + k, 6 + k1, 12});
    }
    return m;
}

// A cube with an extra vertex on its top-front edge, pushed outwards: the top
// and front faces become (non-planar) pentagons sharing an edge.
PolygonMesh cubeWithPentagons() {
    PolygonMesh m;
    m.positions = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1),
                   Vec3(-1, 1, -1),  Vec3(-1, -1, 1), Vec3(1, -1, 1),
                   Vec3(1, 1, 1),    Vec3(-1, 1, 1),  Vec3(0.1, -1.25, 1.2)};
    m.addFace({0, 3, 2, 1});    // bottom
    m.addFace({0, 1, 5, 8, 4}); // front (y = -1), pentagon
    m.addFace({1, 2, 6, 5});    // right
    m.addFace({2, 3, 7, 6});    // back
    m.addFace({3, 0, 4, 7});    // left
    m.addFace({4, 8, 5, 6, 7}); // top, pentagon
    return m;
}

// An open frustum-shaped tube ("vase"): n quads around, rims at z = 0 and 1.
PolygonMesh vase(int n) {
    PolygonMesh m;
    for (int ring = 0; ring < 3; ++ring) {
        const double r = 1.0 - 0.25 * ring * ring / 2.0, z = 0.5 * ring;
        for (int k = 0; k < n; ++k)
            m.positions.emplace_back(r * std::cos(2 * kPi * k / n), r * std::sin(2 * kPi * k / n),
                                     z);
    }
    for (Index ring = 0; ring < 2; ++ring)
        for (Index k = 0; k < n; ++k) {
            const Index k1 = (k + 1) % n;
            m.addFace({ring * n + k, ring * n + k1, (ring + 1) * n + k1, (ring + 1) * n + k});
        }
    return m;
}

// One convex polygon with n corners in the plane through `origin` spanned by
// e1, e2 (slightly irregular).
PolygonMesh planarPolygon(int n, const Vec3& origin, const Vec3& e1, const Vec3& e2) {
    PolygonMesh m;
    std::vector<Index> face;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * kPi * (k + 0.15 * std::sin(3.0 * k)) / n;
        const double r = 1.0 + 0.03 * std::cos(2.0 * k);
        m.positions.push_back(origin + r * std::cos(t) * e1 + 0.8 * r * std::sin(t) * e2);
        face.push_back(k);
    }
    m.addFace(std::span<const Index>(face));
    return m;
}

struct NamedMesh {
    const char* name;
    PolygonMesh mesh;
};
std::vector<NamedMesh> crackMeshes() {
    return {{"sphere", makeSphere(1.0, 12)},         {"torus", makeTorus(1.0, 0.4, 16)},
            {"dodecahedron", dodecahedron()},        {"hexagon-house", hexagonHouse()},
            {"cube-pentagons", cubeWithPentagons()}, {"octagon-prism", prism(8, 0.7)}};
}

double sceneScale(const PolygonMesh& m) {
    return std::max(1.0, m.boundingBox().diagonal());
}

Vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    return Vec3(g(rng), g(rng), g(rng)).normalized();
}

// Whether (u, v) is at least `margin` away from the sub-patch seams of its
// face (b_i = 1/2 on triangles, u or v = 1/2 on quads).
bool awayFromSeams(bool quad, double u, double v, double margin) {
    if (quad)
        return std::abs(u - 0.5) > margin && std::abs(v - 0.5) > margin;
    const double b[3] = {1.0 - u - v, u, v};
    for (double x : b)
        if (std::abs(x - 0.5) < margin)
            return false;
    return true;
}

// ∫_0^1 |p''|² of a cubic Bézier, the §2.4 minimal-curvature energy.
double bendingEnergy(const std::array<Vec3, 4>& p) {
    const Vec3 a = p[0] - 2 * p[1] + p[2], b = p[1] - 2 * p[2] + p[3];
    return 36.0 * (a.squaredNorm() + a.dot(b) + b.squaredNorm()) / 3.0;
}
// The §2.4 eq. (3) "maximally stretched" energy.
double stretchEnergy(const std::array<Vec3, 4>& p) {
    return (3 * p[1] - 2 * p[0] - p[2]).squaredNorm() + (3 * p[2] - 2 * p[3] - p[1]).squaredNorm();
}

} // namespace

class TestVertexNormalPatches : public QObject {
    Q_OBJECT
private slots:
    // §2.4: constraints n0·(p1 − p0) = 0, n3·(p2 − p3) = 0; swapping the ends
    // swaps p1 and p2; normals ⟂ edge give thirds (minimal curvature) and
    // quarters (maximally stretched); each method is optimal for its energy
    // among points satisfying the constraints; the §2.3 five points.
    void edgeControlPoints() {
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> coord(-2.0, 2.0);
        double worstResidual = 0, worstSwap = 0;
        for (EdgeControlMethod method :
             {EdgeControlMethod::MinimalCurvature, EdgeControlMethod::MaximallyStretched}) {
            for (int trial = 0; trial < 2000; ++trial) {
                const Vec3 p0(coord(rng), coord(rng), coord(rng));
                const Vec3 p3(coord(rng), coord(rng), coord(rng));
                const Vec3 n0 = randomUnit(rng), n3 = randomUnit(rng);
                const auto c = vnp::edgeCubic(p0, n0, p3, n3, method);
                const double scale = (p3 - p0).norm();
                QVERIFY(c[0] == p0 && c[3] == p3);
                const double r = std::max(std::abs(n0.dot(c[1] - p0)), std::abs(n3.dot(c[2] - p3)));
                worstResidual = std::max(worstResidual, r / std::max(1.0, scale));
                const auto s = vnp::edgeCubic(p3, n3, p0, n0, method);
                worstSwap = std::max({worstSwap, (s[1] - c[2]).norm(), (s[2] - c[1]).norm()});
                // Optimality: feasible perturbations (inside the tangent
                // planes) never lower the method's energy.
                if (trial < 200) {
                    const auto energy = method == EdgeControlMethod::MinimalCurvature
                                            ? bendingEnergy
                                            : stretchEnergy;
                    const double e = energy(c);
                    for (int k = 0; k < 20; ++k) {
                        Vec3 d1 = randomUnit(rng), d2 = randomUnit(rng);
                        d1 -= d1.dot(n0) * n0;
                        d2 -= d2.dot(n3) * n3;
                        auto q = c;
                        q[1] += 1e-3 * d1;
                        q[2] += 1e-3 * d2;
                        QVERIFY2(energy(q) >= e - 1e-12 * std::max(1.0, e),
                                 qPrintable(QString("%1 < %2").arg(energy(q)).arg(e)));
                    }
                }
                // §2.3 / Fig. 2: the five points; m is the cubic's midpoint.
                const auto q = vnp::cubicToQuadratics(c);
                const Vec3 mid = 0.125 * c[0] + 0.375 * c[1] + 0.375 * c[2] + 0.125 * c[3];
                QVERIFY((q[2] - mid).norm() < 1e-12 * std::max(1.0, scale));
                QVERIFY((q[1] - (c[0] + 3 * c[1]) / 4).norm() < 1e-12 * std::max(1.0, scale));
                QVERIFY((q[3] - (3 * c[2] + c[3]) / 4).norm() < 1e-12 * std::max(1.0, scale));
                // C1 at m: q1, m, q3 collinear with m the midpoint.
                QVERIFY((q[2] - 0.5 * (q[1] + q[3])).norm() < 1e-12 * std::max(1.0, scale));
                const auto qr = vnp::cubicToQuadratics({c[3], c[2], c[1], c[0]});
                for (int i = 0; i < 5; ++i)
                    QVERIFY(qr[i] == q[4 - i]); // bit for bit
            }
            // Normals perpendicular to the edge.
            const Vec3 p0(0.3, -0.2, 0.5), p3(2.1, 0.7, -0.4);
            const Vec3 e = (p3 - p0).normalized();
            Vec3 n0 = Vec3(0.2, 1, 0.3), n3 = Vec3(-0.5, 0.1, 1);
            n0 = (n0 - n0.dot(e) * e).normalized();
            n3 = (n3 - n3.dot(e) * e).normalized();
            const auto c = vnp::edgeCubic(p0, n0, p3, n3, method);
            const double f = method == EdgeControlMethod::MinimalCurvature ? 1.0 / 3.0 : 0.25;
            QVERIFY((c[1] - (p0 + f * (p3 - p0))).norm() < 1e-14);
            QVERIFY((c[2] - (p3 + f * (p0 - p3))).norm() < 1e-14);
        }
        QVERIFY2(worstResidual < 1e-12, qPrintable(QString::number(worstResidual)));
        QVERIFY2(worstSwap < 1e-12, qPrintable(QString::number(worstSwap)));
        // Antiparallel normals: the 2x2 systems stay solvable.
        const auto c = vnp::edgeCubic(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, -1),
                                      EdgeControlMethod::MinimalCurvature);
        QVERIFY(c[1].allFinite() && c[2].allFinite());
        qInfo("edge control points: worst constraint residual %.3g, worst swap mismatch %.3g",
              worstResidual, worstSwap);
    }

    // The constraints on every edge of real cages, as used by the patches.
    void cageEdgesSatisfyConstraints() {
        double worst = 0;
        for (const NamedMesh& m : crackMeshes()) {
            const auto s = VertexNormalPatches::create(m.mesh);
            const auto& n = s->vertexNormals();
            for (Index f = 0; f < m.mesh.faceCount(); ++f) {
                const auto face = m.mesh.face(f);
                for (size_t i = 0; i < face.size(); ++i) {
                    const Index a = face[i], b = face[(i + 1) % face.size()];
                    const auto c = s->cageEdgeCubic(a, b);
                    worst = std::max(
                        {worst, std::abs(n[a].dot(c[1] - c[0])), std::abs(n[b].dot(c[2] - c[3]))});
                    const auto r = s->cageEdgeCubic(b, a);
                    QVERIFY(r[1] == c[2] && r[2] == c[1]);
                }
            }
            for (Index v = 0; v < m.mesh.vertexCount(); ++v)
                QVERIFY(std::abs(n[v].norm() - 1.0) < 1e-12);
        }
        QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
        qInfo("cage edges: worst constraint residual %.3g", worst);
    }

    // §2.7 quadratic normal interpolation: exact on a circular arc (both
    // normals symmetric about the chord's bisector) and on asymmetric
    // planar arcs of a circle it is close; symmetric in the ends.
    void quadraticNormalInterpolation() {
        for (double half : {0.1, 0.4, 0.8}) {
            const Vec3 p0(-std::sin(half), std::cos(half), 0),
                p3(std::sin(half), std::cos(half), 0);
            const Vec3 n = vnp::quadraticMidpointNormal(p0, p0, p3, p3);
            QVERIFY((n - Vec3(0, 1, 0)).norm() < 1e-14);
        }
        std::mt19937 rng(5);
        for (int i = 0; i < 100; ++i) {
            const Vec3 p0 = randomUnit(rng), p3 = randomUnit(rng);
            const Vec3 n0 = randomUnit(rng), n3 = randomUnit(rng);
            const Vec3 a = vnp::quadraticMidpointNormal(p0, n0, p3, n3);
            const Vec3 b = vnp::quadraticMidpointNormal(p3, n3, p0, n0);
            QVERIFY((a - b).norm() < 1e-14);
            QVERIFY(std::abs(a.norm() - 1) < 1e-14);
        }
    }

    // §2.1.1 C0: both faces on a shared domain edge give the same points,
    // sampled through neighbor()/transferAcrossEdge(); domain vertices are
    // surface points; cage edges are the edge-only quadratics.
    void noCracks_data() {
        QTest::addColumn<int>("which");
        QTest::addColumn<int>("method");
        const auto meshes = crackMeshes();
        for (int i = 0; i < static_cast<int>(meshes.size()); ++i)
            for (int method = 0; method < 2; ++method)
                QTest::newRow(qPrintable(QString("%1/%2")
                                             .arg(meshes[i].name)
                                             .arg(method ? "stretched" : "min-curvature")))
                    << i << method;
    }
    void noCracks() {
        QFETCH(int, which);
        QFETCH(int, method);
        const PolygonMesh cage = crackMeshes()[which].mesh;
        VertexNormalPatchOptions o;
        o.edgeMethod =
            method ? EdgeControlMethod::MaximallyStretched : EdgeControlMethod::MinimalCurvature;
        const auto s = VertexNormalPatches::create(cage, o);
        const PolygonMesh& d = s->domain();
        const double tol = 1e-12 * sceneScale(cage);
        double worst = 0;
        int shared = 0;
        for (Index f = 0; f < d.faceCount(); ++f) {
            const bool quad = s->isQuad(f);
            const int n = quad ? 4 : 3;
            const auto corners = d.face(f);
            for (int c = 0; c < n; ++c) {
                const Vec2 x = SmoothSurface::cornerCoordinates(quad, c);
                worst = std::max(
                    worst,
                    (s->evaluate({f, x.x(), x.y()}).position - d.positions[corners[c]]).norm());
            }
            for (int e = 0; e < n; ++e) {
                const auto nb = s->neighbor(f, e);
                QVERIFY2(nb.face != kInvalidIndex, "closed cage: every domain edge is shared");
                QCOMPARE(s->neighbor(nb.face, nb.edge).face, f);
                ++shared;
                const Vec2 a0 = SmoothSurface::cornerCoordinates(quad, e);
                const Vec2 a1 = SmoothSurface::cornerCoordinates(quad, (e + 1) % n);
                const Index ca = corners[e], cb = corners[(e + 1) % n];
                const bool cageEdge = ca < s->cageVertexCount() && cb < s->cageVertexCount();
                std::array<Vec3, 5> q{};
                if (cageEdge)
                    q = vnp::cubicToQuadratics(s->cageEdgeCubic(ca, cb));
                for (int i = 0; i <= 16; ++i) {
                    const double t = i / 16.0;
                    const Vec2 x = a0 + t * (a1 - a0);
                    const Preimage p{f, x.x(), x.y()};
                    const Preimage o2 = s->transferAcrossEdge(p, e);
                    const double slack = 1e-12;
                    QVERIFY(o2.u >= -slack && o2.v >= -slack &&
                            (s->isQuad(o2.face) ? o2.u <= 1 + slack && o2.v <= 1 + slack
                                                : o2.u + o2.v <= 1 + slack));
                    const Vec3 here = s->evaluate(p).position;
                    worst = std::max(worst, (here - s->evaluate(o2).position).norm());
                    if (cageEdge) {
                        // The two quadratics p0 q1 m and m q3 p3 (§2.3 step 2).
                        const double w = t < 0.5 ? 2 * t : 2 * t - 1;
                        const int k = t < 0.5 ? 0 : 2;
                        const Vec3 curve = (1 - w) * (1 - w) * q[k] + 2 * w * (1 - w) * q[k + 1] +
                                           w * w * q[k + 2];
                        worst = std::max(worst, (here - curve).norm());
                    }
                }
            }
        }
        qInfo("%d shared edge sides, worst position mismatch %.3g", shared, worst);
        QVERIFY2(worst < tol, qPrintable(QString::number(worst)));
    }

    // A planar polygon whose normals all equal the plane's normal stays in
    // the plane: positions and all derivatives, and the refined output.
    void planarPolygonStaysPlanar_data() {
        QTest::addColumn<int>("corners");
        for (int n : {3, 4, 5, 6, 8, 11})
            QTest::newRow(qPrintable(QString("%1-gon").arg(n))) << n;
    }
    void planarPolygonStaysPlanar() {
        QFETCH(int, corners);
        const Vec3 origin(0.3, -1.2, 2.0);
        const Vec3 e1 = Vec3(1, 0.4, -0.3).normalized();
        const Vec3 e2 = e1.cross(Vec3(0.2, 1, 0.5)).normalized();
        const Vec3 normal = e1.cross(e2);
        const PolygonMesh cage = planarPolygon(corners, origin, e1, e2);
        double worst = 0;
        for (EdgeControlMethod method :
             {EdgeControlMethod::MinimalCurvature, EdgeControlMethod::MaximallyStretched})
            for (double lambda : {0.0, 0.5, 1.0})
                for (bool border : {true, false}) {
                    VertexNormalPatchOptions o;
                    o.edgeMethod = method;
                    o.apexLambda = lambda;
                    o.boundaryNormalsInBorderPlane = border;
                    const auto s = VertexNormalPatches::create(cage, o);
                    for (const Vec3& n : s->vertexNormals())
                        QVERIFY((n - normal).norm() < 1e-12);
                    for (Index f = 0; f < s->domain().faceCount(); ++f)
                        for (int i = 0; i <= 10; ++i)
                            for (int j = 0; j <= 10; ++j) {
                                if (!s->isQuad(f) && i + j > 10)
                                    continue;
                                const SurfacePoint p = s->evaluate({f, i / 10.0, j / 10.0});
                                for (const Vec3& d :
                                     {Vec3(p.position - origin), p.du, p.dv, p.duu, p.duv, p.dvv})
                                    worst = std::max(worst, std::abs(d.dot(normal)));
                                QVERIFY(p.normal().dot(normal) > 1 - 1e-12);
                            }
                    const RefinedMesh r = s->refine(3);
                    for (Index v = 0; v < r.mesh.vertexCount(); ++v) {
                        worst =
                            std::max(worst, std::abs((r.mesh.position(v) - origin).dot(normal)));
                        QVERIFY((r.normals[v] - normal).norm() < 1e-12);
                    }
                }
        QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
    }

    // §2.5: a triangle becomes 4 triangles, a quad 8 and an n-gon 4n; every
    // later pass multiplies by 4. The refined mesh of a closed cage is closed
    // (no cracks), its first-pass vertices lie on the patches and its
    // normals are unit.
    void refineCounts() {
        const Vec3 o(0, 0, 0), e1(1, 0, 0), e2(0, 1, 0);
        for (int n = 3; n <= 9; ++n) {
            const auto s = VertexNormalPatches::create(planarPolygon(n, o, e1, e2));
            const int first = n == 3 ? 4 : n == 4 ? 8 : 4 * n;
            QCOMPARE(s->refine(1).mesh.faceCount(), first);
            QCOMPARE(s->refine(2).mesh.faceCount(), 4 * first);
            QCOMPARE(s->refine(3).mesh.faceCount(), 16 * first);
        }
        for (const NamedMesh& m : crackMeshes()) {
            const auto s = VertexNormalPatches::create(m.mesh);
            long long expected = 0;
            for (Index f = 0; f < m.mesh.faceCount(); ++f) {
                const auto n = static_cast<long long>(m.mesh.face(f).size());
                expected += n == 3 ? 4 : n == 4 ? 8 : 4 * n;
            }
            const RefinedMesh r1 = s->refine(1);
            QCOMPARE(static_cast<long long>(r1.mesh.faceCount()), expected);
            QCOMPARE(r1.mesh.boundaryEdgeCount(), 0);
            // First-pass vertices are surface points: each triangle's
            // corners are corners of the sub-patches.
            for (Index f = 0; f < r1.mesh.faceCount(); ++f)
                QVERIFY(r1.mesh.sourcePolygon(f) >= 0 &&
                        r1.mesh.sourcePolygon(f) < m.mesh.faceCount());
            const RefinedMesh r3 = s->refine(3);
            QCOMPARE(static_cast<long long>(r3.mesh.faceCount()), 16 * expected);
            QCOMPARE(r3.mesh.boundaryEdgeCount(), 0);
            QCOMPARE(static_cast<size_t>(r3.mesh.vertexCount()), r3.normals.size());
            for (const Vec3& n : r3.normals)
                QVERIFY(std::abs(n.norm() - 1) < 1e-12);
            const RefinedMesh r0 = s->refine(0);
            QCOMPARE(r0.mesh.vertexCount(), s->domain().vertexCount());
        }
        // Side midpoints of the first pass are the patch points at the
        // domain edges' midpoints.
        const auto s = VertexNormalPatches::create(hexagonHouse());
        const RefinedMesh r1 = s->refine(1);
        double worst = 0;
        for (Index f = 0; f < s->domain().faceCount(); ++f) {
            const bool quad = s->isQuad(f);
            for (int e = 0; e < (quad ? 4 : 3); ++e) {
                const Vec2 x =
                    0.5 * (SmoothSurface::cornerCoordinates(quad, e) +
                           SmoothSurface::cornerCoordinates(quad, (e + 1) % (quad ? 4 : 3)));
                const Vec3 p = s->evaluate({f, x.x(), x.y()}).position;
                double best = 1e300;
                for (const Vec3& q : r1.mesh.positions())
                    best = std::min(best, (q - p).norm());
                worst = std::max(worst, best);
            }
        }
        QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, s->refine(-1));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, s->refine(40));
    }

    // First and second derivatives against central differences, at random
    // points of every sub-patch (away from the sub-patch seams, where the
    // patches are only C0 and a stencil would straddle two pieces).
    void derivativesMatchFiniteDifferences() {
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        double worstFirst = 0, worstSecond = 0;
        int samples = 0;
        std::vector<NamedMesh> meshes = crackMeshes();
        meshes.push_back({"vase", vase(7)});
        for (const NamedMesh& m : meshes) {
            const auto s = VertexNormalPatches::create(m.mesh);
            for (Index f = 0; f < s->domain().faceCount(); ++f) {
                const bool quad = s->isQuad(f);
                for (int k = 0; k < 24; ++k) {
                    double u = unit(rng), v = unit(rng);
                    if (!quad && u + v > 1) {
                        u = 1 - u;
                        v = 1 - v;
                    }
                    if (!awayFromSeams(quad, u, v, 0.02))
                        continue;
                    const auto at = [&](double du, double dv) {
                        return s->evaluate({f, u + du, v + dv});
                    };
                    const SurfacePoint p = at(0, 0);
                    const double h1 = 1e-5, h2 = 1e-3;
                    const Vec3 fu = (at(h1, 0).position - at(-h1, 0).position) / (2 * h1);
                    const Vec3 fv = (at(0, h1).position - at(0, -h1).position) / (2 * h1);
                    const Vec3 fuu =
                        (at(h2, 0).position - 2 * p.position + at(-h2, 0).position) / (h2 * h2);
                    const Vec3 fvv =
                        (at(0, h2).position - 2 * p.position + at(0, -h2).position) / (h2 * h2);
                    const Vec3 fuv = (at(h2, h2).position - at(h2, -h2).position -
                                      at(-h2, h2).position + at(-h2, -h2).position) /
                                     (4 * h2 * h2);
                    const double s1 = std::max({1.0, p.du.norm(), p.dv.norm()});
                    const double s2 = std::max({1.0, p.duu.norm(), p.duv.norm(), p.dvv.norm()});
                    worstFirst =
                        std::max({worstFirst, (fu - p.du).norm() / s1, (fv - p.dv).norm() / s1});
                    worstSecond = std::max({worstSecond, (fuu - p.duu).norm() / s2,
                                            (fuv - p.duv).norm() / s2, (fvv - p.dvv).norm() / s2});
                    ++samples;
                }
            }
        }
        qInfo("%d samples: worst relative FD error, first derivatives %.3g, second %.3g", samples,
              worstFirst, worstSecond);
        QVERIFY2(worstFirst < 1e-8, qPrintable(QString::number(worstFirst)));
        QVERIFY2(worstSecond < 1e-6, qPrintable(QString::number(worstSecond)));
    }

    // §2.5: λ = 0 (our default) puts the apex of a regular polygon at the
    // height of the interior points: all fan patches share the tangent plane
    // there and the surface falls off monotonically from the apex (no
    // inflection between apex and corners). λ > 0 sinks the apex into a
    // dimple ("buckling"), λ < 0 raises a cone-like peak.
    void apexLambda() {
        QCOMPARE(VertexNormalPatchOptions{}.apexLambda, 0.0);
        for (int n : {5, 6, 8, 12}) {
            const double h = 0.6;
            const PolygonMesh cage = prism(n, h);
            for (double lambda : {-0.5, 0.0, 0.5}) {
                VertexNormalPatchOptions o;
                o.apexLambda = lambda;
                const auto s = VertexNormalPatches::create(cage, o);
                double crease = 0, firstSlope = 0, maxSlope = -1e300;
                bool found = false;
                Vec3 apexNormal = Vec3::Zero();
                for (Index f = 0; f < s->domain().faceCount(); ++f) {
                    if (s->isQuad(f) || s->evaluate({f, 0, 1}).position.z() < h)
                        continue; // a fan triangle of the top cap
                    const Vec3 nf = s->evaluate({f, 0, 1}).normal();
                    if (!found)
                        apexNormal = nf;
                    crease = std::max(crease, std::acos(std::min(1.0, nf.dot(apexNormal))));
                    if (found)
                        continue;
                    found = true;
                    // Height against distance from the axis, from the apex
                    // to the midpoint of the cage edge.
                    Vec3 prev = s->evaluate({f, 0, 1}).position;
                    for (int i = 1; i <= 100; ++i) {
                        const double t = i / 100.0;
                        const Vec3 p = s->evaluate({f, 0.5 * t, 1 - t}).position;
                        const double slope =
                            (p.z() - prev.z()) / (p.head<2>().norm() - prev.head<2>().norm());
                        if (i == 1)
                            firstSlope = slope;
                        maxSlope = std::max(maxSlope, slope);
                        prev = p;
                    }
                }
                QVERIFY(found);
                if (lambda == 0.0) {
                    QVERIFY2(crease < 1e-9, qPrintable(QString::number(crease)));
                    QVERIFY((apexNormal - Vec3(0, 0, 1)).norm() < 1e-9);
                    QVERIFY2(maxSlope <= 1e-9, qPrintable(QString::number(maxSlope)));
                } else if (lambda > 0) {
                    QVERIFY2(firstSlope > 1e-3, qPrintable(QString::number(firstSlope))); // dimple
                } else {
                    QVERIFY(crease > 1e-3); // peak
                    QVERIFY(firstSlope < -1e-3);
                }
            }
        }
    }

    // §2.8: with border normals forced into the plane of the border edges,
    // the rims of an open tube are planar curves; without, they undulate.
    void borderNormals() {
        const PolygonMesh cage = vase(7);
        for (bool force : {true, false}) {
            VertexNormalPatchOptions o;
            o.boundaryNormalsInBorderPlane = force;
            const auto s = VertexNormalPatches::create(cage, o);
            double worst = 0;
            int borderEdges = 0;
            for (Index f = 0; f < s->domain().faceCount(); ++f)
                for (int e = 0; e < 4; ++e) {
                    if (s->neighbor(f, e).face != kInvalidIndex)
                        continue;
                    ++borderEdges;
                    const Vec2 a0 = SmoothSurface::cornerCoordinates(true, e);
                    const Vec2 a1 = SmoothSurface::cornerCoordinates(true, (e + 1) % 4);
                    const double z0 = s->evaluate({f, a0.x(), a0.y()}).position.z();
                    for (int i = 1; i < 10; ++i) {
                        const Vec2 x = a0 + (i / 10.0) * (a1 - a0);
                        worst = std::max(
                            worst, std::abs(s->evaluate({f, x.x(), x.y()}).position.z() - z0));
                    }
                }
            QCOMPARE(borderEdges, 14);
            qInfo("border normals %s: rim height variation %.3g",
                  force ? "in border plane" : "averaged", worst);
            if (force)
                QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
            else
                QVERIFY(worst > 1e-3);
        }
    }

    // The surface follows a sphere much more closely than the flat cage;
    // `factor` is the improvement required (the cube, with vertex normals
    // 70° apart, is the coarsest case).
    void sphereAccuracy_data() {
        QTest::addColumn<int>("which");
        QTest::addColumn<double>("factor");
        QTest::newRow("lat-long sphere 8") << 0 << 3.0;
        QTest::newRow("lat-long sphere 16") << 1 << 3.0;
        QTest::newRow("dodecahedron") << 2 << 3.0;
        QTest::newRow("icosahedron") << 3 << 8.0;
        QTest::newRow("cube") << 4 << 2.0;
    }
    void sphereAccuracy() {
        QFETCH(int, which);
        QFETCH(double, factor);
        const PolygonMesh cage = which == 0   ? makeSphere(1.0, 8)
                                 : which == 1 ? makeSphere(1.0, 16)
                                 : which == 2 ? dodecahedron()
                                 : which == 3 ? icosahedron()
                                              : cube();
        // Flat: the cage's polygons as fans of triangles from their centroid.
        double flat = 0;
        for (Index f = 0; f < cage.faceCount(); ++f) {
            const auto face = cage.face(f);
            Vec3 c = Vec3::Zero();
            for (Index v : face)
                c += cage.positions[v];
            c /= static_cast<double>(face.size());
            for (size_t k = 0; k < face.size(); ++k)
                for (int i = 0; i <= 20; ++i)
                    for (int j = 0; i + j <= 20; ++j) {
                        const Vec3 p = c + i / 20.0 * (cage.positions[face[k]] - c) +
                                       j / 20.0 * (cage.positions[face[(k + 1) % face.size()]] - c);
                        flat = std::max(flat, std::abs(p.norm() - 1));
                    }
        }
        const auto s = VertexNormalPatches::create(cage);
        double patches = 0, normalAngle = 0;
        for (Index f = 0; f < s->domain().faceCount(); ++f)
            for (int i = 0; i <= 20; ++i)
                for (int j = 0; j <= 20; ++j) {
                    if (!s->isQuad(f) && i + j > 20)
                        continue;
                    const SurfacePoint p = s->evaluate({f, i / 20.0, j / 20.0});
                    patches = std::max(patches, std::abs(p.position.norm() - 1));
                    normalAngle =
                        std::max(normalAngle,
                                 std::acos(std::min(1.0, p.normal().dot(p.position.normalized()))));
                }
        const RefinedMesh r = s->refine(3);
        double refined = 0, refinedNormal = 0;
        for (Index v = 0; v < r.mesh.vertexCount(); ++v) {
            refined = std::max(refined, std::abs(r.mesh.position(v).norm() - 1));
            refinedNormal = std::max(
                refinedNormal,
                std::acos(std::min(1.0, r.normals[v].dot(r.mesh.position(v).normalized()))));
        }
        qInfo(
            "max | |p| - 1 |: flat cage %.4f, patches %.4f (%.1fx closer), refine(3) vertices "
            "%.4f; max angle to the radial direction: patches %.1f deg, refine(3) normals %.1f deg",
            flat, patches, flat / patches, refined, normalAngle * 180 / kPi,
            refinedNormal * 180 / kPi);
        QVERIFY(patches < flat / factor);
        QVERIFY(refined < flat / factor);
    }

    // Convergence on the latitude-longitude sphere, away from the poles
    // (|z| < 0.5): the flat cage's error falls as h², the patches' as about
    // h³. Near the poles the area-weighted vertex normals themselves are off
    // by O(h) (the polygons above and below a ring differ in area), which
    // limits the patches there to O(h²).
    void sphereConvergence() {
        double previousFlat = 0, previousPatches = 0;
        for (int resolution : {16, 32, 64}) {
            const PolygonMesh cage = makeSphere(1.0, resolution);
            const auto s = VertexNormalPatches::create(cage);
            double flat = 0, patches = 0;
            for (Index f = 0; f < s->domain().faceCount(); ++f) {
                if (!s->isQuad(f))
                    continue;
                const auto c = s->domain().face(f);
                for (int i = 0; i <= 20; ++i)
                    for (int j = 0; j <= 20; ++j) {
                        const double u = i / 20.0, v = j / 20.0;
                        const Vec3 p = s->evaluate({f, u, v}).position;
                        const Vec3 q = (1 - u) * (1 - v) * cage.positions[c[0]] +
                                       u * (1 - v) * cage.positions[c[1]] +
                                       u * v * cage.positions[c[2]] +
                                       (1 - u) * v * cage.positions[c[3]];
                        if (std::abs(p.z()) < 0.5)
                            patches = std::max(patches, std::abs(p.norm() - 1));
                        if (std::abs(q.z()) < 0.5)
                            flat = std::max(flat, std::abs(q.norm() - 1));
                    }
            }
            qInfo("resolution %d, |z| < 0.5: flat (bilinear) %.3g, patches %.3g (%.1fx closer)",
                  resolution, flat, patches, flat / patches);
            if (previousFlat > 0) {
                const double flatOrder = std::log2(previousFlat / flat);
                const double patchOrder = std::log2(previousPatches / patches);
                qInfo("  observed order: flat %.2f, patches %.2f", flatOrder, patchOrder);
                QVERIFY(flatOrder > 1.8 && flatOrder < 2.2);
                QVERIFY(patchOrder > 2.8);
            }
            QVERIFY(patches < flat / 8);
            previousFlat = flat;
            previousPatches = patches;
        }
    }

    void rejectsBadInput() {
        PolygonMesh empty;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, VertexNormalPatches::create(empty));
        PolygonMesh twoCorners;
        twoCorners.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
        twoCorners.addFace({0, 1});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, VertexNormalPatches::create(twoCorners));
        PolygonMesh outOfRange;
        outOfRange.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        outOfRange.addFace({0, 1, 3});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, VertexNormalPatches::create(outOfRange));
        PolygonMesh nan = outOfRange;
        nan.indices.back() = 2;
        nan.positions[1].x() = std::nan("");
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, VertexNormalPatches::create(nan));
        PolygonMesh degenerate;
        degenerate.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
        degenerate.addFace({0, 1, 2});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, VertexNormalPatches::create(degenerate));
        VertexNormalPatchOptions o;
        o.apexLambda = std::nan("");
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 VertexNormalPatches::create(makeSphere(1, 8), o));
        QCOMPARE(edgeControlMethodFromName("maximally-stretched"),
                 EdgeControlMethod::MaximallyStretched);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, edgeControlMethodFromName("cubic"));
    }

    void evaluationSpeed() {
        const auto s = VertexNormalPatches::create(makeTorus(1.0, 0.4, 64));
        std::vector<Preimage> pre;
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::uniform_int_distribution<Index> face(0, s->domain().faceCount() - 1);
        for (int i = 0; i < 1'000'000; ++i)
            pre.push_back({face(rng), unit(rng), unit(rng)});
        Vec3 sum = Vec3::Zero();
        QElapsedTimer timer;
        timer.start();
        for (const Preimage& p : pre)
            sum += s->evaluate(p).duv;
        const double seconds = std::max(1e-9, timer.nsecsElapsed() * 1e-9);
        QVERIFY(sum.allFinite());
        qInfo("%.2f million evaluations (position + 1st + 2nd derivatives) per second, one thread",
              pre.size() / seconds * 1e-6);
    }
};

QTEST_APPLESS_MAIN(TestVertexNormalPatches)
#include "test_vertex_normal_patches.moc"
