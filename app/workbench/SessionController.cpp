#include "SessionController.h"

#include "MainWindow.h"
#include "MethodComparison.h"
#include "MethodPanel.h"
#include "Resources.h"
#include "SceneView3D.h"
#include "contours/Methods.h"
#include "mesh/MeshError.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QSettings>
#include <QStatusBar>
#include <array>

namespace contour {

namespace {

const char* const kRecentKey = "recentFiles";
const char* const kSessionFolderKey = "folders/session";
const char* const kSnapshotFolderKey = "folders/snapshot";
const char* const kGeometryKey = "window/geometry";
const char* const kStateKey = "window/state";
const char* const kKeepOrientationKey = "mesh/keepFileOrientation";

// Stable names of the display toggles in a session file (not the menu
// texts, which may change).
const std::array<const char*, kSceneOverlayCount> kOverlayKeys{
    "overlay.inconsistent-faces", "overlay.radial-faces", "overlay.contour-vertices",
    "overlay.cusps", "overlay.radial-edges", "overlay.patch-edges", "overlay.cones"};
const std::array<const char*, MainWindow::kViewGraphToggleCount> kViewGraphKeys{
    "view-graph.hidden-curves", "view-graph.colour-by-qi", "view-graph.nodes",
    "view-graph.simplified-curves"};

const char* const kCageKey = "overlay.control-cage";
// Which views are shown (MainWindow::ViewLayout, in its order).
const char* const kLayoutKey = "layout";
const std::array<const char*, 3> kLayoutNames{"both", "3d-only", "2d-only"};

const char* boolText(bool on) {
    return on ? "true" : "false";
}

} // namespace

SessionController::SessionController(MainWindow* window) : QObject(window), window_(window) {}

QString SessionController::overlayKey(int sceneOverlay) {
    return QString::fromLatin1(kOverlayKeys.at(static_cast<size_t>(sceneOverlay)));
}

QString SessionController::viewGraphKey(int toggle) {
    return QString::fromLatin1(kViewGraphKeys.at(static_cast<size_t>(toggle)));
}

void SessionController::addFileActions(QMenu* file, QAction* before) {
    openAction_ =
        new QAction(resourceIcon(QStringLiteral("open-session")), tr("Open &session…"), this);
    openAction_->setObjectName(QStringLiteral("openSession"));
    openAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_O));
    openAction_->setToolTip(tr("Reopen a saved session: mesh, analysis camera, method, "
                               "parameters, phase reached and display (Ctrl+Shift+O)"));
    connect(openAction_, &QAction::triggered, this, &SessionController::openDialog);
    saveAction_ =
        new QAction(resourceIcon(QStringLiteral("save-session")), tr("&Save session…"), this);
    saveAction_->setObjectName(QStringLiteral("saveSession"));
    saveAction_->setShortcut(QKeySequence::Save);
    saveAction_->setToolTip(tr("Save the mesh path, analysis camera, method, parameters, phase "
                               "reached and display choices as a .cwsession file (Ctrl+S)"));
    connect(saveAction_, &QAction::triggered, this, &SessionController::saveDialog);
    exportAction_ = new QAction(resourceIcon(QStringLiteral("export-snapshot")),
                                tr("&Export diagnostic snapshot…"), this);
    exportAction_->setObjectName(QStringLiteral("exportSnapshot"));
    exportAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_E));
    exportAction_->setToolTip(
        tr("Write into a folder: both views as PNG, the 2D view as SVG, a JSON report (method, "
           "parameters, camera, every phase's counters and time, every inconsistent face), the "
           "labelled mesh as PLY and the session; all files or none (Ctrl+E)"));
    connect(exportAction_, &QAction::triggered, this, &SessionController::exportDialog);
    illustrationAction_ = new QAction(tr("Export &illustration SVG…"), this);
    illustrationAction_->setObjectName(QStringLiteral("exportIllustration"));
    illustrationAction_->setToolTip(
        tr("Write the clean drawing of the current phase as SVG: visible strokes tapered at "
           "curtain folds and dead ends, hidden lines when the 2D view shows them, no node "
           "glyphs, one Inkscape layer per curve type"));
    connect(illustrationAction_, &QAction::triggered, this, &SessionController::illustrationDialog);
    recentMenu_ = new QMenu(tr("Open &recent"), file);
    connect(recentMenu_, &QMenu::aboutToShow, this, &SessionController::fillRecentMenu);

    file->insertAction(before, openAction_);
    file->insertMenu(before, recentMenu_);
    file->insertSeparator(before);
    file->insertAction(before, saveAction_);
    file->insertAction(before, exportAction_);
    file->insertAction(before, illustrationAction_);
    fillRecentMenu();
}

