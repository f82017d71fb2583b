// Fields on smooth surfaces (SurfaceFields.h), the uniform tessellation
// (SurfaceTessellation.h) and the surface phase of the mesh-based methods,
// checked against analytic surfaces with exact derivatives defined here: a
// sphere as the central projection of a cube (6 quad charts) or of an
// octahedron (8 triangle charts), a cylinder and a torus on quad grids.
//
// Sign convention under test: II_ij = f_ij · n with the outward unit normal,
// so a sphere of radius R has normal curvature -1/R in every direction and
// radial curvature -1/R, Gaussian curvature 1/R^2 and mean curvature -1/R.
#include "ContourTestSupport.h"
#include "camera/Facing.h"
#include "contours/common/SurfacePhase.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"
#include "surface/SurfaceFields.h"
#include "surface/SurfaceTessellation.h"

#include <QtTest>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <thread>

using namespace contour;
using namespace contour::testing;

namespace {

constexpr double kPi = std::numbers::pi;

// The analytic surfaces say they are Catmull-Clark only because kind() must
// return something; nothing in these tests looks at it.
class AnalyticSurface : public SmoothSurface {
public:
    SurfaceKind kind() const override { return SurfaceKind::CatmullClark; }

protected:
    void setDomain(PolygonMesh domain) {
        domain_ = std::move(domain);
        buildAdjacency();
    }
};

// c + R q / |q| over the faces of a polyhedron whose faces are charts:
// bilinear on quads, linear on triangles.
class ProjectedSphere final : public AnalyticSurface {
public:
    ProjectedSphere(PolygonMesh polyhedron, double radius, const Vec3& center)
        : radius_(radius), center_(center) {
        corners_ = polyhedron.positions;
        for (Vec3& p : polyhedron.positions)
            p = center + radius * p.normalized();
        setDomain(std::move(polyhedron));
    }
    std::string description() const override { return "analytic sphere"; }
    using SmoothSurface::evaluate; // the batch overload
    double radius() const { return radius_; }
    const Vec3& center() const { return center_; }

    SurfacePoint evaluate(const Preimage& p) const override {
        const auto c = domain().face(p.face);
        const double u = p.u, v = p.v;
        Vec3 q, qu, qv, quv = Vec3::Zero();
        if (c.size() == 4) {
            const Vec3 &p0 = corners_[c[0]], &p1 = corners_[c[1]], &p2 = corners_[c[2]],
                       &p3 = corners_[c[3]];
            const Vec3 d = p0 - p1 + p2 - p3;
            q = p0 + u * (p1 - p0) + v * (p3 - p0) + u * v * d;
            qu = (p1 - p0) + v * d;
            qv = (p3 - p0) + u * d;
            quv = d;
        } else {
            const Vec3 &p0 = corners_[c[0]], &p1 = corners_[c[1]], &p2 = corners_[c[2]];
            q = p0 + u * (p1 - p0) + v * (p2 - p0);
            qu = p1 - p0;
            qv = p2 - p0;
        }
        // h(q) = q / |q|: Dh a = (a - qh (qh·a)) / r, and
        // D2h[a, b] = -(a (qh·b) + b (qh·a) + qh (a·b) - 3 qh (qh·a)(qh·b)) / r^2.
        const double r = q.norm();
        const Vec3 qh = q / r;
        const auto dh = [&](const Vec3& a) -> Vec3 {
            return (a - qh * qh.dot(a)) / r;
        };
        const auto d2h = [&](const Vec3& a, const Vec3& b) -> Vec3 {
            return -(a * qh.dot(b) + b * qh.dot(a) + qh * a.dot(b) -
                     3.0 * qh * qh.dot(a) * qh.dot(b)) /
                   (r * r);
        };
        SurfacePoint s;
        s.position = center_ + radius_ * qh;
        s.du = radius_ * dh(qu);
        s.dv = radius_ * dh(qv);
        s.duu = radius_ * d2h(qu, qu);
        s.duv = radius_ * (d2h(qu, qv) + dh(quv));
        s.dvv = radius_ * d2h(qv, qv);
        return s;
    }

private:
    double radius_;
    Vec3 center_;
    std::vector<Vec3> corners_;
};

PolygonMesh cube() {
    PolygonMesh m;
    m.positions = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(-1, 1, -1),
                   Vec3(-1, -1, 1),  Vec3(1, -1, 1),  Vec3(1, 1, 1),  Vec3(-1, 1, 1)};
    m.addFace({0, 3, 2, 1});
    m.addFace({4, 5, 6, 7});
    m.addFace({0, 1, 5, 4});
    m.addFace({2, 3, 7, 6});
    m.addFace({0, 4, 7, 3});
    m.addFace({1, 2, 6, 5});
    return m;
}

PolygonMesh octahedron() {
    PolygonMesh m;
    m.positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                   Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    const int top = 4, bottom = 5;
    const int ring[4] = {0, 2, 1, 3}; // counter-clockwise around +z
    for (int k = 0; k < 4; ++k) {
        m.addFace({ring[k], ring[(k + 1) % 4], top});
        m.addFace({ring[(k + 1) % 4], ring[k], bottom});
    }
    return m;
}

// A surface F(a, b) over a grid of quads: face (i, j) maps (u, v) to
// a = a0 + (i + u) da, b = b0 + (j + v) db. The grid wraps around in a (and in
// b when closedB).
class GridSurface : public AnalyticSurface {
public:
    struct Derivatives {
        Vec3 f, fa, fb, faa, fab, fbb;
    };
    virtual Derivatives at(double a, double b) const = 0;
    using SmoothSurface::evaluate; // the batch overload

