#include "MainWindow.h"

#include "AboutDialog.h"
#include "FieldLabels.h"
#include "GroundTruthComputation.h"
#include "ImageView2D.h"
#include "Inspector.h"
#include "MethodComparison.h"
#include "MethodPanel.h"
#include "ParameterDomainView.h"
#include "PhaseStepper.h"
#include "Resources.h"
#include "SceneColors.h"
#include "SceneView3D.h"
#include "SelectionController.h"
#include "SessionController.h"
#include "SnapshotExport.h"
#include "ViewGraphStyle.h"
#include "contours/Methods.h"
#include "contours/common/SurfacePhase.h"
#include "export/CurveComparison.h"
#include "export/IllustrationSvg.h"
#include "mesh/MeshError.h"
#include "mesh/Orientation.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QComboBox>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace contour {

namespace {

// Layout names as in session files (SessionController), ViewLayout order.
const std::array<const char*, 3> kLayoutNames{"both", "3d-only", "2d-only"};

// A legend entry: a square of `color` and its meaning, as rich text.
QString swatch(const SceneColor& color, const QString& text) {
    return QStringLiteral("<span style=\"color:%1\">&#9632;</span>&nbsp;%2")
        .arg(color.toQColor().name(), text.toHtmlEscaped());
}

// The overlays' names, tool tips and icons (resources/icons/overlay-*.svg,
// drawn in the overlay's colours).
struct OverlayInfo {
    SceneOverlay overlay;
    const char* name;
    const char* toolTip;
    const char* icon;
};

const std::array<OverlayInfo, kSceneOverlayCount> kOverlays{{
    {SceneOverlay::InconsistentFaces, "Inconsistent faces",
     "Outline, drawn over everything, the faces whose VBO disagrees with their facing "
     "(contour-inconsistent, Bénard 2014 Definition 2)",
     "overlay-inconsistent-faces"},
    {SceneOverlay::RadialFaces, "Radial faces",
     "Tint radial triangles (Definition 5) orange, standard radial triangles (§6.3) teal",
     "overlay-radial-faces"},
    {SceneOverlay::ContourVertices, "C vertices",
     "Mark the contour vertices (label C, g = 0 at their preimage, §6.2) with white dots",
     "overlay-contour-vertices"},
    {SceneOverlay::Cusps, "Cusps",
     "Mark the cusp vertices (g = 0 and radial curvature 0, §6.2 d) with large cyan squares, "
     "drawn over everything",
     "overlay-cusps"},
    {SceneOverlay::RadialEdges, "Radial edges",
     "Draw the radial edges p-r (Definition 5, §6.3) in charcoal", "overlay-radial-edges"},
    {SceneOverlay::PatchEdges, "Patch boundaries",
     "Draw the Powell-Sabin spline's patch boundaries (grey), macro-patch boundaries (the "
     "layout's triangles, charcoal) and the cut through the cones (magenta), Capouellez et al. "
     "2023 §5",
     "overlay-patch-edges"},
    {SceneOverlay::Cones, "Cones",
     "Mark the cones of the flat metric (Capouellez et al. 2023 §5.1) with black dots",
     "overlay-cones"},
}};

// The view-graph toggles; their icons (resources/icons/view-graph-*.svg) are
// drawn in the view graph's colours (resources/colormaps/view-graph-colors.json).
struct ViewGraphToggleInfo {
    const char* name;
    const char* toolTip;
    bool checked; // at start
    const char* icon;
};

const std::array<ViewGraphToggleInfo, MainWindow::kViewGraphToggleCount> kViewGraphToggles{{
    {"Hidden curves",
     "Draw the view graph's hidden chains (QI > 0): dashed in the 2D view, thinner and darker "
     "on the surface in the 3D view (orbit to see them), and the nodes that only touch them",
     true, "view-graph-hidden-curves"},
    {"Colour by QI",
     "Colour the view graph's chains by quantitative invisibility (QI 0 black in 2D, red in 3D; "
     "1, 2, 3+ in purples); unchecked: one colour per chain",
     true, "view-graph-colour-by-qi"},
    {"View-graph nodes",
     "Mark the view graph's nodes by type: curtain folds (cusps), boundary curtain folds, "
     "T-junctions, Y junctions, bifurcations, surface-intersection ends, curve ends "
     "(glyphs in 2D, dots over everything in 3D)",
     true, "view-graph-nodes"},
    {"Simplified curves",
     "Draw, very faint, the visible chains that topological simplification hid (Bénard 2014 "
     "§9)",
     false, "view-graph-simplified-curves"},
}};

} // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), defaults_(WorkbenchDefaults::load()) {
    setWindowTitle(tr("Contour Workbench"));
    setWindowIcon(resourceIcon(QStringLiteral("contour-workbench")));
    setAcceptDrops(true);
    run_ = new RunController(this);
    createLayout();
    createActions();
    createSelection();
    createDisplayDock();
    connect(run_, &RunController::snapshotReady, this, &MainWindow::showRunnerState);
    connect(run_, &RunController::busyChanged, this, &MainWindow::onBusyChanged);
    connect(run_, &RunController::progress, this, &MainWindow::onProgress);
    connect(run_, &RunController::failed, this, &MainWindow::showError);
    connect(run_, &RunController::cancelled, this,
            [this] { statusBar()->showMessage(tr("Cancelled"), 3000); });
    connect(run_, &RunController::idle, this, &MainWindow::onRunIdle);
    if (methodPanel_->methodName() != defaults_.method)
        methodPanel_->setMethod(defaults_.method);
    connect(methodPanel_, &MethodPanel::methodChanged, this, [this] { rebuildRunner(-1); });
    // New parameters: run again up to the phase reached (or being run to).
    connect(methodPanel_, &MethodPanel::parametersChanged, this,
            [this] { rebuildRunner(run_->hasRunner() ? run_->reachedPhases() : -1); });
    connect(stepper_, &PhaseStepper::stepRequested, this, &MainWindow::stepPhase);
    connect(stepper_, &PhaseStepper::backRequested, this, &MainWindow::stepBack);
    connect(stepper_, &PhaseStepper::resetRequested, this, &MainWindow::resetPhases);
    connect(stepper_, &PhaseStepper::runToEndRequested, this, &MainWindow::runToEnd);
    connect(sceneView_, &SceneView3D::viewMatchChanged, this, &MainWindow::updateActions);
    connect(sceneView_, &SceneView3D::colorFieldsChanged, this, &MainWindow::updateColorSelector);
    connect(sceneView_, &SceneView3D::overlaysChanged, this, &MainWindow::updateOverlayActions);
    // currentIndexChanged for programmatic changes, activated for the user
    // picking the entry already shown (e.g. facing while a remembered field
    // is missing), so that it becomes the choice.
    connect(colorSelector_, &QComboBox::currentIndexChanged, this, &MainWindow::onColorSelected);
    connect(colorSelector_, &QComboBox::activated, this, &MainWindow::onColorSelected);
    connect(comparison_, &MethodComparison::changed, this, &MainWindow::updateComparison);
    connect(groundTruth_, &GroundTruthComputation::changed, this, &MainWindow::showGroundTruth);
    sceneView_->setColorField(defaults_.colourBy.toStdString());
    updateColorSelector();
    updateOverlayActions();
    stepper_->setMethod(methodPanel_->method());
    for (std::size_t i = 1; i < kLayoutNames.size(); ++i)
        if (defaults_.layout == QLatin1String(kLayoutNames[i]))
            setViewLayout(static_cast<ViewLayout>(i));
    updateActions();
    updateStatus();
    resize(defaults_.windowSize);
}

