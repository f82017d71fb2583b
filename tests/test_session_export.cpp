// Sessions and diagnostic snapshots of the real main window. On the spot sample with the consistent
// method stepped phase by phase up to its visibility phase (one parameter changed, display toggles
// changed): File › Export diagnostic snapshot writes exactly its six files,
// each PNG decodes and shows more than the background, the SVG parses and
// holds the view graph's chains, the JSON report has every field (method,
// parameters, camera, per-phase counters and times, every inconsistent face
// with its details), the PLY reloads with the labels of the snapshot; a
// session saved and opened in a second window restores the method, the
// analysis and view cameras, the parameters, the phase, the display and the
// preset the parameters started from (shown modified when they differ) and
// whether the mesh's inward faces were flipped or kept as in the file; an
// export that cannot be written fails naming the file and leaves nothing
// behind (a file kept aside is put back). Needs a display: run under
// `xvfb-run -a` (Mesa llvmpipe).
#include "AboutDialog.h"
#include "ContourTestSupport.h"
#include "ImageView2D.h"
#include "MainWindow.h"
#include "MethodComparison.h"
#include "MethodPanel.h"
#include "SceneView3D.h"
#include "SessionController.h"
#include "SurfaceFormat.h"
#include "contours/Methods.h"
#include "export/DiagnosticSnapshot.h"
#include "export/SessionFile.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "mesh/io/MeshWriter.h"
#include "pipeline/FieldNames.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QImage>
#include <QSet>
#include <QSettings>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QXmlStreamReader>
#include <QtTest>
#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 300000;
const char* const kSample = CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj";

QStringList filesIn(const QString& dir) {
    QStringList names = QDir(dir).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot);
    names.sort();
    return names;
}

nlohmann::json readJson(const QString& path) {
    std::ifstream in(path.toStdString());
    return nlohmann::json::parse(in);
}

// Not blank: several colours, and a real share of pixels unlike the corner
// (background) colour.
void checkNotBlank(const QString& path, int minColours, double minForeground) {
    QImage image;
    QVERIFY2(image.load(path, "PNG"), qPrintable(path));
    QVERIFY(image.width() > 50 && image.height() > 50);
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const QRgb background = rgb.pixel(0, 0);
    QSet<QRgb> colours;
    long long foreground = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QRgb c = rgb.pixel(x, y);
            colours.insert(c);
            foreground += c != background;
        }
    const double share = static_cast<double>(foreground) / (rgb.width() * rgb.height());
    qInfo("%s: %dx%d, %lld colours, %.1f %% not background", qPrintable(QFileInfo(path).fileName()),
          rgb.width(), rgb.height(), static_cast<long long>(colours.size()), 100.0 * share);
    QVERIFY2(colours.size() >= minColours, qPrintable(path));
    QVERIFY2(share >= minForeground, qPrintable(path));
}

void compareCameras(const Camera& a, const Camera& b) {
    QVERIFY(a.projection == b.projection);
    for (int i = 0; i < 3; ++i) {
        QCOMPARE(a.eye[i], b.eye[i]);
        QCOMPARE(a.target[i], b.target[i]);
        QCOMPARE(a.up[i], b.up[i]);
    }
    QCOMPARE(a.fovYDegrees, b.fovYDegrees);
    QCOMPARE(a.orthoHeight, b.orthoHeight);
    QCOMPARE(a.viewport.width, b.viewport.width);
    QCOMPARE(a.viewport.height, b.viewport.height);
}

} // namespace

class TestSessionExport : public QObject {
    Q_OBJECT

private:
    std::unique_ptr<MainWindow> window_;
    QTemporaryDir dir_;

private slots:
    void initTestCase();
    void shortcutsAndAbout();
    void exportSnapshot();
    void exportIllustration();
    void sessionRoundTrip();
    void sessionRestoresThePreset();
    void sessionKeepsTheMeshOrientation();
    void failedExportLeavesNothing();
    void cleanupTestCase();
};