    SurfacePoint evaluate(const Preimage& p) const override {
        const int i = p.face % n_, j = p.face / n_;
        const Derivatives d = at(a0_ + (i + p.u) * da_, b0_ + (j + p.v) * db_);
        SurfacePoint s;
        s.position = d.f;
        s.du = da_ * d.fa;
        s.dv = db_ * d.fb;
        s.duu = da_ * da_ * d.faa;
        s.duv = da_ * db_ * d.fab;
        s.dvv = db_ * db_ * d.fbb;
        return s;
    }
    // The preimage of (a, b), with a in [a0, a0 + n da) and b in range.
    Preimage preimageOf(double a, double b) const {
        const double x = (a - a0_) / da_, y = (b - b0_) / db_;
        const int i = std::clamp(static_cast<int>(std::floor(x)), 0, n_ - 1);
        const int j = std::clamp(static_cast<int>(std::floor(y)), 0, m_ - 1);
        return {j * n_ + i, x - i, y - j};
    }
    int columns() const { return n_; }
    int rows() const { return m_; }

protected:
    void build(int n, int m, bool closedB, double a0, double da, double b0, double db) {
        n_ = n, m_ = m, a0_ = a0, da_ = da, b0_ = b0, db_ = db;
        PolygonMesh grid;
        const int rowsOfVertices = closedB ? m : m + 1;
        for (int j = 0; j < rowsOfVertices; ++j)
            for (int i = 0; i < n; ++i)
                grid.positions.push_back(at(a0 + i * da, b0 + j * db).f);
        const auto vertex = [&](int i, int j) {
            return (j % rowsOfVertices) * n + (i % n);
        };
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < n; ++i)
                grid.addFace(
                    {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
        setDomain(std::move(grid));
    }

private:
    int n_ = 0, m_ = 0;
    double a0_ = 0, da_ = 1, b0_ = 0, db_ = 1;
};

// Torus around z: major radius R, minor r; a = theta around z, b = phi
// around the tube (phi = 0 on the outer equator, pi/2 on top).
class Torus final : public GridSurface {
public:
    Torus(double major, double minor, int n, int m) : major_(major), minor_(minor) {
        build(n, m, true, 0.0, 2 * kPi / n, 0.0, 2 * kPi / m);
    }
    std::string description() const override { return "analytic torus"; }
    Derivatives at(double t, double p) const override {
        const double R = major_, r = minor_, ct = std::cos(t), st = std::sin(t), cp = std::cos(p),
                     sp = std::sin(p), w = R + r * cp;
        return {Vec3(w * ct, w * st, r * sp),
                Vec3(-w * st, w * ct, 0),
                Vec3(-r * sp * ct, -r * sp * st, r * cp),
                Vec3(-w * ct, -w * st, 0),
                Vec3(r * sp * st, -r * sp * ct, 0),
                Vec3(-r * cp * ct, -r * cp * st, -r * sp)};
    }
    double major() const { return major_; }
    double minor() const { return minor_; }

private:
    double major_, minor_;
};

// Open cylinder around z: radius rho, z in [0, height].
class Cylinder final : public GridSurface {
public:
    Cylinder(double radius, double height, int n, int m) : radius_(radius) {
        build(n, m, false, 0.0, 2 * kPi / n, 0.0, height / m);
    }
    std::string description() const override { return "analytic cylinder"; }
    Derivatives at(double t, double z) const override {
        const double c = std::cos(t), s = std::sin(t), r = radius_;
        return {Vec3(r * c, r * s, z),   Vec3(-r * s, r * c, 0), Vec3(0, 0, 1),
                Vec3(-r * c, -r * s, 0), Vec3::Zero(),           Vec3::Zero()};
    }
    double radius() const { return radius_; }

private:
    double radius_;
};

Camera perspectiveAt(const Vec3& eye, const Vec3& target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.up = std::abs((target - eye).normalized().z()) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
    return c;
}

Camera orthographicAlong(const Vec3& toCamera) {
    Camera c = perspectiveAt(toCamera, Vec3::Zero());
    c.projection = Projection::Orthographic;
    return c;
}

Vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    return Vec3(n(rng), n(rng), n(rng)).normalized();
}

Preimage randomPreimage(const SmoothSurface& s, std::mt19937& rng) {
    std::uniform_int_distribution<Index> face(0, s.domain().faceCount() - 1);
    std::uniform_real_distribution<double> x(0.0, 1.0);
    Preimage p{face(rng), x(rng), x(rng)};
    if (!s.isQuad(p.face) && p.u + p.v > 1.0) {
        p.u = 1.0 - p.u;
        p.v = 1.0 - p.v;
    }
    return p;
}

// Tangent basis at a point: unit du and n x du.
std::pair<Vec3, Vec3> tangentBasis(const SurfacePoint& p) {
    const Vec3 e1 = p.du.normalized();
    return {e1, p.normal().cross(e1)};
}

double signedVolume(const TriangleMesh& mesh) {
    double v = 0;
    for (const Triangle& t : mesh.triangles())
        v += mesh.position(t[0]).dot(mesh.position(t[1]).cross(mesh.position(t[2])));
    return v / 6.0;
}

