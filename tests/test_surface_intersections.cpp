// Surface–surface intersection curves: exact triangle pairs
// from CGAL, chained through mesh edges/vertices into polylines.
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "visibility/SurfaceIntersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <QElapsedTimer>
#include <QtTest>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

using namespace contour;

namespace {

// Appends b's vertices and faces to a, as a second connected component.
void append(PolygonMesh& a, const PolygonMesh& b) {
    const Index base = a.vertexCount();
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (Index f = 0; f < b.faceCount(); ++f) {
        std::vector<Index> face(b.face(f).begin(), b.face(f).end());
        for (Index& v : face)
            v += base;
        a.addFace(face);
    }
}

// An axis-aligned cube [lo, lo + 2]^3 whose faces are 2 x 2 grids of quads,
// outward oriented (a vertex at each face centre and edge midpoint).
PolygonMesh gridCube(const Vec3& lo) {
    PolygonMesh mesh;
    std::map<std::array<int, 3>, Index> ids;
    auto vertex = [&](std::array<int, 3> c) {
        const auto [it, inserted] = ids.emplace(c, mesh.vertexCount());
        if (inserted)
            mesh.positions.push_back(lo + Vec3(c[0], c[1], c[2]));
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side <= 2; side += 2) {
            for (int i = 0; i < 2; ++i) {
                for (int j = 0; j < 2; ++j) {
                    auto at = [&](int di, int dj) {
                        std::array<int, 3> c{};
                        c[axis] = side;
                        c[u] = i + di;
                        c[v] = j + dj;
                        return vertex(c);
                    };
                    // (u, v, axis) is right-handed: CCW in (u, v) faces +axis.
                    if (side == 2)
                        mesh.addFace({at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
                    else
                        mesh.addFace({at(0, 0), at(0, 1), at(1, 1), at(1, 0)});
                }
            }
        }
    }
    return mesh;
}

// The largest distance from a facet of a lat-long sphere of `resolution` to
// the sphere (a bound: the polar fans and the quads' diagonals stay within
// one longitude step of a vertex).
double tessellationError(double radius, int resolution) {
    return radius * (1.0 - std::cos(2.0 * std::numbers::pi / resolution));
}

using FacePair = std::pair<Index, Index>;

// An independent oracle: CGAL's Polygon_mesh_processing::self_intersections
// (its own box intersection and triangle tests) on a Surface_mesh with the
// same faces in the same order, keeping the pairs that share no vertex.
// `adjacent` counts the pairs PMP reports between faces sharing a vertex
// (they cross beyond it), which surfaceIntersectionCurves skips on purpose.
std::set<FacePair> oraclePairs(const TriangleMesh& mesh, long long& adjacent) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Mesh = CGAL::Surface_mesh<K::Point_3>;
    Mesh sm;
    for (const Vec3& p : mesh.positions())
        sm.add_vertex(K::Point_3(p.x(), p.y(), p.z()));
    for (const Triangle& t : mesh.triangles())
        sm.add_face(Mesh::Vertex_index(static_cast<Mesh::size_type>(t[0])),
                    Mesh::Vertex_index(static_cast<Mesh::size_type>(t[1])),
                    Mesh::Vertex_index(static_cast<Mesh::size_type>(t[2])));
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
    std::set<FacePair> out;
    for (const auto& [a, b] : pairs) {
        const Index f = static_cast<Index>(a.idx()), g = static_cast<Index>(b.idx());
        bool shared = false;
        for (Index u : mesh.triangle(f))
            for (Index v : mesh.triangle(g))
                shared = shared || u == v;
        if (!shared)
            out.emplace(std::min(f, g), std::max(f, g));
        else
            ++adjacent;
    }
    return out;
}

std::set<FacePair> curvePairs(const SurfaceIntersectionCurves& result) {
    std::set<FacePair> out;
    for (size_t c = 0; c < result.curves.size(); ++c)
        for (size_t i = 0; i < result.curves[c].segmentElement.size(); ++i) {
            const Index f = result.curves[c].segmentElement[i], g = result.secondFaces[c][i];
            out.emplace(std::min(f, g), std::max(f, g));
        }
    return out;
}

} // namespace

class TestSurfaceIntersections : public QObject {
    Q_OBJECT
private slots:
    // Two interpenetrating spheres meet in one circle: one closed loop whose
    // points lie on both (faceted) spheres, each segment with one face on
    // each sphere and the first face always on the same sphere.
    void twoSpheresMeetInOneLoop_data() {
        QTest::addColumn<int>("resolution");
        QTest::addRow("coarse") << 16;
        QTest::addRow("medium") << 48;
        QTest::addRow("fine") << 96;
    }
    void twoSpheresMeetInOneLoop() {
        QFETCH(int, resolution);
        const Vec3 ca(0, 0, 0), cb(1.1, 0.23, 0.17);
        const double ra = 1.0, rb = 0.8;
        PolygonMesh both = makeSphere(ra, resolution, ca);
        const Index firstFaceOfB = static_cast<Index>(both.triangulate().faceCount());
        append(both, makeSphere(rb, resolution, cb));
        const TriangleMesh mesh = both.triangulate();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);

