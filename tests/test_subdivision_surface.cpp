// Catmull-Clark and Loop limit surfaces (SubdivisionSurface, OpenSubdiv):
// first and second derivatives against central finite differences (the
// regression for two slips that are easy with OpenSubdiv's EvaluateBasis),
// Catmull-Clark
// on a regular grid against an independent bicubic B-spline, agreement across
// every shared domain edge, a convex Loop surface without sign flips of the
// second fundamental form, transferAcrossEdge round trips, creases from OBJ
// tags, and bad input.
#include "mesh/MeshError.h"
#include "mesh/io/MeshReader.h"
#include "surface/SubdivisionSurface.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <random>

using namespace contour;

namespace {

// ---------------------------------------------------------------- meshes

// Orients every face of a convex polyhedron (or of a part of one)
// counter-clockwise seen from outside, judged from the centroid.
void orientOutward(PolygonMesh& mesh) {
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : mesh.positions)
        centroid += p;
    centroid /= static_cast<double>(mesh.vertexCount());
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto corners = mesh.face(f);
        Vec3 normal = Vec3::Zero(), center = Vec3::Zero();
        for (size_t k = 0; k < corners.size(); ++k) {
            const Vec3& a = mesh.positions[corners[k]];
            const Vec3& b = mesh.positions[corners[(k + 1) % corners.size()]];
            normal += a.cross(b);
            center += a;
        }
        center /= static_cast<double>(corners.size());
        if (normal.dot(center - centroid) < 0.0)
            std::reverse(mesh.indices.begin() + mesh.offsets[f],
                         mesh.indices.begin() + mesh.offsets[f + 1]);
    }
}

PolygonMesh octahedron() {
    PolygonMesh m;
    m.positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                   Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    for (const Index x : {0, 1})
        for (const Index y : {2, 3})
            for (const Index z : {4, 5})
                m.addFace({x, y, z});
    orientOutward(m);
    return m;
}

// The icosahedron split once (edge midpoints pushed to the unit sphere):
// 12 vertices of valence 5, 30 of valence 6.
PolygonMesh icosphere() {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                           {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                           {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    PolygonMesh m;
    for (Vec3& q : p)
        m.positions.push_back(q.normalized());
    std::map<std::pair<Index, Index>, Index> midpoints;
    const auto midpoint = [&](Index a, Index b) {
        const auto key = std::minmax(a, b);
        const auto it = midpoints.find(key);
        if (it != midpoints.end())
            return it->second;
        m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
        return midpoints[key] = m.vertexCount() - 1;
    };
    for (const auto& f : faces) {
        const Index a = f[0], b = f[1], c = f[2];
        const Index ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        m.addFace({a, ab, ca});
        m.addFace({b, bc, ab});
        m.addFace({c, ca, bc});
        m.addFace({ab, bc, ca});
    }
    orientOutward(m);
    return m;
}

// Keeps the faces for which `keep` holds, and the vertices they use.
PolygonMesh keepFaces(const PolygonMesh& mesh, const std::function<bool(Vec3)>& keep) {
    PolygonMesh out;
    std::vector<Index> renumber(static_cast<size_t>(mesh.vertexCount()), kInvalidIndex);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto corners = mesh.face(f);
        Vec3 center = Vec3::Zero();
        for (const Index v : corners)
            center += mesh.positions[v];
        if (!keep(center / static_cast<double>(corners.size())))
            continue;
        std::vector<Index> polygon;
        for (const Index v : corners) {
            Index& r = renumber[static_cast<size_t>(v)];
            if (r == kInvalidIndex) {
                r = out.vertexCount();
                out.positions.push_back(mesh.positions[v]);
            }
            polygon.push_back(r);
        }
        out.addFace(polygon);
    }
    return out;
}

// Moves every vertex by a small random offset (fixed seed): breaks symmetry.
void jitter(PolygonMesh& mesh, double amount, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-amount, amount);
    for (Vec3& p : mesh.positions)
        p += Vec3(d(rng), d(rng), d(rng));
}

// Two pentagons and five quads; every vertex has valence 3.
PolygonMesh pentagonalPrism(bool withTop = true) {
    PolygonMesh m;
    for (int level = 0; level < 2; ++level)
        for (int i = 0; i < 5; ++i) {
            const double a = 2.0 * std::numbers::pi * i / 5.0;
            m.positions.emplace_back(std::cos(a), std::sin(a), 1.3 * level);
        }
    m.addFace({0, 1, 2, 3, 4});
    if (withTop)
        m.addFace({5, 6, 7, 8, 9});
    for (Index i = 0; i < 5; ++i)
        m.addFace({i, static_cast<Index>((i + 1) % 5), static_cast<Index>((i + 1) % 5 + 5),
                   static_cast<Index>(i + 5)});
    orientOutward(m);
    return m;
}