// Runs the phases after `surface` of a method on a snapshot whose surface
// phase was applied by hand, counting post-conditions as the Runner does.
Snapshot runAfterSurface(const std::string& method, Snapshot s, const Camera& camera) {
    const Method& m = *findMethod(method);
    const ParameterSet p = ParameterSet::defaults(m.parameters);
    const PhaseContext ctx(camera, p);
    long long violations = 0;
    for (size_t i = 1; i < m.phases.size(); ++i) {
        m.phases[i].run(ctx, s);
        for (const InvariantCheck& c : m.phases[i].postconditions(ctx, s))
            violations += c.violations;
    }
    s.invariants = {{"all post-conditions", violations, ""}};
    return s;
}

Snapshot withSurface(const std::shared_ptr<const SmoothSurface>& surface, int level,
                     const Camera& camera) {
    Snapshot s = makeInputSnapshot(std::make_shared<const PolygonMesh>(surface->domain()));
    applySmoothSurface(s, surface, level, camera);
    return s;
}

// How far an interpolated contour point is from the smooth contour
// generator: its preimage u* (linear along the edge, in the triangle's domain
// face) maps to f(u*), at |f(u*) - p| from the point, and f(u*) is about
// |g(u*)| / |grad g| from the zero set of g (first order, surface gradient
// |grad g|^2 = dg^T I^-1 dg).
double contourDistance(const SmoothSurface& surface, const SurfaceTessellation& t,
                       const Camera& camera, const CurvePoint& point) {
    const TriangleMesh& mesh = *t.mesh;
    const Index h = mesh.edgeHalfedge(point.edge);
    const Index f = TriangleMesh::face(h);
    const int k = static_cast<int>(h % 3);
    const Vec2 uv = (1.0 - point.t) * t.cornerUv[f][k] + point.t * t.cornerUv[f][(k + 1) % 3];
    const SurfacePoint x = surface.evaluate({t.sourceFace[f], uv.x(), uv.y()});
    const Vec2 dg = orientationGradient(x, camera);
    const FundamentalForms ff = fundamentalForms(x);
    const double gradient2 =
        (ff.G * dg.x() * dg.x() - 2.0 * ff.F * dg.x() * dg.y() + ff.E * dg.y() * dg.y()) /
        ff.firstDeterminant();
    return (x.position - point.position).norm() +
           std::abs(orientation(x, camera)) / std::sqrt(gradient2);
}

} // namespace

class TestSurfaceFields : public QObject {
    Q_OBJECT
private slots:
    // The test surfaces themselves: exact derivatives agree with central
    // differences, and the charts meet edge to edge.
    void analyticSurfacesAreConsistent() {
        std::mt19937 rng(7);
        const ProjectedSphere cubeSphere(cube(), 1.5, Vec3(0.2, -0.1, 0.3));
        const ProjectedSphere octaSphere(octahedron(), 0.8, Vec3::Zero());
        const Torus torus(1.0, 0.4, 8, 6);
        const Cylinder cylinder(0.7, 2.0, 6, 3);
        const double h = 1e-5;
        for (const SmoothSurface* s : std::initializer_list<const SmoothSurface*>{
                 &cubeSphere, &octaSphere, &torus, &cylinder}) {
            double worst = 0;
            for (int i = 0; i < 200; ++i) {
                Preimage p = randomPreimage(*s, rng);
                p.u = std::clamp(p.u, 0.01, 0.98);
                p.v = std::clamp(p.v, 0.01, 0.98 - (s->isQuad(p.face) ? 0.0 : p.u));
                const SurfacePoint x = s->evaluate(p);
                const auto at = [&](double du, double dv) {
                    return s->evaluate({p.face, p.u + du, p.v + dv});
                };
                const SurfacePoint up = at(h, 0), um = at(-h, 0), vp = at(0, h), vm = at(0, -h);
                const double scale = 1.0 + x.duu.norm() + x.dvv.norm();
                worst = std::max({worst, (x.du - (up.position - um.position) / (2 * h)).norm(),
                                  (x.dv - (vp.position - vm.position) / (2 * h)).norm(),
                                  (x.duu - (up.du - um.du) / (2 * h)).norm() / scale,
                                  (x.duv - (vp.du - vm.du) / (2 * h)).norm() / scale,
                                  (x.dvv - (vp.dv - vm.dv) / (2 * h)).norm() / scale});
            }
            QVERIFY2(worst < 1e-7, qPrintable(QString::number(worst)));
            // Both sides of every shared edge give the same point and normal.
            for (Index f = 0; f < s->domain().faceCount(); ++f)
                for (int e = 0; e < (s->isQuad(f) ? 4 : 3); ++e) {
                    if (s->neighbor(f, e).face == kInvalidIndex)
                        continue;
                    const Vec2 a = SmoothSurface::cornerCoordinates(s->isQuad(f), e);
                    const Vec2 b = SmoothSurface::cornerCoordinates(
                        s->isQuad(f), (e + 1) % (s->isQuad(f) ? 4 : 3));
                    const Vec2 m = a + 0.3 * (b - a);
                    const Preimage p{f, m.x(), m.y()};
                    const Preimage q = s->transferAcrossEdge(p, e);
                    const SurfacePoint x = s->evaluate(p), y = s->evaluate(q);
                    QVERIFY((x.position - y.position).norm() < 1e-12);
                    QVERIFY((x.normal() - y.normal()).norm() < 1e-12);
                }
        }
    }

