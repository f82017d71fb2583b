// The workbench on the Powell-Sabin method (Capouellez et al. 2023 §5): the
// real window steps every phase on the sphere sample; the parameter-domain
// view appears with the layout and draws as many uv triangles, cut-edge
// sides and cone images as the snapshot's fields hold (its image has the
// cut's red and the distortion's colours); the Cones and Patch boundaries
// overlays of the 3D view are there exactly when their fields are; a new
// analysis camera re-runs the fit only (the preprocessing comes from the
// cache). Needs a display: run under `xvfb-run -a -s "-screen 0 1600x1200x24"`.
#include "ImageView2D.h"
#include "MainWindow.h"
#include "ParameterDomainView.h"
#include "SceneView3D.h"
#include "SurfaceFormat.h"
#include "pipeline/FieldNames.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QtTest>
#include <algorithm>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 600000;

long long countNonZero(const Field* field) {
    if (!field || !field->labels())
        return 0;
    return std::count_if(field->labels()->begin(), field->labels()->end(),
                         [](int v) { return v != 0; });
}

struct DomainPixels {
    long long total = 0, red = 0, colored = 0;
};
DomainPixels countDomainPixels(const QImage& image) {
    DomainPixels n;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            ++n.total;
            n.red += c.red() >= 180 && c.green() <= 40 && c.blue() <= 40;
            n.colored += c.hsvSaturationF() > 0.15 && !(c.red() >= 180 && c.green() <= 40);
        }
    return n;
}

} // namespace

class TestPowellSabinView : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        window_ = new MainWindow;
        window_->setInteractive(false);
        window_->resize(1500, 850);
        window_->show();
        QVERIFY(QTest::qWaitForWindowExposed(window_));
    }
    void cleanupTestCase() {
        delete window_;
        window_ = nullptr;
    }

    void stepsEveryPhaseWithTheDomainView() {
        QVERIFY(window_->openMesh(QStringLiteral(CONTOUR_SOURCE_DIR "/samples/sphere.obj")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY(window_->setMethod(QStringLiteral("powell-sabin")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
        window_->resetPhases();
        ParameterDomainView* domain = window_->domainView();
        SceneView3D* scene = window_->sceneView();
        QVERIFY(domain && domain->isHidden());
        const int phases = window_->runner()->phaseCount();
        QCOMPARE(phases, 10);
        for (int phase = 0; phase < phases; ++phase) {
            window_->stepPhase();
            QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
            QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
            const Snapshot& s = window_->runner()->current();
            QVERIFY2(s.invariantViolations() == 0, s.phaseName.c_str());
            const bool hasLayout = s.field(fields::kCornerUv0) != nullptr;
            QCOMPARE(domain->isVisible(), hasLayout);
            QCOMPARE(scene->isOverlayAvailable(SceneOverlay::Cones),
                     s.field(fields::kCone) != nullptr);
            QCOMPARE(scene->isOverlayAvailable(SceneOverlay::PatchEdges),
                     s.field(fields::kPatchEdge) != nullptr);
            if (s.field(fields::kCone))
                QCOMPARE(scene->overlayElementCount(SceneOverlay::Cones),
                         countNonZero(s.field(fields::kCone)));
            if (!hasLayout)
                continue;
            QCOMPARE(domain->triangleCount(), static_cast<int>(s.mesh->faceCount()));
            if (s.phaseName == "layout") {
                // Both uv images of every cut edge are drawn.
                QCOMPARE(domain->cutSegmentCount(),
                         static_cast<int>(2 * countNonZero(s.field(fields::kCutEdge))));
                QCOMPARE(domain->colorField(), QString::fromLatin1(fields::kLogAreaRatio));
                QVERIFY(domain->colorLow() < 0.0 && domain->colorHigh() > 0.0);
                // 8 cones; a cone on the cut has several uv images.
                QVERIFY(domain->coneCount() >= 8);
                const QImage image = domain->grab().toImage();
                image.save(QDir::temp().filePath(QStringLiteral("test_powell_sabin_domain.png")));
                const DomainPixels px = countDomainPixels(image);
                QVERIFY2(px.red > 100, qPrintable(QString::number(px.red)));
                QVERIFY2(px.colored > px.total / 20, qPrintable(QString::number(px.colored)));
            }
        }
        // The last phase keeps the fit's surface and fields; its curves are
        // the chained contours, drawn in both views.
        const Snapshot& fit = window_->runner()->current();
        QCOMPARE(QString::fromStdString(fit.phaseName), QStringLiteral("visibility"));
        QVERIFY(window_->imageView()->showsViewGraph());
        QVERIFY(window_->imageView()->curveCount() > 0);
        QCOMPARE(domain->colorField(), QString::fromLatin1(fields::kFitOffset));
        QCOMPARE(scene->overlayElementCount(SceneOverlay::PatchEdges),
                 countNonZero(fit.field(fields::kPatchEdge)));
        window_->overlayAction(SceneOverlay::PatchEdges)->setChecked(false);
        QVERIFY(!scene->isOverlayShown(SceneOverlay::PatchEdges));
        window_->overlayAction(SceneOverlay::PatchEdges)->setChecked(true);
        QVERIFY(scene->isOverlayShown(SceneOverlay::PatchEdges));
        QVERIFY(window_->setColorField(QString::fromLatin1(fields::kFitOffset)));
    }

    void aNewCameraRefitsOnly() {
        Camera camera = window_->runner()->camera();
        camera.eye =
            camera.target + Eigen::AngleAxisd(0.7, Vec3::UnitY()) * (camera.eye - camera.target);
        window_->sceneView()->setViewCamera(camera);
        window_->setAnalysisCameraFromView();
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        const Runner* runner = window_->runner();
        QCOMPARE(runner->completedPhases(), runner->phaseCount());
        for (int i = 1; i < runner->phaseCount(); ++i)
            QVERIFY2(runner->snapshot(i).counter(counters::kPreprocessingCached) == 1.0,
                     runner->snapshot(i).phaseName.c_str());
        QVERIFY(window_->domainView()->isVisible());
    }

private:
    MainWindow* window_ = nullptr;
};

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestPowellSabinView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_powell_sabin_view.moc"
