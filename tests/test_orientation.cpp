// The orientation report and the flip of inward components
// (mesh/Orientation.h): closed, consistently oriented components are decided
// by their signed volume and flipped when it is negative; open and
// inconsistently oriented ones are reported and left alone.
#include "ContourTestSupport.h"
#include "mesh/Orientation.h"
#include "mesh/ProceduralShapes.h"

#include <QtTest>
#include <cmath>
#include <numbers>

using namespace contour;
using testing::reversedFaces;

namespace {

// The unit cube [0, 1]^3 as six quads, counter-clockwise seen from outside.
PolygonMesh makeCube() {
    return readMesh(CONTOUR_SOURCE_DIR "/tests/data/good/cube_quads.obj");
}

PolygonMesh withoutFace(const PolygonMesh& mesh, Index removed) {
    PolygonMesh out;
    out.positions = mesh.positions;
    for (Index f = 0; f < mesh.faceCount(); ++f)
        if (f != removed)
            out.addFace(mesh.face(f));
    return out;
}

// The faces, positions and tags of two meshes are the same, bit for bit.
bool sameMesh(const PolygonMesh& a, const PolygonMesh& b) {
    if (a.positions != b.positions || a.offsets != b.offsets || a.indices != b.indices ||
        a.creases.size() != b.creases.size() || a.cornerSharpness != b.cornerSharpness)
        return false;
    for (size_t i = 0; i < a.creases.size(); ++i)
        if (a.creases[i].a != b.creases[i].a || a.creases[i].b != b.creases[i].b ||
            a.creases[i].sharpness != b.creases[i].sharpness)
            return false;
    return true;
}

// 0: the cube with a crease and a corner tag, 1: a sphere of quads and
// triangle fans.
PolygonMesh shapeFor(int shape) {
    if (shape == 0) {
        PolygonMesh cube = makeCube();
        cube.creases.push_back({0, 1, 2.5});
        cube.cornerSharpness.emplace_back(7, 3.0);
        return cube;
    }
    return makeSphere(1.0, 24);
}

} // namespace

class TestOrientation : public QObject {
    Q_OBJECT

private slots:
    void outwardMeshesAreLeftAlone_data();
    void outwardMeshesAreLeftAlone();
    void reversedMeshesAreFlippedBack_data();
    void reversedMeshesAreFlippedBack();
    void onlyTheInwardComponentIsFlipped();
    void openMeshIsReportedAndUntouched();
    void inconsistentMeshIsReportedAndUntouched();
    void volumeFarFromTheOrigin();
    void keepingTheFileOrientation();
};

void TestOrientation::outwardMeshesAreLeftAlone_data() {
    QTest::addColumn<int>("shape");
    QTest::addColumn<double>("volume");
    QTest::addColumn<double>("tolerance");
    QTest::newRow("cube") << 0 << 1.0 << 1e-15;
    // The inscribed polyhedron's volume is a little below the ball's.
    QTest::newRow("sphere") << 1 << 4.0 / 3.0 * std::numbers::pi << 0.05;
}

void TestOrientation::outwardMeshesAreLeftAlone() {
    QFETCH(int, shape);
    QFETCH(double, volume);
    QFETCH(double, tolerance);
    const PolygonMesh mesh = shapeFor(shape);
    OrientationReport report;
    const PolygonMesh oriented = orientOutward(mesh, &report);
    QCOMPARE(report.components.size(), size_t(1));
    const ComponentOrientation& c = report.components[0];
    QCOMPARE(c.faces, mesh.faceCount());
    QCOMPARE(c.firstFace, 0);
    QVERIFY(c.closed);
    QVERIFY(c.consistent);
    QVERIFY(c.signedVolume > 0.0);
    QVERIFY2(std::abs(c.signedVolume - volume) <= tolerance * volume,
             qPrintable(QString::number(c.signedVolume, 'g', 17)));
    QVERIFY(!c.flipped);
    QVERIFY(!c.inward());
    QCOMPARE(report.flippedCount(), 0);
    QVERIFY(!report.hasMessage());
    QVERIFY(orientationMessage(report, "--keep-orientation").empty());
    QVERIFY(sameMesh(oriented, mesh));
    QVERIFY(c.describe().find("closed, outward") == 0);
}