    // The facing convention (Bénard 2014 eq. 1): g > 0 on the hemisphere
    // nearer the camera.
    void nearHemisphereIsFront() {
        const ProjectedSphere sphere(cube(), 1.0, Vec3::Zero());
        std::mt19937 rng(3);
        const Camera camera = perspectiveAt(Vec3(0, 0, 5), Vec3::Zero());
        for (int i = 0; i < 500; ++i) {
            const SurfacePoint p = sphere.evaluate(randomPreimage(sphere, rng));
            const double g = orientation(p, camera);
            QCOMPARE(g, facingFunction(camera, p.position, p.normal()));
            // The contour of a unit sphere seen from z = 5 is the circle z = 1/5.
            if (std::abs(p.position.z() - 0.2) > 1e-9)
                QCOMPARE(g > 0, p.position.z() > 0.2);
        }
    }

    // A sphere of radius R: normal curvature -1/R in every direction, kr =
    // -1/R for every camera, K = 1/R^2, H = -1/R; NaN where the view is along
    // the normal.
    void sphereCurvatures_data() {
        QTest::addColumn<bool>("quads");
        QTest::addColumn<bool>("orthographic");
        QTest::newRow("cube charts, perspective") << true << false;
        QTest::newRow("cube charts, orthographic") << true << true;
        QTest::newRow("octahedron charts, perspective") << false << false;
        QTest::newRow("octahedron charts, orthographic") << false << true;
    }
    void sphereCurvatures() {
        QFETCH(bool, quads);
        QFETCH(bool, orthographic);
        const double R = 2.5;
        const Vec3 center(1.0, -2.0, 0.5);
        const ProjectedSphere sphere(quads ? cube() : octahedron(), R, center);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> distance(1.2 * R, 6.0 * R);
        const double tol = 1e-9 / R;
        for (int i = 0; i < 2000; ++i) {
            const SurfacePoint p = sphere.evaluate(randomPreimage(sphere, rng));
            const Vec3 eye = center + distance(rng) * randomDirection(rng);
            const Camera camera =
                orthographic ? orthographicAlong(eye - center) : perspectiveAt(eye, center);
            const double kr = radialCurvature(p, camera);
            QVERIFY2(std::abs(kr + 1.0 / R) < tol, qPrintable(QString::number(kr)));
            const Vec3 t = randomDirection(rng);
            QVERIFY(std::abs(normalCurvature(p, t) + 1.0 / R) < tol);
            const Curvatures c = curvatures(p);
            QVERIFY(std::abs(c.kMin + 1.0 / R) < tol && std::abs(c.kMax + 1.0 / R) < tol);
            QVERIFY(std::abs(c.gaussian - 1.0 / (R * R)) < tol / R);
            QVERIFY(std::abs(c.mean + 1.0 / R) < tol);
            QVERIFY(std::abs(gaussianCurvature(p) - 1.0 / (R * R)) < tol / R);
            QVERIFY(std::abs(meanCurvature(p) + 1.0 / R) < tol);
            const FundamentalForms ff = fundamentalForms(p);
            QVERIFY(std::abs(normalCurvature(p, Vec2(0.3, -0.7)) + 1.0 / R) < tol);
            QVERIFY(ff.second(Vec2(1, 0)) < 0); // II negative definite: convex, outward n
        }
        // Looking along the normal: the centre of a chart seen from straight above.
        const SurfacePoint top =
            sphere.evaluate({quads ? 1 : 0, quads ? 0.5 : 1.0 / 3, quads ? 0.5 : 1.0 / 3});
        const Vec3 n = top.normal();
        const Camera along = orthographic ? orthographicAlong(n)
                                          : perspectiveAt(top.position + 3.0 * n, top.position);
        QVERIFY(std::isnan(radialCurvature(top, along)));
        // Slightly off the normal it is defined again, and still -1/R.
        const Vec3 side = n.unitOrthogonal();
        const Camera tilted =
            orthographic ? orthographicAlong(n + 1e-6 * side)
                         : perspectiveAt(top.position + 3.0 * n + 1e-6 * side, top.position);
        QVERIFY(std::abs(radialCurvature(top, tilted) + 1.0 / R) < 1e-6);
    }

    // A cylinder of radius rho: kr = 0 when the projected view vector runs
    // along the axis, -1/rho across it, and Euler's formula in between.
    void cylinderRadialCurvature() {
        const double rho = 0.7;
        const Cylinder cyl(rho, 2.0, 6, 3);
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> x(0.0, 1.0), len(0.5, 4.0), sgn(-1.0, 1.0);
        for (int i = 0; i < 500; ++i) {
            const SurfacePoint p = cyl.evaluate(randomPreimage(cyl, rng));
            const Vec3 n = p.normal();
            const Vec3 axis(0, 0, 1);
            const Vec3 around = p.du.normalized();
            QVERIFY(std::abs(n.dot(axis)) < 1e-14 && std::abs(n.dot(around)) < 1e-14);
            const double a = len(rng); // the camera is in front, off the surface
            const double b = (sgn(rng) < 0 ? -1 : 1) * len(rng);
            for (bool ortho : {false, true}) {
                const auto camera = [&](const Vec3& offset) {
                    return ortho ? orthographicAlong(offset)
                                 : perspectiveAt(p.position + offset, p.position);
                };
                QVERIFY(std::abs(radialCurvature(p, camera(a * n + b * axis))) < 1e-12);
                QVERIFY(std::abs(radialCurvature(p, camera(a * n + b * around)) + 1.0 / rho) <
                        1e-12);
                const Vec3 w = sgn(rng) * axis + sgn(rng) * around;
                const double expected = -std::pow(w.normalized().dot(around), 2) / rho;
                QVERIFY(std::abs(radialCurvature(p, camera(a * n + w)) - expected) < 1e-12);
            }
            const Curvatures c = curvatures(p);
            QVERIFY(std::abs(c.kMin + 1.0 / rho) < 1e-12 && std::abs(c.kMax) < 1e-12);
            QVERIFY(std::abs(std::abs(c.dirMin.dot(around)) - 1.0) < 1e-12);
            QVERIFY(std::abs(std::abs(c.dirMax.dot(axis)) - 1.0) < 1e-12);
            QVERIFY(std::abs(c.gaussian) < 1e-12);
            QVERIFY(std::abs(c.mean + 0.5 / rho) < 1e-12);
        }
    }