void TestSessionExport::initTestCase() {
    // Settings (recent files, geometry) go to a test location, not the user's.
    QStandardPaths::setTestModeEnabled(true);
    QSettings().clear();
    QVERIFY(dir_.isValid());
    // CONTOUR_KEEP_SNAPSHOT=1 keeps the exported files to look at.
    if (qEnvironmentVariableIsSet("CONTOUR_KEEP_SNAPSHOT")) {
        dir_.setAutoRemove(false);
        qInfo("files kept in %s", qPrintable(dir_.path()));
    }
    window_ = std::make_unique<MainWindow>();
    window_->setInteractive(false);
    window_->sessionController()->setUseSettings(true);
    qInfo("settings: %s", qPrintable(QSettings().fileName()));
    window_->resize(1400, 850);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    QVERIFY(window_->openMesh(QString::fromLatin1(kSample)));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY(window_->setMethod(QStringLiteral("consistent")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    // Step a few phases one by one, then on to the view graph.
    window_->resetPhases();
    for (int i = 0; i < 3; ++i) {
        window_->stepPhase();
        QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    }
    QCOMPARE(window_->completedPhases(), 3);
    const int visibility = window_->runner()->method().phaseIndex("visibility") + 1;
    QVERIFY(visibility > 3);
    window_->runToPhase(visibility);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), visibility);
    // A parameter off its default (the run is redone up to the same phase).
    auto* snap = qobject_cast<QDoubleSpinBox*>(
        window_->methodPanel()->editor(QStringLiteral("snap-fraction")));
    QVERIFY(snap);
    snap->setValue(0.25);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), visibility);
    QCOMPARE(window_->runner()->parameters().getDouble("snap-fraction"), 0.25);
    // Display choices off their defaults.
    window_->overlayAction(SceneOverlay::RadialEdges)
        ->setChecked(!window_->overlayAction(SceneOverlay::RadialEdges)->isChecked());
    window_->viewGraphAction(MainWindow::ViewGraphToggle::Nodes)->setChecked(false);
    QVERIFY(window_->setColorField(QString::fromLatin1(fields::kVbo)));
    QVERIFY(window_->setComparisonMethod(QStringLiteral("mesh")));
    QTest::qWait(200);
}

void TestSessionExport::shortcutsAndAbout() {
    QVERIFY(window_->cancelAction());
    QCOMPARE(window_->cancelAction()->shortcut(), QKeySequence(Qt::Key_Escape));
    QVERIFY(!window_->cancelAction()->isEnabled()); // nothing runs
    // Esc stops a run to the end at once (between or inside phases); the
    // phases finished so far stay.
    const int reached = window_->completedPhases();
    // Shortcuts reach only the active window.
    // Under Xvfb without a window manager, activation can take longer than
    // QTest's default 5 s while the other suite loads both cores.
    window_->raise();
    window_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(window_.get(), 30000));
    window_->resetPhases();
    window_->runToEnd();
    QVERIFY(window_->isBusy() && window_->cancelAction()->isEnabled());
    QTest::keyClick(window_.get(), Qt::Key_Escape);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->completedPhases() < window_->runner()->phaseCount(),
             "the run was not cancelled");
    qInfo("Esc: cancelled after %d of %d phases", window_->completedPhases(),
          window_->runner()->phaseCount());
    window_->runToPhase(reached);
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QCOMPARE(window_->completedPhases(), reached);
    SessionController* sessions = window_->sessionController();
    QCOMPARE(sessions->exportSnapshotAction()->shortcut(), QKeySequence(Qt::CTRL | Qt::Key_E));
    QCOMPARE(sessions->saveSessionAction()->shortcut(), QKeySequence(QKeySequence::Save));
    QVERIFY(sessions->recentFiles().contains(
        QFileInfo(QString::fromLatin1(kSample)).absoluteFilePath()));
    sessions->saveWindowSettings();
    QVERIFY(QSettings().contains(QStringLiteral("window/geometry")));
    QVERIFY(QSettings().contains(QStringLiteral("window/state")));
    const QString versions = libraryVersionsText();
    qInfo("%s", qPrintable(versions));
    for (const char* library : {"Qt ", "VTK ", "CGAL ", "Eigen ", "OpenSubdiv ", "Embree ",
                                "oneTBB ", "nlohmann-json ", "CLI11 "}) {
        const QRegularExpression line(
            QStringLiteral("^%1\\d+\\.\\d+")
                .arg(QRegularExpression::escape(QString::fromLatin1(library))),
            QRegularExpression::MultilineOption);
        QVERIFY2(line.match(versions).hasMatch(), library);
    }
}

