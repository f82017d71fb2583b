// Interpolated contours (tutorial §6.2): closed loops on closed meshes, open
// chains ending on boundaries, and every crossing on its edge with the
// linearly interpolated g equal to zero, over the 26-view protocol plus
// random views.
#include "ContourTestSupport.h"
#include "camera/Facing.h"
#include "pipeline/FieldNames.h"

#include <QtTest>
#include <cmath>

using namespace contour;
using namespace contour::testing;

namespace {
constexpr int kRandomViews = 10;

// Checks a finished snapshot against the definition, recomputing g from the
// published vertex normals (not from the method's g field).
void checkCrossings(const Snapshot& s, const Camera& camera) {
    const TriangleMesh& mesh = *s.mesh;
    const auto& normals = *s.field(fields::kVertexNormal)->vectors();
    for (const Polyline& line : *s.curves) {
        if (line.type != CurveType::Contour)
            continue;
        QCOMPARE(line.segmentElement.size(), line.segmentCount());
        for (size_t k = 0; k < line.points.size(); ++k) {
            const CurvePoint& p = line.points[k];
            QVERIFY(p.edge >= 0 && p.edge < mesh.edgeCount());
            QVERIFY(p.t >= 0.0 && p.t <= 1.0);
            const Index h = mesh.edgeHalfedge(p.edge);
            const Index i = mesh.from(h), j = mesh.to(h);
            const double gi = facingFunction(camera, mesh.position(i), normals[i]);
            const double gj = facingFunction(camera, mesh.position(j), normals[j]);
            QVERIFY2((gi > 0) != (gj > 0), "a crossing on an edge without a sign change");
            const double g = (1.0 - p.t) * gi + p.t * gj;
            QVERIFY2(std::abs(g) <= 1e-12 * std::max(std::abs(gi), std::abs(gj)),
                     qPrintable(QString("interpolated g = %1 at edge %2").arg(g).arg(p.edge)));
            const Vec3 onEdge = mesh.position(i) + p.t * (mesh.position(j) - mesh.position(i));
            QVERIFY((onEdge - p.position).norm() <= 1e-12 * (1.0 + onEdge.norm()));
            // Consecutive points lie on two edges of the segment's face.
            if (k + 1 < line.points.size() || line.closed) {
                const Index f = line.segmentElement[k];
                const Index nextEdge = line.points[(k + 1) % line.points.size()].edge;
                int found = 0;
                for (int c = 0; c < 3; ++c) {
                    const Index e = mesh.edge(TriangleMesh::halfedge(f, c));
                    found += e == p.edge || e == nextEdge;
                }
                QCOMPARE(found, 2);
            }
        }
    }
}
} // namespace

class TestInterpolatedContours : public QObject {
    Q_OBJECT
private slots:
    void closedMeshesGiveClosedLoops_data() {
        QTest::addColumn<QString>("shapeName");
        QTest::addColumn<int>("view");
        for (const QString name : {"sphere", "ellipsoid", "torus", "bumpy-torus", "two-spheres"})
            for (int v = 0; v < 26 + kRandomViews; ++v)
                QTest::addRow("%s view %d", qPrintable(name), v) << name << v;
    }
    void closedMeshesGiveClosedLoops() {
        QFETCH(QString, shapeName);
        QFETCH(int, view);
        const auto mesh = shape(shapeName.toStdString(), 48);
        const Camera camera = protocolViews(mesh->boundingBox(), kRandomViews)[view];
        const Snapshot s = runMethod("interpolated", mesh, camera);
        int open = 0;
        const int loops = contourLoops(s, &open);
        QCOMPARE(open, 0);
        QVERIFY(loops >= 1);
        if (shapeName == "sphere" || shapeName == "ellipsoid")
            QCOMPARE(loops, 1);
        if (shapeName == "two-spheres")
            QCOMPARE(loops, 2);
        QCOMPARE(s.invariantViolations(), 0LL);
        QCOMPARE(s.counter(counters::kContourSegments), [&] {
            double n = 0;
            for (const Polyline& l : *s.curves)
                n += l.type == CurveType::Contour ? l.segmentCount() : 0;
            return n;
        }());
        checkCrossings(s, camera);
    }