    // Torus (R, r): principal curvatures -1/r (around the tube) and
    // -cos(phi) / (R + r cos(phi)) (around the axis); K > 0 on the outer half,
    // < 0 on the inner half, 0 on the top and bottom circles.
    void torusCurvatures() {
        const Torus torus(1.0, 0.4, 8, 6);
        const double R = torus.major(), r = torus.minor();
        std::mt19937 rng(13);
        std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
        int outer = 0, inner = 0;
        for (int i = 0; i < 2000; ++i) {
            const double theta = angle(rng), phi = angle(rng);
            const SurfacePoint p = torus.evaluate(torus.preimageOf(theta, phi));
            const GridSurface::Derivatives d = torus.at(theta, phi);
            QVERIFY((p.position - d.f).norm() < 1e-12);
            const double tube = -1.0 / r, ring = -std::cos(phi) / (R + r * std::cos(phi));
            const Curvatures c = curvatures(p);
            QVERIFY(std::abs(c.kMin - std::min(tube, ring)) < 1e-12);
            QVERIFY(std::abs(c.kMax - std::max(tube, ring)) < 1e-12);
            const double K = std::cos(phi) / (r * (R + r * std::cos(phi)));
            QVERIFY(std::abs(c.gaussian - K) < 1e-12);
            QVERIFY(std::abs(gaussianCurvature(p) - K) < 1e-12);
            QVERIFY(std::abs(meanCurvature(p) - 0.5 * (tube + ring)) < 1e-12);
            // The tube direction carries -1/r, the ring direction the other.
            const Vec3 tubeDir = d.fb.normalized();
            const Vec3& dirTube = tube < ring ? c.dirMin : c.dirMax;
            if (std::abs(tube - ring) > 1e-6)
                QVERIFY(std::abs(std::abs(dirTube.dot(tubeDir)) - 1.0) < 1e-9);
            QVERIFY(std::abs(c.dirMax.cross(c.dirMin).dot(p.normal()) - 1.0) < 1e-12);
            if (std::cos(phi) > 1e-3) {
                QVERIFY(c.gaussian > 0);
                ++outer;
            } else if (std::cos(phi) < -1e-3) {
                QVERIFY(c.gaussian < 0);
                ++inner;
            }
            // Euler: kn(t) = kMax cos^2 + kMin sin^2 of the angle to dirMax.
            const auto [e1, e2] = tangentBasis(p);
            const double alpha = angle(rng);
            const Vec3 t = std::cos(alpha) * e1 + std::sin(alpha) * e2;
            const double ca = t.dot(c.dirMax), sa = t.dot(c.dirMin);
            QVERIFY(std::abs(normalCurvature(p, t) - (c.kMax * ca * ca + c.kMin * sa * sa)) <
                    1e-12);
        }
        QVERIFY(outer > 500 && inner > 500);
        for (double phi : {kPi / 2, 3 * kPi / 2})
            for (double theta : {0.1, 1.0, 2.5, 4.0}) {
                const SurfacePoint p = torus.evaluate(torus.preimageOf(theta, phi));
                QVERIFY(std::abs(gaussianCurvature(p)) < 1e-12);
                QVERIFY(std::abs(curvatures(p).gaussian) < 1e-12);
            }
    }

    // dg/du, dg/dv against central differences of g, both projections, on
    // the torus and the sphere; and the unit normal's derivatives.
    void orientationGradientMatchesFiniteDifferences() {
        const Torus torus(1.0, 0.4, 8, 6);
        const ProjectedSphere sphere(cube(), 1.3, Vec3(0.1, 0.2, -0.3));
        const ProjectedSphere octa(octahedron(), 0.9, Vec3::Zero());
        std::mt19937 rng(17);
        const double h = 1e-6;
        double worst = 0, worstNormal = 0;
        for (const SmoothSurface* s :
             std::initializer_list<const SmoothSurface*>{&torus, &sphere, &octa})
            for (int i = 0; i < 300; ++i) {
                Preimage p = randomPreimage(*s, rng);
                p.u = std::clamp(p.u, 0.01, 0.98);
                p.v = std::clamp(p.v, 0.01, 0.98 - (s->isQuad(p.face) ? 0.0 : p.u));
                const Vec3 eye = 4.0 * randomDirection(rng);
                for (bool ortho : {false, true}) {
                    const Camera camera =
                        ortho ? orthographicAlong(eye) : perspectiveAt(eye, Vec3::Zero());
                    const SurfacePoint x = s->evaluate(p);
                    const auto g = [&](double du, double dv) {
                        return orientation(s->evaluate({p.face, p.u + du, p.v + dv}), camera);
                    };
                    const Vec2 fd((g(h, 0) - g(-h, 0)) / (2 * h), (g(0, h) - g(0, -h)) / (2 * h));
                    const Vec2 exact = orientationGradient(x, camera);
                    worst = std::max(worst, (exact - fd).norm() / (1.0 + exact.norm()));
                }
                Vec3 dnu, dnv;
                unitNormalDerivatives(s->evaluate(p), dnu, dnv);
                const auto n = [&](double du, double dv) {
                    return s->evaluate({p.face, p.u + du, p.v + dv}).normal();
                };
                worstNormal = std::max({worstNormal, (dnu - (n(h, 0) - n(-h, 0)) / (2 * h)).norm(),
                                        (dnv - (n(0, h) - n(0, -h)) / (2 * h)).norm()});
            }
        qInfo("worst relative g-gradient error %.2g, unit normal derivative error %.2g", worst,
              worstNormal);
        QVERIFY(worst < 1e-7);
        QVERIFY(worstNormal < 1e-7);
    }