// A cube with a pyramid roof: quads and triangles, apex of valence 4 made
// of triangles, eaves of valence 4 and base corners of valence 3.
PolygonMesh house() {
    PolygonMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),      Vec3(0, 0, 1),
                   Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1), Vec3(0.5, 0.5, 1.8)};
    m.addFace({0, 1, 2, 3});
    for (Index i = 0; i < 4; ++i) {
        const Index j = (i + 1) % 4;
        m.addFace({i, j, static_cast<Index>(j + 4), static_cast<Index>(i + 4)});
        m.addFace({static_cast<Index>(i + 4), static_cast<Index>(j + 4), 8});
    }
    orientOutward(m);
    return m;
}

PolygonMesh cube() {
    PolygonMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    m.addFace({0, 1, 3, 2});
    m.addFace({4, 5, 7, 6});
    m.addFace({0, 1, 5, 4});
    m.addFace({2, 3, 7, 6});
    m.addFace({0, 2, 6, 4});
    m.addFace({1, 3, 7, 5});
    orientOutward(m);
    return m;
}

// n x n control points over [0, n-1]^2 with a random height field.
PolygonMesh grid(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-0.5, 0.5);
    PolygonMesh m;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            m.positions.emplace_back(i + 0.2 * d(rng), j + 0.2 * d(rng), d(rng));
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i)
            m.addFace({j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i});
    return m;
}

// spot and bob are bundled in samples/ (public domain), so these checks run
// in every clone; other meshes come from ../shared/meshes when it is there.
QString sharedMesh(const char* name) {
    const QString bundled = QStringLiteral(CONTOUR_SOURCE_DIR "/samples/") + QLatin1String(name);
    if (QFileInfo::exists(bundled))
        return bundled;
    return QStringLiteral(CONTOUR_SHARED_DIR "/meshes/") + QLatin1String(name);
}

// ---------------------------------------------------------------- sampling

double triangleOrSquareU(std::mt19937& rng, bool quad, double& v) {
    std::uniform_real_distribution<double> d(0.05, 0.95);
    for (;;) {
        const double u = d(rng);
        v = d(rng);
        if (quad || u + v <= 0.95)
            return u;
    }
}

struct FdError {
    double first = 0.0, second = 0.0;
    void merge(const FdError& o) {
        first = std::max(first, o.first);
        second = std::max(second, o.second);
    }
};

// Worst relative error of the derivatives at p against central differences
// with step h: first derivatives from positions, second from first.
FdError fdError(const SmoothSurface& s, const Preimage& p, double h = 1e-4) {
    const auto at = [&](double du, double dv) {
        return s.evaluate({p.face, p.u + du, p.v + dv});
    };
    const SurfacePoint c = at(0, 0);
    const SurfacePoint up = at(h, 0), um = at(-h, 0), vp = at(0, h), vm = at(0, -h);
    const double firstScale = std::max(c.du.norm(), c.dv.norm());
    const double secondScale =
        std::max({c.duu.norm(), c.duv.norm(), c.dvv.norm(), 1e-6 * firstScale});
    FdError e;
    e.first = std::max(((up.position - um.position) / (2 * h) - c.du).norm(),
                       ((vp.position - vm.position) / (2 * h) - c.dv).norm()) /
              firstScale;
    e.second = std::max({((up.du - um.du) / (2 * h) - c.duu).norm(),
                         ((vp.du - vm.du) / (2 * h) - c.duv).norm(),
                         ((up.dv - um.dv) / (2 * h) - c.duv).norm(),
                         ((vp.dv - vm.dv) / (2 * h) - c.dvv).norm()}) /
               secondScale;
    return e;
}

// `perFace` random preimages in every domain face (fixed seed), away from
// the face's border by 0.05.
FdError fdErrorEverywhere(const SmoothSurface& s, int perFace, unsigned seed) {
    std::mt19937 rng(seed);
    FdError worst;
    for (Index f = 0; f < s.domain().faceCount(); ++f)
        for (int k = 0; k < perFace; ++k) {
            double v = 0.0;
            const double u = triangleOrSquareU(rng, s.isQuad(f), v);
            worst.merge(fdError(s, {f, u, v}));
        }
    return worst;
}

