// Comparing two methods' drawings in the image: the parts
// of one side's curves with no curve of the other within the tolerance, on
// hand-made polylines whose answer is known, on hand-made view graphs, and on
// real runs (a method against itself differs nowhere; mesh against
// consistent contours (both on the limit surface) on the torus differs somewhere, and less than
// all).
#include "ContourTestSupport.h"
#include "export/CurveComparison.h"
#include "pipeline/ViewGraph.h"

#include <QtTest>

using namespace contour;
using namespace contour::testing;

namespace {

ImagePolyline square(double x0, double y0, double side, bool closed = true) {
    ImagePolyline s{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
    if (closed)
        s.push_back(s.front());
    return s;
}

} // namespace

class TestCurveComparison : public QObject {
    Q_OBJECT

private slots:
    void knownDifferences_data();
    void knownDifferences();
    void symmetric();
    void drawnCurvesOfAViewGraph();
    void realRuns();
    void distanceField();
    void nodesOnlyOneSideDraws();
};

void TestCurveComparison::knownDifferences_data() {
    QTest::addColumn<double>("shift");     // B is A moved right by this many px
    QTest::addColumn<bool>("dropBottom");  // B lacks A's bottom side (y = 10)
    QTest::addColumn<double>("tolerance"); // px
    QTest::addColumn<double>("onlyInA");   // expected length, px
    QTest::addColumn<double>("onlyInB");
    QTest::addColumn<double>("slack"); // allowed error, px

    // A 100 px square from (10, 10).
    QTest::newRow("identical") << 0.0 << false << 1.0 << 0.0 << 0.0 << 0.0;
    QTest::newRow("within tolerance") << 0.8 << false << 1.0 << 0.0 << 0.0 << 0.0;
    // The vertical sides are 5 px apart: one whole, the other but for the
    // tolerance at each end where the other side's horizontal ones pass; the
    // horizontal sides overlap but for 5 px minus the tolerance at one end.
    QTest::newRow("shifted") << 5.0 << false << 1.0 << 100.0 + 98.0 + 2 * 4.0
                             << 100.0 + 98.0 + 2 * 4.0 << 1.5;
    // The side missing from B, but for the tolerance at both ends where the
    // vertical sides are near.
    QTest::newRow("side missing") << 0.0 << true << 2.0 << 100.0 - 2 * 2.0 << 0.0 << 1.0;
}

void TestCurveComparison::knownDifferences() {
    QFETCH(double, shift);
    QFETCH(bool, dropBottom);
    QFETCH(double, tolerance);
    QFETCH(double, onlyInA);
    QFETCH(double, onlyInB);
    QFETCH(double, slack);
    const std::vector<ImagePolyline> a{square(10, 10, 100)};
    std::vector<ImagePolyline> b;
    if (dropBottom)
        b.push_back({{110 + shift, 10}, {110 + shift, 110}, {10 + shift, 110}, {10 + shift, 10}});
    else
        b.push_back(square(10 + shift, 10, 100));
    const CurveDifference d = compareCurves(a, b, tolerance);
    QCOMPARE(d.lengthA, 400.0);
    QCOMPARE(d.lengthB, dropBottom ? 300.0 : 400.0);
    QVERIFY2(std::abs(d.onlyInALength - onlyInA) <= slack,
             qPrintable(QString("only in A %1 px, expected %2").arg(d.onlyInALength).arg(onlyInA)));
    QVERIFY2(std::abs(d.onlyInBLength - onlyInB) <= slack,
             qPrintable(QString("only in B %1 px, expected %2").arg(d.onlyInBLength).arg(onlyInB)));
    // Every unmatched point is farther than the tolerance from B.
    for (const ImagePolyline& run : d.onlyInA)
        for (const Vec2& p : run)
            QCOMPARE(compareCurves({{p, p}}, b, tolerance).onlyInA.size(), std::size_t(1));
    QCOMPARE(d.onlyInA.empty(), onlyInA == 0.0);
}

void TestCurveComparison::symmetric() {
    const std::vector<ImagePolyline> a{square(0, 0, 50), {{200, 0}, {260, 40}}};
    const std::vector<ImagePolyline> b{square(3, 0, 50, false)};
    const CurveDifference ab = compareCurves(a, b, 1.5);
    const CurveDifference ba = compareCurves(b, a, 1.5);
    QCOMPARE(ab.onlyInALength, ba.onlyInBLength);
    QCOMPARE(ab.onlyInBLength, ba.onlyInALength);
    QCOMPARE(ab.onlyInA.size(), ba.onlyInB.size());
    // The lone segment is entirely in A only.
    QVERIFY(ab.onlyInALength >= std::hypot(60.0, 40.0) - 1e-9);
}

void TestCurveComparison::drawnCurvesOfAViewGraph() {
    auto graph = std::make_shared<ViewGraph>();
    auto chain = [](int qi, bool simplified, double y) {
        ViewChain c;
        c.image = {{0, y}, {10, y}};
        c.points = {{0, y, 0}, {10, y, 0}};
        c.qi = qi;
        c.simplifiedAway = simplified;
        return c;
    };
    graph->chains = {chain(0, false, 0), chain(1, false, 5), chain(0, true, 10),
                     chain(0, false, 15), chain(-1, false, 20)};
    Snapshot s;
    s.viewGraph = graph;
    const std::vector<ImagePolyline> drawn = drawnCurves(s, Camera{});
    QCOMPARE(drawn.size(), std::size_t(2)); // the visible ones only
    QCOMPARE(drawn[0][0].y(), 0.0);
    QCOMPARE(drawn[1][0].y(), 15.0);
}

void TestCurveComparison::realRuns() {
    const auto torus = shape("torus", 24);
    const BoundingBox box = torus->boundingBox();
    const std::vector<Camera> views = protocolViews(box, 0);
    // The mesh method on the same Catmull-Clark limit surface as the
    // consistent method (its default is the cage itself).
    Overrides limit;
    limit.set("surface", std::string("catmull-clark"));
    limit.set("tessellation-level", 2);
    int differing = 0;
    for (std::size_t v = 0; v < views.size(); v += 5) {
        const Snapshot mesh = runMethod("mesh", torus, views[v], limit);
        const Snapshot again = runMethod("mesh", torus, views[v], limit);
        const Snapshot consistent = runMethod("consistent", torus, views[v]);
        const auto m = drawnCurves(mesh, views[v]);
        const auto c = drawnCurves(consistent, views[v]);
        QVERIFY(!m.empty() && !c.empty());
        const CurveDifference same = compareCurves(m, drawnCurves(again, views[v]), 1.0);
        QCOMPARE(same.onlyInALength, 0.0);
        QCOMPARE(same.onlyInBLength, 0.0);
        const CurveDifference d = compareCurves(m, c, 2.0);
        qInfo("view %zu: mesh %.0f px, consistent %.0f px; only mesh %.1f px, only consistent "
              "%.1f px",
              v, d.lengthA, d.lengthB, d.onlyInALength, d.onlyInBLength);
        // Both draw the same silhouette up to the tessellation: most of each
        // side matches, not all of it.
        QVERIFY(d.onlyInALength < 0.5 * d.lengthA);
        QVERIFY(d.onlyInBLength < 0.5 * d.lengthB);
        differing += d.onlyInALength + d.onlyInBLength > 0.0;
    }
    QVERIFY(differing > 0);
}

// The distance along a line 1.5 px above another, capped where the other
// ends: 1.5 px over the shared part, the cap beyond; every vertex and a
// point at least every step measured.
void TestCurveComparison::distanceField() {
    const std::vector<ImagePolyline> a{{{0.0, 0.0}, {20.0, 0.0}}};
    const std::vector<ImagePolyline> b{{{0.0, 1.5}, {10.0, 1.5}}};
    const CurveDistanceField f = distanceAlongCurves(a, b, 5.0, 1.0);
    QCOMPARE(f.points.size(), size_t(1));
    QCOMPARE(f.points[0].size(), size_t(21));
    QCOMPARE(f.count, 21LL);
    for (size_t i = 0; i < f.points[0].size(); ++i) {
        const double x = f.points[0][i].x();
        const double expected = x <= 10.0 ? 1.5 : std::min(5.0, std::hypot(x - 10.0, 1.5));
        QVERIFY2(std::abs(f.distances[0][i] - expected) < 1e-12,
                 qPrintable(QString("x %1: %2").arg(x).arg(f.distances[0][i])));
    }
    QCOMPARE(f.max, 5.0);
    QVERIFY(f.mean > 1.5 && f.mean < 5.0);
    // Nothing on the other side: every point at the cap.
    const CurveDistanceField none = distanceAlongCurves(a, {}, 3.0, 1.0);
    QCOMPARE(none.mean, 3.0);
    QCOMPARE(none.p95, 3.0);
}

// Cusps and T-junctions matched within the tolerance; the rest listed per
// side.
void TestCurveComparison::nodesOnlyOneSideDraws() {
    DrawingNodes a, b;
    a.cusps = {{10.0, 10.0}, {50.0, 50.0}};
    b.cusps = {{11.0, 10.0}, {90.0, 10.0}, {91.0, 10.0}};
    a.tJunctions = {{0.0, 0.0}};
    const NodeDifference d = compareNodes(a, b, 2.0);
    QCOMPARE(d.cuspsOnlyInA, (std::vector<Vec2>{{50.0, 50.0}}));
    QCOMPARE(d.cuspsOnlyInB.size(), size_t(2));
    QCOMPARE(d.tJunctionsOnlyInA.size(), size_t(1));
    QVERIFY(d.tJunctionsOnlyInB.empty());
    const NodeDifference swapped = compareNodes(b, a, 2.0);
    QCOMPARE(swapped.cuspsOnlyInB, d.cuspsOnlyInA);
}

QTEST_GUILESS_MAIN(TestCurveComparison)
#include "test_curve_comparison.moc"