void TestOrientation::reversedMeshesAreFlippedBack_data() {
    QTest::addColumn<int>("shape");
    QTest::newRow("cube") << 0;
    QTest::newRow("sphere") << 1;
}

void TestOrientation::reversedMeshesAreFlippedBack() {
    QFETCH(int, shape);
    const PolygonMesh original = shapeFor(shape);
    const PolygonMesh inward = reversedFaces(original);
    const double outwardVolume = orientationReport(original).components.at(0).signedVolume;

    OrientationReport report;
    const PolygonMesh oriented = orientOutward(inward, &report);
    QCOMPARE(report.components.size(), size_t(1));
    const ComponentOrientation& c = report.components[0];
    QVERIFY(c.closed && c.consistent);
    QVERIFY(c.inward());
    QVERIFY(c.flipped);
    QVERIFY(std::abs(c.signedVolume + outwardVolume) <= 1e-12 * outwardVolume);
    QCOMPARE(report.inwardCount(), 1);
    QCOMPARE(report.flippedCount(), 1);
    // Every face is the original one again, corner for corner; vertices and
    // tags were not touched.
    QVERIFY(sameMesh(oriented, original));
    for (Index f = 0; f < original.faceCount(); ++f)
        QVERIFY(std::ranges::equal(oriented.face(f), original.face(f)));
    // The flipped mesh reads as outward.
    const OrientationReport again = orientationReport(oriented);
    QVERIFY(again.components.at(0).signedVolume > 0.0);

    const std::string message = orientationMessage(report, "--keep-orientation");
    QVERIFY2(message.find("1 of 1 closed components had inward normals (signed volume -") == 0,
             message.c_str());
    QVERIFY2(message.find("; flipped (--keep-orientation keeps them)") != std::string::npos,
             message.c_str());
    QVERIFY(c.describe().find("closed, inward") == 0);
    QVERIFY(c.describe().find("flipped") != std::string::npos);
}

void TestOrientation::onlyTheInwardComponentIsFlipped() {
    const PolygonMesh spheres = makeTwoSpheres(16);
    const OrientationReport before = orientationReport(spheres);
    QCOMPARE(before.components.size(), size_t(2));
    QCOMPARE(before.decidableCount(), 2);
    std::vector<Index> second;
    for (Index f = 0; f < spheres.faceCount(); ++f)
        if (before.faceComponent[f] == 1)
            second.push_back(f);
    QCOMPARE(Index(second.size()), before.components[1].faces);
    QCOMPARE(second.front(), before.components[1].firstFace);
    const PolygonMesh mixed = reversedFaces(spheres, second);

    OrientationReport report;
    const PolygonMesh oriented = orientOutward(mixed, &report);
    QCOMPARE(report.components.size(), size_t(2));
    QVERIFY(!report.components[0].inward() && !report.components[0].flipped);
    QVERIFY(report.components[1].inward() && report.components[1].flipped);
    QCOMPARE(report.components[1].signedVolume, -before.components[1].signedVolume);
    QVERIFY(sameMesh(oriented, spheres));
    const std::string message = orientationMessage(report, "--keep-orientation");
    QVERIFY2(message.find("1 of 2 closed components had inward normals") == 0, message.c_str());
}

void TestOrientation::openMeshIsReportedAndUntouched() {
    for (const PolygonMesh& open :
         {withoutFace(makeCube(), 1), reversedFaces(withoutFace(makeCube(), 1)),
          makeSaddlePatch(8)}) {
        OrientationReport report;
        const PolygonMesh oriented = orientOutward(open, &report);
        QCOMPARE(report.components.size(), size_t(1));
        const ComponentOrientation& c = report.components[0];
        QVERIFY(!c.closed);
        QVERIFY(c.consistent);
        QCOMPARE(c.signedVolume, 0.0);
        QVERIFY(!c.decidable() && !c.inward() && !c.flipped);
        QCOMPARE(report.openCount(), 1);
        QVERIFY(sameMesh(oriented, open));
        QCOMPARE(c.describe(), std::string("open: its orientation cannot be decided by volume"));
        QCOMPARE(orientationMessage(report, "--keep-orientation"),
                 std::string("1 open component left as in the file: its orientation cannot be "
                             "decided by volume"));
    }
}

