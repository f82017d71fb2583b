// Exact predicates: sign conventions, and exactness where plain doubles fail.
#include "camera/Facing.h"
#include "core/Predicates.h"

#include <QtTest>
#include <cmath>

using namespace contour;

class TestPredicates : public QObject {
    Q_OBJECT
private slots:
    void frontFacingSigns() {
        const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0); // normal +z
        QCOMPARE(frontSide(a, b, c, Vec3(0.2, 0.2, 1)), 1);
        QCOMPARE(frontSide(a, b, c, Vec3(0.2, 0.2, -1)), -1);
        QCOMPARE(frontSide(a, b, c, Vec3(5, -3, 0)), 0);
        // Swapping two corners flips the orientation.
        QCOMPARE(frontSide(b, a, c, Vec3(0.2, 0.2, 1)), -1);
        QCOMPARE(frontSide(a, b, c, Vec3(0, 0, 1e-300)), 1);
    }

    // Shewchuk's classic: points a few ulps off the line y = x. Naive
    // floating-point orientation gets some of these wrong; the exact
    // predicate must give sign(j - i) for every one.
    void orientation2dIsExact() {
        const double ulp = std::ldexp(1.0, -53);
        int naiveWrong = 0;
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j) {
                const Vec2 p(0.5 + i * ulp, 0.5 + j * ulp), q(12, 12), r(24, 24);
                const int expected = (j > i) - (j < i);
                QCOMPARE(orientation2d(q, r, p), expected);
                const double naive =
                    (r.x() - q.x()) * (p.y() - q.y()) - (r.y() - q.y()) * (p.x() - q.x());
                naiveWrong += ((naive > 0) - (naive < 0)) != expected;
            }
        // The test is only meaningful if plain doubles really fail here.
        QVERIFY(naiveWrong > 0);
    }

    // Perspective facing: orient3d against the eye, a few ulps off the plane.
    void frontSideIsExact() {
        const double ulp = std::ldexp(1.0, -52);
        const Vec3 a(0.1, 0.2, 0.3), b(1.1, 0.2, 0.3), c(0.1, 1.2, 0.3); // plane z = 0.3
        for (int k = -8; k <= 8; ++k) {
            const Vec3 d(7.3, -2.9, 0.3 + k * ulp * 0.3);
            QCOMPARE(frontSide(a, b, c, d), (k > 0) - (k < 0));
        }
    }

    // Orthographic facing: det[b - a, c - a, direction] with the direction a
    // few ulps from the plane; the filter must hand these to the exact path.
    void frontSideOfDirectionIsExact() {
        const Vec3 a(0, 0, 0), b(0, 1, 0), c(1, 0, 1); // normal (1, 0, -1)
        const double ulp = std::ldexp(1.0, -52);
        for (int k = -8; k <= 8; ++k) {
            const Vec3 d(1.0 + k * ulp, 0.0, 1.0);
            QCOMPARE(frontSideOfDirection(a, b, c, d), (k > 0) - (k < 0));
        }
        QCOMPARE(frontSideOfDirection(a, b, c, Vec3(1, 0, 0)), 1);
        QCOMPARE(frontSideOfDirection(a, b, c, Vec3(0, 0, 1)), -1);
    }

    void collinearIsExact() {
        QVERIFY(collinear(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3)));
        QVERIFY(!collinear(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3 + std::ldexp(1.0, -50))));
    }

    // Notes, errata 1: for a unit sphere with outward normals and the camera
    // outside, the hemisphere nearer the camera is front-facing (g > 0).
    void facingConvention_data() {
        QTest::addColumn<bool>("orthographic");
        QTest::newRow("perspective") << false;
        QTest::newRow("orthographic") << true;
    }
    void facingConvention() {
        QFETCH(bool, orthographic);
        Camera camera;
        camera.eye = Vec3(0, 0, 10);
        camera.target = Vec3::Zero();
        camera.projection = orthographic ? Projection::Orthographic : Projection::Perspective;
        const Vec3 nearPoint(0, 0, 1), farPoint(0, 0, -1);
        QVERIFY(facingFunction(camera, nearPoint, nearPoint) > 0);
        QVERIFY(facingFunction(camera, farPoint, farPoint) < 0);
        // A small triangle on the near side, counter-clockwise seen from outside.
        const Vec3 a(0, 0, 1), b(0.1, 0, 1), c(0, 0.1, 1);
        QCOMPARE(triangleFacing(camera, a, b, c), Facing::Front);
        QCOMPARE(triangleFacing(camera, a, c, b), Facing::Back);
        // Edge-on: the camera in the triangle's plane.
        const Vec3 p(0, 0, 0), q(0, 0, 1), r(1, 0, 0); // plane y = 0, camera at y = 0
        QCOMPARE(triangleFacing(camera, p, q, r), Facing::EdgeOn);
    }
};

QTEST_APPLESS_MAIN(TestPredicates)
#include "test_predicates.moc"