MainWindow::~MainWindow() {
    // The views are going away: stop the job without showing its end.
    run_->disconnect(this);
    run_->cancelAndWait();
}

// ------------------------------------------- linked selection, inspector

void MainWindow::createSelection() {
    inspector_ = new Inspector;
    auto* dock = new QDockWidget(tr("Inspector"), this);
    dock->setObjectName(QStringLiteral("inspectorDock"));
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    dock->setWidget(inspector_);
    dock->setMinimumWidth(300);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    selection_ = new SelectionController(sceneView_, imageView_, inspector_, this);
    selection_->setPhaseNames([this] {
        std::vector<std::string> names;
        if (const Method* method = methodPanel_->method())
            for (const Phase& phase : method->phases)
                names.push_back(phase.name);
        return names;
    });
    connect(selection_, &SelectionController::message, this,
            [this](const QString& text) { statusBar()->showMessage(text, 6000); });
    nextInconsistentAction_ = new QAction(resourceIcon(QStringLiteral("next-inconsistent")),
                                          tr("&Next inconsistent face"), this);
    nextInconsistentAction_->setObjectName(QStringLiteral("nextInconsistentFace"));
    nextInconsistentAction_->setShortcut(Qt::Key_N);
    nextInconsistentAction_->setToolTip(
        tr("Select the next contour-inconsistent face of this phase and zoom the 3D view onto "
           "it; the analysis camera stays (N)"));
    connect(nextInconsistentAction_, &QAction::triggered, selection_,
            &SelectionController::selectNextInconsistentFace);
    QAction* clear =
        new QAction(resourceIcon(QStringLiteral("clear-selection")), tr("C&lear selection"), this);
    clear->setObjectName(QStringLiteral("clearSelection"));
    connect(clear, &QAction::triggered, selection_, &SelectionController::clear);
    QMenu* menu = menuBar()->addMenu(tr("&Selection"));
    menu->addAction(nextInconsistentAction_);
    menu->addAction(clear);
    menu->addAction(dock->toggleViewAction());
    QToolBar* bar = addToolBar(tr("Selection"));
    bar->setObjectName(QStringLiteral("selectionToolBar"));
    bar->addAction(nextInconsistentAction_);
}

void MainWindow::createLayout() {
    sceneView_ = new SceneView3D(this);
    sceneView_->setToolTip(tr("3D view: drag to orbit (left), pan (middle, shift+left), zoom "
                              "(right, wheel). Faces: yellow front, blue back (by VBO: green "
                              "undefined); curves red. Coloured by a scalar field: blue "
                              "negative, red positive, grey NaN; curves black. Overlays: see "
                              "the Overlays tool bar."));
    imageView_ = new ImageView2D(this);
    splitter_ = new QSplitter(Qt::Horizontal, this);
    splitter_->addWidget(sceneView_);
    splitter_->addWidget(imageView_);
    domainView_ = new ParameterDomainView(this);
    domainView_->setVisible(false);
    splitter_->addWidget(domainView_);
    splitter_->setStretchFactor(0, 1);
    splitter_->setStretchFactor(1, 1);
    splitter_->setStretchFactor(2, 1);
    splitter_->setChildrenCollapsible(false);
    setCentralWidget(splitter_);

    methodPanel_ = new MethodPanel;
    stepper_ = new PhaseStepper;
    // A method with many parameters (the consistent one has ~25) scrolls its
    // form instead of squeezing the phase list.
    auto* form = new QScrollArea;
    form->setWidget(methodPanel_);
    form->setWidgetResizable(true);
    form->setFrameShape(QFrame::NoFrame);
    form->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    // As wide as the form needs next to the vertical scroll bar.
    const auto fitForm = [this, form] {
        form->setMinimumWidth(methodPanel_->minimumSizeHint().width() +
                              form->verticalScrollBar()->sizeHint().width());
    };
    fitForm();
    connect(methodPanel_, &MethodPanel::methodChanged, form, fitForm);
    auto* panel = new QSplitter(Qt::Vertical);
    panel->addWidget(form);
    panel->addWidget(stepper_);
    panel->setStretchFactor(0, 1);
    panel->setStretchFactor(1, 1);
    panel->setChildrenCollapsible(false);
    auto* dock = new QDockWidget(tr("Method"), this);
    dock->setObjectName(QStringLiteral("methodDock"));
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    dock->setWidget(panel);
    dock->setMinimumWidth(320);
    addDockWidget(Qt::LeftDockWidgetArea, dock);

    meshLabel_ = new QLabel(this);
    phaseLabel_ = new QLabel(this);
    busyBar_ = new QProgressBar(this);
    busyBar_->setObjectName(QStringLiteral("busyBar"));
    busyBar_->setRange(0, 0);
    busyBar_->setMaximumWidth(160);
    busyBar_->setVisible(false);
    statusBar()->addPermanentWidget(busyBar_);
    statusBar()->addPermanentWidget(phaseLabel_);
    statusBar()->addPermanentWidget(meshLabel_);
}