std::optional<Session> SessionController::capture(QString* error) const {
    const auto fail = [&](const QString& why) -> std::optional<Session> {
        if (error)
            *error = why;
        return std::nullopt;
    };
    if (window_->isBusy())
        return fail(tr("a phase is running: wait for it or cancel it (Esc)"));
    if (!window_->hasMesh())
        return fail(tr("no mesh is open"));
    const QFileInfo mesh(window_->meshPath());
    if (!mesh.isFile())
        return fail(tr("the mesh \"%1\" was not read from a file").arg(window_->meshPath()));
    const std::optional<Camera> camera = window_->analysisCamera();
    if (!camera)
        return fail(tr("there is no analysis camera"));
    Session s;
    s.meshPath = QDir::cleanPath(mesh.absoluteFilePath()).toStdString();
    s.keepFileOrientation = window_->meshKeptFileOrientation();
    s.method = window_->methodName().toStdString();
    const Runner* runner = window_->runner();
    s.parameters = runner ? runner->parameters() : window_->methodPanel()->parameters();
    if (const Method* method = findMethod(s.method)) {
        try {
            setSessionPreset(s, *method, window_->methodPanel()->presetName().toStdString());
        } catch (const std::invalid_argument&) {
            setSessionPreset(s, *method, "default");
        }
    }
    s.camera = runner ? runner->camera() : *camera;
    s.viewCamera = window_->sceneView()->viewCamera();
    s.phaseReached = window_->completedPhases();
    s.phaseName = runner ? runner->current().phaseName : std::string("input");
    s.display[kColourKey] = window_->sceneView()->colorField();
    s.display[kCompareKey] = window_->methodComparison()->otherMethod().toStdString();
    for (int i = 0; i < kSceneOverlayCount; ++i)
        if (const QAction* a = window_->overlayAction(static_cast<SceneOverlay>(i)))
            s.display[kOverlayKeys[static_cast<size_t>(i)]] = boolText(a->isChecked());
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        if (const QAction* a =
                window_->viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i)))
            s.display[kViewGraphKeys[static_cast<size_t>(i)]] = boolText(a->isChecked());
    if (const QAction* a = window_->controlCageAction())
        s.display[kCageKey] = boolText(a->isChecked());
    s.display[kLayoutKey] = kLayoutNames.at(static_cast<size_t>(window_->viewLayout()));
    return s;
}

bool SessionController::save(const QString& path) {
    QString why;
    const std::optional<Session> session = capture(&why);
    if (!session) {
        window_->reportError(tr("Cannot save the session"),
                             QStringLiteral("%1: %2").arg(path, why));
        return false;
    }
    try {
        writeSession(path.toStdString(), *session);
    } catch (const std::exception& e) {
        window_->reportError(tr("Cannot save the session"), QString::fromStdString(e.what()));
        return false;
    }
    noteRecentFile(path);
    window_->statusBar()->showMessage(tr("Session saved to %1").arg(path), 5000);
    return true;
}

