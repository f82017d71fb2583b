// Crossings that bound a sub-pixel loop (core/SmallLoopCrossings.h): bigons
// of two curves, monogons of one, the threshold, closed curves, one loop per
// crossing; and the oracle's count of projected polylines that leaves them
// out (reference/DenseGroundTruth.h imageCrossings).
#include "core/SmallLoopCrossings.h"
#include "reference/DenseGroundTruth.h"

#include <QtTest>
#include <algorithm>

using namespace contour;

namespace {

int flagged(const std::vector<std::uint8_t>& f) {
    return static_cast<int>(std::count(f.begin(), f.end(), std::uint8_t(1)));
}

// An orthographic camera looking down -z with one pixel per world unit.
Camera pixelCamera() {
    Camera c;
    c.projection = Projection::Orthographic;
    c.eye = Vec3(0, 0, 10);
    c.target = Vec3(0, 0, 0);
    c.up = Vec3(0, 1, 0);
    c.viewport = {200, 200};
    c.orthoHeight = 200.0;
    return c;
}

Polyline line(const std::vector<Vec2>& points, bool closed = false) {
    Polyline p;
    p.type = CurveType::Contour;
    p.closed = closed;
    for (const Vec2& q : points)
        p.points.push_back({Vec3(q.x(), q.y(), 0.0)});
    p.segmentElement.assign(p.segmentCount(), 0);
    return p;
}

} // namespace

class TestSmallLoopCrossings : public QObject {
    Q_OBJECT
private slots:
    void bigonOfTwoCurves() {
        // Two crossings of curves 0 and 1, 0.3 px apart along both.
        const std::vector<CurveCrossing> x = {{0, 10.0, 1, 5.0}, {0, 10.3, 1, 5.3}};
        const std::vector<CurveArc> curves = {{100.0, false}, {50.0, false}};
        QCOMPARE(flagged(smallLoopCrossings(x, curves, 1.0)), 2);
        // The threshold: a loop of 0.3 px is kept below 0.3, and 0 flags none.
        QCOMPARE(flagged(smallLoopCrossings(x, curves, 0.3)), 0);
        QCOMPARE(flagged(smallLoopCrossings(x, curves, 0.0)), 0);
        // Close along one curve only: two real crossings.
        const std::vector<CurveCrossing> apart = {{0, 10.0, 1, 5.0}, {0, 10.3, 1, 25.0}};
        QCOMPARE(flagged(smallLoopCrossings(apart, curves, 1.0)), 0);
        // Different pairs of curves never form a bigon.
        const std::vector<CurveCrossing> pairs = {{0, 10.0, 1, 5.0}, {0, 10.3, 2, 5.3}};
        const std::vector<CurveArc> three = {{100.0, false}, {50.0, false}, {50.0, false}};
        QCOMPARE(flagged(smallLoopCrossings(pairs, three, 1.0)), 0);
    }

    void monogonAroundACusp() {
        const std::vector<CurveArc> curves = {{100.0, false}};
        // A self-crossing 0.8 px of arc apart (around a cusp) and one 30 px
        // apart (a real loop).
        const std::vector<CurveCrossing> x = {{0, 40.0, 0, 40.8}, {0, 60.0, 0, 90.0}};
        const std::vector<std::uint8_t> f = smallLoopCrossings(x, curves, 1.0);
        QCOMPARE(f[0], std::uint8_t(1));
        QCOMPARE(f[1], std::uint8_t(0));
    }

    void closedCurveWrapsAround() {
        // On a closed curve of length 100, arcs 99.8 and 0.2 are 0.4 apart.
        const std::vector<CurveCrossing> x = {{0, 99.8, 1, 3.0}, {0, 0.2, 1, 3.4}};
        QCOMPARE(flagged(smallLoopCrossings(x, std::vector<CurveArc>{{100.0, true}, {10.0, false}},
                                            1.0)),
                 2);
        // Open, the same positions are 99.6 apart.
        QCOMPARE(flagged(smallLoopCrossings(x, std::vector<CurveArc>{{100.0, false}, {10.0, false}},
                                            1.0)),
                 0);
    }

    void eachCrossingInOneLoop() {
        // Three crossings of the same two curves within a pixel: the closest
        // two make a bigon, the third is a crossing.
        const std::vector<CurveCrossing> x = {
            {0, 10.0, 1, 5.0}, {0, 10.1, 1, 5.1}, {0, 10.5, 1, 5.5}};
        const std::vector<std::uint8_t> f =
            smallLoopCrossings(x, std::vector<CurveArc>{{100.0, false}, {50.0, false}}, 1.0);
        QCOMPARE(f[0], std::uint8_t(1));
        QCOMPARE(f[1], std::uint8_t(1));
        QCOMPARE(f[2], std::uint8_t(0));
    }

    // The oracle's count on projected polylines: a straight line crossed by
    // a curve that zig-zags across it within a fraction of a pixel counts
    // once, as the smooth curve it samples crosses it once.
    void polylineCountLeavesOutZigZags() {
        const Camera camera = pixelCamera();
        const Polyline straight = line({{-50, 0}, {50, 0}});
        // Down across y = 0, back up, and down again, 0.2 px apart.
        const Polyline zigzag = line({{0.0, 20}, {0.0, -0.1}, {0.2, 0.1}, {0.4, -0.1}, {0.4, -20}});
        const std::vector<Polyline> curves = {straight, zigzag};
        QCOMPARE(imageCrossings(curves, camera, 0.0), 3);
        QCOMPARE(imageCrossings(curves, camera, 1.0), 1);
        // A curve that crosses the line twice 10 px apart is kept.
        const Polyline arch = line({{-5, 10}, {-5, -10}, {5, -10}, {5, 10}});
        QCOMPARE(imageCrossings(std::vector<Polyline>{straight, arch}, camera, 1.0), 2);
    }
};

QTEST_GUILESS_MAIN(TestSmallLoopCrossings)
#include "test_small_loop_crossings.moc"