    // Counts, welding, closedness and orientation of the tessellation.
    void tessellationTopology_data() {
        QTest::addColumn<int>("level");
        for (int level : {1, 2, 3, 4, 7})
            QTest::addRow("level %d", level) << level;
    }
    void tessellationTopology() {
        QFETCH(int, level);
        const int L = level;
        const auto torus = std::make_shared<const Torus>(2.0, 0.5, 10, 6);
        const auto cubeSphere = std::make_shared<const ProjectedSphere>(cube(), 1.0, Vec3::Zero());
        const auto octaSphere =
            std::make_shared<const ProjectedSphere>(octahedron(), 1.0, Vec3::Zero());
        const auto cylinder = std::make_shared<const Cylinder>(1.0, 2.0, 7, 3);
        struct Case {
            const SmoothSurface* surface;
            long long vertices;
            long long faces;
            long long boundaryEdges;
            double volume; // 0: do not check
        };
        const long long l1 = L - 1;
        const std::vector<Case> cases = {
            // V + E (L - 1) + F (L - 1)^2 for all-quad domains.
            {torus.get(), 60 + 120 * l1 + 60 * l1 * l1, 2LL * 60 * L * L, 0,
             2 * kPi * kPi * 2.0 * 0.25},
            {cubeSphere.get(), 8 + 12 * l1 + 6 * l1 * l1, 2LL * 6 * L * L, 0, 4.0 / 3.0 * kPi},
            // V + E (L - 1) + F (L - 1)(L - 2) / 2 for triangle domains.
            {octaSphere.get(), 6 + 12 * l1 + 8 * l1 * (L - 2) / 2, 8LL * L * L, 0, 4.0 / 3.0 * kPi},
            {cylinder.get(), 28 + 49 * l1 + 21 * l1 * l1, 2LL * 21 * L * L, 2LL * 7 * L, 0.0},
        };
        for (const Case& c : cases) {
            const SurfaceTessellation t = tessellate(*c.surface, L);
            const TriangleMesh& mesh = *t.mesh;
            QCOMPARE(static_cast<long long>(mesh.vertexCount()), c.vertices);
            QCOMPARE(static_cast<long long>(mesh.faceCount()), c.faces);
            QCOMPARE(static_cast<long long>(mesh.boundaryEdgeCount()), c.boundaryEdges);
            QCOMPARE(t.preimages.size(), size_t(mesh.vertexCount()));
            QCOMPARE(t.sourceFace.size(), size_t(mesh.faceCount()));
            QCOMPARE(t.cornerUv.size(), size_t(mesh.faceCount()));
            // Every vertex is the surface point of its preimage, with its normal.
            for (Index v = 0; v < mesh.vertexCount(); ++v) {
                QVERIFY(c.surface->contains(t.preimages[v]));
                const SurfacePoint p = c.surface->evaluate(t.preimages[v]);
                QCOMPARE(mesh.position(v), p.position);
                QVERIFY((t.normals[v] - p.normal()).norm() == 0.0);
                QVERIFY(std::abs(t.normals[v].norm() - 1.0) < 1e-12);
            }
            // Welded completely: no two vertices at the same place.
            std::set<std::array<long long, 3>> cells;
            for (Index v = 0; v < mesh.vertexCount(); ++v) {
                const Vec3 q = mesh.position(v) * 1e6;
                cells.insert({std::llround(q.x()), std::llround(q.y()), std::llround(q.z())});
            }
            QCOMPARE(static_cast<Index>(cells.size()), mesh.vertexCount());
            // Each triangle's corners, read from its face's chart, are its vertices;
            // its geometric normal agrees with the surface normals (outward).
            for (Index f = 0; f < mesh.faceCount(); ++f) {
                const Triangle& tri = mesh.triangle(f);
                for (int k = 0; k < 3; ++k) {
                    const Vec2 uv = t.cornerUv[f][k];
                    const Vec3 at = c.surface->evaluate({t.sourceFace[f], uv.x(), uv.y()}).position;
                    QVERIFY((at - mesh.position(tri[k])).norm() < 1e-12);
                    QVERIFY(mesh.faceNormal(f).dot(t.normals[tri[k]]) > 0.0);
                }
            }
            if (c.volume > 0) {
                const double volume = signedVolume(mesh);
                QVERIFY(volume > 0);
                // The inscribed polyhedron approaches the true volume from below.
                if (L >= 7)
                    QVERIFY2(std::abs(volume - c.volume) < 0.05 * c.volume,
                             qPrintable(QString("%1 vs %2").arg(volume).arg(c.volume)));
            }
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, tessellate(*torus, 0));
    }