void MainWindow::createActions() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    openAction_ = file->addAction(tr("&Open mesh…"), this, &MainWindow::openFileDialog);
    openAction_->setShortcut(QKeySequence::Open);
    openAction_->setObjectName(QStringLiteral("openMesh"));
    openAction_->setIcon(resourceIcon(QStringLiteral("open")));
    keepOrientationAction_ = file->addAction(tr("&Keep file orientation"));
    keepOrientationAction_->setObjectName(QStringLiteral("keepFileOrientation"));
    keepOrientationAction_->setCheckable(true);
    keepOrientationAction_->setToolTip(
        tr("Use meshes as their files orient the faces. Unchecked, each closed component whose "
           "faces are oriented inward (negative signed volume) is flipped when the mesh is "
           "opened, since all its contours would read as hidden"));
    connect(keepOrientationAction_, &QAction::triggered, this, &MainWindow::reorientMesh);
    QAction* quitSeparator = file->addSeparator();
    QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
    quit->setObjectName(QStringLiteral("quit"));
    quit->setIcon(resourceIcon(QStringLiteral("quit")));
    quit->setShortcut(QKeySequence::Quit);
    // Sessions, diagnostic snapshot export, recent files (SessionController).
    sessions_ = new SessionController(this);
    sessions_->addFileActions(file, quitSeparator);

    QMenu* run = menuBar()->addMenu(tr("&Run"));
    stepAction_ = run->addAction(tr("&Step"), this, &MainWindow::stepPhase);
    stepAction_->setObjectName(QStringLiteral("step"));
    stepAction_->setIcon(resourceIcon(QStringLiteral("step")));
    stepAction_->setShortcut(Qt::Key_F10);
    stepAction_->setToolTip(tr("Run the next phase (F10)"));
    backAction_ = run->addAction(tr("&Back"), this, &MainWindow::stepBack);
    backAction_->setObjectName(QStringLiteral("back"));
    backAction_->setIcon(resourceIcon(QStringLiteral("back")));
    backAction_->setShortcut(QKeySequence(Qt::SHIFT | Qt::Key_F10));
    backAction_->setToolTip(tr("Drop the last phase result (Shift+F10)"));
    runAction_ = run->addAction(tr("Run to &end"), this, &MainWindow::runToEnd);
    runAction_->setObjectName(QStringLiteral("runToEnd"));
    runAction_->setIcon(resourceIcon(QStringLiteral("run-to-end")));
    runAction_->setShortcut(Qt::Key_F5);
    runAction_->setToolTip(tr("Run every remaining phase (F5)"));
    resetAction_ = run->addAction(tr("&Reset"), this, &MainWindow::resetPhases);
    resetAction_->setObjectName(QStringLiteral("reset"));
    resetAction_->setIcon(resourceIcon(QStringLiteral("reset")));
    resetAction_->setShortcut(QKeySequence(Qt::SHIFT | Qt::Key_F5));
    resetAction_->setToolTip(tr("Return to the input (Shift+F5)"));
    cancelAction_ = run->addAction(tr("&Cancel"), this, &MainWindow::cancelPhases);
    cancelAction_->setObjectName(QStringLiteral("cancel"));
    cancelAction_->setIcon(resourceIcon(QStringLiteral("cancel")));
    cancelAction_->setShortcut(Qt::Key_Escape);
    cancelAction_->setToolTip(tr("Stop the running phase; the last finished one stays (Esc)"));

    QMenu* view = menuBar()->addMenu(tr("&View"));
    viewMenu_ = view;
    cameraFromViewAction_ = view->addAction(tr("Set analysis &camera from this view"), this,
                                            &MainWindow::setAnalysisCameraFromView);
    cameraFromViewAction_->setObjectName(QStringLiteral("cameraFromView"));
    cameraFromViewAction_->setIcon(resourceIcon(QStringLiteral("camera-from-view")));
    cameraFromViewAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_K));
    cameraFromViewAction_->setToolTip(
        tr("Use the 3D view's camera as the analysis camera and run the phases again (Ctrl+K)"));
    viewToCameraAction_ = view->addAction(tr("&Look through the analysis camera"), this,
                                          &MainWindow::resetViewToAnalysisCamera);
    viewToCameraAction_->setObjectName(QStringLiteral("lookThroughCamera"));
    viewToCameraAction_->setIcon(resourceIcon(QStringLiteral("look-through-camera")));
    viewToCameraAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_L));
    view->addSeparator();
    cageAction_ = view->addAction(tr("Control &cage"));
    cageAction_->setObjectName(QStringLiteral("controlCage"));
    cageAction_->setIcon(resourceIcon(QStringLiteral("control-cage")));
    cageAction_->setCheckable(true);
    cageAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_C));
    cageAction_->setToolTip(tr("Draw the control cage as a wireframe in the 3D view"));
    connect(cageAction_, &QAction::toggled, sceneView_, &SceneView3D::setShowControlCage);
    cageAction_->setChecked(defaults_.toggle("overlay.control-cage", false));
    auto* layouts = new QActionGroup(this);
    const std::array<std::pair<QString, Qt::Key>, 3> layoutNames{
        {{tr("&Both views"), Qt::Key_0},
         {tr("&3D view only"), Qt::Key_1},
         {tr("&2D view only"), Qt::Key_2}}};
    const std::array<const char*, 3> layoutIcons{"layout-both", "layout-3d", "layout-2d"};
    for (std::size_t i = 0; i < layoutNames.size(); ++i) {
        QAction* a = view->addAction(layoutNames[i].first);
        a->setIcon(resourceIcon(QString::fromLatin1(layoutIcons[i])));
        a->setObjectName(QString::fromLatin1(layoutIcons[i]));
        a->setCheckable(true);
        a->setShortcut(QKeySequence(Qt::CTRL | layoutNames[i].second));
        layouts->addAction(a);
        connect(a, &QAction::triggered, this,
                [this, i] { setViewLayout(static_cast<ViewLayout>(i)); });
        layoutActions_[i] = a;
    }
    layoutActions_[0]->setChecked(true);
    view->addSeparator();

    QToolBar* tools = addToolBar(tr("Phases"));
    tools->setObjectName(QStringLiteral("phaseToolBar"));
    tools->addAction(openAction_);
    tools->addSeparator();
    tools->addAction(resetAction_);
    tools->addAction(backAction_);
    tools->addAction(stepAction_);
    tools->addAction(runAction_);
    tools->addAction(cancelAction_);
    tools->addSeparator();
    tools->addAction(cameraFromViewAction_);
    tools->addAction(viewToCameraAction_);

    QToolBar* display = addToolBar(tr("Display"));
    display->setObjectName(QStringLiteral("displayToolBar"));
    auto* colorLabel = new QLabel(tr(" Colour by: "), display);
    colorSelector_ = new QComboBox(display);
    colorSelector_->setObjectName(QStringLiteral("colorBySelector"));
    // Wide enough for "radial curvature κr", so the tool bar does not jump.
    colorSelector_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    colorSelector_->setMinimumContentsLength(22);
    colorSelector_->setToolTip(
        tr("What the 3D view colours the surface by: front/back faces (by facing, or by the "
           "consistent method's vertex-based orientation, VBO), or a signed scalar field "
           "of the current phase on a symmetric blue-white-red map centred on 0 (range ±m, m = "
           "98th percentile of |value|; NaN grey)"));
    colorLabel->setBuddy(colorSelector_);
    display->addWidget(colorLabel);
    display->addWidget(colorSelector_);
    // Shown in the right dock (createDisplayDock).
    colorLegend_ = new QLabel;
    colorLegend_->setObjectName(QStringLiteral("colorLegend"));
    colorLegend_->setTextFormat(Qt::RichText);
    colorLegend_->setContentsMargins(8, 0, 8, 0);
    createCompareSelector(display);

    createOverlayActions(view);

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    QAction* about =
        help->addAction(tr("&About Contour Workbench…"), this, [this] { showAboutDialog(this); });
    about->setObjectName(QStringLiteral("about"));
    about->setIcon(resourceIcon(QStringLiteral("about")));
}