bool SessionController::open(const QString& path) {
    const QString title = tr("Cannot open the session");
    Session session;
    ParameterSet parameters;
    std::vector<std::string> warnings;
    int phases = 0;
    std::string preset;
    MainWindow::LoadedMesh mesh;
    try {
        session = readSession(path.toStdString());
        const Method* method = findMethod(session.method);
        if (!method)
            throw std::runtime_error(path.toStdString() + ": method \"" + session.method +
                                     "\" is not available");
        try {
            parameters = sessionParameters(session, *method, &warnings);
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(path.toStdString() + ": " + e.what());
        }
        phases = sessionPhaseTarget(session, *method, &warnings);
        preset = sessionPresetName(session, *method, &warnings);
        QApplication::setOverrideCursor(Qt::WaitCursor);
        try {
            mesh = MainWindow::readMeshFile(QString::fromStdString(session.meshPath),
                                            session.keepFileOrientation);
        } catch (const MeshError& e) {
            QApplication::restoreOverrideCursor();
            throw std::runtime_error(path.toStdString() + ": the session's mesh: " + e.what());
        }
        QApplication::restoreOverrideCursor();
    } catch (const std::exception& e) {
        window_->reportError(title, QString::fromStdString(e.what()));
        return false;
    }
    if (!window_->restoreRun(mesh, QString::fromStdString(session.meshPath),
                             QString::fromStdString(session.method), parameters, session.camera,
                             phases))
        return false;
    // The session's mesh is oriented as it was saved; the menu shows it.
    window_->keepOrientationAction()->setChecked(session.keepFileOrientation);
    window_->methodPanel()->setStartingPreset(QString::fromStdString(preset));
    applyDisplay(session);
    if (session.viewCamera)
        window_->sceneView()->setViewCamera(*session.viewCamera);
    noteRecentFile(path);
    QString message = tr("Session %1 opened").arg(QFileInfo(path).fileName());
    for (const std::string& w : warnings)
        message += QStringLiteral("; ") + QString::fromStdString(w);
    const QString orientation = window_->meshOrientationMessage();
    if (!orientation.isEmpty())
        message += QStringLiteral("; ") + orientation;
    window_->statusBar()->showMessage(message,
                                      warnings.empty() && orientation.isEmpty() ? 5000 : 0);
    return true;
}

void SessionController::applyDisplay(const Session& session) {
    const auto flag = [&](const char* key) -> std::optional<bool> {
        const auto it = session.display.find(key);
        if (it == session.display.end() || (it->second != "true" && it->second != "false"))
            return std::nullopt;
        return it->second == "true";
    };
    for (int i = 0; i < kSceneOverlayCount; ++i)
        if (const std::optional<bool> on = flag(kOverlayKeys[static_cast<size_t>(i)]))
            if (QAction* a = window_->overlayAction(static_cast<SceneOverlay>(i)))
                a->setChecked(*on);
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        if (const std::optional<bool> on = flag(kViewGraphKeys[static_cast<size_t>(i)]))
            if (QAction* a = window_->viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i)))
                a->setChecked(*on);
    if (const std::optional<bool> on = flag(kCageKey))
        if (QAction* a = window_->controlCageAction())
            a->setChecked(*on);
    if (const auto it = session.display.find(kLayoutKey); it != session.display.end())
        for (size_t i = 0; i < kLayoutNames.size(); ++i)
            if (it->second == kLayoutNames[i])
                window_->setViewLayout(static_cast<MainWindow::ViewLayout>(i));
    if (const auto it = session.display.find(kCompareKey); it != session.display.end())
        window_->setComparisonMethod(QString::fromStdString(it->second));
    if (const auto it = session.display.find(kColourKey); it != session.display.end())
        window_->setColorField(QString::fromStdString(it->second)); // remembered if not yet there
}

QStringList SessionController::recentFiles() const {
    return useSettings_ ? QSettings().value(kRecentKey).toStringList() : recentInMemory_;
}