void TestSessionExport::exportSnapshot() {
    const QString out = dir_.filePath(QStringLiteral("snapshot"));
    QVERIFY(QDir().mkpath(out));
    QElapsedTimer timer;
    timer.start();
    QVERIFY2(window_->exportDiagnosticSnapshot(out), qPrintable(window_->lastError()));
    qInfo("export: %lld ms", static_cast<long long>(timer.elapsed()));
    // Exactly the six files; no temporary folder left.
    QCOMPARE(filesIn(out), QStringList({"mesh.ply", "report.json", "session.cwsession",
                                        "view-2d.png", "view-2d.svg", "view-3d.png"}));
    checkNotBlank(out + "/view-3d.png", 8, 0.05);
    checkNotBlank(out + "/view-2d.png", 3, 0.002);

    const Runner* runner = window_->runner();
    QVERIFY(runner);
    const Snapshot& current = runner->current();
    QVERIFY(current.viewGraph);

    // SVG: well-formed, one polyline per drawn chain piece at least.
    QFile svg(out + "/view-2d.svg");
    QVERIFY(svg.open(QIODevice::ReadOnly));
    QXmlStreamReader xml(&svg);
    int polylines = 0;
    bool sawSvg = false;
    while (!xml.atEnd()) {
        xml.readNext();
        if (xml.isStartElement()) {
            sawSvg |= xml.name() == QLatin1String("svg");
            polylines += xml.name() == QLatin1String("polyline");
        }
    }
    QVERIFY2(!xml.hasError(), qPrintable(xml.errorString()));
    QVERIFY(sawSvg);
    QVERIFY(polylines >= static_cast<int>(current.viewGraph->chains.size()) / 2);
    QVERIFY(polylines > 0);

    // JSON: every field.
    const nlohmann::json report = readJson(out + "/report.json");
    for (const char* key : {"tool", "mesh", "method", "views", "snapshot"})
        QVERIFY2(report.contains(key), key);
    QCOMPARE(report["method"]["name"].get<std::string>(), std::string("consistent"));
    QCOMPARE(report["snapshot"]["files"].size(), size_t(6));
    for (const ParameterSpec& spec : runner->method().parameters)
        QVERIFY2(report["method"]["parameters"].contains(spec.name), spec.name.c_str());
    QCOMPARE(report["method"]["parameters"]["snap-fraction"].get<double>(), 0.25);
    QCOMPARE(report["views"].size(), size_t(1));
    const nlohmann::json& view = report["views"][0];
    compareCameras(Camera::fromJson(view["camera"]), runner->camera());
    QCOMPARE(view["completed_phases"].get<int>(), runner->completedPhases());
    QCOMPARE(view["phases"].size(), static_cast<size_t>(runner->completedPhases()));
    for (size_t i = 0; i < view["phases"].size(); ++i) {
        const nlohmann::json& phase = view["phases"][i];
        for (const char* key : {"name", "seconds", "counters", "invariants", "notes"})
            QVERIFY2(phase.contains(key), key);
        QCOMPARE(phase["name"].get<std::string>(), runner->method().phases[i].name);
        QCOMPARE(phase["seconds"].get<double>(),
                 runner->snapshot(static_cast<int>(i) + 1).phaseSeconds);
    }
    QVERIFY(view.contains("view_graph"));
    const int inconsistent = static_cast<int>(current.counter(counters::kInconsistentFaces));
    QVERIFY(inconsistent >= 0);
    QCOMPARE(view["inconsistent_faces"].size(), static_cast<size_t>(inconsistent));
    QCOMPARE(view["totals"]["counters"]["inconsistent faces"].get<int>(), inconsistent);
    qInfo("snapshot after %s: %d inconsistent faces, %d polylines", current.phaseName.c_str(),
          inconsistent, polylines);
    for (const nlohmann::json& face : view["inconsistent_faces"]) {
        for (const char* key : {"face", "vertices", "reason", "vbo", "facing", "vertex_labels", "g",
                                "radial_curvature", "positions", "preimages", "provenance",
                                "radial", "standard_radial", "folded", "changed_by_phase",
                                "changed_by_phase_name", "neighbours"})
            QVERIFY2(face.contains(key), key);
        // The reason agrees with the labels: undefined VBO, or VBO against facing.
        const std::string vbo = face["vbo"];
        if (vbo == "undefined")
            QVERIFY(face["reason"].get<std::string>().find("VBO undefined") == 0);
        else
            QVERIFY(face["facing"].get<std::string>() != (vbo == "F" ? "front" : "back"));
    }

    // PLY: the snapshot's mesh and labels.
    PlyLabels labels;
    const PolygonMesh mesh = readMesh((out + "/mesh.ply").toStdString(), &labels);
    QCOMPARE(mesh.faceCount(), current.mesh->faceCount());
    QCOMPARE(mesh.vertexCount(), current.mesh->vertexCount());
    for (const char* name : {fields::kConsistent, fields::kVbo, fields::kFacing, fields::kRadial})
        QVERIFY2(labels.faceLabels.count(name), name);
    for (const char* name : {fields::kLabel, fields::kCusp})
        QVERIFY2(labels.vertexLabels.count(name), name);
    QVERIFY(labels.vertexScalars.count(fields::kG));
    const std::vector<int>& consistent = labels.faceLabels[fields::kConsistent];
    QCOMPARE(static_cast<int>(std::count(consistent.begin(), consistent.end(), 0)), inconsistent);
    QCOMPARE(labels.faceLabels[fields::kVbo], *current.field(fields::kVbo)->labels());

    // The session inside the snapshot.
    const Session session = readSession((out + "/session.cwsession").toStdString());
    QCOMPARE(session.method, std::string("consistent"));
    QCOMPARE(session.phaseReached, runner->completedPhases());
    QCOMPARE(session.phaseName, current.phaseName);
}