void MainWindow::createOverlayActions(QMenu* viewMenu) {
    addToolBarBreak();
    overlayBar_ = addToolBar(tr("Overlays"));
    overlayBar_->setObjectName(QStringLiteral("overlayToolBar"));
    overlayBar_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    QMenu* menu = viewMenu->addMenu(tr("&Overlays"));
    for (const OverlayInfo& info : kOverlays) {
        auto* action =
            new QAction(resourceIcon(QString::fromLatin1(info.icon)), tr(info.name), this);
        action->setCheckable(true);
        action->setChecked(sceneView_->isOverlayEnabled(info.overlay));
        action->setToolTip(tr(info.toolTip));
        action->setStatusTip(tr(info.toolTip));
        const SceneOverlay overlay = info.overlay;
        connect(action, &QAction::toggled, this,
                [this, overlay](bool on) { sceneView_->setOverlayEnabled(overlay, on); });
        action->setChecked(defaults_.toggle(
            SessionController::overlayKey(static_cast<int>(overlay)).toStdString(), true));
        overlayActions_[static_cast<int>(overlay)] = action;
        overlayBar_->addAction(action);
        menu->addAction(action);
    }
    createViewGraphActions(menu);
    createGroundTruthAction(menu);
}

void MainWindow::createGroundTruthAction(QMenu* overlayMenu) {
    groundTruth_ = new GroundTruthComputation(this);
    groundTruthSeparator_ = overlayBar_->addSeparator();
    overlayMenu->addSeparator();
    groundTruthAction_ =
        new QAction(resourceIcon(QStringLiteral("ground-truth")), tr("Ground-truth contour"), this);
    groundTruthAction_->setObjectName(QStringLiteral("groundTruthContour"));
    groundTruthAction_->setCheckable(true);
    groundTruthAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_G));
    connect(groundTruthAction_, &QAction::toggled, this, &MainWindow::updateGroundTruthRequest);
    groundTruthAction_->setChecked(defaults_.toggle("overlay.ground-truth", false));
    overlayBar_->addAction(groundTruthAction_);
    overlayMenu->addAction(groundTruthAction_);
}

void MainWindow::createViewGraphActions(QMenu* overlayMenu) {
    viewGraphSeparator_ = overlayBar_->addSeparator();
    overlayMenu->addSeparator();
    for (int i = 0; i < kViewGraphToggleCount; ++i) {
        const ViewGraphToggleInfo& info = kViewGraphToggles[static_cast<size_t>(i)];
        const auto toggle = static_cast<ViewGraphToggle>(i);
        auto* action =
            new QAction(resourceIcon(QString::fromLatin1(info.icon)), tr(info.name), this);
        action->setCheckable(true);
        action->setChecked(info.checked);
        action->setToolTip(tr(info.toolTip));
        action->setStatusTip(tr(info.toolTip));
        connect(action, &QAction::toggled, this, [this, toggle](bool on) {
            switch (toggle) {
            case ViewGraphToggle::HiddenCurves:
                sceneView_->setShowHiddenCurves(on);
                imageView_->setShowHiddenCurves(on);
                break;
            case ViewGraphToggle::ColourByQi: {
                const ChainColoring coloring = on ? ChainColoring::ByQi : ChainColoring::ByChain;
                sceneView_->setChainColoring(coloring);
                imageView_->setChainColoring(coloring);
                break;
            }
            case ViewGraphToggle::Nodes:
                sceneView_->setShowViewGraphNodes(on);
                imageView_->setShowNodes(on);
                break;
            case ViewGraphToggle::SimplifiedCurves:
                sceneView_->setShowSimplifiedCurves(on);
                imageView_->setShowSimplifiedCurves(on);
                break;
            }
            updateViewGraphLegend();
        });
        // The views' own defaults are info.checked; the defaults file may
        // change them through the action.
        action->setChecked(
            defaults_.toggle(SessionController::viewGraphKey(i).toStdString(), info.checked));
        viewGraphActions_[static_cast<size_t>(i)] = action;
        overlayBar_->addAction(action);
        overlayMenu->addAction(action);
    }
    viewGraphLegend_ = new QLabel; // shown in the right dock (createDisplayDock)
    viewGraphLegend_->setObjectName(QStringLiteral("viewGraphLegend"));
    viewGraphLegend_->setTextFormat(Qt::RichText);
    viewGraphLegend_->setContentsMargins(8, 0, 8, 0);
    viewGraphLegend_->setToolTip(tr("3D view: chain colours by QI and node dot colours by type "
                                    "(the 2D view draws its own legend)"));
}

void MainWindow::createDisplayDock() {
    // The overlay toggles and the legends in the right dock
    // under the inspector (the tool bars keep the toggles for quick access;
    // the actions are shared, so both stay in step).
    auto* dock = new QDockWidget(tr("Overlays and legends"), this);
    dock->setObjectName(QStringLiteral("displayDock"));
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                      QDockWidget::DockWidgetClosable);
    auto* content = new QWidget(dock);
    auto* layout = new QVBoxLayout(content);
    auto* toggles = new QToolBar(content);
    toggles->setObjectName(QStringLiteral("displayDockToggles"));
    toggles->setOrientation(Qt::Vertical);
    toggles->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    for (QAction* action : overlayActions_)
        toggles->addAction(action);
    for (QAction* action : viewGraphActions_)
        toggles->addAction(action);
    toggles->addAction(groundTruthAction_);
    toggles->addAction(cageAction_);
    layout->addWidget(toggles);
    for (QLabel* legend : {colorLegend_, viewGraphLegend_}) {
        legend->setParent(content);
        legend->setWordWrap(true);
        layout->addWidget(legend);
    }
    layout->addStretch(1);
    dock->setWidget(content);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* inspector = findChild<QDockWidget*>(QStringLiteral("inspectorDock")))
        splitDockWidget(inspector, dock, Qt::Vertical);
    viewMenu_->addAction(dock->toggleViewAction());
}

void MainWindow::updateViewGraphLegend() {
    if (!viewGraphLegend_)
        return;
    QStringList entries;
    const Snapshot& snapshot = sceneView_->snapshot();
    if (sceneView_->hasViewGraph() && snapshot.viewGraph) {
        const ViewGraph& graph = *snapshot.viewGraph;
        if (sceneView_->chainColoring() == ChainColoring::ByQi) {
            entries << swatch(sceneView_->showsScalarField() ? sceneColors::kContourOverField
                                                             : sceneColors::kContour3D,
                              tr("QI 0"));
            if (sceneView_->showsHiddenCurves())
                entries << swatch(viewGraphColors::kHiddenQi[0], tr("1"))
                        << swatch(viewGraphColors::kHiddenQi[1], tr("2"))
                        << swatch(viewGraphColors::kHiddenQi[2], tr("3+"));
        }
        if (sceneView_->showsViewGraphNodes()) {
            std::array<int, kViewNodeTypeCount> counts{};
            for (const ViewNode& node : graph.nodes)
                ++counts[static_cast<size_t>(node.type)];
            for (int t = 0; t < kViewNodeTypeCount; ++t)
                if (counts[static_cast<size_t>(t)] > 0)
                    entries
                        << QStringLiteral("<span style=\"color:%1\">&#9679;</span>&nbsp;%2")
                               .arg(nodeStyle(static_cast<ViewNodeType>(t)).color.toQColor().name(),
                                    tr(nodeStyle(static_cast<ViewNodeType>(t)).label));
        }
    }
    viewGraphLegend_->setText(entries.join(QStringLiteral("<br>")));
}

