#pragma once
// The workbench window: opens a mesh, hands it with the chosen method, its
// parameters and the analysis camera to its RunController (which owns the
// contour::Runner and runs the phases off the GUI thread) and shows each
// resulting immutable Snapshot in the views.
//
// Layout: the 3D scene view and the 2D image view side by side in a
// splitter, a dock with the method panel and the phase stepper on the left,
// a "Display" tool bar with the 3D view's "Colour by" selector and its
// legend, an "Overlays" tool bar with the 3D view's overlay toggles (shown
// only for the overlays the snapshot has fields for) and the view graph
// toggles of both views (shown when the snapshot has a view graph) and the
// ground-truth toggle, a status bar. The small public API
// below is what the menus call, and what tests drive.
#include "RunController.h"
#include "SceneView3D.h"
#include "WorkbenchDefaults.h"
#include "camera/Camera.h"
#include "mesh/PolygonMesh.h"
#include "pipeline/Runner.h"
#include "pipeline/Snapshot.h"

#include <QMainWindow>
#include <QString>
#include <array>
#include <memory>
#include <optional>

class QAction;
class QComboBox;
class QLabel;
class QMenu;
class QProgressBar;
class QToolBar;
class QSplitter;

namespace contour {

class GroundTruthComputation;
class ImageView2D;
class ParameterDomainView;
class Inspector;
class MethodComparison;
class MethodPanel;
class PhaseStepper;
class SelectionController;
class SessionController;

class MainWindow : public QMainWindow {
    Q_OBJECT

public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    // A mesh file as the workbench uses it: read, then with its inward closed
    // components flipped outward unless the file's orientation is kept
    // (mesh/Orientation.h).
    struct LoadedMesh {
        std::shared_ptr<const PolygonMesh> mesh;
        bool keptFileOrientation = false;
        int inwardComponents = 0; // closed components the file orients inward
        // What orienting did or could not decide (orientationMessage), "" when
        // there is nothing to say.
        QString orientation;
    };
    // Throws MeshError (or std::exception) like readMesh().
    static LoadedMesh readMeshFile(const QString& path, bool keepFileOrientation);

    // Reads a mesh (OBJ, OFF, PLY; oriented as keepOrientationAction() says),
    // frames the analysis camera on it, makes the runner and starts running
    // every phase. What orienting did is shown in the status bar and is a
    // note of the input snapshot. Returns false (and shows the error in a
    // message box and the status bar) when the file cannot be used. The run
    // goes on in the background: see waitForIdle().
    bool openMesh(const QString& path);
    // Same for a mesh already in memory (used as it is); `name` is shown in
    // the title.
    bool setMesh(std::shared_ptr<const PolygonMesh> mesh, const QString& name);
    // File › Keep file orientation: checked, meshes are used as their files
    // orient them. Toggling it reloads the open mesh when that changes it,
    // keeping the method, parameters, cameras and phase reached.
    QAction* keepOrientationAction() const { return keepOrientationAction_; }
    // Whether the open mesh was used as its file orients it, and what
    // orienting it said ("" when nothing), as "name: message".
    bool meshKeptFileOrientation() const { return meshOrientation_.keptFileOrientation; }
    QString meshOrientationMessage() const;
    bool hasMesh() const { return static_cast<bool>(cage_); }
    QString meshPath() const { return meshName_; }

    QString methodName() const;
    // Switches to a runnable method: re-creates the runner and runs to the
    // end. False for an unknown or planned method.
    bool setMethod(const QString& name);

    // Phase control; each does nothing while a phase runs.
    void stepPhase();
    void stepBack();
    void runToEnd();
    void resetPhases();
    void runToPhase(int completed);

    // Takes the 3D view's camera as the analysis camera, re-creates the runner
    // and re-runs to the phase that was reached.
    void setAnalysisCameraFromView();
    // Puts the 3D view back on the analysis camera.
    void resetViewToAnalysisCamera();

    bool isBusy() const { return run_->isBusy(); }
    // Processes events until no phase runs; false on timeout.
    bool waitForIdle(int timeoutMs = 120000);

    // Valid while idle.
    const Runner* runner() const { return run_->runner(); }
    int completedPhases() const;
    // The snapshot the views show (the input before any phase; an empty
    // snapshot when no mesh is open).
    Snapshot currentSnapshot() const;
    std::optional<Camera> analysisCamera() const { return run_->camera(); }
    QString lastError() const { return lastError_; }