// File › Export illustration SVG: the clean drawing of the current phase,
// hidden lines as the 2D view shows them, no node glyphs.
void TestSessionExport::exportIllustration() {
    QAction* action = window_->sessionController()->exportIllustrationAction();
    QVERIFY(action && action->objectName() == QStringLiteral("exportIllustration"));
    const auto groupsOf = [](const QString& path, int* paths) {
        QFile file(path);
        QStringList ids;
        *paths = 0;
        if (!file.open(QIODevice::ReadOnly))
            return ids;
        QXmlStreamReader xml(&file);
        while (!xml.atEnd()) {
            xml.readNext();
            if (xml.isStartElement() && xml.name() == QLatin1String("g"))
                ids << xml.attributes().value(QStringLiteral("id")).toString();
            if (xml.isStartElement() && xml.name() == QLatin1String("path"))
                ++*paths;
            if (xml.isStartElement())
                for (const QXmlStreamAttribute& a : xml.attributes())
                    if (a.name().startsWith(QLatin1String("data-")))
                        ids << QStringLiteral("data attribute");
        }
        if (xml.hasError())
            ids << QStringLiteral("error: ") + xml.errorString();
        return ids;
    };
    QAction* hidden = window_->viewGraphAction(MainWindow::ViewGraphToggle::HiddenCurves);
    const bool wasShown = hidden->isChecked();
    for (const bool show : {true, false}) {
        hidden->setChecked(show);
        const QString path = dir_.filePath(show ? "with-hidden.svg" : "visible-only.svg");
        QVERIFY2(window_->exportIllustrationSvg(path), qPrintable(window_->lastError()));
        int paths = 0;
        const QStringList ids = groupsOf(path, &paths);
        QVERIFY2(ids.contains("visible") && ids.contains("visible-contour"),
                 qPrintable(ids.join(' ')));
        QCOMPARE(ids.contains("hidden"), show);
        QVERIFY(!ids.contains("nodes") && !ids.contains("data attribute"));
        QVERIFY(paths > 0);
        QVERIFY(!ids.join(' ').contains("error"));
    }
    hidden->setChecked(wasShown);
}

