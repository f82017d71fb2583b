// The workbench on the Powell-Sabin method (Capouellez et al. 2023 §5): the
// real window steps every phase on the sphere sample; the parameter-domain
// view appears with the layout and draws as many uv triangles, cut-edge
// sides and cone images as the snapshot's fields hold (its image has the
// cut's red and the distortion's colours); the Cones and Patch boundaries
// overlays of the 3D view are there exactly when their fields are; a new
// analysis camera re-runs the fit only (the preprocessing comes from the
// cache). On spot at patch-contours, a click on a face of the spline shows
// its patch in the inspector (describePatch's rows, with the segments'
// conic case), and at visibility a chain's rows name the patches it
// crosses. Needs a display: run under `xvfb-run -a -s "-screen 0 1600x1200x24"`.
#include "ImageView2D.h"
#include "Inspector.h"
#include "MainWindow.h"
#include "ParameterDomainView.h"
#include "SceneView3D.h"
#include "SelectionController.h"
#include "SurfaceFormat.h"
#include "contours/powell_sabin/PatchDescription.h"
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
        ParameterDomainView* domain = window_->domainView();
        SceneView3D* scene = window_->sceneView();
        QVERIFY(domain && domain->isVisible());
        // Back before the layout, the view stays where it is for this
        // method and says it has no layout yet.
        window_->resetPhases();
        QVERIFY(domain->isVisible());
        QCOMPARE(domain->triangleCount(), 0);
        QVERIFY(domain->caption().contains(QStringLiteral("no uv layout")));
        const int phases = window_->runner()->phaseCount();
        QCOMPARE(phases, 10);
        for (int phase = 0; phase < phases; ++phase) {
            window_->stepPhase();
            QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
            QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
            const Snapshot& s = window_->runner()->current();
            QVERIFY2(s.invariantViolations() == 0, s.phaseName.c_str());
            const bool hasLayout = s.field(fields::kCornerUv0) != nullptr;
            QVERIFY(domain->isVisible());
            QCOMPARE(scene->isOverlayAvailable(SceneOverlay::Cones),
                     s.field(fields::kCone) != nullptr);
            QCOMPARE(scene->isOverlayAvailable(SceneOverlay::PatchEdges),
                     s.field(fields::kPatchEdge) != nullptr);
            if (s.field(fields::kCone))
                QCOMPARE(scene->overlayElementCount(SceneOverlay::Cones),
                         countNonZero(s.field(fields::kCone)));
            if (!hasLayout) {
                QCOMPARE(domain->triangleCount(), 0);
                continue;
            }
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

    // A click on a large front face whose patch holds a contour segment
    // (the same path as a user's click: the scene view's picker, then the
    // selection controller and the inspector).
    void clickShowsThePatch() {
        QVERIFY(
            window_->openMesh(QStringLiteral(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY(window_->setMethod(QStringLiteral("powell-sabin")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        window_->resetPhases();
        while (window_->runner()->current().phaseName != "patch-contours" &&
               !window_->runner()->atEnd()) {
            window_->stepPhase();
            QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        }
        QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
        window_->resetViewToAnalysisCamera();
        window_->selectionController()->clear();
        const Snapshot s = window_->currentSnapshot();
        QCOMPARE(QString::fromStdString(s.phaseName), QStringLiteral("patch-contours"));
        const auto* state = powell_sabin::powellSabinState(s);
        QVERIFY(state && state->segments && !state->segments->empty());
        const std::vector<int>* patch = s.field(fields::kPatch)->labels();
        QVERIFY(patch);
        std::vector<char> hasContour(state->spline->patches.size(), 0);
        for (const powell_sabin::ContourSegment& segment : *state->segments)
            hasContour[static_cast<size_t>(segment.patch)] = 1;

        // The candidates, largest on screen first.
        SceneView3D* scene = window_->sceneView();
        const Camera camera = scene->viewCamera();
        const double ratio = scene->devicePixelRatioF();
        std::vector<std::pair<double, Index>> candidates;
        for (Index f = 0; f < s.mesh->faceCount(); ++f) {
            if (!hasContour[static_cast<size_t>((*patch)[static_cast<size_t>(f)])])
                continue;
            std::array<Vec2, 3> q;
            for (int i = 0; i < 3; ++i)
                q[static_cast<size_t>(i)] =
                    camera.project(s.mesh->position(s.mesh->triangle(f)[i])).pixel;
            const Vec2 ab = q[1] - q[0], ac = q[2] - q[0];
            candidates.emplace_back(-std::abs(ab.x() * ac.y() - ab.y() * ac.x()), f);
        }
        std::sort(candidates.begin(), candidates.end());
        Index face = kInvalidIndex;
        QPoint click;
        for (size_t i = 0; i < std::min<size_t>(candidates.size(), 200) && face < 0; ++i) {
            const Index f = candidates[i].second;
            Vec2 c = Vec2::Zero();
            for (int k = 0; k < 3; ++k)
                c += camera.project(s.mesh->position(s.mesh->triangle(f)[k])).pixel / 3.0;
            const QPoint at(static_cast<int>(std::lround(c.x() / ratio)),
                            static_cast<int>(std::lround(c.y() / ratio)));
            if (scene->pick(QPointF(at)) == Selection::face(f)) {
                face = f;
                click = at;
            }
        }
        QVERIFY2(face != kInvalidIndex, "no face of a contour patch to click");
        QTest::mouseClick(scene, Qt::LeftButton, Qt::NoModifier, click);
        QCOMPARE(window_->selectionController()->selection(), Selection::face(face));

        const Inspector* inspector = window_->inspector();
        const Index p = (*patch)[static_cast<size_t>(face)];
        QCOMPARE(inspector->value(QStringLiteral("face")), QString::number(face));
        QCOMPARE(inspector->value(QStringLiteral("patch")), QString::number(p));
        // Every row of describePatch, in order, under the "patch" heading.
        const auto described = powell_sabin::describePatch(*state, p);
        const std::vector<InspectorRow>& rows = inspector->rows();
        const auto heading =
            std::find_if(rows.begin(), rows.end(), [](const InspectorRow& r) { return r.heading; });
        QVERIFY(heading != rows.end());
        QCOMPARE(heading->property, QStringLiteral("patch"));
        QCOMPARE(static_cast<size_t>(rows.end() - heading), described.size());
        for (size_t i = 0; i < described.size(); ++i) {
            QCOMPARE(heading[static_cast<std::ptrdiff_t>(i)].property,
                     QString::fromStdString(described[i].first));
            QCOMPARE(heading[static_cast<std::ptrdiff_t>(i)].value,
                     QString::fromStdString(described[i].second));
        }
        // The conic case is the one of the patch's segments (Table 1).
        QString kind;
        for (const powell_sabin::ContourSegment& segment : *state->segments)
            if (segment.patch == p && kind.isEmpty())
                kind = QString::fromLatin1(toString(segment.kind));
        QVERIFY(inspector->value(QStringLiteral("conic case")).startsWith(kind));
        QVERIFY(!inspector->value(QStringLiteral("contour interval 1")).isEmpty());
        QVERIFY(!inspector->value(QStringLiteral("τ·n: A")).isEmpty());

        // At visibility, a chain's rows name the patches it crosses.
        window_->runToEnd();
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        const Snapshot end = window_->currentSnapshot();
        QVERIFY(end.viewGraph && !end.viewGraph->chains.empty());
        window_->selectionController()->select(Selection::chain(0));
        const QString crossed = inspector->value(QStringLiteral("patches"));
        QCOMPARE(crossed, QString::fromStdString(
                              powell_sabin::describeChainPatches(end.viewGraph->chains[0])));
        QVERIFY2(!crossed.startsWith(QStringLiteral("0 ")), qPrintable(crossed));
    }

    void anotherMethodHidesTheDomainView() {
        QVERIFY(window_->setMethod(QStringLiteral("powell-sabin")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY(window_->domainView()->isVisible());
        QVERIFY(window_->setMethod(QStringLiteral("consistent")));
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
        QVERIFY(window_->domainView()->isHidden());
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