    // What the 3D view colours the mesh by: "facing" (front/back) or a scalar
    // field of the snapshot (SceneView3D::setColorField). False when the
    // current snapshot has no such field (the choice is still remembered).
    bool setColorField(const QString& field);
    // The field the 3D view shows.
    QString colorField() const;
    // Its selector: item data is the field name, text the readable name.
    QComboBox* colorSelector() const { return colorSelector_; }
    // The legend of the shown face colours (empty under a scalar field,
    // which has its scalar bar).
    QLabel* colorLegend() const { return colorLegend_; }
    // The checkable action toggling an overlay of the 3D view; visible only
    // while the snapshot has the overlay's fields.
    QAction* overlayAction(SceneOverlay overlay) const {
        return overlayActions_[static_cast<int>(overlay)];
    }

    // The view graph toggles (Overlays tool bar, View › Overlays), applied to
    // the 2D and the 3D view alike; visible only while the snapshot has a
    // view graph. ColourByQi unchecked colours chains by chain index.
    enum class ViewGraphToggle { HiddenCurves, ColourByQi, Nodes, SimplifiedCurves };
    static constexpr int kViewGraphToggleCount = 4;
    QAction* viewGraphAction(ViewGraphToggle toggle) const {
        return viewGraphActions_[static_cast<int>(toggle)];
    }
    // The 3D view's view graph legend (QI colours, node dot colours).
    QLabel* viewGraphLegend() const { return viewGraphLegend_; }

    // View › Overlays › Ground-truth contour (also on the Overlays tool bar):
    // while checked, the dense ground truth of the smooth contour
    // (reference/DenseGroundTruth.h) for the analysis camera is computed in
    // the background (groundTruth()) and drawn in both views, with a legend
    // entry in the 2D view and its time in the status bar; it is computed
    // again when the mesh, the smooth surface or the analysis camera changes.
    // Unchecked, it is cleared. Disabled, with a tool tip saying why, while
    // the method has no smooth surface (surface = none).
    QAction* groundTruthAction() const { return groundTruthAction_; }
    GroundTruthComputation* groundTruth() const { return groundTruth_; }

    // View › Control cage: the cage as a wireframe in the 3D view.
    QAction* controlCageAction() const { return cageAction_; }
    // View › Both views / 3D view only / 2D view only: either view can take
    // the whole splitter.
    enum class ViewLayout { Both, SceneOnly, ImageOnly };
    void setViewLayout(ViewLayout layout);
    ViewLayout viewLayout() const;

    // Method comparison: a second method run on the same
    // mesh and camera, its curves and the differences shown in the 2D view.
    // An empty name turns it off; false for a name that is not a method.
    bool setComparisonMethod(const QString& name);
    MethodComparison* methodComparison() const { return comparison_; }
    QComboBox* compareSelector() const { return compareSelector_; }

    // Sessions, diagnostic snapshots, recent files, settings (the
    // logic is in SessionController and SnapshotExport). Each
    // returns false and shows why on failure.
    bool saveSession(const QString& path);
    bool openSession(const QString& path);
    bool exportDiagnosticSnapshot(const QString& folder);
    // The illustration SVG (export/IllustrationSvg.h) of the current phase,
    // with hidden lines when the 2D view shows them.
    bool exportIllustrationSvg(const QString& path);
    // A session (.cwsession, .json) or a mesh, by its suffix.
    bool openFile(const QString& path);
    // Shows a mesh already read with this method, parameters and analysis
    // camera, running only to `phases` (no intermediate run starts).
    bool restoreRun(const LoadedMesh& mesh, const QString& name, const QString& method,
                    const ParameterSet& parameters, const Camera& camera, int phases);
    // Asks the running phase job to stop (Run › Cancel, Esc); returns at once.
    void cancelPhases();
    void reportError(const QString& title, const QString& message) { showError(title, message); }
    SessionController* sessionController() const { return sessions_; }
    QAction* cancelAction() const { return cancelAction_; }
    // The status bar's busy bar: shown while a phase job runs; busy without a
    // fraction until the running phase reports one, then the fraction of
    // kBusyBarSteps, with the phase's name.
    QProgressBar* busyBar() const { return busyBar_; }
    static constexpr int kBusyBarSteps = 1000;

    // Linked selection and the inspector (the logic is in
    // SelectionController): the right dock's inspector, the selection shared
    // by both views, and View › Next inconsistent face (N).
    Inspector* inspector() const { return inspector_; }
    SelectionController* selectionController() const { return selection_; }
    QAction* nextInconsistentAction() const { return nextInconsistentAction_; }

    // The runner and its background jobs (RunController.h).
    RunController* runController() const { return run_; }
    SceneView3D* sceneView() const { return sceneView_; }
    ImageView2D* imageView() const { return imageView_; }
    ParameterDomainView* domainView() const { return domainView_; }
    PhaseStepper* phaseStepper() const { return stepper_; }
    MethodPanel* methodPanel() const { return methodPanel_; }