double unitRandom(std::mt19937& rng) {
    return std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

// Uniform cubic B-spline basis and its first two derivatives at t.
void bspline(double t, double b[4], double d[4], double dd[4]) {
    const double s = 1.0 - t;
    b[0] = s * s * s / 6.0;
    b[1] = (3 * t * t * t - 6 * t * t + 4) / 6.0;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6.0;
    b[3] = t * t * t / 6.0;
    d[0] = -s * s / 2.0;
    d[1] = (3 * t * t - 4 * t) / 2.0;
    d[2] = (-3 * t * t + 2 * t + 1) / 2.0;
    d[3] = t * t / 2.0;
    dd[0] = s;
    dd[1] = 3 * t - 2;
    dd[2] = -3 * t + 1;
    dd[3] = t;
}

double worstFd[2][2] = {{0, 0}, {0, 0}}; // [loop?][second?]

void recordFd(bool loop, const FdError& e) {
    worstFd[loop][0] = std::max(worstFd[loop][0], e.first);
    worstFd[loop][1] = std::max(worstFd[loop][1], e.second);
}

// Positions and normals of the two faces at sample points along every
// shared domain edge; returns the worst distances.
std::pair<double, double> edgeMismatch(const SmoothSurface& s, const std::vector<double>& ts) {
    double position = 0.0, normal = 0.0;
    const PolygonMesh& d = s.domain();
    for (Index f = 0; f < d.faceCount(); ++f) {
        const bool quad = s.isQuad(f);
        const int n = quad ? 4 : 3;
        for (int e = 0; e < n; ++e) {
            const auto nb = s.neighbor(f, e);
            if (nb.face == kInvalidIndex)
                continue;
            const Vec2 a = SmoothSurface::cornerCoordinates(quad, e);
            const Vec2 b = SmoothSurface::cornerCoordinates(quad, (e + 1) % n);
            for (const double t : ts) {
                const Vec2 x = a + t * (b - a);
                const Preimage p{f, x.x(), x.y()};
                const Preimage q = s.transferAcrossEdge(p, e);
                if (q.face != nb.face)
                    return {1e300, 1e300};
                const SurfacePoint sp = s.evaluate(p), sq = s.evaluate(q);
                position = std::max(position, (sp.position - sq.position).norm());
                normal = std::max(normal, (sp.normal() - sq.normal()).norm());
            }
        }
    }
    return {position, normal};
}

} // namespace

class TestSubdivisionSurface : public QObject {
    Q_OBJECT

private slots:
    void loopDerivativesMatchFiniteDifferences_data();
    void loopDerivativesMatchFiniteDifferences();
    void catmullClarkDerivativesMatchFiniteDifferences_data();
    void catmullClarkDerivativesMatchFiniteDifferences();
    void sharedMeshDerivativesMatchFiniteDifferences_data();
    void sharedMeshDerivativesMatchFiniteDifferences();
    void catmullClarkGridIsBicubicBSpline();
    void domainIsTheCageSubdividedOnce();
    void surfaceAgreesAcrossEdges_data();
    void surfaceAgreesAcrossEdges();
    void endCapsMatchTheirNeighbours();
    void convexLoopSurfaceHasDefiniteSecondFundamentalForm();
    void transferAcrossEdgeRoundTrips();
    void infinitelySharpCreasesKeepCubeFacesFlat();
    void objCreaseTagsAreRead();
    void objCreaseTagErrorsNameTheLine();
    void badInputIsRejected();
    void cleanupTestCase();
};

void TestSubdivisionSurface::loopDerivativesMatchFiniteDifferences_data() {
    QTest::addColumn<int>("which");
    QTest::newRow("octahedron (valence 4)") << 0;
    QTest::newRow("icosphere (valence 5 and 6)") << 1;
    QTest::newRow("open icosphere cap (boundary)") << 2;
    QTest::newRow("jittered icosphere, edge-only boundary") << 3;
}

void TestSubdivisionSurface::loopDerivativesMatchFiniteDifferences() {
    QFETCH(int, which);
    PolygonMesh mesh = which == 0 ? octahedron() : icosphere();
    SubdivisionOptions options;
    if (which == 2)
        mesh = keepFaces(mesh, [](Vec3 c) { return c.z() < 0.45; });
    if (which == 3) {
        mesh = keepFaces(mesh, [](Vec3 c) { return c.x() > -0.6; });
        jitter(mesh, 0.05, 7);
        options.boundary = SubdivisionOptions::Boundary::EdgeOnly;
    }
    const auto s = SubdivisionSurface::create(mesh, SurfaceKind::Loop, options);
    QCOMPARE(s->domain().faceCount(), mesh.faceCount());
    const FdError e = fdErrorEverywhere(*s, 6, 11);
    recordFd(true, e);
    qInfo("Loop FD relative error: first %.2e, second %.2e", e.first, e.second);
    QVERIFY2(e.first < 1e-6, qPrintable(QString::number(e.first)));
    QVERIFY2(e.second < 1e-4, qPrintable(QString::number(e.second)));
}