void TestSessionExport::sessionRoundTrip() {
    const QString path = dir_.filePath(QStringLiteral("spot.cwsession"));
    // The control cage and the view layout are part of the display too.
    window_->controlCageAction()->setChecked(true);
    window_->setViewLayout(MainWindow::ViewLayout::SceneOnly);
    const bool saved = window_->saveSession(path);
    window_->setViewLayout(MainWindow::ViewLayout::Both);
    window_->controlCageAction()->setChecked(false);
    QVERIFY2(saved, qPrintable(window_->lastError()));
    QVERIFY(
        window_->sessionController()->recentFiles().contains(QFileInfo(path).absoluteFilePath()));

    MainWindow other;
    other.setInteractive(false);
    other.resize(1200, 800);
    other.show();
    QVERIFY(QTest::qWaitForWindowExposed(&other));
    QVERIFY2(other.openFile(path), qPrintable(other.lastError())); // by suffix
    QVERIFY(other.waitForIdle(kIdleTimeoutMs));
    QVERIFY2(other.lastError().isEmpty(), qPrintable(other.lastError()));

    QCOMPARE(other.methodName(), window_->methodName());
    QCOMPARE(QFileInfo(other.meshPath()).canonicalFilePath(),
             QFileInfo(window_->meshPath()).canonicalFilePath());
    compareCameras(*other.analysisCamera(), *window_->analysisCamera());
    compareCameras(other.runner()->camera(), window_->runner()->camera());
    const Camera a = other.sceneView()->viewCamera(), b = window_->sceneView()->viewCamera();
    for (int i = 0; i < 3; ++i) {
        QVERIFY(std::abs(a.eye[i] - b.eye[i]) < 1e-9);
        QVERIFY(std::abs(a.target[i] - b.target[i]) < 1e-9);
    }
    QVERIFY(other.runner()->parameters().values() == window_->runner()->parameters().values());
    QVERIFY(other.methodPanel()->parameters().values() == window_->runner()->parameters().values());
    QCOMPARE(other.completedPhases(), window_->completedPhases());
    QCOMPARE(other.currentSnapshot().phaseName, window_->currentSnapshot().phaseName);
    // The same run: the same mesh and counts.
    QCOMPARE(other.currentSnapshot().mesh->faceCount(),
             window_->currentSnapshot().mesh->faceCount());
    QCOMPARE(other.currentSnapshot().counter(counters::kInconsistentFaces),
             window_->currentSnapshot().counter(counters::kInconsistentFaces));
    for (int i = 0; i < kSceneOverlayCount; ++i)
        QCOMPARE(other.overlayAction(static_cast<SceneOverlay>(i))->isChecked(),
                 window_->overlayAction(static_cast<SceneOverlay>(i))->isChecked());
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        QCOMPARE(
            other.viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i))->isChecked(),
            window_->viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i))->isChecked());
    QVERIFY(other.controlCageAction()->isChecked());
    QVERIFY(other.sceneView()->showsControlCage());
    QVERIFY(other.sceneView()->controlCageEdgesShown() > 0);
    QCOMPARE(other.viewLayout(), MainWindow::ViewLayout::SceneOnly);
    QVERIFY(other.imageView()->isHidden());
    QCOMPARE(other.colorField(), QString::fromLatin1(fields::kVbo));
    QCOMPARE(other.methodComparison()->otherMethod(), QStringLiteral("mesh"));
    QCOMPARE(other.sceneView()->isOverlayEnabled(SceneOverlay::RadialEdges),
             window_->sceneView()->isOverlayEnabled(SceneOverlay::RadialEdges));

    // A damaged session is refused with the file's name; the window keeps its run.
    const QString bad = dir_.filePath(QStringLiteral("bad.cwsession"));
    {
        QFile f(bad);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "contour-workbench-session", "version": 1, "mesh": "x.obj"})");
    }
    QVERIFY(!other.openSession(bad));
    QVERIFY2(other.lastError().contains(QStringLiteral("bad.cwsession")) &&
                 other.lastError().contains(QStringLiteral("method")),
             qPrintable(other.lastError()));
    QCOMPARE(other.completedPhases(), window_->completedPhases());
}