void MainWindow::updateOverlayActions() {
    bool any = false;
    for (int i = 0; i < kSceneOverlayCount; ++i) {
        const bool available = sceneView_->isOverlayAvailable(static_cast<SceneOverlay>(i));
        overlayActions_[i]->setVisible(available);
        any |= available;
    }
    const bool graph = sceneView_->hasViewGraph();
    for (QAction* action : viewGraphActions_)
        action->setVisible(graph);
    viewGraphSeparator_->setVisible(graph);
    viewGraphLegend_->setVisible(graph);
    any |= graph;
    // The ground-truth toggle is there for any mesh (disabled without a
    // smooth surface, saying why).
    const bool mesh = run_->input().has_value();
    groundTruthAction_->setVisible(mesh);
    groundTruthSeparator_->setVisible(mesh && any);
    any |= mesh;
    updateViewGraphLegend();
    // The bar only takes room when it has something to offer.
    overlayBar_->setVisible(any);
}

void MainWindow::updateColorLegend() {
    const std::string& field = sceneView_->displayedColorField();
    QStringList entries;
    if (field == fields::kVbo) {
        entries << swatch(sceneColors::kFrontFace, tr("F"))
                << swatch(sceneColors::kBackFace, tr("B"))
                << swatch(sceneColors::kUndefinedVbo, tr("undefined"));
    } else if (field == fields::kFacing && sceneView_->showsFacing()) {
        entries << swatch(sceneColors::kFrontFace, tr("front"))
                << swatch(sceneColors::kBackFace, tr("back"));
    }
    colorLegend_->setText(entries.join(QStringLiteral("<br>")));
    // Visible chains coloured by QI follow the curves' colour (black over a
    // scalar field).
    updateViewGraphLegend();
}

void MainWindow::openFileDialog() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open mesh"), QFileInfo(meshName_).absolutePath(),
        tr("Meshes (*.obj *.off *.ply *.OBJ *.OFF *.PLY);;All files (*)"));
    if (!path.isEmpty())
        openMesh(path);
}

MainWindow::LoadedMesh MainWindow::readMeshFile(const QString& path, bool keepFileOrientation) {
    OrientationReport report;
    LoadedMesh loaded;
    loaded.mesh = std::make_shared<const PolygonMesh>(
        orientForContours(readMesh(path.toStdString()), keepFileOrientation, report));
    loaded.keptFileOrientation = keepFileOrientation;
    loaded.inwardComponents = report.inwardCount();
    loaded.orientation = QString::fromStdString(
        orientationMessage(report, tr("File › Keep file orientation").toStdString()));
    return loaded;
}

QString MainWindow::meshOrientationMessage() const {
    if (meshOrientation_.orientation.isEmpty())
        return {};
    return QFileInfo(meshName_).fileName() + QStringLiteral(": ") + meshOrientation_.orientation;
}

bool MainWindow::openMesh(const QString& path) {
    LoadedMesh loaded;
    QApplication::setOverrideCursor(Qt::WaitCursor);
    try {
        loaded = readMeshFile(path, keepOrientationAction_->isChecked());
    } catch (const MeshError& e) {
        QApplication::restoreOverrideCursor();
        showError(tr("Cannot open mesh"), QString::fromStdString(e.what()));
        return false;
    } catch (const std::exception& e) {
        QApplication::restoreOverrideCursor();
        showError(tr("Cannot open mesh"),
                  QStringLiteral("%1: %2").arg(path, QString::fromStdString(e.what())));
        return false;
    }
    QApplication::restoreOverrideCursor();
    if (!installMesh(loaded, path))
        return false;
    sessions_->noteRecentFile(path);
    return true;
}

bool MainWindow::setMesh(std::shared_ptr<const PolygonMesh> mesh, const QString& name) {
    LoadedMesh loaded;
    loaded.mesh = std::move(mesh);
    loaded.keptFileOrientation = true; // in memory: used as it is
    return installMesh(loaded, name);
}

bool MainWindow::installMesh(const LoadedMesh& loaded, const QString& name) {
    const std::shared_ptr<const PolygonMesh>& mesh = loaded.mesh;
    if (!mesh) {
        showError(tr("Cannot open mesh"), tr("%1: no mesh").arg(name));
        return false;
    }
    Snapshot input;
    try {
        input = makeInputSnapshot(mesh);
    } catch (const std::exception& e) {
        showError(tr("Cannot open mesh"),
                  QStringLiteral("%1: %2").arg(name, QString::fromStdString(e.what())));
        return false;
    }
    const BoundingBox box = mesh->boundingBox();
    if (box.isEmpty() || input.mesh->faceCount() == 0) {
        showError(tr("Cannot open mesh"), tr("%1: the mesh has no faces").arg(name));
        return false;
    }
    cage_ = mesh;
    meshName_ = name;
    meshOrientation_ = loaded;
    meshOrientation_.mesh.reset();
    const QString orientation = meshOrientationMessage();
    if (!orientation.isEmpty())
        input.notes.push_back(orientation.toStdString());
    run_->setInput(std::move(input));

    Viewport viewport = defaults_.fallbackViewport;
    const double ratio = sceneView_->devicePixelRatioF();
    if (sceneView_->isVisible() && sceneView_->width() >= 16 && sceneView_->height() >= 16)
        viewport = {static_cast<int>(sceneView_->width() * ratio),
                    static_cast<int>(sceneView_->height() * ratio)};
    const Camera camera = Camera::framing(box, defaults_.viewDirection, viewport);
    run_->setCamera(camera);
    sceneView_->setViewCamera(camera);
    setWindowTitle(tr("%1 — Contour Workbench").arg(QFileInfo(name).fileName()));
    lastError_.clear();
    statusBar()->clearMessage();
    rebuildRunner(-1);
    // A flipped (or kept inward) mesh changes what every method shows: said
    // until the next message. Undecidable orientations only for a while.
    if (!orientation.isEmpty())
        statusBar()->showMessage(orientation, loaded.inwardComponents > 0 ? 0 : 8000);
    return true;
}

void MainWindow::reorientMesh() {
    const bool keep = keepOrientationAction_->isChecked();
    if (!cage_ || meshOrientation_.keptFileOrientation == keep ||
        meshOrientation_.inwardComponents == 0 || !QFileInfo(meshName_).isFile())
        return; // the open mesh would not change
    LoadedMesh loaded;
    try {
        loaded = readMeshFile(meshName_, keep);
    } catch (const std::exception& e) {
        showError(tr("Cannot open mesh"), QString::fromStdString(e.what()));
        return;
    }
    const std::optional<Camera> camera = run_->camera();
    const Camera viewCamera = sceneView_->viewCamera();
    const int phases = run_->hasRunner() ? run_->reachedPhases() : -1;
    if (!camera ||
        !restoreRun(loaded, meshName_, methodName(), methodPanel_->parameters(), *camera, phases))
        return;
    sceneView_->setViewCamera(viewCamera);
}