void TestSubdivisionSurface::catmullClarkDerivativesMatchFiniteDifferences_data() {
    QTest::addColumn<int>("which");
    QTest::newRow("pentagonal prism") << 0;
    QTest::newRow("house (triangles, quads)") << 1;
    QTest::newRow("open pentagonal cup (boundary)") << 2;
    QTest::newRow("icosphere (all triangles)") << 3;
    QTest::newRow("open icosphere cap, edge-only boundary") << 4;
    QTest::newRow("cube with semi-sharp creases") << 5;
}

void TestSubdivisionSurface::catmullClarkDerivativesMatchFiniteDifferences() {
    QFETCH(int, which);
    PolygonMesh mesh;
    SubdivisionOptions options;
    switch (which) {
    case 0:
        mesh = pentagonalPrism();
        break;
    case 1:
        mesh = house();
        break;
    case 2:
        mesh = pentagonalPrism(false);
        break;
    case 3:
        mesh = icosphere();
        break;
    case 4:
        mesh = keepFaces(icosphere(), [](Vec3 c) { return c.z() < 0.45; });
        options.boundary = SubdivisionOptions::Boundary::EdgeOnly;
        break;
    default:
        mesh = cube();
        mesh.creases = {{0, 1, 1.5}, {1, 3, 2.0}, {4, 5, 0.7}};
        mesh.cornerSharpness = {{7, 1.2}};
        break;
    }
    jitter(mesh, 0.03, 5 + static_cast<unsigned>(which));
    const auto s = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark, options);
    const FdError e = fdErrorEverywhere(*s, 6, 13);
    recordFd(false, e);
    qInfo("Catmull-Clark FD relative error: first %.2e, second %.2e", e.first, e.second);
    QVERIFY2(e.first < 1e-6, qPrintable(QString::number(e.first)));
    QVERIFY2(e.second < 1e-4, qPrintable(QString::number(e.second)));
}

void TestSubdivisionSurface::sharedMeshDerivativesMatchFiniteDifferences_data() {
    QTest::addColumn<QString>("file");
    QTest::newRow("spot (triangles, pentagons)") << "spot_control_mesh.obj";
    QTest::newRow("bob") << "bob_controlmesh.obj";
}

void TestSubdivisionSurface::sharedMeshDerivativesMatchFiniteDifferences() {
    QFETCH(QString, file);
    const QString path = sharedMesh(file.toUtf8().constData());
    if (!QFile::exists(path))
        QSKIP("../shared/meshes is absent: the shared-mesh checks need it");
    const PolygonMesh mesh = readMesh(path.toStdString());
    const auto s = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark);
    const FdError e = fdErrorEverywhere(*s, 3, 17);
    recordFd(false, e);
    qInfo("%s: %d domain faces, %d patches (%d end caps); FD relative error: first %.2e, "
          "second %.2e",
          qPrintable(file), s->domain().faceCount(), s->patchCount(), s->endCapPatchCount(),
          e.first, e.second);
    QVERIFY2(e.first < 1e-6, qPrintable(QString::number(e.first)));
    QVERIFY2(e.second < 1e-4, qPrintable(QString::number(e.second)));
}

void TestSubdivisionSurface::catmullClarkGridIsBicubicBSpline() {
    const int n = 8;
    const PolygonMesh mesh = grid(n, 3);
    const auto s = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark);
    std::mt19937 rng(5);
    double worst = 0.0;
    int checked = 0;
    // Base faces (i, j) with 2 <= i, j <= 4 have a full ring of interior
    // neighbours: their limit surface is the B-spline patch of the 4x4
    // control points around them.
    for (Index f = 0; f < s->domain().faceCount(); ++f) {
        const auto& chart = s->chart(f);
        const int bi = chart.ptexFace % (n - 1), bj = chart.ptexFace / (n - 1);
        if (bi < 2 || bi > 4 || bj < 2 || bj > 4)
            continue;
        for (int k = 0; k < 20; ++k) {
            const double u = unitRandom(rng), v = unitRandom(rng);
            const SurfacePoint p = s->evaluate({f, u, v});
            const double st = chart.s0 + chart.j00 * u + chart.j01 * v;
            const double tt = chart.t0 + chart.j10 * u + chart.j11 * v;
            double bs[4], ds[4], dds[4], bt[4], dt[4], ddt[4];
            bspline(st, bs, ds, dds);
            bspline(tt, bt, dt, ddt);
            Vec3 x = Vec3::Zero(), xs = Vec3::Zero(), xt = Vec3::Zero();
            Vec3 xss = Vec3::Zero(), xst = Vec3::Zero(), xtt = Vec3::Zero();
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 4; ++a) {
                    const Vec3& c = mesh.positions[(bj - 1 + b) * n + (bi - 1 + a)];
                    x += bs[a] * bt[b] * c;
                    xs += ds[a] * bt[b] * c;
                    xt += bs[a] * dt[b] * c;
                    xss += dds[a] * bt[b] * c;
                    xst += ds[a] * dt[b] * c;
                    xtt += bs[a] * ddt[b] * c;
                }
            // Chain rule to the domain face's (u, v).
            const double a00 = chart.j00, a01 = chart.j01, a10 = chart.j10, a11 = chart.j11;
            const Vec3 xu = a00 * xs + a10 * xt, xv = a01 * xs + a11 * xt;
            const Vec3 xuu = a00 * a00 * xss + 2 * a00 * a10 * xst + a10 * a10 * xtt;
            const Vec3 xuv = a00 * a01 * xss + (a00 * a11 + a01 * a10) * xst + a10 * a11 * xtt;
            const Vec3 xvv = a01 * a01 * xss + 2 * a01 * a11 * xst + a11 * a11 * xtt;
            worst =
                std::max({worst, (p.position - x).norm(), (p.du - xu).norm(), (p.dv - xv).norm(),
                          (p.duu - xuu).norm(), (p.duv - xuv).norm(), (p.dvv - xvv).norm()});
            ++checked;
        }
    }
    QCOMPARE(checked, 9 * 4 * 20);
    qInfo("regular grid vs bicubic B-spline: worst difference %.2e", worst);
    QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
}