    // Interpolated contours on the tessellated analytic sphere are one closed
    // loop, with exact normals, and converge to the true contour generator
    // (for a unit sphere and an eye e, the circle x · e = 1 on the sphere) at
    // second order.
    void interpolatedContoursOnAnalyticSphereConverge() {
        const auto sphere = std::make_shared<const ProjectedSphere>(cube(), 1.0, Vec3::Zero());
        const Vec3 eye(0.3, -0.5, 4.0);
        const Camera camera = perspectiveAt(eye, Vec3::Zero());
        double previous = 1.0, first = 0.0;
        for (int level : {2, 4, 8, 16}) {
            const Snapshot s =
                runAfterSurface("interpolated", withSurface(sphere, level, camera), camera);
            QCOMPARE(s.invariantViolations(), 0LL);
            int open = 0;
            QCOMPARE(contourLoops(s, &open), 1);
            QCOMPARE(open, 0);
            const Vec3 axis = eye.normalized(), center = eye / eye.squaredNorm();
            const double radius = std::sqrt(1.0 - 1.0 / eye.squaredNorm());
            double worst = 0;
            for (const Polyline& line : *s.curves)
                for (const CurvePoint& p : line.points) {
                    const Vec3 d = p.position - center;
                    const double along = d.dot(axis), across = (d - along * axis).norm();
                    worst = std::max(worst, std::hypot(along, across - radius));
                }
            qInfo("analytic sphere, level %d: worst distance to the contour circle %.3g", level,
                  worst);
            QVERIFY2(worst < 0.5 * previous, qPrintable(QString::number(worst)));
            if (level == 2)
                first = worst;
            previous = worst;
        }
        QVERIFY2(previous < first / 15, qPrintable(QString::number(previous)));
    }

    // Radial curvature in the snapshot is the field of the tessellation's
    // vertices, for the snapshot's camera.
    void surfacePhasePublishesFields() {
        const auto sphere = std::make_shared<const ProjectedSphere>(cube(), 2.0, Vec3::Zero());
        const Camera camera = perspectiveAt(Vec3(1, 2, 9), Vec3::Zero());
        const Snapshot s = withSurface(sphere, 3, camera);
        const Index n = s.mesh->vertexCount();
        for (const char* name :
             {fields::kRadialCurvature, fields::kGaussianCurvature, fields::kMeanCurvature}) {
            QVERIFY(s.field(name) && s.field(name)->scalars());
            QCOMPARE(static_cast<Index>(s.field(name)->scalars()->size()), n);
        }
        for (Index v = 0; v < n; ++v) {
            QVERIFY(std::abs((*s.field(fields::kRadialCurvature)->scalars())[v] + 0.5) < 1e-9);
            QVERIFY(std::abs((*s.field(fields::kGaussianCurvature)->scalars())[v] - 0.25) < 1e-9);
            QVERIFY(std::abs((*s.field(fields::kMeanCurvature)->scalars())[v] + 0.5) < 1e-9);
            const int face = (*s.field(fields::kPreimageFace)->labels())[v];
            const Vec3 uv = (*s.field(fields::kPreimageUv)->vectors())[v];
            QCOMPARE(uv.z(), 0.0);
            QCOMPARE(sphere->evaluate({face, uv.x(), uv.y()}).position, s.mesh->position(v));
        }
        QCOMPARE(s.field(fields::kDomainFace)->labels()->size(), size_t(s.mesh->faceCount()));
        QCOMPARE(s.counter(counters::kDomainFaces), 6.0);
        QCOMPARE(s.counter(counters::kTessellationFaces), 2.0 * 6 * 9);
        // A second view reuses the tessellation: same mesh and normals.
        const Snapshot t = withSurface(sphere, 3, perspectiveAt(Vec3(-5, 0, 1), Vec3::Zero()));
        QVERIFY(t.mesh == s.mesh);
        QVERIFY(t.fields.at(fields::kVertexNormal) == s.fields.at(fields::kVertexNormal));
        QCOMPARE(t.counter(counters::kTessellationCached), 1.0);
        QVERIFY(withSurface(sphere, 4, camera).mesh != s.mesh);
    }

    // --- through the methods, on the subdivision surfaces of cages ----------

    void surfaceParameterDefaultsToTheCage() {
        for (const char* method : {"mesh", "interpolated"}) {
            const Method& m = *findMethod(method);
            QCOMPARE(std::get<std::string>(m.parameter("surface")->defaultValue),
                     std::string("none"));
            QCOMPARE(std::get<int>(m.parameter("tessellation-level")->defaultValue), 4);
            const auto cage = shape("torus", 16);
            const Snapshot s = runMethod(method, cage, protocolViews(cage->boundingBox(), 0)[3]);
            QCOMPARE(s.mesh->faceCount(), cage->triangulate().faceCount());
            QVERIFY(!s.field(fields::kRadialCurvature));
        }
        ParameterSet p;
        const PolygonMesh triangles = octahedron(), quads = cube();
        p.set("surface", std::string("auto"));
        QCOMPARE(*selectedSurfaceKind(p, triangles), SurfaceKind::Loop);
        QCOMPARE(*selectedSurfaceKind(p, quads), SurfaceKind::CatmullClark);
        p.set("surface", std::string("none"));
        QVERIFY(!selectedSurfaceKind(p, quads));
    }