QString MainWindow::methodName() const {
    return methodPanel_->methodName();
}

bool MainWindow::setMethod(const QString& name) {
    if (name == methodName())
        return findMethod(name.toStdString()) != nullptr;
    return methodPanel_->setMethod(name); // methodChanged re-creates the runner
}

void MainWindow::rebuildRunner(int completed) {
    run_->setMethod(methodPanel_->method());
    run_->setParameters(methodPanel_->parameters());
    if (restoring_)
        return; // restoreRun() rebuilds once, at the end
    comparison_->setPrimary(run_->input(), run_->camera(), methodPanel_->parameters());
    updateGroundTruthRequest();
    stepper_->setMethod(methodPanel_->method());
    run_->restart(completed);
    updateActions();
    updateStatus();
}

void MainWindow::stepPhase() {
    run_->step();
}

void MainWindow::runToEnd() {
    run_->runToEnd();
}

void MainWindow::runToPhase(int completed) {
    run_->runTo(completed);
}

void MainWindow::stepBack() {
    run_->back();
}

void MainWindow::resetPhases() {
    run_->reset();
}

void MainWindow::setAnalysisCameraFromView() {
    if (!run_->input())
        return;
    const int reached = run_->hasRunner() ? run_->reachedPhases() : -1;
    Camera camera = sceneView_->viewCamera();
    if (const std::string problem = camera.validate(); !problem.empty()) {
        showError(tr("Cannot use this view"), QString::fromStdString(problem));
        return;
    }
    run_->setCamera(camera);
    rebuildRunner(reached);
}

void MainWindow::resetViewToAnalysisCamera() {
    if (run_->camera())
        sceneView_->setViewCamera(*run_->camera());
}

void MainWindow::onBusyChanged(bool busy) {
    if (busy)
        stepper_->setBusy(true, run_->runningPhase());
    else
        stepper_->setBusy(false);
    updateActions();
    updateStatus();
}

void MainWindow::onProgress(int phase, double fraction) {
    stepper_->setBusy(true, phase);
    const Method* method = run_->method();
    const QString name =
        method && phase >= 0 && phase < static_cast<int>(method->phases.size())
            ? QString::fromStdString(method->phases[static_cast<size_t>(phase)].name)
            : QString();
    if (!name.isEmpty())
        phaseLabel_->setText(tr("running %1…").arg(name));
    // A phase that reports how far it is fills the bar; until it does (and
    // for phases that never do) the bar is busy without a fraction.
    if (fraction > 0.0) {
        busyBar_->setRange(0, kBusyBarSteps);
        busyBar_->setValue(static_cast<int>(std::lround(std::min(fraction, 1.0) * kBusyBarSteps)));
        busyBar_->setFormat(name.isEmpty() ? QStringLiteral("%p%") : name + QStringLiteral(" %p%"));
        busyBar_->setTextVisible(true);
    } else {
        busyBar_->setRange(0, 0);
        busyBar_->setTextVisible(false);
    }
}

void MainWindow::onRunIdle() {
    updateActions();
    updateStatus();
    emit idle();
}

bool MainWindow::waitForIdle(int timeoutMs) {
    return run_->waitForIdle(timeoutMs);
}

int MainWindow::completedPhases() const {
    return run_->completedPhases();
}

Snapshot MainWindow::currentSnapshot() const {
    return run_->currentSnapshot();
}

void MainWindow::showRunnerState() {
    const Runner* runner = run_->runner();
    if (!runner) {
        if (run_->isBusy())
            return;
        if (const std::optional<Snapshot>& input = run_->input()) {
            sceneView_->setSnapshot(*input);
            if (const std::optional<Camera>& camera = run_->camera()) {
                sceneView_->setAnalysisCamera(*camera);
                imageView_->setScene(*input, *camera);
            }
        } else {
            sceneView_->clearScene();
            imageView_->clearScene();
        }
        domainView_->clearScene();
        domainView_->setVisible(false);
        domainViewMethod_ = nullptr;
        stepper_->setSnapshots({});
        updateColorLegend();
        return;
    }
    const Snapshot& snapshot = runner->current();
    sceneView_->setAnalysisCamera(runner->camera());
    sceneView_->setSnapshot(snapshot);
    imageView_->setScene(snapshot, runner->camera());
    domainView_->setSnapshot(snapshot);
    if (domainView_->hasLayout() && domainView_->isHidden()) {
        // Appearing: the three views share the width.
        domainView_->setVisible(true);
        const int third = std::max(1, splitter_->width() / 3);
        splitter_->setSizes({third, third, third});
        domainViewMethod_ = &runner->method();
    } else if (!domainView_->hasLayout() && domainViewMethod_ != &runner->method()) {
        // Only another method hides it: the phases before the layout of the
        // method that has one (a new camera re-runs from the first) keep
        // the view in place, saying there is no layout yet, instead of
        // re-laying out the window twice per run.
        domainView_->setVisible(false);
        domainViewMethod_ = nullptr;
    }
    stepper_->setSnapshots(runner->snapshots());
    // Facing appears with its phase without the selector's list changing.
    updateColorLegend();
    updateComparison();
    updateActions();
    updateStatus();
}

void MainWindow::setViewLayout(ViewLayout layout) {
    sceneView_->setVisible(layout != ViewLayout::ImageOnly);
    imageView_->setVisible(layout != ViewLayout::SceneOnly);
    layoutActions_[static_cast<std::size_t>(layout)]->setChecked(true);
}

MainWindow::ViewLayout MainWindow::viewLayout() const {
    if (sceneView_->isHidden())
        return ViewLayout::ImageOnly;
    return imageView_->isHidden() ? ViewLayout::SceneOnly : ViewLayout::Both;
}

void MainWindow::createCompareSelector(QToolBar* toolBar) {
    comparison_ = new MethodComparison(this);
    auto* label = new QLabel(tr(" Compare with: "), toolBar);
    compareSelector_ = new QComboBox(toolBar);
    compareSelector_->setObjectName(QStringLiteral("compareSelector"));
    compareSelector_->setToolTip(
        tr("Runs a second method on the same mesh and analysis camera (with the parameters the "
           "two methods share) and overlays its curves in the 2D view: its curves thin blue, "
           "the parts only the window's method draws under red, the parts only the other "
           "draws under blue (farther than 2 px from any curve of the other)"));
    compareSelector_->addItem(tr("nothing"), QString());
    for (const Method& m : contourMethods())
        compareSelector_->addItem(QString::fromStdString(m.label), QString::fromStdString(m.name));
    label->setBuddy(compareSelector_);
    toolBar->addWidget(label);
    toolBar->addWidget(compareSelector_);
    connect(compareSelector_, &QComboBox::currentIndexChanged, this, [this](int index) {
        comparison_->setOtherMethod(compareSelector_->itemData(index).toString());
        comparison_->setPrimary(run_->input(), run_->camera(), methodPanel_->parameters());
    });
}