void TestSubdivisionSurface::domainIsTheCageSubdividedOnce() {
    const PolygonMesh mesh = house();
    const auto s = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark);
    const PolygonMesh& d = s->domain();
    // 5 quads -> 20 quads, 4 triangles -> 12 quads; V - E + F = 2 stays.
    QCOMPARE(d.faceCount(), 32);
    QVERIFY(d.isQuadMesh());
    QCOMPARE(d.vertexCount(), 9 + 16 + 9);
    QCOMPARE(s->ptexFaceCount(), 5 + 4 * 3);
    // Every domain vertex sits on the limit surface: the corners of every
    // face evaluate to it.
    double worst = 0.0;
    for (Index f = 0; f < d.faceCount(); ++f)
        for (int k = 0; k < 4; ++k) {
            const Vec2 uv = SmoothSurface::cornerCoordinates(true, k);
            worst = std::max(
                worst,
                (s->evaluate({f, uv.x(), uv.y()}).position - d.positions[d.face(f)[k]]).norm());
        }
    QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
    // Outward normals on a convex cage.
    const Vec3 inside(0.5, 0.5, 0.6);
    for (Index f = 0; f < d.faceCount(); ++f) {
        const SurfacePoint p = s->evaluate({f, 0.5, 0.5});
        QVERIFY(p.normal().dot(p.position - inside) > 0.0);
    }
    // Loop: the cage itself.
    const PolygonMesh ico = icosphere();
    const auto loop = SubdivisionSurface::create(ico, SurfaceKind::Loop);
    QCOMPARE(loop->domain().indices, ico.indices);
    for (Index f = 0; f < loop->domain().faceCount(); ++f) {
        const SurfacePoint p = loop->evaluate({f, 1.0 / 3, 1.0 / 3});
        QVERIFY(p.normal().dot(p.position) > 0.0);
    }
    QVERIFY(!s->description().empty());
}

void TestSubdivisionSurface::surfaceAgreesAcrossEdges_data() {
    QTest::addColumn<QString>("mesh");
    QTest::addColumn<int>("kind");
    QTest::newRow("spot, Catmull-Clark") << "spot_control_mesh.obj" << 0;
    QTest::newRow("bob, Catmull-Clark") << "bob_controlmesh.obj" << 0;
    QTest::newRow("house, Catmull-Clark") << "house" << 0;
    QTest::newRow("icosphere, Loop") << "icosphere" << 1;
    QTest::newRow("octahedron, Loop") << "octahedron" << 1;
}