        QCOMPARE(result.curves.size(), size_t(1));
        QCOMPARE(result.secondFaces.size(), size_t(1));
        QCOMPARE(result.openEnds, 0);
        QCOMPARE(result.branchPoints, 0);
        QCOMPARE(result.coplanarPairs, 0LL);
        const Polyline& loop = result.curves[0];
        QVERIFY(loop.closed);
        QCOMPARE(loop.type, CurveType::SurfaceIntersection);
        QCOMPARE(loop.source, SegmentSource::Face);
        QCOMPARE(loop.segmentElement.size(), loop.segmentCount());
        QCOMPARE(result.secondFaces[0].size(), loop.segmentCount());
        QVERIFY(loop.points.size() >= 6);

        const double ea = tessellationError(ra, resolution), eb = tessellationError(rb, resolution);
        double worst = 0.0;
        for (const CurvePoint& p : loop.points) {
            const double da = (p.position - ca).norm(), db = (p.position - cb).norm();
            // Facets are chords: inside the sphere, by at most the sagitta.
            QVERIFY2(da <= ra + 1e-12 && da >= ra - ea,
                     qPrintable(QString("distance to centre A %1").arg(da)));
            QVERIFY2(db <= rb + 1e-12 && db >= rb - eb,
                     qPrintable(QString("distance to centre B %1").arg(db)));
            worst = std::max({worst, ra - da, rb - db});
            // Every point of a segment end lies on a mesh edge or vertex.
            QVERIFY(p.edge != kInvalidIndex || p.vertex != kInvalidIndex);
        }
        const bool firstOnA = loop.segmentElement[0] < firstFaceOfB;
        for (size_t i = 0; i < loop.segmentCount(); ++i) {
            QCOMPARE(loop.segmentElement[i] < firstFaceOfB, firstOnA);
            QCOMPARE(result.secondFaces[0][i] < firstFaceOfB, !firstOnA);
        }
        qInfo("resolution %d: %zu points, largest distance inside a sphere %.2e (bound %.2e), %lld "
              "pairs not in generic position",
              resolution, loop.points.size(), worst, std::max(ea, eb), result.exactPairs);
    }

    // Closed surfaces without self-intersections have no curves: a sphere, a
    // torus, a bumpy torus (neighbouring faces share a vertex and are skipped).
    void cleanShapesHaveNone_data() {
        QTest::addColumn<QString>("name");
        QTest::addRow("sphere") << "sphere";
        QTest::addRow("torus") << "torus";
        QTest::addRow("bumpy-torus") << "bumpy-torus";
        QTest::addRow("two-spheres (disjoint)") << "two-spheres";
    }
    void cleanShapesHaveNone() {
        QFETCH(QString, name);
        const TriangleMesh mesh = makeProceduralShape(name.toStdString(), 48).triangulate();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);
        QCOMPARE(result.curves.size(), size_t(0));
        QCOMPARE(result.intersectingPairs, 0LL);
        QCOMPARE(result.touchingPairs, 0LL);
    }

    // A fully degenerate case: two grid cubes offset by (1, 1, 1). The curve
    // is the hexagon (2,1,1) (2,1,2) (1,1,2) (1,2,2) (1,2,1) (2,2,1); every
    // piece lies along a mesh edge of both cubes and every corner is a mesh
    // vertex of both, so many pairs report the same pieces and many pairs
    // only touch. Chaining by mesh simplices must still give one closed loop.
    void degenerateCubesGiveOneHexagon() {
        PolygonMesh both = gridCube(Vec3::Zero());
        append(both, gridCube(Vec3(1, 1, 1)));
        const TriangleMesh mesh = both.triangulate();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);
        QCOMPARE(result.curves.size(), size_t(1));
        QCOMPARE(result.openEnds, 0);
        QCOMPARE(result.branchPoints, 0);
        QVERIFY(result.duplicateSegments > 0);
        QVERIFY(result.exactPairs > 0); // every intersecting pair is degenerate here
        const Polyline& loop = result.curves[0];
        QVERIFY(loop.closed);
        QCOMPARE(loop.points.size(), size_t(6));
        const std::vector<Vec3> corners{{2, 1, 1}, {2, 1, 2}, {1, 1, 2},
                                        {1, 2, 2}, {1, 2, 1}, {2, 2, 1}};
        for (const Vec3& c : corners) {
            bool found = false;
            for (const CurvePoint& p : loop.points)
                found = found || (p.position - c).norm() == 0.0;
            QVERIFY2(found,
                     qPrintable(QString("corner %1 %2 %3").arg(c.x()).arg(c.y()).arg(c.z())));
        }
    }

    // An open patch whose boundary lies inside a sphere: one open arc, its
    // two ends on the patch's boundary edges.
    void patchThroughSphereGivesOneOpenArc() {
        PolygonMesh both = makeSaddlePatch(24);
        append(both, makeSphere(0.5, 32, Vec3(1.0, 0.013, 0.51)));
        const TriangleMesh mesh = both.triangulate();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);
        QCOMPARE(result.curves.size(), size_t(1));
        QCOMPARE(result.openEnds, 2);
        QCOMPARE(result.branchPoints, 0);
        const Polyline& arc = result.curves[0];
        QVERIFY(!arc.closed);
        QCOMPARE(arc.segmentElement.size(), arc.points.size() - 1);
        for (const CurvePoint* end : {&arc.points.front(), &arc.points.back()}) {
            QVERIFY(end->edge != kInvalidIndex);
            QVERIFY(mesh.isBoundaryEdge(end->edge));
            QVERIFY(std::abs(end->position.x() - 1.0) < 1e-12); // the patch's x = 1 side
        }
    }

    // Against CGAL's own self-intersection test: every face pair of a curve
    // segment is an intersecting pair there, and every other intersecting
    // pair there is one we counted as touching, coplanar or a duplicate.
    void agreesWithPolygonMeshProcessing_data() {
        QTest::addColumn<QString>("mesh");
        QTest::addRow("two spheres") << "spheres";
        QTest::addRow("grid cubes (degenerate)") << "cubes";
        QTest::addRow("cube and sphere") << "cube-sphere";
        QTest::addRow("spot control mesh") << "spot";
    }
    void agreesWithPolygonMeshProcessing() {
        QFETCH(QString, mesh);
        PolygonMesh shape;
        if (mesh == "spheres") {
            shape = makeSphere(1.0, 40);
            append(shape, makeSphere(0.7, 40, Vec3(0.9, 0.2, 0.1)));
        } else if (mesh == "cubes") {
            shape = gridCube(Vec3::Zero());
            append(shape, gridCube(Vec3(1, 1, 1)));
        } else if (mesh == "cube-sphere") {
            shape = gridCube(Vec3(0.3, 0.21, 0.17));
            append(shape, makeSphere(1.0, 40, Vec3(0.05, 0.02, 0.03)));
        } else {
            shape = readMesh(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj");
        }
        const TriangleMesh triangles = shape.triangulate();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(triangles);
        const std::set<FacePair> mine = curvePairs(result);
        long long adjacent = 0;
        const std::set<FacePair> oracle = oraclePairs(triangles, adjacent);
        for (const FacePair& p : mine)
            QVERIFY2(oracle.count(p),
                     qPrintable(QString("pair %1 %2 not in PMP").arg(p.first).arg(p.second)));
        const long long others =
            result.touchingPairs + result.coplanarPairs + result.duplicateSegments;
        qInfo("%s: %zu curves, %zu segment pairs; PMP %zu pairs; touching %lld, coplanar %lld, "
              "duplicates %lld, open ends %d; PMP pairs sharing a vertex (skipped) %lld",
              qPrintable(mesh), result.curves.size(), mine.size(), oracle.size(),
              result.touchingPairs, result.coplanarPairs, result.duplicateSegments, result.openEnds,
              adjacent);
        QCOMPARE(static_cast<long long>(oracle.size()),
                 static_cast<long long>(mine.size()) + others);
    }

    // A cube interpenetrating a sphere in general position: still one loop.
    void offsetCubeAndSphere() {
        PolygonMesh both = gridCube(Vec3(0.3, 0.21, 0.17));
        append(both, makeSphere(1.0, 40, Vec3(0.05, 0.02, 0.03)));
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(both.triangulate());
        QCOMPARE(result.curves.size(), size_t(1));
        QVERIFY(result.curves[0].closed);
        QCOMPARE(result.openEnds, 0);
    }

    // Timing on about 50k faces: two interpenetrating spheres of ~25k each.
    void timingOn50kFaces() {
        const int n = 160; // 2 n (n/2 - 1) = 25,280 triangles per sphere
        PolygonMesh both = makeSphere(1.0, n);
        append(both, makeSphere(0.9, n, Vec3(0.93, 0.31, 0.12)));
        const TriangleMesh mesh = both.triangulate();
        QElapsedTimer timer;
        timer.start();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);
        const qint64 ms = timer.elapsed();
        QCOMPARE(result.curves.size(), size_t(1));
        QVERIFY(result.curves[0].closed);
        qInfo("%d faces: %lld ms, %lld candidate pairs, %lld intersecting, %zu points",
              mesh.faceCount(), static_cast<long long>(ms), result.candidatePairs,
              result.intersectingPairs, result.curves[0].points.size());
    }

    // The common case, a clean mesh (the visibility phase runs this per view):
    // ~100k faces of a bumpy torus, no curve.
    void timingOnCleanMesh() {
        const TriangleMesh mesh = makeProceduralShapeWithFaces("bumpy-torus", 100000).triangulate();
        QElapsedTimer timer;
        timer.start();
        const SurfaceIntersectionCurves result = surfaceIntersectionCurves(mesh);
        const qint64 ms = timer.elapsed();
        QCOMPARE(result.curves.size(), size_t(0));
        qInfo("clean bumpy torus, %d faces: %lld ms, %lld candidate pairs", mesh.faceCount(),
              static_cast<long long>(ms), result.candidatePairs);
    }
};

QTEST_GUILESS_MAIN(TestSurfaceIntersections)
#include "test_surface_intersections.moc"
