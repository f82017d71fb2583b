// Mesh contours (tutorial §3.4, appendix B/C): loops on known shapes, the
// convex/concave classification, boundaries, and post-conditions.
#include "ContourTestSupport.h"
#include "core/Predicates.h"
#include "pipeline/FieldNames.h"

#include <QtTest>

using namespace contour;
using namespace contour::testing;

namespace {
Camera lookAt(const Vec3& eye, const Vec3& target = Vec3::Zero()) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.up = Vec3(0, 0, 1);
    c.fovYDegrees = 50;
    return c;
}
} // namespace

class TestMeshContours : public QObject {
    Q_OBJECT
private slots:
    // A convex mesh seen from outside has one loop of convex contour edges.
    void sphereHasOneConvexLoop_data() {
        QTest::addColumn<int>("view");
        const auto views = protocolViews(makeSphere(1.0, 8).boundingBox(), 10);
        for (int i = 0; i < static_cast<int>(views.size()); ++i)
            QTest::addRow("view %d", i) << i;
    }
    void sphereHasOneConvexLoop() {
        QFETCH(int, view);
        const auto sphere = shape("sphere", 40);
        const Camera camera = protocolViews(sphere->boundingBox(), 10)[view];
        const Snapshot s = runMethod("mesh", sphere, camera);
        int open = 0;
        QCOMPARE(contourLoops(s, &open), 1);
        QCOMPARE(open, 0);
        QCOMPARE(s.counter(counters::kConcaveContourEdges), 0.0);
        QCOMPARE(s.counter(counters::kBifurcationVertices), 0.0);
        QVERIFY(s.counter(counters::kContourEdges) > 10);
        QCOMPARE(s.invariantViolations(), 0LL);
    }

    // A torus (axis z) seen from the side, slightly above its equator: the
    // outer silhouette loop and the inner loop. Concave contour edges can only
    // lie on the inner, saddle-shaped half (distance to the axis < R).
    void torusFromTheSide_data() {
        QTest::addColumn<double>("height");
        QTest::newRow("tilt 0.5") << 0.5;
        QTest::newRow("tilt 1.5") << 1.5;
        QTest::newRow("tilt 3") << 3.0;
    }
    void torusFromTheSide() {
        QFETCH(double, height);
        const auto torus = std::make_shared<const PolygonMesh>(makeTorus(1.0, 0.4, 96));
        const Snapshot s = runMethod("mesh", torus, lookAt(Vec3(0, -6, height)));
        int open = 0;
        QCOMPARE(contourLoops(s, &open), 2);
        QCOMPARE(open, 0);
        QVERIFY(s.counter(counters::kConcaveContourEdges) > 0);
        QCOMPARE(s.invariantViolations(), 0LL);
        const TriangleMesh& mesh = *s.mesh;
        const auto& label = *s.field(fields::kContourEdge)->labels();
        for (Index e = 0; e < mesh.edgeCount(); ++e) {
            if (label[e] != 2)
                continue;
            const Index h = mesh.edgeHalfedge(e);
            const Vec3 mid = 0.5 * (mesh.position(mesh.from(h)) + mesh.position(mesh.to(h)));
            QVERIFY2(mid.head<2>().norm() < 1.0 + 1e-9, qPrintable(QString("edge %1").arg(e)));
        }
    }

    // Appendix C: edge ab with triangles abd and bae is concave iff
    // FRONTSIDE(a, b, d, e) > 0. Two-triangle valley and ridge, normals up,
    // seen from a camera that makes the shared edge a contour.
    void convexity_data() {
        QTest::addColumn<double>("wingHeight");
        QTest::addColumn<int>("expectedLabel");
        QTest::newRow("valley is concave") << 1.0 << 2;
        QTest::newRow("ridge is convex") << -1.0 << 1;
    }
    void convexity() {
        QFETCH(double, wingHeight);
        QFETCH(int, expectedLabel);
        auto m = std::make_shared<PolygonMesh>();
        m->positions = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0.5, wingHeight),
                        Vec3(-1, 0.5, wingHeight)};
        m->addFace({1, 0, 2});
        m->addFace({0, 1, 3});
        const Snapshot s = runMethod("mesh", m, lookAt(Vec3(5, 0.5, 0.2), Vec3(0, 0.5, 0)));
        const TriangleMesh& mesh = *s.mesh;
        const auto& label = *s.field(fields::kContourEdge)->labels();
        int contourEdges = 0;
        for (Index e = 0; e < mesh.edgeCount(); ++e) {
            if (mesh.isBoundaryEdge(e))
                continue;
            QCOMPARE(label[e], expectedLabel);
            ++contourEdges;
        }
        QCOMPARE(contourEdges, 1);
    }

    // The saddle patch has one boundary loop, and contours that end on it.
    void boundaries() {
        const auto saddle = shape("saddle", 40);
        const Snapshot s = runMethod("mesh", saddle, lookAt(Vec3(2.5, -3, 1.5)));
        int boundaryLoops = 0;
        for (const Polyline& line : *s.curves)
            boundaryLoops += line.type == CurveType::Boundary && line.closed;
        QCOMPARE(boundaryLoops, 1);
        QVERIFY(s.counter(counters::kBoundaryEdges) > 0);
        QCOMPARE(s.invariantViolations(), 0LL);
        Overrides noBoundaries;
        noBoundaries.set("include-boundaries", false);
        const Snapshot t = runMethod("mesh", saddle, lookAt(Vec3(2.5, -3, 1.5)), noBoundaries);
        for (const Polyline& line : *t.curves)
            QVERIFY(line.type != CurveType::Boundary);
    }

    void twoSpheresGiveTwoLoops() {
        const auto spheres = shape("two-spheres", 32);
        const Snapshot s = runMethod("mesh", spheres, lookAt(Vec3(0.3, 0.2, 6)));
        QCOMPARE(contourLoops(s), 2);
    }

    // Every contour edge separates a front face from a back face, counted
    // directly from the face normals here (not from the method's fields).
    void contourEdgesAreFrontBackPairs() {
        const auto torus = shape("bumpy-torus", 64);
        const Camera camera = lookAt(Vec3(1.5, -4, 2.5));
        const Snapshot s = runMethod("mesh", torus, camera);
        const TriangleMesh& mesh = *s.mesh;
        const auto& label = *s.field(fields::kContourEdge)->labels();
        long long expected = 0;
        for (Index e = 0; e < mesh.edgeCount(); ++e) {
            const Index h = mesh.edgeHalfedge(e);
            if (mesh.isBoundary(h))
                continue;
            const auto front = [&](Index f) {
                const Triangle& t = mesh.triangle(f);
                return frontSide(mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2]),
                                 camera.eye) > 0;
            };
            const bool contourHere =
                front(TriangleMesh::face(h)) != front(TriangleMesh::face(mesh.opposite(h)));
            expected += contourHere;
            QCOMPARE(label[e] != 0, contourHere);
        }
        QCOMPARE(s.counter(counters::kContourEdges), static_cast<double>(expected));
        // Dropping concave edges keeps only convex ones in the chains.
        Overrides drop;
        drop.set("drop-concave", true);
        const Snapshot t = runMethod("mesh", torus, camera, drop);
        size_t chained = 0;
        for (const Polyline& line : *t.curves)
            if (line.type == CurveType::Contour)
                chained += line.segmentElement.size();
        QCOMPARE(static_cast<double>(chained), t.counter(counters::kConvexContourEdges));
    }
};

QTEST_APPLESS_MAIN(TestMeshContours)
#include "test_mesh_contours.moc"