void TestSubdivisionSurface::surfaceAgreesAcrossEdges() {
    QFETCH(QString, mesh);
    QFETCH(int, kind);
    PolygonMesh cage;
    if (mesh == "house") {
        cage = house();
    } else if (mesh == "icosphere") {
        cage = icosphere();
        jitter(cage, 0.05, 3);
    } else if (mesh == "octahedron") {
        cage = octahedron();
    } else {
        const QString path = sharedMesh(mesh.toUtf8().constData());
        if (!QFile::exists(path))
            QSKIP("../shared/meshes is absent: the shared-mesh checks need it");
        cage = readMesh(path.toStdString());
    }
    const auto s =
        SubdivisionSurface::create(cage, kind == 0 ? SurfaceKind::CatmullClark : SurfaceKind::Loop);
    // Interior points of every edge (the end caps at extraordinary corners
    // are smaller than 0.01 of a domain edge).
    const auto [position, normal] = edgeMismatch(*s, {0.02, 0.1, 0.25, 0.5, 0.75, 0.9, 0.98});
    // The corners themselves, where Gregory end caps meet.
    const auto [cornerPosition, cornerNormal] = edgeMismatch(*s, {0.0, 1.0});
    const double scale = s->domain().boundingBox().diagonal();
    qInfo("%s: worst edge mismatch: position %.2e, normal %.2e; at corners: position %.2e, "
          "normal %.2e (bounding box diagonal %.3g)",
          qPrintable(mesh), position, normal, cornerPosition, cornerNormal, scale);
    QVERIFY2(position < 1e-9, qPrintable(QString::number(position)));
    QVERIFY2(normal < 1e-9, qPrintable(QString::number(normal)));
    QVERIFY2(cornerPosition < 1e-9, qPrintable(QString::number(cornerPosition)));
    QVERIFY2(cornerNormal < 1e-6, qPrintable(QString::number(cornerNormal)));
}

void TestSubdivisionSurface::endCapsMatchTheirNeighbours() {
    // Inside the end caps (within 2/256 of a domain face's corner at level
    // 8): both kinds are watertight; Gregory caps also keep the normal
    // continuous, B-spline caps do not quite (SubdivisionOptions::EndCap).
    PolygonMesh spiky = house();
    jitter(spiky, 0.05, 41);
    for (const auto endCap :
         {SubdivisionOptions::EndCap::GregoryBasis, SubdivisionOptions::EndCap::BSplineBasis}) {
        SubdivisionOptions options;
        options.endCap = endCap;
        const auto s = SubdivisionSurface::create(spiky, SurfaceKind::CatmullClark, options);
        QVERIFY(s->endCapPatchCount() > 0);
        const auto [position, normal] = edgeMismatch(*s, {0.0, 0.002, 0.005, 0.995, 0.998, 1.0});
        const bool gregory = endCap == SubdivisionOptions::EndCap::GregoryBasis;
        qInfo("%s end caps: edge mismatch near extraordinary vertices: position %.2e, normal "
              "%.2e",
              gregory ? "Gregory" : "B-spline", position, normal);
        QVERIFY2(position < 1e-9, qPrintable(QString::number(position)));
        if (gregory)
            QVERIFY2(normal < 1e-8, qPrintable(QString::number(normal)));
    }
}