    // When false, errors go to the status bar and lastError() only, without a
    // message box (for scripted use).
    void setInteractive(bool interactive) { interactive_ = interactive; }

signals:
    // A phase job finished (successfully or not) and the views are updated.
    void idle();

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;
    void closeEvent(QCloseEvent* event) override;

private:
    void createActions();
    // The inspector dock, the selection and its actions.
    void createSelection();
    void createLayout();
    void openFileDialog();
    // The mesh, with what loading it noted as a note of the input snapshot.
    bool installMesh(const LoadedMesh& mesh, const QString& name);
    // Reloads the open mesh file after File › Keep file orientation changed.
    void reorientMesh();
    void showError(const QString& title, const QString& message);
    // Makes a new runner for the current mesh, method, parameters and camera,
    // then runs to `completed` phases (-1: to the end).
    void rebuildRunner(int completed);
    // The run controller's reports.
    void onBusyChanged(bool busy);
    // Entering a phase (fraction 0) or its progress fraction in (0, 1].
    void onProgress(int phase, double fraction);
    void onRunIdle();
    void showRunnerState();
    void updateActions();
    void updateStatus();
    // Lists facing and the 3D view's scalar fields in the selector and
    // selects the one it shows.
    void updateColorSelector();
    void onColorSelected(int index);
    void createOverlayActions(QMenu* viewMenu);
    // Shows the actions of the overlays the 3D view can draw.
    void updateOverlayActions();
    void updateColorLegend();
    void createViewGraphActions(QMenu* overlayMenu);
    void updateViewGraphLegend();
    // The right dock's overlay toggles and legends (below the inspector).
    void createDisplayDock();
    // Method comparison: the difference of the current snapshot's drawing
    // and the other method's, shown in the 2D view.
    void createCompareSelector(QToolBar* toolBar);
    void updateComparison();
    // The ground-truth toggle and what it computes for.
    void createGroundTruthAction(QMenu* overlayMenu);
    void updateGroundTruthRequest();
    void showGroundTruth();

    MethodComparison* comparison_ = nullptr;
    GroundTruthComputation* groundTruth_ = nullptr;
    QAction* groundTruthAction_ = nullptr;
    QAction* groundTruthSeparator_ = nullptr;
    QAction* cageAction_ = nullptr;
    std::array<QAction*, 3> layoutActions_{};
    QComboBox* compareSelector_ = nullptr;
    SceneView3D* sceneView_ = nullptr;
    ImageView2D* imageView_ = nullptr;
    // Shown beside the others while the snapshot has a uv layout.
    ParameterDomainView* domainView_ = nullptr;
    const Method* domainViewMethod_ = nullptr; // the method whose layout it shows
    MethodPanel* methodPanel_ = nullptr;
    PhaseStepper* stepper_ = nullptr;
    QSplitter* splitter_ = nullptr;
    QLabel* meshLabel_ = nullptr;
    QLabel* phaseLabel_ = nullptr;
    QProgressBar* busyBar_ = nullptr;
    QComboBox* colorSelector_ = nullptr;
    QLabel* colorLegend_ = nullptr;
    QToolBar* overlayBar_ = nullptr;
    std::array<QAction*, kSceneOverlayCount> overlayActions_{};
    std::array<QAction*, kViewGraphToggleCount> viewGraphActions_{};
    QAction* viewGraphSeparator_ = nullptr;
    QLabel* viewGraphLegend_ = nullptr;
    QMenu* viewMenu_ = nullptr;
    bool updatingColorSelector_ = false;

    QAction* openAction_ = nullptr;
    QAction* keepOrientationAction_ = nullptr;
    QAction* stepAction_ = nullptr;
    QAction* backAction_ = nullptr;
    QAction* runAction_ = nullptr;
    QAction* resetAction_ = nullptr;
    QAction* cameraFromViewAction_ = nullptr;
    QAction* viewToCameraAction_ = nullptr;
    // Sessions, snapshots, recent files, settings, About, Cancel.
    SessionController* sessions_ = nullptr;
    QAction* cancelAction_ = nullptr;
    bool restoring_ = false; // restoreRun: rebuildRunner waits for the last call
    // Linked selection and the inspector.
    Inspector* inspector_ = nullptr;
    SelectionController* selection_ = nullptr;
    QAction* nextInconsistentAction_ = nullptr;

    std::shared_ptr<const PolygonMesh> cage_;
    QString meshName_;
    LoadedMesh meshOrientation_; // how the open mesh was oriented (its mesh left empty)
    // What the window starts with (resources/settings/defaults.json).
    WorkbenchDefaults defaults_;
    RunController* run_ = nullptr;
    QString lastError_;
    bool interactive_ = true;
};

} // namespace contour