void TestSessionExport::sessionRestoresThePreset() {
    // The window runs the defaults with snap-fraction changed.
    MethodPanel* panel = window_->methodPanel();
    QCOMPARE(panel->presetName(), QStringLiteral("default"));
    QVERIFY(panel->isPresetModified());
    QCOMPARE(panel->presetSelector()->currentText(), QStringLiteral("default (modified)"));
    const QString path = dir_.filePath(QStringLiteral("preset.cwsession"));
    QVERIFY2(window_->saveSession(path), qPrintable(window_->lastError()));
    const nlohmann::json saved = readJson(path);
    QCOMPARE(saved["preset"]["name"].get<std::string>(), std::string("default"));
    QCOMPARE(saved["preset"]["changed"], nlohmann::json({{"snap-fraction", 0.25}}));

    // A session that started from the paper preset with one value changed,
    // at the first phase.
    const Method& method = *findMethod("consistent");
    const ParameterSet paper = presetValues(method.parameters, *method.preset("paper"));
    Session session = readSession(path.toStdString());
    session.parameters = paper;
    session.parameters.set("snap-fraction", 0.3);
    session.phaseReached = 1;
    session.phaseName = method.phases.front().name;
    setSessionPreset(session, method, "paper");
    const QString paperPath = dir_.filePath(QStringLiteral("paper.cwsession"));
    writeSession(paperPath.toStdString(), session);

    MainWindow other;
    other.setInteractive(false);
    other.resize(1200, 800);
    other.show();
    QVERIFY(QTest::qWaitForWindowExposed(&other));
    QVERIFY2(other.openSession(paperPath), qPrintable(other.lastError()));
    QVERIFY(other.waitForIdle(kIdleTimeoutMs));
    MethodPanel* otherPanel = other.methodPanel();
    QCOMPARE(otherPanel->presetName(), QStringLiteral("paper"));
    QVERIFY(otherPanel->isPresetModified());
    QCOMPARE(otherPanel->presetSelector()->currentText(), QStringLiteral("paper (modified)"));
    QCOMPARE(other.runner()->parameters().getDouble("snap-fraction"), 0.3);
    QCOMPARE(other.completedPhases(), 1);

    // Choosing the preset again runs with its values, unmodified.
    QComboBox* presets = otherPanel->presetSelector();
    emit presets->activated(presets->findData(QStringLiteral("paper")));
    QVERIFY(other.waitForIdle(kIdleTimeoutMs));
    QVERIFY2(other.lastError().isEmpty(), qPrintable(other.lastError()));
    QVERIFY(other.runner()->parameters().values() == paper.values());
    QVERIFY(!otherPanel->isPresetModified());
    QCOMPARE(presets->currentText(), QStringLiteral("paper"));
    const QString again = dir_.filePath(QStringLiteral("paper-again.cwsession"));
    QVERIFY2(other.saveSession(again), qPrintable(other.lastError()));
    const nlohmann::json resaved = readJson(again);
    QCOMPARE(resaved["preset"]["name"].get<std::string>(), std::string("paper"));
    QVERIFY(resaved["preset"]["changed"].empty());
}