bool MainWindow::setComparisonMethod(const QString& name) {
    const int index = compareSelector_->findData(name);
    if (index < 0)
        return false;
    compareSelector_->setCurrentIndex(index);
    return true;
}

void MainWindow::updateComparison() {
    const QString other = comparison_->otherMethod();
    if (other.isEmpty() || !run_->camera()) {
        imageView_->clearComparison();
        return;
    }
    const Method* otherMethod = findMethod(other.toStdString());
    const QString otherLabel = otherMethod ? QString::fromStdString(otherMethod->label) : other;
    if (run_->isBusy())
        return; // shown when the phase job ends (showRunnerState)
    if (comparison_->isRunning()) {
        statusBar()->showMessage(tr("Running %1 for the comparison…").arg(otherLabel), 5000);
        return;
    }
    if (!comparison_->error().isEmpty() || !comparison_->result()) {
        imageView_->clearComparison();
        statusBar()->showMessage(
            tr("Comparison with %1 failed: %2").arg(otherLabel, comparison_->error()));
        return;
    }
    const Camera& camera = run_->runner() ? run_->runner()->camera() : *run_->camera();
    const std::vector<ImagePolyline> here = drawnCurves(currentSnapshot(), camera);
    const std::vector<ImagePolyline> there = drawnCurves(*comparison_->result(), camera);
    // Short registry names ("consistent"): the 2D view's legend is narrow.
    const Method* method = methodPanel_->method();
    const double tolerance = defaults_.comparisonTolerancePixels;
    imageView_->setComparison(method ? QString::fromStdString(method->name) : tr("this method"),
                              other, there, compareCurves(here, there, tolerance));
    // The distance field along this method's curves to the other's, up to
    // ten tolerances, and the cusps and T-junctions only one side draws.
    imageView_->setComparisonDetail(
        distanceAlongCurves(here, there, 10.0 * tolerance, 0.5 * tolerance),
        compareNodes(drawnNodes(currentSnapshot(), camera),
                     drawnNodes(*comparison_->result(), camera), 2.0 * tolerance));
}

void MainWindow::updateGroundTruthRequest() {
    // What the toggle can compute for: the smooth surface the method's
    // `surface` parameter selects for the open cage, seen by the analysis
    // camera.
    std::optional<GroundTruthRequest> request;
    QString unavailable;
    const Method* method = methodPanel_->method();
    const ParameterSet parameters = methodPanel_->parameters();
    const std::optional<Snapshot>& input = run_->input();
    if (!method || !input || !input->cage || !run_->camera()) {
        unavailable = tr("Open a mesh first");
    } else if (!parameters.has("surface")) {
        unavailable = tr("%1 has no smooth surface to compare with")
                          .arg(QString::fromStdString(method->label));
    } else {
        try {
            if (const std::optional<SurfaceKind> kind =
                    selectedSurfaceKind(parameters, *input->cage))
                request = GroundTruthRequest{input->cage, *kind, *run_->camera(),
                                             parameters.has("t-junction-min-loop")
                                                 ? parameters.getDouble("t-junction-min-loop")
                                                 : 0.0};
            else
                unavailable = tr("The ground truth is the contour of a smooth surface, and %1 "
                                 "runs on the triangulated cage (surface = none): choose a smooth "
                                 "surface in the method's parameters to compare with it")
                                  .arg(QString::fromStdString(method->label));
        } catch (const std::exception& e) {
            unavailable = QString::fromStdString(e.what());
        }
    }
    groundTruthAction_->setEnabled(request.has_value());
    const QString tip =
        request ? tr("Compute the dense ground truth of the smooth contour for the analysis "
                     "camera in the background (g = 0 on an N × N lattice per domain face of the "
                     "smooth surface, sharing no code with the methods; cusps where the radial "
                     "curvature changes sign) and draw it over both views: thin teal loops, "
                     "visible or not, cusps as small rings (Ctrl+Shift+G)")
                : unavailable;
    groundTruthAction_->setToolTip(tip);
    groundTruthAction_->setStatusTip(tip);
    groundTruth_->setRequest(groundTruthAction_->isChecked() ? request : std::nullopt);
    updateOverlayActions(); // the toggle shows once a mesh is open
}

void MainWindow::showGroundTruth() {
    const std::optional<GroundTruthResult>& result = groundTruth_->result();
    const std::optional<GroundTruthRequest>& request = groundTruth_->request();
    // Drawn only for the camera the views project with.
    if (!result || !request || request->camera != run_->camera()) {
        imageView_->clearGroundTruth();
        sceneView_->clearGroundTruth();
        if (groundTruth_->isRunning())
            statusBar()->showMessage(tr("Computing the ground truth of the smooth contour…"));
        else if (!groundTruth_->error().isEmpty())
            statusBar()->showMessage(tr("Ground truth failed: %1").arg(groundTruth_->error()));
        else if (statusBar()->currentMessage().startsWith(tr("Computing the ground truth")))
            statusBar()->clearMessage();
        return;
    }
    imageView_->setGroundTruth(result->truth, result->imageCrossings);
    sceneView_->setGroundTruth(result->truth);
    const QString sampling =
        result->samplingReused
            ? tr("lattice reused")
            : tr("lattice sampled in %1 s").arg(result->samplingSeconds, 0, 'f', 2);
    statusBar()->showMessage(
        tr("Ground truth (N = %1, %2 M lattice points on %3 domain faces): %4 loops, %5 cusps, "
           "%6 crossings in %7 s (%8, contour %9 s)")
            .arg(result->samples)
            .arg(static_cast<double>(result->latticePoints) / 1e6, 0, 'f', 1)
            .arg(result->domainFaces)
            .arg(result->truth->loops.size())
            .arg(result->truth->cusps.size())
            .arg(result->imageCrossings)
            .arg(result->totalSeconds, 0, 'f', 2)
            .arg(sampling)
            .arg(result->contourSeconds + result->crossingSeconds, 0, 'f', 2));
}

bool MainWindow::setColorField(const QString& field) {
    sceneView_->setColorField(field.toStdString());
    return sceneView_->displayedColorField() == sceneView_->colorField();
}

QString MainWindow::colorField() const {
    return QString::fromStdString(sceneView_->displayedColorField());
}

