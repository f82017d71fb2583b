// Drives the real workbench window: opens samples, steps phases back and
// forth, switches methods, orbits the 3D view and sets the analysis camera
// from it, and checks what the views draw in grabbed images. Needs a display:
// run under `xvfb-run -a -s "-screen 0 1600x1200x24"` (Mesa llvmpipe).
#include "ContourTestSupport.h"
#include "GroundTruthComputation.h"
#include "ImageView2D.h"
#include "MainWindow.h"
#include "MethodPanel.h"
#include "PhaseStepper.h"
#include "SceneColors.h"
#include "SceneView3D.h"
#include "SurfaceFormat.h"
#include "contours/Methods.h"
#include "export/DiagnosticSnapshot.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshWriter.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QToolBar>
#include <QUrl>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <vtkCamera.h>
#include <vtkRenderer.h>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 120000;

// Where grabbed images go, for a person to look at after a run.
QString grabPath(const QString& name) {
    return QDir::temp().filePath(QStringLiteral("test_main_window_%1.png").arg(name));
}

struct ColourCounts {
    long long total = 0;
    long long front = 0;
    long long back = 0;
    long long contour = 0;
    double frontFraction() const { return total ? double(front) / double(total) : 0.0; }
    double backFraction() const { return total ? double(back) / double(total) : 0.0; }
};

double hueDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// Shading scales a face colour, so hue and saturation identify it.
bool matchesHue(const QColor& pixel, const SceneColor& reference) {
    const QColor ref = reference.toQColor();
    const double refHue = ref.hsvHueF() * 360.0;
    if (pixel.hsvSaturationF() < 0.6 * ref.hsvSaturationF() || pixel.valueF() < 0.15)
        return false;
    return hueDistance(pixel.hsvHueF() * 360.0, refHue) < 12.0;
}

ColourCounts countColours(const QImage& image) {
    ColourCounts counts;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            ++counts.total;
            counts.front += matchesHue(c, sceneColors::kFrontFace);
            counts.back += matchesHue(c, sceneColors::kBackFace);
            counts.contour += matchesHue(c, sceneColors::kContour3D);
        }
    return counts;
}

int distinctColours(const QImage& image) {
    QSet<QRgb> colours;
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    for (int y = 0; y < rgb.height(); y += 2)
        for (int x = 0; x < rgb.width(); x += 2)
            colours.insert(rgb.pixel(x, y));
    return static_cast<int>(colours.size());
}

// Dark pixels (curves are black on the white image) inside `area`.
long long darkPixels(const QImage& image, const QRect& area) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    long long n = 0;
    const QRect r = area.intersected(rgb.rect());
    for (int y = r.top(); y <= r.bottom(); ++y)
        for (int x = r.left(); x <= r.right(); ++x) {
            const QRgb p = rgb.pixel(x, y);
            n += qRed(p) < 90 && qGreen(p) < 90 && qBlue(p) < 90;
        }
    return n;
}

QRect deviceRect(const QRectF& r, double ratio) {
    return QRectF(r.topLeft() * ratio, r.size() * ratio).toAlignedRect();
}

// Pixels of the ground truth's teal (hue within 10°, clearly saturated)
// inside `area`.
long long groundTruthPixels(const QImage& image, const QRect& area) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const double hue = sceneColors::kGroundTruth.toQColor().hsvHueF() * 360.0;
    long long n = 0;
    const QRect r = area.intersected(rgb.rect());
    for (int y = r.top(); y <= r.bottom(); ++y)
        for (int x = r.left(); x <= r.right(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            n += c.hsvSaturationF() > 0.35 && hueDistance(c.hsvHueF() * 360.0, hue) < 10.0;
        }
    return n;
}

QMessageBox* openMessageBox(QWidget* window) {
    for (QMessageBox* box : window->findChildren<QMessageBox*>())
        if (box->isVisible())
            return box;
    return nullptr;
}

void closeMessageBoxes(QWidget* window) {
    for (QMessageBox* box : window->findChildren<QMessageBox*>())
        box->close();
    QCoreApplication::processEvents();
}

} // namespace

class TestMainWindow : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void plannedMethodsAreListedDisabled();
    void opensSampleAndRunsToEnd();
    void stepsBackAndForward();
    void stepperCountersMatchSnapshots();
    void stepperMarksBranchRuns();
    void switchesMethod();
    void parameterFormRerunsMethod();
    void smoothSurfaceReplacesWorkingMesh();
    void busyBarShowsPhaseProgress();
    void orbitShowsFrontAndBackFacesAndFrustum();
    void setAnalysisCameraFromView();
    void imageViewShowsCurves();
    void badFileShowsErrorWithoutCrash();
    void dropOpensFile();
    void inwardMeshIsFlippedOnOpen();
    void grabMainWindow();
    void controlCageWireframe();
    void lighterDrawingWhileOrbiting();
    void eitherViewMaximised();
    void rightDockHoldsTogglesAndLegends();
    void decimatedCopyWhileDraggingLargeMesh();
    void groundTruthOverlay();

private:
    QString sample(const QString& name);
    void checkStepperMatchesRunner();

    MainWindow* window_ = nullptr;
    QTemporaryDir tmp_;
};

QString TestMainWindow::sample(const QString& name) {
    const QString path = QStringLiteral(CONTOUR_SOURCE_DIR "/samples/%1.obj").arg(name);
    if (QFileInfo::exists(path))
        return path;
    // Samples not there (a partial checkout): make a procedural shape here;
    // other meshes come back empty and the test using them skips.
    const QString shape = QString(name).replace('_', '-');
    const std::vector<std::string> shapes = proceduralShapeNames();
    if (std::find(shapes.begin(), shapes.end(), shape.toStdString()) == shapes.end())
        return {};
    const QString generated = tmp_.filePath(name + QStringLiteral(".obj"));
    if (!QFileInfo::exists(generated))
        writeObj(makeProceduralShape(shape.toStdString(), 48), generated.toStdString());
    return generated;
}

void TestMainWindow::initTestCase() {
    QVERIFY(tmp_.isValid());
    window_ = new MainWindow;
    window_->resize(1400, 850);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_));
    QVERIFY(!window_->hasMesh());
    QVERIFY(window_->sceneView()->width() > 100);
}

void TestMainWindow::cleanupTestCase() {
    delete window_;
    window_ = nullptr;
}

