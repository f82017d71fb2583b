// Comparing two methods in the real main window: the
// Compare-with selector runs a second method on the same mesh and camera;
// the 2D view shows the difference compareCurves gives for the two
// snapshots, re-computed for each phase the window steps to; red and blue
// highlight pixels appear only while a comparison is shown; the other method
// re-runs when the analysis camera changes. Needs a display: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"`.
#include "ImageView2D.h"
#include "MainWindow.h"
#include "MethodComparison.h"
#include "SceneColors.h"
#include "SceneView3D.h"
#include "SurfaceFormat.h"
#include "WindowTestSupport.h"
#include "export/CurveComparison.h"

#include <QApplication>
#include <QComboBox>
#include <QtTest>
#include <cmath>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 300000;

double hueDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// Pixels within 12° of `reference`'s hue, with some saturation (the
// highlights are translucent over white).
long long huePixels(const QImage& image, const SceneColor& reference) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const double hue = reference.toQColor().hsvHueF() * 360.0;
    long long n = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            n += c.hsvSaturationF() >= 0.25 && c.valueF() > 0.3 &&
                 hueDistance(c.hsvHueF() * 360.0, hue) < 12.0;
        }
    return n;
}

} // namespace

class TestMethodComparison : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void differenceShown();
    void followsThePhases();
    void rerunsForANewCamera();
    void powellSabinSideBySide();
    void distanceToTheTracedContour();
    void turnedOff();

private:
    // The window's difference against one computed here from the snapshots.
    void checkShownDifference();
    // Selects `method` as the comparison, waits for it, checks the shown
    // difference and prints the lengths.
    void compareWith(const QString& method, CurveDifference* difference);
    MainWindow* window_ = nullptr;
};

void TestMethodComparison::initTestCase() {
    window_ = new MainWindow;
    const QString error = testing::showAndRunToEnd(
        *window_, QStringLiteral(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj"),
        QStringLiteral("consistent"), {1400, 850}, kIdleTimeoutMs);
    QVERIFY2(error.isEmpty(), qPrintable(error));
}

void TestMethodComparison::cleanupTestCase() {
    delete window_;
}

void TestMethodComparison::checkShownDifference() {
    const MethodComparison* comparison = window_->methodComparison();
    QVERIFY(comparison->result().has_value());
    const Camera camera = *window_->analysisCamera();
    const CurveDifference expected = compareCurves(drawnCurves(window_->currentSnapshot(), camera),
                                                   drawnCurves(*comparison->result(), camera), 2.0);
    const CurveDifference* shown = window_->imageView()->comparison();
    QVERIFY(shown);
    QCOMPARE(shown->lengthA, expected.lengthA);
    QCOMPARE(shown->lengthB, expected.lengthB);
    QCOMPARE(shown->onlyInALength, expected.onlyInALength);
    QCOMPARE(shown->onlyInBLength, expected.onlyInBLength);
    QVERIFY(window_->imageView()->comparisonCaption().contains(
        QString::number(expected.onlyInBLength, 'f', 0)));
}

void TestMethodComparison::compareWith(const QString& method, CurveDifference* difference) {
    QVERIFY(window_->setComparisonMethod(method));
    QCOMPARE(window_->compareSelector()->currentData().toString(), method);
    QVERIFY(window_->methodComparison()->waitForResult(kIdleTimeoutMs));
    QVERIFY2(window_->methodComparison()->error().isEmpty(),
             qPrintable(window_->methodComparison()->error()));
    QVERIFY(window_->imageView()->showsComparison());
    checkShownDifference();
    *difference = *window_->imageView()->comparison();
    qInfo("spot, consistent (%.0f px) against %s (%.0f px): only consistent %.1f px, "
          "only %s %.1f px",
          difference->lengthA, qPrintable(method), difference->lengthB, difference->onlyInALength,
          qPrintable(method), difference->onlyInBLength);
    QVERIFY(difference->lengthA > 0.0 && difference->lengthB > 0.0);
}

void TestMethodComparison::differenceShown() {
    const QImage before = window_->imageView()->grab().toImage();
    QVERIFY(!window_->imageView()->showsComparison());
    // Interpolated contours on the same limit surface: their heuristic
    // visibility draws halos and leaves gaps where the consistent method
    // does not (README, depth-buffer agreement).
    CurveDifference d;
    compareWith(QStringLiteral("interpolated"), &d);
    if (QTest::currentTestFailed())
        return;
    QVERIFY(d.onlyInALength > 20.0 && d.onlyInBLength > 20.0);

    const QImage after = window_->imageView()->grab().toImage();
    after.save(QDir::temp().filePath(QStringLiteral("test_method_comparison_2d.png")));
    // Each highlight is 9 px wide: at least a few pixels per pixel of length
    // (the image is scaled into the widget, so not more than that).
    const long long red = huePixels(after, sceneColors::kComparisonOnlyHere) -
                          huePixels(before, sceneColors::kComparisonOnlyHere);
    const long long blue = huePixels(after, sceneColors::kComparisonOther) -
                           huePixels(before, sceneColors::kComparisonOther);
    qInfo("highlight pixels: red %lld, blue %lld", red, blue);
    QVERIFY(red > static_cast<long long>(d.onlyInALength));
    QVERIFY(blue > static_cast<long long>(d.onlyInBLength));
}

void TestMethodComparison::followsThePhases() {
    QVERIFY(window_->imageView()->showsComparison());
    // Back to before any contour: the window's method draws nothing, so all
    // of the other's drawing is its own.
    window_->runToPhase(1);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    checkShownDifference();
    const CurveDifference* early = window_->imageView()->comparison();
    QCOMPARE(early->lengthA, 0.0);
    QVERIFY(early->onlyInBLength > 0.0);
    QCOMPARE(early->onlyInBLength, early->lengthB);
    window_->runToEnd();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    checkShownDifference();
    QVERIFY(window_->imageView()->comparison()->lengthA > 0.0);
}

void TestMethodComparison::rerunsForANewCamera() {
    const auto before = window_->methodComparison()->result();
    QVERIFY(before.has_value());
    window_->sceneView()->orbit(40.0, 15.0);
    window_->setAnalysisCameraFromView();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->methodComparison()->waitForResult(kIdleTimeoutMs));
    const auto after = window_->methodComparison()->result();
    QVERIFY(after.has_value());
    // Same mesh, new camera: the other run's curves moved with it.
    QVERIFY(drawnCurves(*after, *window_->analysisCamera()) !=
            drawnCurves(*before, *window_->analysisCamera()));
    checkShownDifference();
}

