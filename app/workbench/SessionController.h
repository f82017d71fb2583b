#pragma once
// The workbench's sessions, recent files and kept settings:
// - captures the window's state as a Session (export/SessionFile.h: mesh
//   path and whether its file orientation was kept, analysis camera, 3D view
//   camera, method, parameters, phase reached, and the display choices as
//   strings: colour field, overlay and view-graph toggles) and restores one
//   through MainWindow::restoreRun, so that reopening gives the same picture;
// - the File menu's Open session…, Save session…, Export diagnostic
//   snapshot… (SnapshotExport.h) and Open recent entries;
// - QSettings: the recent meshes and sessions, the last folders used, the
//   window's geometry and dock/tool bar state, and File › Keep file
//   orientation.
#include "MainWindow.h"
#include "export/SessionFile.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <optional>

class QAction;
class QMenu;

namespace contour {

class SessionController : public QObject {
    Q_OBJECT

public:
    static constexpr int kMaxRecentFiles = 10;

    explicit SessionController(MainWindow* window);

    // Adds the session, snapshot and recent-file entries to the File menu,
    // before `before` (null: at the end).
    void addFileActions(QMenu* file, QAction* before);

    // The window's current state; nullopt (and `error` says why) while a
    // phase runs or when the mesh did not come from a file.
    std::optional<Session> capture(QString* error = nullptr) const;
    // Saves capture() atomically; false (the window shows why) on failure.
    bool save(const QString& path);
    // Reads a session and restores it: mesh, method, parameters, camera,
    // phase (run in the background: MainWindow::waitForIdle), display.
    bool open(const QString& path);
    // Applies a session's display choices (unknown keys are ignored).
    void applyDisplay(const Session& session);

    // Whether the recent files and the window's geometry and state live in
    // QSettings (the application turns this on; off, e.g. in tests that make
    // windows, the recent files are kept in memory and nothing is saved).
    void setUseSettings(bool use) { useSettings_ = use; }
    bool usesSettings() const { return useSettings_; }

    // Recent files, newest first (meshes and sessions, existing or not).
    QStringList recentFiles() const;
    void noteRecentFile(const QString& path);

    // Both do nothing unless usesSettings().
    void restoreWindowSettings();
    void saveWindowSettings() const;

    QAction* saveSessionAction() const { return saveAction_; }
    QAction* openSessionAction() const { return openAction_; }
    QAction* exportSnapshotAction() const { return exportAction_; }
    QAction* exportIllustrationAction() const { return illustrationAction_; }

    // Display keys (the "display" map of a session).
    static QString overlayKey(int sceneOverlay);
    static QString viewGraphKey(int toggle);
    static constexpr const char* kColourKey = "colour_by";
    // The method the 2D view compares with ("" for none).
    static constexpr const char* kCompareKey = "compare_with";

private:
    void saveDialog();
    void openDialog();
    void exportDialog();
    void illustrationDialog();
    void fillRecentMenu();

    MainWindow* window_;
    QAction* openAction_ = nullptr;
    QAction* saveAction_ = nullptr;
    QAction* exportAction_ = nullptr;
    QAction* illustrationAction_ = nullptr;
    QMenu* recentMenu_ = nullptr;
    bool useSettings_ = false;
    QStringList recentInMemory_;
};

} // namespace contour