void SessionController::noteRecentFile(const QString& path) {
    const QString absolute = QDir::cleanPath(QFileInfo(path).absoluteFilePath());
    QStringList files = recentFiles();
    files.removeAll(absolute);
    files.prepend(absolute);
    while (files.size() > kMaxRecentFiles)
        files.removeLast();
    if (useSettings_)
        QSettings().setValue(kRecentKey, files);
    else
        recentInMemory_ = files;
}

void SessionController::fillRecentMenu() {
    recentMenu_->clear();
    const QStringList files = recentFiles();
    for (const QString& path : files) {
        QAction* action = recentMenu_->addAction(QFileInfo(path).fileName());
        action->setToolTip(path);
        action->setStatusTip(path);
        action->setEnabled(QFileInfo::exists(path));
        connect(action, &QAction::triggered, window_, [this, path] { window_->openFile(path); });
    }
    if (files.isEmpty())
        recentMenu_->addAction(tr("(none)"))->setEnabled(false);
    else {
        recentMenu_->addSeparator();
        recentMenu_->addAction(tr("Clear the list"), this, [this] {
            recentInMemory_.clear();
            if (useSettings_)
                QSettings().remove(QString::fromLatin1(kRecentKey));
        });
    }
}

void SessionController::restoreWindowSettings() {
    if (!useSettings_)
        return;
    const QSettings settings;
    if (settings.contains(kGeometryKey))
        window_->restoreGeometry(settings.value(kGeometryKey).toByteArray());
    if (settings.contains(kStateKey))
        window_->restoreState(settings.value(kStateKey).toByteArray());
    window_->keepOrientationAction()->setChecked(
        settings.value(kKeepOrientationKey, false).toBool());
}

void SessionController::saveWindowSettings() const {
    if (!useSettings_)
        return;
    QSettings settings;
    settings.setValue(kGeometryKey, window_->saveGeometry());
    settings.setValue(kStateKey, window_->saveState());
    settings.setValue(kKeepOrientationKey, window_->keepOrientationAction()->isChecked());
}

void SessionController::saveDialog() {
    QSettings settings;
    QString folder = settings.value(kSessionFolderKey).toString();
    if (folder.isEmpty())
        folder = QFileInfo(window_->meshPath()).absolutePath();
    const QString suggested = QDir(folder).filePath(
        QFileInfo(window_->meshPath()).completeBaseName() + QStringLiteral(".cwsession"));
    const QString path = QFileDialog::getSaveFileName(
        window_, tr("Save session"), suggested,
        tr("Workbench sessions (*.cwsession);;JSON (*.json);;All files (*)"));
    if (path.isEmpty())
        return;
    settings.setValue(kSessionFolderKey, QFileInfo(path).absolutePath());
    save(path);
}

void SessionController::openDialog() {
    QSettings settings;
    const QString path = QFileDialog::getOpenFileName(
        window_, tr("Open session"), settings.value(kSessionFolderKey).toString(),
        tr("Workbench sessions (*.cwsession *.json);;All files (*)"));
    if (path.isEmpty())
        return;
    settings.setValue(kSessionFolderKey, QFileInfo(path).absolutePath());
    open(path);
}

void SessionController::exportDialog() {
    QSettings settings;
    const QString folder =
        QFileDialog::getExistingDirectory(window_, tr("Export diagnostic snapshot into"),
                                          settings.value(kSnapshotFolderKey).toString());
    if (folder.isEmpty())
        return;
    settings.setValue(kSnapshotFolderKey, folder);
    window_->exportDiagnosticSnapshot(folder);
}

void SessionController::illustrationDialog() {
    QSettings settings;
    const QString path = QFileDialog::getSaveFileName(window_, tr("Export illustration SVG"),
                                                      settings.value(kSnapshotFolderKey).toString(),
                                                      tr("SVG (*.svg)"));
    if (path.isEmpty())
        return;
    settings.setValue(kSnapshotFolderKey, QFileInfo(path).absolutePath());
    window_->exportIllustrationSvg(path);
}

} // namespace contour