void TestSubdivisionSurface::convexLoopSurfaceHasDefiniteSecondFundamentalForm() {
    // With outward normals a convex surface bends away from its normal:
    // II(w, w) = w^T [L M; M N] w < 0 for every tangent direction w. The
    // rotated-triangle slip flipped II on the rotated sub-patches, about half
    // of the surface.
    const auto s = SubdivisionSurface::create(octahedron(), SurfaceKind::Loop);
    std::mt19937 rng(23);
    int samples = 0, flips = 0;
    double worstRatio = -1e300;
    for (Index f = 0; f < s->domain().faceCount(); ++f)
        for (int k = 0; k < 2000; ++k) {
            double u = unitRandom(rng), v = unitRandom(rng);
            if (u + v > 1.0) {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            const SurfacePoint p = s->evaluate({f, u, v});
            const Vec3 n = p.normal();
            const double l = p.duu.dot(n), m = p.duv.dot(n), nn = p.dvv.dot(n);
            // Largest II(w, w) over unit w (in the (u, v) metric), relative
            // to the metric.
            const double e = p.du.dot(p.du), fm = p.du.dot(p.dv), g = p.dv.dot(p.dv);
            const double det = e * g - fm * fm;
            const double mean = (l * g - 2 * m * fm + nn * e) / (2 * det);
            const double gauss = (l * nn - m * m) / det;
            const double k1 = mean + std::sqrt(std::max(0.0, mean * mean - gauss));
            worstRatio = std::max(worstRatio, k1);
            ++samples;
            if (k1 >= 0.0)
                ++flips;
        }
    qInfo("convex octahedron (Loop): %d samples, %d with II not negative definite; largest "
          "principal curvature %.3g",
          samples, flips, worstRatio);
    QCOMPARE(flips, 0);
}

void TestSubdivisionSurface::transferAcrossEdgeRoundTrips() {
    std::vector<std::unique_ptr<SubdivisionSurface>> surfaces;
    surfaces.push_back(SubdivisionSurface::create(house(), SurfaceKind::CatmullClark));
    surfaces.push_back(
        SubdivisionSurface::create(pentagonalPrism(false), SurfaceKind::CatmullClark));
    surfaces.push_back(SubdivisionSurface::create(icosphere(), SurfaceKind::Loop));
    std::mt19937 rng(29);
    double worstRoundTrip = 0.0, worstOnEdge = 0.0;
    int boundaries = 0;
    for (const auto& s : surfaces)
        for (Index f = 0; f < s->domain().faceCount(); ++f) {
            const bool quad = s->isQuad(f);
            const int n = quad ? 4 : 3;
            for (int e = 0; e < n; ++e) {
                const auto nb = s->neighbor(f, e);
                if (nb.face == kInvalidIndex) {
                    ++boundaries;
                    QVERIFY_THROWS_EXCEPTION(std::out_of_range,
                                             s->transferAcrossEdge({f, 0.2, 0.2}, e));
                    continue;
                }
                QCOMPARE(s->neighbor(nb.face, nb.edge).face, f);
                QCOMPARE(s->neighbor(nb.face, nb.edge).edge, e);
                for (int k = 0; k < 5; ++k) {
                    double v = 0.0;
                    const double u = triangleOrSquareU(rng, quad, v);
                    const Preimage p{f, u, v};
                    const Preimage q = s->transferAcrossEdge(p, e);
                    const Preimage back = s->transferAcrossEdge(q, nb.edge);
                    QCOMPARE(back.face, f);
                    worstRoundTrip =
                        std::max({worstRoundTrip, std::abs(back.u - p.u), std::abs(back.v - p.v)});
                    // A point on the shared edge: same surface point.
                    const Vec2 a = SmoothSurface::cornerCoordinates(quad, e);
                    const Vec2 b = SmoothSurface::cornerCoordinates(quad, (e + 1) % n);
                    const Vec2 x = a + unitRandom(rng) * (b - a);
                    const Preimage onEdge{f, x.x(), x.y()};
                    const Preimage other = s->transferAcrossEdge(onEdge, e);
                    // On the neighbour's edge, up to rounding.
                    const Preimage clamped{other.face, std::clamp(other.u, 0.0, 1.0),
                                           std::clamp(other.v, 0.0, 1.0)};
                    QVERIFY(std::abs(clamped.u - other.u) + std::abs(clamped.v - other.v) < 1e-15);
                    QVERIFY(s->contains(clamped));
                    worstOnEdge = std::max(
                        worstOnEdge,
                        (s->evaluate(onEdge).position - s->evaluate(other).position).norm());
                }
            }
        }
    QCOMPARE(boundaries, 10); // the cup's rim: 5 cage edges, 2 domain edges each
    qInfo("transferAcrossEdge: round trip %.2e, on-edge position mismatch %.2e", worstRoundTrip,
          worstOnEdge);
    QVERIFY(worstRoundTrip < 1e-14);
    QVERIFY(worstOnEdge < 1e-9);
}

void TestSubdivisionSurface::infinitelySharpCreasesKeepCubeFacesFlat() {
    PolygonMesh mesh = cube();
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto corners = mesh.face(f);
        for (size_t k = 0; k < 4; ++k)
            if (corners[k] < corners[(k + 1) % 4])
                mesh.creases.push_back({corners[k], corners[(k + 1) % 4], 10.0});
    }
    QCOMPARE(mesh.creases.size(), size_t(12));
    const auto sharp = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark);
    std::mt19937 rng(31);
    double worst = 0.0;
    for (Index f = 0; f < sharp->domain().faceCount(); ++f) {
        const Vec3 n0 = sharp->evaluate({f, 0.5, 0.5}).normal();
        for (int k = 0; k < 10; ++k) {
            const SurfacePoint p = sharp->evaluate({f, unitRandom(rng), unitRandom(rng)});
            // On a face of the unit cube: one coordinate is 0 or 1.
            double off = 1.0;
            for (int i = 0; i < 3; ++i)
                off = std::min({off, std::abs(p.position[i]), std::abs(p.position[i] - 1.0)});
            worst = std::max({worst, off, (p.normal() - n0).norm(), std::abs(p.duu.dot(n0)),
                              std::abs(p.dvv.dot(n0))});
        }
    }
    QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
    // Without the creases (or with them switched off) the cube rounds off.
    SubdivisionOptions off;
    off.creases = false;
    const auto smooth = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark, off);
    double nearest = 1e300;
    for (const Vec3& p : smooth->domain().positions)
        nearest = std::min(nearest, p.norm());
    QVERIFY(nearest > 0.1);
}