    // Vertex normals are view-independent: two views of one mesh share them,
    // another weighting or another mesh does not.
    void normalsAreSharedAcrossViews() {
        const auto mesh = shape("torus", 32);
        const auto views = protocolViews(mesh->boundingBox(), 0);
        const Method& m = *findMethod("interpolated");
        const Snapshot input = makeInputSnapshot(mesh);
        const auto normalsFor = [&](const Camera& camera, const std::string& weighting) {
            ParameterSet p = ParameterSet::defaults(m.parameters);
            p.set("normal-weighting", weighting);
            Runner r(m, input, camera, p);
            r.step();
            return r.current().fields.at(fields::kVertexNormal);
        };
        const auto a = normalsFor(views[0], "area");
        QVERIFY(normalsFor(views[5], "area") == a);
        QVERIFY(normalsFor(views[5], "angle") != a);
        QVERIFY(runMethod("interpolated", mesh, views[0]).fields.at(fields::kVertexNormal) != a);
    }

    // The torus (axis z) seen from the side: two loops, for every weighting.
    void torusFromTheSide_data() {
        QTest::addColumn<QString>("weighting");
        QTest::addColumn<bool>("orthographic");
        for (const QString w : {"area", "angle", "max"}) {
            QTest::addRow("%s perspective", qPrintable(w)) << w << false;
            QTest::addRow("%s orthographic", qPrintable(w)) << w << true;
        }
    }
    void torusFromTheSide() {
        QFETCH(QString, weighting);
        QFETCH(bool, orthographic);
        const auto torus = std::make_shared<const PolygonMesh>(makeTorus(1.0, 0.4, 96));
        Camera camera;
        camera.eye = Vec3(0, -6, 1.5);
        camera.up = Vec3(0, 0, 1);
        camera.projection = orthographic ? Projection::Orthographic : Projection::Perspective;
        camera.orthoHeight = 3.0;
        Overrides p;
        p.set("normal-weighting", weighting.toStdString());
        const Snapshot s = runMethod("interpolated", torus, camera, p);
        int open = 0;
        QCOMPARE(contourLoops(s, &open), 2);
        QCOMPARE(open, 0);
        QCOMPARE(s.invariantViolations(), 0LL);
        checkCrossings(s, camera);
    }

    // On an open mesh, chains that are not loops end on boundary edges.
    void openChainsEndOnBoundaries_data() {
        QTest::addColumn<int>("view");
        for (int v = 0; v < 26; ++v)
            QTest::addRow("view %d", v) << v;
    }
    void openChainsEndOnBoundaries() {
        QFETCH(int, view);
        const auto saddle = shape("saddle", 40);
        const Camera camera = protocolViews(saddle->boundingBox(), 0)[view];
        const Snapshot s = runMethod("interpolated", saddle, camera);
        for (const Polyline& line : *s.curves) {
            if (line.type != CurveType::Contour || line.closed)
                continue;
            QVERIFY(s.mesh->isBoundaryEdge(line.points.front().edge));
            QVERIFY(s.mesh->isBoundaryEdge(line.points.back().edge));
        }
        QCOMPARE(s.invariantViolations(), 0LL);
        checkCrossings(s, camera);
    }

    // The interpolated contour of a sphere converges to the true contour:
    // for a unit sphere and an eye at distance d, the contour generator is the
    // circle of points p with p · (eye - p) = 0. Area-weighted normals on a
    // latitude-longitude triangulation are first-order accurate (faces above
    // and below a vertex differ in area), so the error must at least halve
    // with each doubling of the resolution.
    void sphereContourConvergesToTheTrueCircle() {
        const Vec3 eye(0, 0, 4);
        Camera camera;
        camera.eye = eye;
        double previous = 0.4;
        for (int resolution : {24, 48, 96}) {
            const Snapshot s = runMethod("interpolated", shape("sphere", resolution), camera);
            double worst = 0;
            for (const Polyline& line : *s.curves)
                for (const CurvePoint& p : line.points)
                    worst = std::max(worst, std::abs(p.position.dot(eye - p.position)));
            qInfo("resolution %d: worst |p . (eye - p)| = %.3g", resolution, worst);
            QVERIFY2(worst < 0.52 * previous, qPrintable(QString::number(worst)));
            previous = worst;
        }
        QVERIFY(previous < 0.05);
    }
};

QTEST_APPLESS_MAIN(TestInterpolatedContours)
#include "test_interpolated_contours.moc"