void TestMethodComparison::powellSabinSideBySide() {
    // The algebraic contours of the fitted spline (Capouellez et al. 2023)
    // against the consistent ones, on the same camera: both drawings are
    // there and the shown difference is the one of their snapshots.
    CurveDifference d;
    compareWith(QStringLiteral("powell-sabin"), &d);
    if (QTest::currentTestFailed())
        return;
    const Snapshot& other = *window_->methodComparison()->result();
    QCOMPARE(QString::fromStdString(other.phaseName), QStringLiteral("visibility"));
    QVERIFY(other.viewGraph && !other.viewGraph->chains.empty());
    // The spline fits the cage's vertices (§5.3) and the consistent method
    // draws the Catmull-Clark limit surface, which lies inside the cage: the
    // drawings differ by more than 2 px along most of their length (spot:
    // about 80 %), yet each shares some of its length with the other.
    QVERIFY(d.onlyInALength < d.lengthA && d.onlyInBLength < d.lengthB);
}

// Against the traced contour (Summers 2016, the smooth surface's own): the
// distance from the consistent drawing to it along the curves, and the cusps
// and T-junctions only one side draws, as the window computes them.
void TestMethodComparison::distanceToTheTracedContour() {
    CurveDifference d;
    compareWith(QStringLiteral("traced"), &d);
    if (QTest::currentTestFailed())
        return;
    const Camera camera = *window_->analysisCamera();
    const auto here = drawnCurves(window_->currentSnapshot(), camera);
    const auto there = drawnCurves(*window_->methodComparison()->result(), camera);
    const CurveDistanceField expected = distanceAlongCurves(here, there, 20.0, 1.0);
    const CurveDistanceField* shown = window_->imageView()->comparisonDistances();
    QVERIFY(shown);
    QCOMPARE(shown->count, expected.count);
    QCOMPARE(shown->mean, expected.mean);
    QCOMPARE(shown->max, expected.max);
    const NodeDifference* nodes = window_->imageView()->comparisonNodes();
    QVERIFY(nodes);
    const NodeDifference expectedNodes =
        compareNodes(drawnNodes(window_->currentSnapshot(), camera),
                     drawnNodes(*window_->methodComparison()->result(), camera), 4.0);
    QCOMPARE(nodes->a.cusps.size(), expectedNodes.a.cusps.size());
    QCOMPARE(nodes->b.cusps.size(), expectedNodes.b.cusps.size());
    QCOMPARE(nodes->cuspsOnlyInA.size(), expectedNodes.cuspsOnlyInA.size());
    QCOMPARE(nodes->a.curves, expectedNodes.a.curves);
    qInfo("spot, consistent against traced: distance mean %.3f, 95 %% %.3f, max %.3f px over "
          "%lld points; curves %d vs %d; cusps %zu vs %zu (%zu, %zu unmatched); T %zu vs %zu",
          shown->mean, shown->p95, shown->max, shown->count, nodes->a.curves, nodes->b.curves,
          nodes->a.cusps.size(), nodes->b.cusps.size(), nodes->cuspsOnlyInA.size(),
          nodes->cuspsOnlyInB.size(), nodes->a.tJunctions.size(), nodes->b.tJunctions.size());
    // Both draw the smooth surface's contour: within a pixel on average.
    QVERIFY(shown->mean < 1.0);
    QVERIFY(nodes->a.cusps.size() > 0);
    QVERIFY(
        window_->imageView()->comparisonCaption().contains(QStringLiteral("distance to traced")));
}

void TestMethodComparison::turnedOff() {
    QVERIFY(window_->setComparisonMethod(QString()));
    QVERIFY(!window_->imageView()->showsComparison());
    QVERIFY(window_->imageView()->comparisonCaption().isEmpty());
    QVERIFY(!window_->setComparisonMethod(QStringLiteral("no-such-method")));
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestMethodComparison test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_method_comparison.moc"
