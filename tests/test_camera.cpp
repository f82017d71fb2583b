// Camera: projection round trips, JSON, validation, and the 26-view protocol.
#include "camera/Camera.h"

#include <QTemporaryDir>
#include <QtTest>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

using namespace contour;

namespace {
Camera perspective() {
    Camera c;
    c.eye = Vec3(3, 2, 5);
    c.target = Vec3(0.1, -0.2, 0.3);
    c.up = Vec3(0, 1, 0);
    c.fovYDegrees = 40;
    c.viewport = {640, 480};
    return c;
}
} // namespace

class TestCamera : public QObject {
    Q_OBJECT
private slots:
    void roundTrip_data() {
        QTest::addColumn<bool>("orthographic");
        QTest::newRow("perspective") << false;
        QTest::newRow("orthographic") << true;
    }
    void roundTrip() {
        QFETCH(bool, orthographic);
        Camera c = perspective();
        if (orthographic) {
            c.projection = Projection::Orthographic;
            c.orthoHeight = 3.0;
        }
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-1.5, 1.5);
        for (int i = 0; i < 1000; ++i) {
            const Vec3 p(u(rng), u(rng), u(rng));
            const ProjectedPoint q = c.project(p);
            QVERIFY(q.depth > 0);
            const Vec3 back = c.unproject(q.pixel, q.depth);
            QVERIFY2((back - p).norm() < 1e-12, qPrintable(QString::number((back - p).norm())));
        }
    }

    void targetProjectsToCentreAndAxesPointTheRightWay() {
        const Camera c = perspective();
        const ProjectedPoint t = c.project(c.target);
        QVERIFY(std::abs(t.pixel.x() - 320) < 1e-9);
        QVERIFY(std::abs(t.pixel.y() - 240) < 1e-9);
        QVERIFY(c.project(c.target + 0.1 * c.trueUp()).pixel.y() < 240); // y down in images
        QVERIFY(c.project(c.target + 0.1 * c.right()).pixel.x() > 320);
        QVERIFY(std::abs(t.depth - (c.eye - c.target).norm()) < 1e-12);
    }

    // The vertical field of view maps the frustum's top edge to pixel row 0.
    void fieldOfViewFillsTheViewport() {
        const Camera c = perspective();
        for (const Vec3& corner : c.frustumCorners(2.0)) {
            const Vec2 px = c.project(corner).pixel;
            QVERIFY(std::abs(px.x()) < 1e-9 || std::abs(px.x() - 640) < 1e-9);
            QVERIFY(std::abs(px.y()) < 1e-9 || std::abs(px.y() - 480) < 1e-9);
        }
    }

    void viewVector() {
        Camera c = perspective();
        const Vec3 p(0.5, 0.5, 0.5);
        QVERIFY((c.toCamera(p) - (c.eye - p)).norm() < 1e-15);
        c.projection = Projection::Orthographic;
        QVERIFY((c.toCamera(p) - (c.eye - c.target)).norm() < 1e-15);
        QVERIFY((c.toCamera(Vec3(9, 9, 9)) - c.toCamera(p)).norm() == 0.0);
    }

    void jsonRoundTrip() {
        Camera c = perspective();
        c.projection = Projection::Orthographic;
        c.orthoHeight = 4.5;
        QTemporaryDir dir;
        const std::string path = dir.filePath("camera.json").toStdString();
        c.writeJson(path);
        const Camera d = Camera::readJson(path);
        QCOMPARE(d.toJson().dump(), c.toJson().dump());
        QVERIFY(d.isOrthographic());
        QCOMPARE(d.viewport.width, 640);
    }

    void jsonErrors_data() {
        QTest::addColumn<QString>("json");
        QTest::addColumn<QString>("message");
        QTest::newRow("missing eye") << R"({"target":[0,0,0]})"
                                     << "missing \"eye\"";
        QTest::newRow("short eye") << R"({"eye":[0,0],"target":[0,0,0]})"
                                   << "array of 3 numbers";
        QTest::newRow("projection") << R"({"projection":"fisheye","eye":[0,0,1],"target":[0,0,0]})"
                                    << "\"projection\" must be";
        QTest::newRow("coincident") << R"({"eye":[1,1,1],"target":[1,1,1]})"
                                    << "coincide";
        QTest::newRow("parallel up") << R"({"eye":[0,5,0],"target":[0,0,0],"up":[0,1,0]})"
                                     << "parallel";
        QTest::newRow("fov") << R"({"eye":[0,0,5],"target":[0,0,0],"fov_y_degrees":190})"
                             << "field of view";
        QTest::newRow("viewport")
            << R"({"eye":[0,0,5],"target":[0,0,0],"viewport":{"width":0,"height":5}})"
            << "viewport";
        QTest::newRow("not an object") << "[1,2,3]"
                                       << "JSON object";
    }
    void jsonErrors() {
        QFETCH(QString, json);
        QFETCH(QString, message);
        try {
            Camera::fromJson(nlohmann::json::parse(json.toStdString()));
            QFAIL("accepted a bad camera");
        } catch (const std::runtime_error& e) {
            QVERIFY2(QString(e.what()).contains(message), e.what());
        }
    }

    void views26Protocol() {
        BoundingBox box;
        box.extend(Vec3(-1, -2, -0.5));
        box.extend(Vec3(3, 2, 1.5));
        const auto cams = Camera::views26(box, Viewport{400, 300});
        QCOMPARE(cams.size(), size_t(26));
        std::set<std::tuple<double, double, double>> eyes;
        for (const Camera& c : cams) {
            QVERIFY(c.validate().empty());
            QVERIFY((c.target - box.center()).norm() < 1e-12);
            QVERIFY(std::abs((c.eye - box.center()).norm() - box.diagonal()) < 1e-12);
            QCOMPARE(c.viewport.width, 400);
            eyes.insert({c.eye.x(), c.eye.y(), c.eye.z()});
            // Every corner of the box is in front of the camera and inside the image.
            for (int i = 0; i < 8; ++i) {
                const Vec3 corner((i & 1) ? box.max.x() : box.min.x(),
                                  (i & 2) ? box.max.y() : box.min.y(),
                                  (i & 4) ? box.max.z() : box.min.z());
                const ProjectedPoint q = c.project(corner);
                QVERIFY(q.depth > 0);
                QVERIFY(q.pixel.x() > -1 && q.pixel.x() < 401);
                QVERIFY(q.pixel.y() > -1 && q.pixel.y() < 301);
            }
        }
        QCOMPARE(eyes.size(), size_t(26));
        // View (2, 1, 1) looks from +x: eye = centre + diagonal * (1, 0, 0).
        const Vec3 expected = box.center() + box.diagonal() * Vec3(1, 0, 0);
        bool found = false;
        for (const Camera& c : cams)
            found = found || (c.eye - expected).norm() < 1e-12;
        QVERIFY(found);
    }
};

QTEST_APPLESS_MAIN(TestCamera)
#include "test_camera.moc"