    // The smooth surface is built once per cage and kind.
    void surfaceIsCachedPerCage() {
        const auto cage = shape("torus", 12);
        const CachedSmoothSurface a = cachedSmoothSurface(cage, SurfaceKind::CatmullClark);
        const CachedSmoothSurface b = cachedSmoothSurface(cage, SurfaceKind::CatmullClark);
        QVERIFY(!a.fromCache && b.fromCache);
        QVERIFY(a.surface == b.surface);
        QVERIFY(cachedSmoothSurface(cage, SurfaceKind::VertexNormalPatches).surface != a.surface);
        const auto copy = std::make_shared<const PolygonMesh>(*cage);
        QVERIFY(cachedSmoothSurface(copy, SurfaceKind::CatmullClark).surface != a.surface);
        QVERIFY_THROWS_EXCEPTION(std::exception,
                                 cachedSmoothSurface(cage, SurfaceKind::Loop)); // quads
        // Concurrent first requests (a batch running views in parallel) build once.
        const auto fresh = shape("torus", 20);
        std::vector<CachedSmoothSurface> results(4);
        std::vector<std::thread> threads;
        for (size_t i = 0; i < results.size(); ++i)
            threads.emplace_back(
                [&, i] { results[i] = cachedSmoothSurface(fresh, SurfaceKind::CatmullClark); });
        for (std::thread& t : threads)
            t.join();
        int built = 0;
        for (const CachedSmoothSurface& r : results) {
            QVERIFY(r.surface == results[0].surface);
            built += !r.fromCache;
        }
        QCOMPARE(built, 1);
    }

    // Interpolated and mesh contours on limit surfaces, 26 views: closed
    // loops, no post-condition violated.
    void contoursOnLimitSurfaces_data() {
        QTest::addColumn<QString>("method");
        QTest::addColumn<QString>("cage");
        QTest::addColumn<QString>("surface");
        QTest::addColumn<int>("level");
        for (const char* method : {"interpolated", "mesh"}) {
            QTest::addRow("%s torus catmull-clark", method) << method << "torus"
                                                            << "catmull-clark" << 4;
            QTest::addRow("%s spot auto", method) << method << "spot"
                                                  << "auto" << 3;
            QTest::addRow("%s octahedron loop", method) << method << "octahedron"
                                                        << "loop" << 6;
            QTest::addRow("%s torus vertex-normal-patches", method) << method << "torus"
                                                                    << "vertex-normal-patches" << 3;
        }
    }
    void contoursOnLimitSurfaces() {
        QFETCH(QString, method);
        QFETCH(QString, cage);
        QFETCH(QString, surface);
        QFETCH(int, level);
        std::shared_ptr<const PolygonMesh> mesh;
        if (cage == "torus")
            mesh = shape("torus", 24);
        else if (cage == "octahedron")
            mesh = std::make_shared<const PolygonMesh>(octahedron());
        else
            mesh = std::make_shared<const PolygonMesh>(
                readMesh(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj"));
        const Overrides p{{"surface", surface.toStdString()}, {"tessellation-level", level}};
        for (const Camera& camera : protocolViews(mesh->boundingBox(), 0)) {
            const Snapshot s = runMethod(method.toStdString(), mesh, camera, p);
            QCOMPARE(s.invariantViolations(), 0LL);
            QCOMPARE(s.mesh->boundaryEdgeCount(), 0);
            QVERIFY(s.field(fields::kRadialCurvature));
            QVERIFY(s.field(fields::kG));
            if (method == "interpolated") {
                int open = 0;
                QVERIFY(contourLoops(s, &open) >= 1);
                QCOMPARE(open, 0);
            }
        }
    }

    // On a sphere-like cage (Catmull-Clark of a cube, and Loop of an
    // octahedron), the interpolated contour approaches the smooth contour
    // generator as the level increases: at second order for Catmull-Clark,
    // slower for Loop, whose worst points sit next to the octahedron's
    // valence-4 (extraordinary) vertices, where the Loop limit surface is
    // less smooth and its end caps approximate.
    void interpolatedContoursConvergeOnLimitSurfaces_data() {
        QTest::addColumn<bool>("loop");
        QTest::newRow("catmull-clark cube") << false;
        QTest::newRow("loop octahedron") << true;
    }
    void interpolatedContoursConvergeOnLimitSurfaces() {
        QFETCH(bool, loop);
        const auto cage = std::make_shared<const PolygonMesh>(loop ? octahedron() : cube());
        const auto surface =
            cachedSmoothSurface(cage, loop ? SurfaceKind::Loop : SurfaceKind::CatmullClark).surface;
        Overrides p{{"surface", loop ? "loop" : "catmull-clark"}};
        const Camera camera = perspectiveAt(Vec3(0.7, -1.1, 4.5), Vec3::Zero());
        double previous = 1.0, first = 0.0;
        for (int level : {2, 4, 8, 16}) {
            p.set("tessellation-level", level);
            const Snapshot s = runMethod("interpolated", cage, camera, p);
            QCOMPARE(s.invariantViolations(), 0LL);
            int open = 0;
            QCOMPARE(contourLoops(s, &open), 1);
            QCOMPARE(open, 0);
            const SurfaceTessellation t = tessellate(*surface, level);
            QCOMPARE(t.mesh->vertexCount(), s.mesh->vertexCount());
            double worst = 0;
            for (const Polyline& line : *s.curves)
                for (const CurvePoint& point : line.points)
                    worst = std::max(worst, contourDistance(*surface, t, camera, point));
            qInfo("%s level %d: worst distance to the smooth contour %.3g",
                  loop ? "loop" : "catmull-clark", level, worst);
            QVERIFY2(worst < 0.5 * previous, qPrintable(QString::number(worst)));
            if (level == 2)
                first = worst;
            previous = worst;
        }
        QVERIFY2(previous < first / 15, qPrintable(QString::number(previous)));
    }
};

QTEST_APPLESS_MAIN(TestSurfaceFields)
#include "test_surface_fields.moc"