void TestMainWindow::checkStepperMatchesRunner() {
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    const PhaseStepper* stepper = window_->phaseStepper();
    QCOMPARE(stepper->phaseCount(), runner->phaseCount());
    QCOMPARE(stepper->completedPhases(), runner->completedPhases());
    for (int phase = 0; phase < runner->phaseCount(); ++phase) {
        const auto state = stepper->phaseState(phase);
        const auto counters = stepper->displayedCounters(phase);
        if (phase < runner->completedPhases()) {
            QCOMPARE(state, phase == runner->completedPhases() - 1
                                ? PhaseStepper::PhaseState::Current
                                : PhaseStepper::PhaseState::Done);
            // Every phase that sets a counter shows it (and only those).
            bool setsCounters = false;
            for (const Counter& c : runner->snapshot(phase + 1).counters) {
                const double before = runner->snapshot(phase).counter(c.name, std::nan(""));
                setsCounters |= std::isnan(before) || before != c.value;
            }
            QVERIFY2(counters.empty() != setsCounters,
                     qPrintable(QStringLiteral("phase %1: counters shown %2, set %3")
                                    .arg(phase)
                                    .arg(counters.size())
                                    .arg(setsCounters)));
            QVERIFY(!stepper->displayedTime(phase).isEmpty());
            const Snapshot& after = runner->snapshot(phase + 1);
            for (const auto& [name, value] : counters)
                QCOMPARE(value, after.counter(name.toStdString(), std::nan("")));
            // With the collapsed group of unchanged ones: every counter of
            // the snapshot.
            const auto all = stepper->displayedCounters(phase, true);
            QCOMPARE(all.size(), after.counters.size());
            for (const auto& [name, value] : all)
                QCOMPARE(value, after.counter(name.toStdString(), std::nan("")));
        } else {
            QCOMPARE(state, PhaseStepper::PhaseState::Pending);
            QVERIFY(counters.empty());
            QVERIFY(stepper->displayedTime(phase).isEmpty());
        }
    }
    // The input row lists the mesh counters of the input snapshot.
    for (const auto& [name, value] : stepper->displayedCounters(-1))
        QCOMPARE(value, runner->snapshot(0).counter(name.toStdString(), std::nan("")));
    QCOMPARE(stepper->stepButton()->isEnabled(), !runner->atEnd());
    QCOMPARE(stepper->backButton()->isEnabled(), runner->completedPhases() > 0);
}

void TestMainWindow::plannedMethodsAreListedDisabled() {
    MethodPanel* panel = window_->methodPanel();
    for (const Method& m : contourMethods()) {
        QVERIFY(panel->listsMethod(QString::fromStdString(m.name)));
        QVERIFY(panel->isMethodEnabled(QString::fromStdString(m.name)));
    }
    for (const PlannedMethod& m : plannedMethods()) {
        const QString name = QString::fromStdString(m.name);
        QVERIFY(panel->listsMethod(name));
        QVERIFY(!panel->isMethodEnabled(name));
        QCOMPARE(panel->methodToolTip(name), QString::fromStdString(m.reason));
        QVERIFY(!window_->setMethod(name));
    }
    // Summers 2016's traced curves run.
    QVERIFY(panel->listsMethod(QStringLiteral("traced")));
    QVERIFY(panel->isMethodEnabled(QStringLiteral("traced")));
    QCOMPARE(window_->methodName(), QStringLiteral("mesh"));
}

void TestMainWindow::opensSampleAndRunsToEnd() {
    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->hasMesh());
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    QVERIFY(runner->atEnd());
    QCOMPARE(runner->method().name, std::string("mesh"));
    // The analysis camera is framed on the mesh and the 3D view looks through it.
    QVERIFY(window_->analysisCamera().has_value());
    QVERIFY(window_->sceneView()->viewMatchesAnalysisCamera());
    QVERIFY(!window_->sceneView()->isFrustumVisible());
    const Snapshot snapshot = window_->currentSnapshot();
    QVERIFY(snapshot.curves && !snapshot.curves->empty());
    QVERIFY(window_->sceneView()->showsFacing());
    QCOMPARE(window_->sceneView()->curveCount(), static_cast<int>(snapshot.curves->size()));
    QCOMPARE(window_->imageView()->curveCount(), static_cast<int>(snapshot.curves->size()));
    checkStepperMatchesRunner();
}

void TestMainWindow::stepsBackAndForward() {
    QVERIFY(window_->runner());
    const int phases = window_->runner()->phaseCount();
    QVERIFY(phases >= 2);

    window_->stepBack();
    QCOMPARE(window_->completedPhases(), phases - 1);
    checkStepperMatchesRunner();

    window_->resetPhases();
    QCOMPARE(window_->completedPhases(), 0);
    QVERIFY(!window_->sceneView()->showsFacing()); // the input has no facing yet
    QCOMPARE(window_->sceneView()->curveCount(), 0);
    checkStepperMatchesRunner();

    window_->stepPhase();
    // The phase runs off the GUI thread; stepping is disabled meanwhile.
    QVERIFY(window_->isBusy());
    QVERIFY(!window_->phaseStepper()->stepButton()->isEnabled());
    QVERIFY(!window_->phaseStepper()->runButton()->isEnabled());
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), 1);
    QCOMPARE(window_->currentSnapshot().phaseName, window_->runner()->method().phases[0].name);
    checkStepperMatchesRunner();

    // Faces get their colours once the facing phase has run.
    const int facing = window_->runner()->method().phaseIndex("facing");
    QVERIFY(facing >= 0);
    QCOMPARE(window_->sceneView()->showsFacing(), facing == 0);
    window_->runToPhase(facing + 1);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), facing + 1);
    QVERIFY(window_->sceneView()->showsFacing());
    checkStepperMatchesRunner();
    window_->runToPhase(1);
    QCOMPARE(window_->completedPhases(), 1);

    window_->stepPhase();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), 2);
    checkStepperMatchesRunner();

    window_->stepBack();
    QCOMPARE(window_->completedPhases(), 1);
    checkStepperMatchesRunner();

    window_->runToEnd();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), phases);
    checkStepperMatchesRunner();
}