// A sphere whose faces are oriented inward, opened flipped (the default) and
// kept as in the file: each session records the choice, reopens the same
// mesh whatever the window's toggle says, and sets the toggle; the
// diagnostic snapshot's report notes the flip.
void TestSessionExport::sessionKeepsTheMeshOrientation() {
    const PolygonMesh outward = makeSphere(1.0, 12);
    const PolygonMesh inward = testing::reversedFaces(outward);
    const QString meshPath = dir_.filePath(QStringLiteral("inward.obj"));
    writeObj(inward, meshPath.toStdString());

    const auto openIn = [&](MainWindow& w, const QString& file, bool keep) {
        w.setInteractive(false);
        w.keepOrientationAction()->setChecked(keep);
        QVERIFY(w.setMethod(QStringLiteral("mesh")));
        QVERIFY2(w.openFile(file), qPrintable(w.lastError()));
        QVERIFY(w.waitForIdle(kIdleTimeoutMs));
        QVERIFY2(w.lastError().isEmpty(), qPrintable(w.lastError()));
    };
    const auto cageIndices = [](const MainWindow& w) {
        return w.runner()->snapshot(0).cage->indices;
    };
    for (const bool keep : {false, true}) {
        MainWindow first;
        openIn(first, meshPath, keep);
        QCOMPARE(first.meshKeptFileOrientation(), keep);
        QVERIFY(cageIndices(first) == (keep ? inward : outward).indices);
        const QString session = dir_.filePath(keep ? QStringLiteral("kept.cwsession")
                                                   : QStringLiteral("flipped.cwsession"));
        QVERIFY2(first.saveSession(session), qPrintable(first.lastError()));
        QCOMPARE(readJson(session)["keep_file_orientation"].get<bool>(), keep);

        // Opened where the toggle says the opposite: the session's choice wins.
        MainWindow second;
        openIn(second, session, !keep);
        QCOMPARE(second.meshKeptFileOrientation(), keep);
        QCOMPARE(second.keepOrientationAction()->isChecked(), keep);
        QVERIFY(cageIndices(second) == cageIndices(first));
        const QString message = second.statusBar()->currentMessage();
        QVERIFY2(message.startsWith(QStringLiteral("Session ")) &&
                     message.contains(keep ? QStringLiteral("kept as in the file")
                                           : QStringLiteral("; flipped (")),
                 qPrintable(message));

        if (!keep) {
            const QString out = dir_.filePath(QStringLiteral("flipped-snapshot"));
            QVERIFY(QDir().mkpath(out));
            QVERIFY2(second.exportDiagnosticSnapshot(out), qPrintable(second.lastError()));
            const nlohmann::json notes = readJson(out + "/report.json")["mesh"]["notes"];
            QCOMPARE(notes.size(), size_t(1));
            QVERIFY2(notes[0].get<std::string>().find("inward.obj: 1 of 1 closed components had "
                                                      "inward normals") == 0,
                     notes.dump().c_str());
            QCOMPARE(readJson(out + "/session.cwsession")["keep_file_orientation"].get<bool>(),
                     false);
        }
    }

    // The toggle is kept with the window's settings.
    QAction* keep = window_->keepOrientationAction();
    keep->setChecked(true);
    window_->sessionController()->saveWindowSettings();
    QCOMPARE(QSettings().value(QStringLiteral("mesh/keepFileOrientation")).toBool(), true);
    keep->setChecked(false);
    window_->sessionController()->restoreWindowSettings();
    QVERIFY(keep->isChecked());
    keep->setChecked(false);
    window_->sessionController()->saveWindowSettings();
}

void TestSessionExport::failedExportLeavesNothing() {
    // 1. The folder is a file: nothing can be written; the message names the
    // first file.
    const QString notAFolder = dir_.filePath(QStringLiteral("plain-file"));
    {
        QFile f(notAFolder);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("x");
    }
    QVERIFY(!window_->exportDiagnosticSnapshot(notAFolder));
    QVERIFY2(window_->lastError().contains(QStringLiteral("plain-file/view-3d.png: cannot write")),
             qPrintable(window_->lastError()));

    // 2. A folder named report.json is in the way: the files already moved
    // into place are taken back, and the file they replaced is restored.
    const QString out = dir_.filePath(QStringLiteral("blocked"));
    QVERIFY(QDir().mkpath(out + "/report.json/inside"));
    {
        QFile f(out + "/view-2d.png");
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("previous");
    }
    QVERIFY(!window_->exportDiagnosticSnapshot(out));
    QVERIFY2(window_->lastError().contains(QStringLiteral("blocked/report.json: cannot write")),
             qPrintable(window_->lastError()));
    QCOMPARE(filesIn(out), QStringList({"report.json", "view-2d.png"}));
    QFile previous(out + "/view-2d.png");
    QVERIFY(previous.open(QIODevice::ReadOnly));
    QCOMPARE(previous.readAll(), QByteArray("previous"));

    // 3. A read-only folder (only meaningful when not running as root).
    if (geteuid() != 0) {
        const QString readOnly = dir_.filePath(QStringLiteral("read-only"));
        QVERIFY(QDir().mkpath(readOnly));
        QVERIFY(QFile::setPermissions(readOnly, QFile::ReadOwner | QFile::ExeOwner));
        QVERIFY(!window_->exportDiagnosticSnapshot(readOnly));
        QVERIFY2(
            window_->lastError().contains(QStringLiteral("read-only/view-3d.png: cannot write")),
            qPrintable(window_->lastError()));
        QVERIFY(filesIn(readOnly).isEmpty());
        QFile::setPermissions(readOnly, QFile::ReadOwner | QFile::WriteOwner | QFile::ExeOwner);
    }
}

void TestSessionExport::cleanupTestCase() {
    window_.reset();
    QSettings().clear();
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    QApplication::setOrganizationName(QStringLiteral("contour-tests"));
    QApplication::setApplicationName(QStringLiteral("test_session_export"));
    TestSessionExport test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_session_export.moc"