void TestSubdivisionSurface::objCreaseTagsAreRead() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath("creased.obj");
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
               "f 1 4 3 2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"
               "t crease 2/1/0 0 1 3.5\n"
               "t crease 4/2 1 2 2 3 1.0 10\n"
               "t corner 1/1 4 2.5\n"
               "t interpolateboundary 1/0/0 1\n");
    file.close();
    const PolygonMesh mesh = readMesh(path.toStdString());
    QCOMPARE(mesh.creases.size(), size_t(3));
    QCOMPARE(mesh.creases[0].a, 0);
    QCOMPARE(mesh.creases[0].b, 1);
    QCOMPARE(mesh.creases[0].sharpness, 3.5);
    QCOMPARE(mesh.creases[2].a, 2);
    QCOMPARE(mesh.creases[2].b, 3);
    QCOMPARE(mesh.creases[2].sharpness, 10.0);
    QCOMPARE(mesh.cornerSharpness.size(), size_t(1));
    QCOMPARE(mesh.cornerSharpness[0].first, 4);
    QCOMPARE(mesh.cornerSharpness[0].second, 2.5);
    // The tags change the surface.
    const auto creased = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark);
    SubdivisionOptions off;
    off.creases = false;
    const auto smooth = SubdivisionSurface::create(mesh, SurfaceKind::CatmullClark, off);
    QVERIFY((creased->evaluate({0, 0.5, 0.0}).position - smooth->evaluate({0, 0.5, 0.0}).position)
                .norm() > 1e-3);
}

void TestSubdivisionSurface::objCreaseTagErrorsNameTheLine() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const char* head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::pair<const char*, const char*> cases[] = {
        {"t crease 2/1 0 7 1.0\n", "line 5: tag vertex index 7 is out of range"},
        {"t crease 2/1 0 -1 1.0\n", "line 5: tag crease: vertex index -1 is out of range"},
        {"t crease 2/1 0 1 -2\n", "line 5: tag crease: sharpness -2 is not"},
        {"t crease 3/1 0 1 2 1.0\n", "line 5: tag crease needs pairs"},
        {"t crease 2/1 0 1\n", "line 5: tag crease: expected 1 sharpness"},
        {"t crease 2 0 1 1.0\n", "line 5: tag crease: counts"},
        {"t corner 1/1 x 1.0\n", "line 5: tag corner: expected 1 vertex indices"},
        {"\nt crease 2/1 0 0 1.0\n", "line 6: tag crease: edge (0, 0)"},
        {"v 1 1 1\nt crease 2/1 0 3 1.0\n", "line 6: tag crease: vertices 0 and 3"},
    };
    int i = 0;
    for (const auto& [tail, expected] : cases) {
        const QString path = dir.filePath(QString("bad%1.obj").arg(i++));
        QFile file(path);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(head);
        file.write(tail);
        file.close();
        try {
            (void)readObj(path.toStdString());
            QFAIL(qPrintable(QString("no error for ") + tail));
        } catch (const MeshError& error) {
            QVERIFY2(std::string(error.what()).find(expected) != std::string::npos, error.what());
        }
    }
}

void TestSubdivisionSurface::badInputIsRejected() {
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(house(), SurfaceKind::Loop));
    try {
        (void)SubdivisionSurface::create(house(), SurfaceKind::Loop);
    } catch (const std::invalid_argument& e) {
        QVERIFY2(std::string(e.what()).find("triangles") != std::string::npos, e.what());
    }
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(house(), SurfaceKind::VertexNormalPatches));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(PolygonMesh{}, SurfaceKind::CatmullClark));
    SubdivisionOptions deep;
    deep.isolationLevel = 11;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(house(), SurfaceKind::CatmullClark, deep));
    PolygonMesh badCrease = house();
    badCrease.creases = {{0, 99, 1.0}};
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(badCrease, SurfaceKind::CatmullClark));
    badCrease.creases = {{0, 1, std::nan("")}};
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             SubdivisionSurface::create(badCrease, SurfaceKind::CatmullClark));
    const auto s = SubdivisionSurface::create(house(), SurfaceKind::CatmullClark);
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, s->evaluate({-1, 0.5, 0.5}));
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, s->evaluate({s->domain().faceCount(), 0.5, 0.5}));
    // Batch evaluation equals single evaluation.
    std::vector<Preimage> ps;
    for (Index f = 0; f < s->domain().faceCount(); ++f)
        ps.push_back({f, 0.3, 0.6});
    std::vector<SurfacePoint> out(ps.size());
    s->evaluate(ps, out);
    for (size_t i = 0; i < ps.size(); ++i)
        QCOMPARE(out[i].duv, s->evaluate(ps[i]).duv);
    std::vector<SurfacePoint> wrong(1);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, s->evaluate(ps, wrong));
}

void TestSubdivisionSurface::cleanupTestCase() {
    qInfo("worst FD relative error: Loop first %.2e second %.2e; Catmull-Clark first %.2e "
          "second %.2e",
          worstFd[1][0], worstFd[1][1], worstFd[0][0], worstFd[0][1]);
}

QTEST_APPLESS_MAIN(TestSubdivisionSurface)
#include "test_subdivision_surface.moc"