void MainWindow::updateColorSelector() {
    updatingColorSelector_ = true;
    std::vector<std::string> names{fields::kFacing};
    const std::vector<std::string>& labels = sceneView_->labelFields();
    names.insert(names.end(), labels.begin(), labels.end());
    const std::vector<std::string>& scalars = sceneView_->scalarFields();
    names.insert(names.end(), scalars.begin(), scalars.end());
    const Snapshot& snapshot = sceneView_->snapshot();
    colorSelector_->clear();
    for (const std::string& name : names) {
        colorSelector_->addItem(QString::fromStdString(fieldDisplayName(name)),
                                QString::fromStdString(name));
        const Field* field = snapshot.field(name);
        if (field && !field->description.empty())
            colorSelector_->setItemData(colorSelector_->count() - 1,
                                        QString::fromStdString(field->description),
                                        Qt::ToolTipRole);
    }
    colorSelector_->setCurrentIndex(std::max(
        0, colorSelector_->findData(QString::fromStdString(sceneView_->displayedColorField()))));
    updatingColorSelector_ = false;
    updateColorLegend();
}

void MainWindow::onColorSelected(int index) {
    if (updatingColorSelector_ || index < 0)
        return;
    sceneView_->setColorField(colorSelector_->itemData(index).toString().toStdString());
}

void MainWindow::updateActions() {
    const Runner* runner = run_->runner(); // null while busy
    stepAction_->setEnabled(runner && !runner->atEnd());
    runAction_->setEnabled(runner && !runner->atEnd());
    backAction_->setEnabled(runner && runner->completedPhases() > 0);
    resetAction_->setEnabled(runner && runner->completedPhases() > 0);
    cameraFromViewAction_->setEnabled(run_->input().has_value());
    viewToCameraAction_->setEnabled(run_->camera().has_value());
    cancelAction_->setEnabled(run_->isBusy());
}

void MainWindow::updateStatus() {
    if (const std::optional<Snapshot>& input = run_->input()) {
        meshLabel_->setText(tr("%1 — %2 faces, %3 vertices")
                                .arg(QFileInfo(meshName_).fileName())
                                .arg(input->mesh->faceCount())
                                .arg(input->mesh->vertexCount()));
    } else {
        meshLabel_->setText(
            tr("no mesh — File > Open, drop a file, or pass one on the command line"));
    }
    busyBar_->setVisible(run_->isBusy());
    if (!run_->isBusy()) {
        busyBar_->setRange(0, 0);
        busyBar_->setTextVisible(false);
    }
    if (run_->isBusy()) {
        phaseLabel_->setText(run_->jobName() + QStringLiteral("…"));
        return;
    }
    const Runner* runner = run_->runner();
    if (!runner) {
        phaseLabel_->setText(QString());
        return;
    }
    const Snapshot& s = runner->current();
    QString text =
        tr("%1: %2 (%3/%4)")
            .arg(QString::fromStdString(runner->method().name), QString::fromStdString(s.phaseName))
            .arg(runner->completedPhases())
            .arg(runner->phaseCount());
    if (s.phaseIndex >= 0)
        text += tr(", %1 ms").arg(s.phaseSeconds * 1000.0, 0, 'f', 1);
    if (const long long violations = s.invariantViolations(); violations > 0)
        text += tr(", %1 post-condition violations").arg(violations);
    phaseLabel_->setText(text);
}

void MainWindow::showError(const QString& title, const QString& message) {
    lastError_ = message;
    statusBar()->showMessage(title + QStringLiteral(": ") + message);
    if (!interactive_)
        return;
    // Not exec(): a nested event loop must not run while the caller's state
    // is half-updated; the box is window-modal and deletes itself.
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    const QMimeData* mime = event->mimeData();
    if (mime->hasUrls() && !mime->urls().isEmpty() && mime->urls().first().isLocalFile())
        event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
    const QList<QUrl> urls = event->mimeData()->urls();
    if (urls.isEmpty() || !urls.first().isLocalFile())
        return;
    event->acceptProposedAction();
    const QString path = urls.first().toLocalFile();
    // Open after the drop returns, so the drag source is not kept waiting.
    QTimer::singleShot(0, this, [this, path] { openFile(path); });
}

void MainWindow::closeEvent(QCloseEvent* event) {
    run_->cancelAndWait();
    sessions_->saveWindowSettings();
    QMainWindow::closeEvent(event);
}

// ------------------------------------------------ sessions and snapshots

bool MainWindow::saveSession(const QString& path) {
    return sessions_->save(path);
}

bool MainWindow::openSession(const QString& path) {
    return sessions_->open(path);
}

bool MainWindow::openFile(const QString& path) {
    const QString suffix = QFileInfo(path).suffix().toLower();
    if (suffix == QLatin1String("cwsession") || suffix == QLatin1String("json"))
        return openSession(path);
    return openMesh(path);
}

bool MainWindow::exportDiagnosticSnapshot(const QString& folder) {
    const SnapshotExportResult result = contour::exportDiagnosticSnapshot(*this, folder);
    if (!result.ok()) {
        showError(tr("Cannot export the diagnostic snapshot"), result.error);
        return false;
    }
    lastError_.clear();
    statusBar()->showMessage(
        tr("Diagnostic snapshot: %1 files written to %2").arg(result.written.size()).arg(folder),
        8000);
    return true;
}

bool MainWindow::exportIllustrationSvg(const QString& path) {
    const Runner* r = runner();
    if (!r) {
        showError(tr("Cannot export the illustration"),
                  tr("Open a mesh and choose a method first"));
        return false;
    }
    IllustrationOptions options;
    options.title = QFileInfo(meshPath()).fileName().toStdString() + " - " + r->method().label +
                    ", after " + r->current().phaseName;
    options.drawHidden = imageView_->showsHiddenCurves();
    try {
        writeIllustrationSvg(path.toStdString(), r->current(), r->camera(), options);
    } catch (const std::exception& e) {
        showError(tr("Cannot export the illustration"), QString::fromStdString(e.what()));
        return false;
    }
    lastError_.clear();
    statusBar()->showMessage(tr("Illustration written to %1").arg(path), 8000);
    return true;
}

bool MainWindow::restoreRun(const LoadedMesh& mesh, const QString& name, const QString& method,
                            const ParameterSet& parameters, const Camera& camera, int phases) {
    if (!findMethod(method.toStdString())) {
        showError(tr("Cannot restore the run"),
                  tr("%1: method \"%2\" is not available").arg(name, method));
        return false;
    }
    if (const std::string problem = camera.validate(); !problem.empty()) {
        showError(tr("Cannot restore the run"), QString::fromStdString(problem));
        return false;
    }
    // The mesh and the method would each start a run: only the last
    // rebuildRunner() below does.
    restoring_ = true;
    const bool ok = installMesh(mesh, name) && setMethod(method);
    restoring_ = false;
    if (!ok)
        return false;
    methodPanel_->setParameters(parameters);
    run_->setCamera(camera);
    sceneView_->setViewCamera(camera);
    rebuildRunner(phases);
    return true;
}

void MainWindow::cancelPhases() {
    if (!run_->isBusy())
        return;
    run_->cancel();
    statusBar()->showMessage(tr("Cancelling…"));
}

} // namespace contour