void TestMainWindow::stepperCountersMatchSnapshots() {
    // The facing phase's counters, as the list shows them.
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    const int phase = runner->method().phaseIndex("facing");
    QVERIFY(phase >= 0 && runner->completedPhases() > phase);
    const auto counters = window_->phaseStepper()->displayedCounters(phase);
    const Snapshot& facing = runner->snapshot(phase + 1);
    bool sawFront = false, sawBack = false;
    for (const auto& [name, value] : counters) {
        QCOMPARE(value, facing.counter(name.toStdString()));
        sawFront |= name == QStringLiteral("front faces");
        sawBack |= name == QStringLiteral("back faces");
    }
    QVERIFY(sawFront && sawBack);
    QCOMPARE(facing.counter(counters::kFrontFaces) + facing.counter(counters::kBackFaces) +
                 facing.counter(counters::kEdgeOnFaces, 0.0),
             static_cast<double>(facing.mesh->faceCount()));
}

// A branch's range in the stepper: each of its phases says which run it
// shows and lists every run judged (pipeline/Branch.h), the phases outside
// the range say nothing of runs.
void TestMainWindow::stepperMarksBranchRuns() {
    Method m;
    m.name = "branching";
    m.parameters = {{"offset", "Offset", "", ParameterType::Int, 0, -10, 10, {}}};
    m.phases = {
        {"start", "", [](const PhaseContext&, Snapshot& s) { s.setCounter("value", 5); }, {}},
        {"adjust",
         "",
         [](const PhaseContext& ctx, Snapshot& s) {
             s.setCounter("value", s.counter("value") + ctx.parameters.getInt("offset"));
         },
         {}},
        {"finish", "", [](const PhaseContext&, Snapshot&) {}, {}},
        {"after", "", [](const PhaseContext&, Snapshot&) {}, {}},
    };
    BranchRule rule;
    rule.name = "toy";
    rule.decideAfter = "finish";
    rule.rerunFrom = "adjust";
    rule.plan = [](const PhaseContext&, const Snapshot&) {
        BranchPlan plan;
        for (int offset : {1, -2, -1})
            plan.variants.push_back({"offset " + std::to_string(offset), {{"offset", offset}}, {}});
        return plan;
    };
    rule.figure = [](const Snapshot& s) {
        return std::optional<double>(s.counter("value"));
    };
    rule.perfect = -100.0;
    rule.report = [](const PhaseContext&, const BranchSummary&, Snapshot&) {
        return std::string("toy branch decided");
    };
    m.branches.push_back(rule);
    auto cage = std::make_shared<PolygonMesh>(makeSphere(1.0, 8));
    Camera camera;
    camera.eye = Vec3(3, 2, 4);
    camera.target = Vec3(0, 0, 0);
    Runner runner(m, makeInputSnapshot(cage), camera, ParameterSet::defaults(m.parameters));
    runner.runToEnd();
    PhaseStepper stepper;
    stepper.setMethod(&m);
    stepper.setSnapshots(runner.snapshots());
    QVERIFY(stepper.displayedRun(0).isEmpty());
    QVERIFY(stepper.displayedRun(3).isEmpty());
    for (int phase : {1, 2}) {
        QCOMPARE(stepper.displayedRun(phase),
                 QStringLiteral("toy: run 2 of 3, adopted (offset -2)"));
        const QStringList runs = stepper.displayedBranchRuns(phase);
        QCOMPARE(runs.size(), 3);
        QVERIFY(runs[0].startsWith(QStringLiteral("run 1: offset 1 — 6")));
        QVERIFY(runs[0].endsWith(QStringLiteral("rejected")));
        QVERIFY(runs[1].endsWith(QStringLiteral("post-conditions kept, adopted")));
        QVERIFY(runs[2].endsWith(QStringLiteral("rejected")));
    }
    // Each phase of the range is inspectable as any phase: its counters.
    bool sawValue = false;
    for (const auto& [name, value] : stepper.displayedCounters(1))
        if (name == QStringLiteral("value")) {
            sawValue = true;
            QCOMPARE(value, 3.0);
        }
    QVERIFY(sawValue);
    QCOMPARE(stepper.displayedNotes(2), QStringList{QStringLiteral("toy branch decided")});
}