void TestOrientation::inconsistentMeshIsReportedAndUntouched() {
    const PolygonMesh cube = reversedFaces(makeCube(), {2});
    OrientationReport report;
    const PolygonMesh oriented = orientOutward(cube, &report);
    QCOMPARE(report.components.size(), size_t(1));
    const ComponentOrientation& c = report.components[0];
    QVERIFY(c.closed);
    QVERIFY(!c.consistent);
    QCOMPARE(c.signedVolume, 0.0);
    QVERIFY(!c.flipped);
    QCOMPARE(report.inconsistentCount(), 1);
    QVERIFY(sameMesh(oriented, cube));
    QVERIFY(c.describe().find("cannot be decided by volume") != std::string::npos);
    const std::string message = orientationMessage(report, "--keep-orientation");
    QVERIFY2(message == "1 inconsistently oriented closed component left as in the file: its "
                        "orientation cannot be decided by volume",
             message.c_str());

    // Next to a flipped component the message says both.
    PolygonMesh both = reversedFaces(makeCube());
    const Index offset = both.vertexCount();
    for (const Vec3& p : cube.positions)
        both.positions.push_back(p + Vec3(3, 0, 0));
    for (Index f = 0; f < cube.faceCount(); ++f) {
        std::vector<Index> face(cube.face(f).begin(), cube.face(f).end());
        for (Index& v : face)
            v += offset;
        both.addFace(face);
    }
    OrientationReport bothReport;
    const PolygonMesh bothOriented = orientOutward(both, &bothReport);
    QCOMPARE(bothReport.components.size(), size_t(2));
    QVERIFY(bothReport.components[0].flipped);
    QVERIFY(!bothReport.components[1].flipped);
    for (Index f = 6; f < 12; ++f)
        QVERIFY(std::ranges::equal(bothOriented.face(f), both.face(f)));
    QCOMPARE(orientationMessage(bothReport, "X"),
             std::string("1 of 1 closed components had inward normals (signed volume -1); "
                         "flipped (X keeps them); 1 inconsistently oriented closed component left "
                         "as in the file: its orientation cannot be decided by volume"));
}

void TestOrientation::volumeFarFromTheOrigin() {
    PolygonMesh cube = reversedFaces(makeCube());
    for (Vec3& p : cube.positions)
        p += Vec3(1e7, -3e6, 5e6);
    const OrientationReport report = orientationReport(cube);
    QVERIFY2(std::abs(report.components.at(0).signedVolume + 1.0) < 1e-6,
             qPrintable(QString::number(report.components.at(0).signedVolume, 'g', 17)));
}

void TestOrientation::keepingTheFileOrientation() {
    const PolygonMesh inward = reversedFaces(makeSphere(1.0, 12));
    OrientationReport report;
    const PolygonMesh kept = orientForContours(inward, true, report);
    QVERIFY(sameMesh(kept, inward));
    QCOMPARE(report.inwardCount(), 1);
    QCOMPARE(report.flippedCount(), 0);
    const std::string message = orientationMessage(report, "--keep-orientation");
    QVERIFY2(message.find("1 of 1 closed components has inward normals (signed volume -") == 0,
             message.c_str());
    QVERIFY2(message.find("kept as in the file (--keep-orientation): its contours will read as "
                          "hidden") != std::string::npos,
             message.c_str());

    const PolygonMesh flipped = orientForContours(inward, false, report);
    QCOMPARE(report.flippedCount(), 1);
    QVERIFY(sameMesh(flipped, makeSphere(1.0, 12)));
}

QTEST_APPLESS_MAIN(TestOrientation)
#include "test_orientation.moc"