void TestMainWindow::switchesMethod() {
    QVERIFY(window_->setMethod(QStringLiteral("interpolated")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->methodName(), QStringLiteral("interpolated"));
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    QCOMPARE(runner->method().name, std::string("interpolated"));
    QVERIFY(runner->atEnd());
    const Snapshot interpolated = window_->currentSnapshot();
    QVERIFY(interpolated.curves && !interpolated.curves->empty());
    for (const Polyline& line : *interpolated.curves)
        if (line.type == CurveType::Contour)
            QCOMPARE(line.source, SegmentSource::Face);
    checkStepperMatchesRunner();
    // The form follows the method: the interpolated method has a choice.
    QVERIFY(qobject_cast<QComboBox*>(
        window_->methodPanel()->editor(QStringLiteral("normal-weighting"))));

    // Step back and forward under this method too.
    window_->stepBack();
    window_->stepBack();
    QCOMPARE(window_->completedPhases(), runner->phaseCount() - 2);
    checkStepperMatchesRunner();
    window_->stepPhase();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    checkStepperMatchesRunner();

    QVERIFY(window_->setMethod(QStringLiteral("mesh")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->runner()->method().name, std::string("mesh"));
    QVERIFY(window_->runner()->atEnd());
    for (const Polyline& line : *window_->currentSnapshot().curves)
        if (line.type == CurveType::Contour)
            QCOMPARE(line.source, SegmentSource::MeshEdge);
    checkStepperMatchesRunner();
}

void TestMainWindow::parameterFormRerunsMethod() {
    // The saddle is open: with boundaries included its boundary is a curve.
    QVERIFY(window_->openMesh(sample(QStringLiteral("saddle"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    const auto countBoundaries = [this] {
        int n = 0;
        for (const Polyline& line : *window_->currentSnapshot().curves)
            n += line.type == CurveType::Boundary;
        return n;
    };
    QVERIFY(window_->runner()->parameters().getBool("include-boundaries"));
    QCOMPARE(countBoundaries(), 1);
    auto* box = qobject_cast<QCheckBox*>(
        window_->methodPanel()->editor(QStringLiteral("include-boundaries")));
    QVERIFY(box);
    QVERIFY(!box->toolTip().isEmpty());
    box->setChecked(false);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(!window_->runner()->parameters().getBool("include-boundaries"));
    QVERIFY(window_->runner()->atEnd());
    QCOMPARE(countBoundaries(), 0);
    box->setChecked(true);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(countBoundaries(), 1);

    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
}

void TestMainWindow::smoothSurfaceReplacesWorkingMesh() {
    // A phase may replace the working mesh (the surface phase tessellates
    // the cage's limit surface); the 3D view follows the snapshot's mesh.
    auto* surface =
        qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    QVERIFY2(surface && surface->findText(QStringLiteral("catmull-clark")) >= 0,
             "the mesh method has no smooth-surface parameter");
    const QString spot = sample(QStringLiteral("spot_control_mesh"));
    QVERIFY2(!spot.isEmpty(), "samples/spot_control_mesh.obj is missing");
    QVERIFY(window_->openMesh(spot));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    const long long cageTriangles = window_->currentSnapshot().mesh->faceCount();
    QCOMPARE(window_->sceneView()->displayedFaceCount(), cageTriangles);
    surface = qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    surface->setCurrentText(QStringLiteral("catmull-clark"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QVERIFY(window_->runner()->atEnd());
    QCOMPARE(window_->runner()->parameters().getChoice("surface"), std::string("catmull-clark"));
    const Snapshot smooth = window_->currentSnapshot();
    QVERIFY(smooth.mesh->faceCount() > cageTriangles);
    QCOMPARE(window_->sceneView()->displayedFaceCount(),
             static_cast<long long>(smooth.mesh->faceCount()));
    QVERIFY(window_->sceneView()->showsFacing());
    QVERIFY(!smooth.curves->empty());
    checkStepperMatchesRunner();
    // Back to the input: the cage's triangulation again.
    window_->resetPhases();
    QCOMPARE(window_->sceneView()->displayedFaceCount(), cageTriangles);
    window_->runToEnd();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    window_->sceneView()->grabImage().save(grabPath(QStringLiteral("3d_spot_smooth")));
    surface->setCurrentText(QStringLiteral("none"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));

    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
}

void TestMainWindow::busyBarShowsPhaseProgress() {
    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QProgressBar* bar = window_->busyBar();
    QVERIFY(bar);
    QVERIFY(!bar->isVisible());
    // What the bar shows at each progress report (the window's own slot runs
    // first: it was connected first).
    struct Seen {
        int phase;
        double fraction;
        int maximum;
        int value;
        QString text;
        bool visible;
    };
    std::vector<Seen> seen;
    const QMetaObject::Connection connection =
        connect(window_->runController(), &RunController::progress, window_,
                [&](int phase, double fraction) {
                    seen.push_back({phase, fraction, bar->maximum(), bar->value(), bar->text(),
                                    bar->isVisible()});
                });
    // The surface phase reports half way once the limit surface is built.
    auto* surface =
        qobject_cast<QComboBox*>(window_->methodPanel()->editor(QStringLiteral("surface")));
    QVERIFY(surface);
    surface->setCurrentText(QStringLiteral("catmull-clark"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    disconnect(connection);
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    const Method* method = findMethod(window_->methodName().toStdString());
    QVERIFY(method);
    const int surfacePhase = method->phaseIndex("surface");
    QVERIFY(surfacePhase >= 0);
    bool sawFraction = false;
    for (const Seen& s : seen) {
        QVERIFY(s.visible);
        if (s.fraction == 0.0) {
            QCOMPARE(s.maximum, 0); // entering a phase: busy, no fraction yet
            continue;
        }
        QCOMPARE(s.phase, surfacePhase);
        QCOMPARE(s.maximum, MainWindow::kBusyBarSteps);
        QCOMPARE(s.value, static_cast<int>(std::lround(s.fraction * MainWindow::kBusyBarSteps)));
        QVERIFY2(s.text.contains(QStringLiteral("surface")), qPrintable(s.text));
        QVERIFY2(s.text.contains(QStringLiteral("%1%").arg(std::lround(s.fraction * 100))),
                 qPrintable(s.text));
        sawFraction = true;
    }
    QVERIFY(sawFraction);
    QCOMPARE(seen.front().phase, 0);
    // Idle again: hidden, and busy without a fraction for the next job.
    QVERIFY(!bar->isVisible());
    QCOMPARE(bar->maximum(), 0);
    surface->setCurrentText(QStringLiteral("none"));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
}

void TestMainWindow::orbitShowsFrontAndBackFacesAndFrustum() {
    SceneView3D* view = window_->sceneView();
    QVERIFY(view->viewMatchesAnalysisCamera());
    const QImage before = view->grabImage();
    QVERIFY(!before.isNull());
    before.save(grabPath(QStringLiteral("3d_analysis_view")));
    const ColourCounts seenFromCamera = countColours(before);
    QVERIFY2(seenFromCamera.frontFraction() > 0.05,
             qPrintable(QString::number(seenFromCamera.frontFraction())));

    // Orbit by dragging with the left button (trackball camera).
    const Camera viewBefore = view->viewCamera();
    const QPoint start(view->width() / 4, view->height() / 2);
    QTest::mousePress(view, Qt::LeftButton, {}, start);
    for (int i = 1; i <= 10; ++i)
        QTest::mouseMove(view, start + QPoint(i * view->width() / 20, i * view->height() / 40));
    QTest::mouseRelease(view, Qt::LeftButton, {},
                        start + QPoint(view->width() / 2, view->height() / 4));
    const Camera viewAfter = view->viewCamera();
    QVERIFY2((viewAfter.eye - viewBefore.eye).norm() >
                 1e-3 * (viewBefore.eye - viewBefore.target).norm(),
             "dragging in the 3D view did not move its camera");
    QVERIFY(!view->viewMatchesAnalysisCamera());
    QVERIFY(view->isFrustumVisible());
    // The analysis camera did not move.
    QVERIFY((window_->runner()->camera().eye - viewBefore.eye).norm() < 1e-9);

    // Look from the side, where the analysis camera's back faces show.
    view->orbit(70.0, 20.0);
    const QImage image = view->grabImage();
    QVERIFY(!image.isNull());
    QVERIFY(image.save(grabPath(QStringLiteral("3d_orbited"))));
    QVERIFY2(distinctColours(image) > 50, "the 3D view looks blank");
    const ColourCounts counts = countColours(image);
    qInfo("orbited 3D view: front %.3f, back %.3f, contour pixels %lld of %lld",
          counts.frontFraction(), counts.backFraction(), counts.contour, counts.total);
    QVERIFY2(counts.frontFraction() > 0.02, qPrintable(QString::number(counts.frontFraction())));
    QVERIFY2(counts.backFraction() > 0.02, qPrintable(QString::number(counts.backFraction())));
    QVERIFY2(counts.contour > 200, "no contour pixels in the 3D view");
}

void TestMainWindow::setAnalysisCameraFromView() {
    SceneView3D* view = window_->sceneView();
    QVERIFY(view->isFrustumVisible());
    const Camera oldCamera = window_->runner()->camera();
    const int reached = window_->runner()->completedPhases();
    const Camera viewCamera = view->viewCamera();

    window_->setAnalysisCameraFromView();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    const Runner* runner = window_->runner();
    QVERIFY(runner);
    QVERIFY((runner->camera().eye - viewCamera.eye).norm() < 1e-9);
    QVERIFY((runner->camera().eye - oldCamera.eye).norm() > 1e-3);
    QCOMPARE(runner->completedPhases(), reached);
    QVERIFY(view->viewMatchesAnalysisCamera());
    QVERIFY(!view->isFrustumVisible());
    QVERIFY(window_->imageView()->camera().has_value());
    QVERIFY((window_->imageView()->camera()->eye - viewCamera.eye).norm() < 1e-9);
    checkStepperMatchesRunner();

    // Seen through the analysis camera, a closed surface shows its front.
    const QImage image = view->grabImage();
    image.save(grabPath(QStringLiteral("3d_new_analysis_view")));
    const ColourCounts counts = countColours(image);
    QVERIFY2(counts.frontFraction() > 0.05, qPrintable(QString::number(counts.frontFraction())));
    QVERIFY2(counts.backFraction() < 0.05 * counts.frontFraction(),
             qPrintable(QStringLiteral("back %1 front %2")
                            .arg(counts.backFraction())
                            .arg(counts.frontFraction())));

    // Orbiting again shows the frustum again; looking through the analysis
    // camera hides it.
    view->orbit(-30.0, 0.0);
    QVERIFY(view->isFrustumVisible());
    window_->resetViewToAnalysisCamera();
    QVERIFY(!view->isFrustumVisible());
}

void TestMainWindow::imageViewShowsCurves() {
    ImageView2D* view = window_->imageView();
    QVERIFY(view->curveCount() > 0);
    const QImage image = view->grab().toImage();
    QVERIFY(image.save(grabPath(QStringLiteral("2d"))));
    const double ratio = image.devicePixelRatio();
    const QRectF frame = view->imageRect();
    QVERIFY(frame.width() > 50 && frame.height() > 50);
    // Aspect ratio of the analysis camera's image is kept.
    const Viewport viewport = view->camera()->viewport;
    QVERIFY(std::abs(frame.width() / frame.height() - viewport.aspect()) <
            0.02 * viewport.aspect());
    const QRect inside =
        QRectF(frame.topLeft() * ratio, frame.size() * ratio).toRect().adjusted(3, 3, -3, -3);
    const long long dark = darkPixels(image, inside);
    QVERIFY2(dark > 300, qPrintable(QStringLiteral("%1 curve pixels").arg(dark)));
}

void TestMainWindow::badFileShowsErrorWithoutCrash() {
    const QString previous = window_->meshPath();
    const QString bad = QStringLiteral(CONTOUR_SOURCE_DIR "/tests/data/bad/garbage.obj");
    const QString badPath =
        QFileInfo::exists(bad) ? bad : tmp_.filePath(QStringLiteral("garbage.obj"));
    if (!QFileInfo::exists(badPath)) {
        QFile f(badPath);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("this is not an obj file\nv 1 2\nf 1 2 3 4 5\n");
    }
    QVERIFY(!window_->openMesh(badPath));
    QVERIFY(window_->lastError().contains(QFileInfo(badPath).fileName()));
    QVERIFY(openMessageBox(window_));
    closeMessageBoxes(window_);
    // The previous mesh and its run are untouched.
    QCOMPARE(window_->meshPath(), previous);
    QVERIFY(window_->runner() && window_->runner()->atEnd());

    QVERIFY(!window_->openMesh(tmp_.filePath(QStringLiteral("does-not-exist.obj"))));
    QVERIFY(!window_->lastError().isEmpty());
    closeMessageBoxes(window_);
    QVERIFY(window_->hasMesh());
}

void TestMainWindow::dropOpensFile() {
    const QString path = sample(QStringLiteral("sphere"));
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(path)});
    const QPoint centre = window_->rect().center();
    QDragEnterEvent enter(centre, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(window_, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(centre, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(window_, &drop);
    QTRY_COMPARE(window_->meshPath(), path);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->runner()->atEnd());
    QVERIFY(!window_->currentSnapshot().curves->empty());
}

// A sphere whose faces are all oriented inward: opening it flips it (the
// status bar and the input's note say so) and its contour is visible; File ›
// Keep file orientation reloads it as the file has it, contours hidden.
void TestMainWindow::inwardMeshIsFlippedOnOpen() {
    const PolygonMesh sphere = makeSphere(1.0, 24);
    const PolygonMesh inward = testing::reversedFaces(sphere);
    const QString path = tmp_.filePath(QStringLiteral("inward_sphere.obj"));
    writeObj(inward, path.toStdString());
    const auto visibleChains = [this] {
        const Snapshot last = window_->currentSnapshot();
        if (!last.viewGraph)
            return -1;
        int visible = 0;
        for (const ViewChain& chain : last.viewGraph->chains)
            visible += chain.visible();
        return visible;
    };
    QVERIFY(window_->setMethod(QStringLiteral("mesh")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));

    QVERIFY(!window_->keepOrientationAction()->isChecked());
    QVERIFY(window_->openMesh(path));
    const QString flipped = window_->statusBar()->currentMessage();
    QVERIFY2(flipped.startsWith(QStringLiteral(
                 "inward_sphere.obj: 1 of 1 closed components had inward normals (signed "
                 "volume -")),
             qPrintable(flipped));
    QVERIFY2(
        flipped.contains(QStringLiteral("; flipped (File › Keep file orientation keeps them)")),
        qPrintable(flipped));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->runner() && window_->runner()->atEnd());
    QCOMPARE(window_->statusBar()->currentMessage(), flipped);
    QVERIFY(!window_->meshKeptFileOrientation());
    const Snapshot input = window_->runner()->snapshot(0);
    QVERIFY(input.cage->indices == sphere.indices);
    QCOMPARE(input.notes.size(), size_t(1));
    QCOMPARE(QString::fromStdString(input.notes.front()), flipped);
    QCOMPARE(window_->phaseStepper()->displayedNotes(-1), QStringList{flipped});
    QVERIFY(visibleChains() > 0);

    window_->keepOrientationAction()->trigger();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->meshKeptFileOrientation());
    QCOMPARE(window_->meshPath(), path);
    QVERIFY(window_->runner() && window_->runner()->atEnd());
    QVERIFY(window_->runner()->snapshot(0).cage->indices == inward.indices);
    const QString kept = window_->statusBar()->currentMessage();
    QVERIFY2(kept.contains(QStringLiteral("has inward normals")) &&
                 kept.contains(QStringLiteral("kept as in the file (File › Keep file "
                                              "orientation): its contours will read as hidden")),
             qPrintable(kept));
    QCOMPARE(visibleChains(), 0);

    window_->keepOrientationAction()->trigger();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(!window_->keepOrientationAction()->isChecked());
    QVERIFY(window_->runner()->snapshot(0).cage->indices == sphere.indices);
    QVERIFY(visibleChains() > 0);
}

void TestMainWindow::grabMainWindow() {
    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    window_->sceneView()->orbit(35.0, 15.0);
    QCoreApplication::processEvents();
    const QImage image = window_->grab().toImage();
    QVERIFY(!image.isNull());
    QVERIFY(image.save(grabPath(QStringLiteral("main_window"))));
    const ColourCounts counts = countColours(image);
    QVERIFY(counts.front > 1000);
    QVERIFY(counts.back > 100);
}

// Near-black pixels: the control cage's wireframe (the surface is shaded in
// yellows and blues, the background is a grey gradient).
long long nearBlackPixels(const QImage& image) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    long long n = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x)
            n += QColor::fromRgb(rgb.pixel(x, y)).valueF() < 0.15;
    return n;
}

void TestMainWindow::controlCageWireframe() {
    QVERIFY(window_->openMesh(sample(QStringLiteral("torus"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    SceneView3D* view = window_->sceneView();
    QAction* cage = window_->controlCageAction();
    QVERIFY(cage && cage->isCheckable() && !cage->isChecked());
    QCOMPARE(view->controlCageEdgesShown(), 0LL);
    const QImage off = view->grabImage();
    cage->trigger();
    QVERIFY(view->showsControlCage());
    // Every edge of the cage once: a closed quad mesh has 2 edges per face.
    const Snapshot s = window_->currentSnapshot();
    QVERIFY(s.cage);
    QCOMPARE(view->controlCageEdgesShown(), 2LL * s.cage->faceCount());
    const QImage on = view->grabImage();
    on.save(grabPath(QStringLiteral("control_cage")));
    const long long added = nearBlackPixels(on) - nearBlackPixels(off);
    qInfo("control cage: %lld edges, %lld more near-black pixels", view->controlCageEdgesShown(),
          added);
    QVERIFY(added > 500);
    // Kept across a step.
    window_->stepBack();
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(view->controlCageEdgesShown(), 2LL * s.cage->faceCount());
    cage->trigger();
    QCOMPARE(view->controlCageEdgesShown(), 0LL);
}

void TestMainWindow::lighterDrawingWhileOrbiting() {
    SceneView3D* view = window_->sceneView();
    QVERIFY(!view->motionDrawing());
    // A drag switches it on until the button is released.
    const QPoint start(view->width() / 3, view->height() / 2);
    QTest::mousePress(view, Qt::LeftButton, {}, start);
    QTest::mouseMove(view, start + QPoint(20, 5));
    QVERIFY(view->motionDrawing());
    QTest::mouseRelease(view, Qt::LeftButton, {}, start + QPoint(20, 5));
    QVERIFY(!view->motionDrawing());
    // Thinner contours while on; back to the very same picture when off.
    const QImage before = view->grabImage();
    view->setMotionDrawing(true);
    const QImage moving = view->grabImage();
    view->setMotionDrawing(false);
    const QImage after = view->grabImage();
    const ColourCounts b = countColours(before), m = countColours(moving);
    qInfo("contour pixels: still %lld, while moving %lld", b.contour, m.contour);
    QVERIFY(m.contour < b.contour);
    QVERIFY(after == before);
    // A small mesh is always drawn in full, even while moving.
    QVERIFY(view->hasMesh());
    QVERIFY(window_->currentSnapshot().mesh->faceCount() < SceneView3D::kLevelOfDetailMinFaces);
    view->setMotionDrawing(true);
    QVERIFY(!view->showsLevelOfDetail());
    view->setMotionDrawing(false);
}

void TestMainWindow::eitherViewMaximised() {
    using L = MainWindow::ViewLayout;
    QCOMPARE(window_->viewLayout(), L::Both);
    const int bothWidth = window_->sceneView()->width();
    window_->setViewLayout(L::SceneOnly);
    QCoreApplication::processEvents();
    QVERIFY(window_->sceneView()->isVisible() && !window_->imageView()->isVisible());
    QVERIFY(window_->sceneView()->width() > bothWidth);
    window_->setViewLayout(L::ImageOnly);
    QCoreApplication::processEvents();
    QVERIFY(!window_->sceneView()->isVisible() && window_->imageView()->isVisible());
    QCOMPARE(window_->viewLayout(), L::ImageOnly);
    window_->setViewLayout(L::Both);
    QCoreApplication::processEvents();
    QVERIFY(window_->sceneView()->isVisible() && window_->imageView()->isVisible());
    QCOMPARE(window_->viewLayout(), L::Both);
}

void TestMainWindow::rightDockHoldsTogglesAndLegends() {
    auto* dock = window_->findChild<QDockWidget*>(QStringLiteral("displayDock"));
    auto* inspector = window_->findChild<QDockWidget*>(QStringLiteral("inspectorDock"));
    QVERIFY(dock && inspector);
    QCOMPARE(window_->dockWidgetArea(dock), Qt::RightDockWidgetArea);
    QCOMPARE(window_->dockWidgetArea(inspector), Qt::RightDockWidgetArea);
    QVERIFY(dock->isVisible());
    // The legends live in the dock.
    QVERIFY(dock->isAncestorOf(window_->colorLegend()));
    QVERIFY(dock->isAncestorOf(window_->viewGraphLegend()));
    // Every overlay and view-graph toggle and the cage, the very actions of
    // the tool bars and menus.
    auto* toggles = dock->findChild<QToolBar*>(QStringLiteral("displayDockToggles"));
    QVERIFY(toggles);
    const QList<QAction*> actions = toggles->actions();
    for (int i = 0; i < kSceneOverlayCount; ++i)
        QVERIFY(actions.contains(window_->overlayAction(static_cast<SceneOverlay>(i))));
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        QVERIFY(actions.contains(
            window_->viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i))));
    QVERIFY(actions.contains(window_->controlCageAction()));
    QVERIFY(actions.contains(window_->groundTruthAction()));
    // The facing legend is filled for the torus's front/back colouring.
    QVERIFY(window_->colorLegend()->text().contains(QStringLiteral("front")));
}

// On a mesh above SceneView3D::kLevelOfDetailMinFaces faces a drag draws the
// decimated copy, coloured like the faces it stands for; the release brings
// back the full mesh: the very same pixels as before the drag.
void TestMainWindow::decimatedCopyWhileDraggingLargeMesh() {
    const QString path = tmp_.filePath(QStringLiteral("large_torus.obj"));
    writeObj(makeProceduralShapeWithFaces("torus", 80000), path.toStdString());
    QVERIFY(window_->openMesh(path));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    SceneView3D* view = window_->sceneView();
    const Snapshot s = window_->currentSnapshot();
    QVERIFY(s.mesh);
    const long long faces = s.mesh->faceCount();
    QVERIFY2(faces >= SceneView3D::kLevelOfDetailMinFaces, qPrintable(QString::number(faces)));
    QVERIFY(view->showsFacing());
    // Built on a worker thread once the snapshot has been shown.
    QTRY_VERIFY_WITH_TIMEOUT(view->levelOfDetailReady(), 120000);
    const long long copyFaces = view->levelOfDetailFaceCount();
    qInfo("decimated copy: %lld of %lld faces, built in %.2f s", copyFaces, faces,
          view->levelOfDetailSeconds());
    QVERIFY(copyFaces > SceneView3D::kLevelOfDetailFaces / 2);
    QVERIFY(copyFaces <= SceneView3D::kLevelOfDetailFaces + SceneView3D::kLevelOfDetailFaces / 20);
    QVERIFY(!view->showsLevelOfDetail());
    QCOMPARE(view->displayedFaceCount(), faces);

    // Sideways to the analysis camera, so that back faces are in sight.
    view->orbit(100.0, 20.0);
    vtkCamera* camera = view->renderer()->GetActiveCamera();
    double position[3], focal[3], up[3];
    camera->GetPosition(position);
    camera->GetFocalPoint(focal);
    camera->GetViewUp(up);
    const QImage before = view->grabImage();

    // A drag from the corner (background: a release there picks nothing).
    const QPoint start(4, 4);
    QTest::mousePress(view, Qt::LeftButton, {}, start);
    QTest::mouseMove(view, start + QPoint(25, 10));
    QVERIFY(view->motionDrawing());
    QVERIFY(view->showsLevelOfDetail());
    QCOMPARE(view->displayedFaceCount(), copyFaces);
    const QImage moving = view->grabImage();
    moving.save(grabPath(QStringLiteral("decimated_copy")));
    // The same moment drawn with the full mesh: another picture, with the
    // same meaning (front and back in about the same proportions).
    view->setLevelOfDetail(false);
    QVERIFY(!view->showsLevelOfDetail());
    const QImage movingFull = view->grabImage();
    view->setLevelOfDetail(true);
    QVERIFY(view->showsLevelOfDetail());
    QVERIFY(moving != movingFull);
    const ColourCounts copy = countColours(moving), full = countColours(movingFull);
    qInfo("front/back pixels while moving: copy %.4f/%.4f, full mesh %.4f/%.4f",
          copy.frontFraction(), copy.backFraction(), full.frontFraction(), full.backFraction());
    QVERIFY(full.frontFraction() > 0.05 && full.backFraction() > 0.005);
    QVERIFY(std::abs(copy.frontFraction() - full.frontFraction()) < 0.1 * full.frontFraction());
    QVERIFY(std::abs(copy.backFraction() - full.backFraction()) < 0.2 * full.backFraction());
    QTest::mouseRelease(view, Qt::LeftButton, {}, start + QPoint(25, 10));
    QVERIFY(!view->motionDrawing());
    QVERIFY(!view->showsLevelOfDetail());
    QCOMPARE(view->displayedFaceCount(), faces);

    // Back at the camera of before the drag: the very same pixels.
    camera->SetPosition(position);
    camera->SetFocalPoint(focal);
    camera->SetViewUp(up);
    const QImage after = view->grabImage();
    QVERIFY(after == before);
}

// View › Overlays › Ground-truth contour on the spot sample: disabled for the
// mesh method on the cage; with the consistent method it computes the dense
// ground truth for the analysis camera in the background and both views draw
// exactly what DenseGroundTruth gives for that camera, with its legend entry;
// the exported 2D picture gains teal pixels; a new analysis camera computes
// it again on the cached lattice; unchecking (or a method without a smooth
// surface) clears it.
void TestMainWindow::groundTruthOverlay() {
    QAction* toggle = window_->groundTruthAction();
    QVERIFY(toggle && toggle->isCheckable());
    QVERIFY(!toggle->isChecked());
    QVERIFY(window_->setMethod(QStringLiteral("mesh")));
    QVERIFY(window_->openMesh(sample(QStringLiteral("spot_control_mesh"))));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    // The mesh method on the triangulated cage (surface = none).
    QVERIFY(toggle->isVisible());
    QVERIFY(!toggle->isEnabled());
    QVERIFY2(toggle->toolTip().contains(QStringLiteral("surface = none")),
             qPrintable(toggle->toolTip()));

    QVERIFY(window_->setMethod(QStringLiteral("consistent")));
    QVERIFY(window_->waitForIdle(300000));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QVERIFY(toggle->isEnabled());
    ImageView2D* image = window_->imageView();
    SceneView3D* scene = window_->sceneView();
    QVERIFY(!image->showsGroundTruth() && !scene->hasGroundTruth());
    const QString withoutDir = tmp_.filePath(QStringLiteral("without_ground_truth"));
    QVERIFY(QDir().mkpath(withoutDir));
    QVERIFY2(window_->exportDiagnosticSnapshot(withoutDir), qPrintable(window_->lastError()));

    toggle->setChecked(true);
    GroundTruthComputation* computation = window_->groundTruth();
    QVERIFY(computation->isRunning()); // in the background
    QVERIFY(computation->waitForResult(120000));
    QVERIFY2(computation->error().isEmpty(), qPrintable(computation->error()));
    QVERIFY(computation->result());
    const GroundTruthResult result = *computation->result();
    QVERIFY(!result.samplingReused);
    const Camera camera = *window_->analysisCamera();
    QCOMPARE(computation->request()->camera, camera);

    // The oracle computed here for the same surface, lattice and camera.
    const std::shared_ptr<const PolygonMesh> cage = window_->currentSnapshot().cage;
    QVERIFY(cage);
    const auto surface = cachedSmoothSurface(cage, automaticSurfaceKind(*cage)).surface;
    QCOMPARE(result.samples, GroundTruthComputation::latticeSteps(surface->domain().faceCount()));
    const DenseGroundTruth oracle(surface, {result.samples});
    const GroundTruth truth = oracle.compute(camera);
    // Crossings of sub-pixel loops left out as the consistent method's
    // t-junction-min-loop says (the window asks with the method's value).
    const double minLoop = window_->methodPanel()->parameters().getDouble("t-junction-min-loop");
    QCOMPARE(computation->request()->smallLoopPixels, minLoop);
    const int crossings = imageCrossings(truth, camera, minLoop);
    qInfo("ground truth on spot: N = %d, %zu loops, %zu cusps, %d crossings in %.2f s",
          result.samples, truth.loops.size(), truth.cusps.size(), crossings, result.totalSeconds);
    QVERIFY(!truth.loops.empty());
    QCOMPARE(result.truth->loops.size(), truth.loops.size());
    QCOMPARE(result.truth->cusps.size(), truth.cusps.size());
    QCOMPARE(result.imageCrossings, crossings);
    size_t points = 0, shownPoints = 0;
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        points += truth.loops[l].points.size();
        shownPoints += result.truth->loops[l].points.size();
    }
    QCOMPARE(shownPoints, points);
    // Both views draw all of it.
    QVERIFY(image->showsGroundTruth());
    QCOMPARE(image->groundTruthLoopsDrawn(), static_cast<int>(truth.loops.size()));
    QCOMPARE(image->groundTruthCuspsDrawn(), static_cast<int>(truth.cusps.size()));
    QCOMPARE(scene->groundTruthLoopsShown(), static_cast<long long>(truth.loops.size()));
    QCOMPARE(scene->groundTruthCuspsShown(), static_cast<long long>(truth.cusps.size()));
    QCOMPARE(scene->groundTruthLoopData()->GetNumberOfPoints(), static_cast<vtkIdType>(points));
    const QString legend = QStringLiteral("ground truth: %1 loops, %2 cusps, %3 crossings (N = %4)")
                               .arg(truth.loops.size())
                               .arg(truth.cusps.size())
                               .arg(crossings)
                               .arg(result.samples);
    QCOMPARE(image->groundTruthLegend(), legend);
    QVERIFY2(image->legendTexts().contains(legend), qPrintable(image->legendTexts().join('|')));
    const QString status = window_->statusBar()->currentMessage();
    QVERIFY2(status.startsWith(QStringLiteral("Ground truth (N = %1").arg(result.samples)) &&
                 status.contains(QStringLiteral(" s ")),
             qPrintable(status));

    // The exported 2D picture: teal lines only with the overlay.
    const QString withDir = tmp_.filePath(QStringLiteral("with_ground_truth"));
    QVERIFY(QDir().mkpath(withDir));
    QVERIFY2(window_->exportDiagnosticSnapshot(withDir), qPrintable(window_->lastError()));
    const QImage without(QDir(withoutDir).filePath(QString::fromLatin1(snapshotFiles::kPng2d)));
    const QImage with(QDir(withDir).filePath(QString::fromLatin1(snapshotFiles::kPng2d)));
    QVERIFY(!without.isNull() && !with.isNull());
    QCOMPARE(with.size(), without.size());
    QVERIFY(with != without);
    with.save(grabPath(QStringLiteral("ground_truth_2d")));
    // The file keeps the device pixels, not their ratio.
    const QRect frame =
        deviceRect(image->imageRect(), static_cast<double>(with.width()) / image->width());
    const long long tealWith = groundTruthPixels(with, frame);
    const long long tealWithout = groundTruthPixels(without, frame);
    qInfo("teal pixels in the 2D image: %lld with the ground truth, %lld without", tealWith,
          tealWithout);
    QVERIFY(tealWith > 200);
    QVERIFY(tealWithout < tealWith / 20);

    // A new analysis camera: computed again, on the lattice sampled before.
    scene->orbit(40.0, 15.0);
    window_->setAnalysisCameraFromView();
    QVERIFY(!image->showsGroundTruth()); // the old one does not fit the new camera
    QVERIFY(window_->waitForIdle(300000));
    QVERIFY(computation->waitForResult(120000));
    QVERIFY(computation->result());
    QCOMPARE(computation->request()->camera, *window_->analysisCamera());
    QVERIFY(computation->result()->samplingReused);
    const GroundTruth turned = oracle.compute(*window_->analysisCamera());
    QCOMPARE(image->groundTruthLoopsDrawn(), static_cast<int>(turned.loops.size()));
    QCOMPARE(image->groundTruthCuspsDrawn(), static_cast<int>(turned.cusps.size()));
    QCOMPARE(scene->groundTruthLoopsShown(), static_cast<long long>(turned.loops.size()));

    // Off: both views drop it, and so does the legend.
    toggle->setChecked(false);
    QVERIFY(!computation->result() && !computation->isRunning());
    QVERIFY(!image->showsGroundTruth() && !scene->hasGroundTruth());
    QCOMPARE(image->groundTruthLoopsDrawn(), 0);
    QCOMPARE(scene->groundTruthLoopsShown(), 0LL);
    QVERIFY(image->groundTruthLegend().isEmpty());
    for (const QString& text : image->legendTexts())
        QVERIFY2(!text.startsWith(QStringLiteral("ground truth")), qPrintable(text));
    const QImage off = image->grab().toImage();
    QVERIFY(groundTruthPixels(off, deviceRect(image->imageRect(), off.devicePixelRatio())) <
            tealWith / 20);

    // On again, then a method on the cage: disabled and cleared.
    toggle->setChecked(true);
    QVERIFY(computation->waitForResult(120000));
    QVERIFY(image->showsGroundTruth());
    QVERIFY(window_->setMethod(QStringLiteral("mesh")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(!toggle->isEnabled());
    QVERIFY(!computation->request());
    QVERIFY(!image->showsGroundTruth() && !scene->hasGroundTruth());
    toggle->setChecked(false);
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestMainWindow test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_main_window.moc"
