#include "SceneView3D.h"

#include "SceneColors.h"
#include "VtkCameraConversion.h"

#include <QMouseEvent>
#include <QTimer>
#include <QtConcurrent>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkInteractorObserver.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>

namespace contour {

SceneView3D::SceneView3D(QWidget* parent) : VtkOpenGLWidget(parent) {
    loadSceneColors();
    vtkRenderer* ren = renderer();
    ren->GradientBackgroundOn();
    ren->SetBackground(sceneColors::kBackgroundBottom.r, sceneColors::kBackgroundBottom.g,
                       sceneColors::kBackgroundBottom.b);
    ren->SetBackground2(sceneColors::kBackgroundTop.r, sceneColors::kBackgroundTop.g,
                        sceneColors::kBackgroundTop.b);
    ren->SetBackgroundAlpha(1.0);

    // Lines (the curves) are pulled towards the viewer and polygons pushed
    // away, so curves lying on the surface are not z-fought.
    vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();

    // What must be seen wherever it is goes on a second layer, which clears
    // the depth buffer and keeps the colours below.
    renderWindow()->SetNumberOfLayers(2);
    overlayRenderer_->SetLayer(1);
    overlayRenderer_->InteractiveOff();
    overlayRenderer_->SetActiveCamera(ren->GetActiveCamera());
    renderWindow()->AddRenderer(overlayRenderer_);
    for (const SceneLayer* layer : std::initializer_list<const SceneLayer*>{
             &coloring_, &motionCopy_, &curves_, &overlays_, &viewGraph_, &groundTruth_,
             &highlight_, &cage_, &frustum_})
        layer->addToRenderers(ren, overlayRenderer_);

    lodPool_.setMaxThreadCount(1);
    lodTimer_ = new QTimer(this);
    lodTimer_->setSingleShot(true);
    lodTimer_->setInterval(kLevelOfDetailDelayMs);
    connect(lodTimer_, &QTimer::timeout, this, &SceneView3D::requestMotionMesh);

    if (vtkInteractorObserver* style = interactor()->GetInteractorStyle()) {
        interactionObservers_ = {
            style->AddObserver(vtkCommand::StartInteractionEvent, this,
                               &SceneView3D::onInteraction),
            style->AddObserver(vtkCommand::EndInteractionEvent, this, &SceneView3D::onInteraction)};
    }
}

SceneView3D::~SceneView3D() {
    // A build still running only touches its own data; wait for it so that
    // no thread outlives the view.
    for (QFutureWatcher<MotionMesh>* watcher : findChildren<QFutureWatcher<MotionMesh>*>())
        watcher->disconnect(this);
    lodPool_.waitForDone();
    if (vtkInteractorObserver* style = interactor()->GetInteractorStyle())
        for (unsigned long tag : interactionObservers_)
            style->RemoveObserver(tag);
    renderWindow()->RemoveRenderer(overlayRenderer_);
}

// ------------------------------------------------------------- snapshot

void SceneView3D::setSnapshot(const Snapshot& snapshot) {
    if (!snapshot.mesh) {
        clearScene();
        return;
    }
    const std::vector<std::string> previousScalars = coloring_.scalarFields();
    const std::vector<std::string> previousLabels = coloring_.labelFields();
    const std::string previousField = coloring_.displayedColorField();
    std::array<bool, kSceneOverlayCount> wasAvailable{};
    for (int i = 0; i < kSceneOverlayCount; ++i)
        wasAvailable[static_cast<size_t>(i)] = overlays_.isAvailable(static_cast<SceneOverlay>(i));
    const bool hadGraph = viewGraph_.hasViewGraph();

    if (snapshot.mesh != mesh_) {
        mesh_ = snapshot.mesh;
        // The decimated copy of the previous mesh is of no use any more; the
        // new one is built once the window has been idle for a moment, so
        // that stepping through phases does not queue a build per phase.
        if (motionMeshWanted())
            lodTimer_->start();
        else
            lodTimer_->stop();
    }
    snapshot_ = snapshot;
    coloring_.update(snapshot);
    overlays_.setSurfaceNormals(coloring_.surfaceNormals());
    overlays_.update(snapshot);
    motionCopy_.update(snapshot);
    ++colourStamp_;
    curves_.update(snapshot);
    cage_.update(snapshot);
    viewGraph_.update(snapshot);
    groundTruth_.update(snapshot);
    syncContrast();
    highlight_.update(snapshot);
    frustum_.update(snapshot);
    updateMeshLevel();
    requestRender();

    bool overlaysChangedNow = hadGraph != viewGraph_.hasViewGraph();
    for (int i = 0; i < kSceneOverlayCount; ++i)
        overlaysChangedNow |= wasAvailable[static_cast<size_t>(i)] !=
                              overlays_.isAvailable(static_cast<SceneOverlay>(i));
    if (coloring_.displayedColorField() != previousField ||
        coloring_.scalarFields() != previousScalars || coloring_.labelFields() != previousLabels)
        emit colorFieldsChanged();
    if (overlaysChangedNow)
        emit overlaysChanged();
    emit snapshotChanged();
}

void SceneView3D::clearScene() {
    const bool hadFields = !coloring_.scalarFields().empty() || !coloring_.labelFields().empty() ||
                           coloring_.displayedColorField() != fields::kFacing;
    bool hadOverlays = viewGraph_.hasViewGraph();
    for (int i = 0; i < kSceneOverlayCount; ++i)
        hadOverlays |= overlays_.isAvailable(static_cast<SceneOverlay>(i));
    mesh_.reset();
    snapshot_ = Snapshot();
    lodTimer_->stop();
    for (SceneLayer* layer : std::initializer_list<SceneLayer*>{
             &coloring_, &motionCopy_, &curves_, &overlays_, &viewGraph_, &groundTruth_,
             &highlight_, &cage_, &frustum_})
        layer->update(snapshot_);
    motionCopy_.clearCopy();
    ++colourStamp_;
    syncContrast();
    updateMeshLevel();
    requestRender();
    if (hadFields)
        emit colorFieldsChanged();
    if (hadOverlays)
        emit overlaysChanged();
    emit snapshotChanged();
}

void SceneView3D::syncContrast() {
    curves_.setOverScalarField(coloring_.showsScalarField());
    viewGraph_.setOverScalarField(coloring_.showsScalarField());
}

// ------------------------------------------------------------- colouring

void SceneView3D::setColorField(const std::string& field) {
    const std::string previous = coloring_.displayedColorField();
    coloring_.setColorField(field);
    if (!meshShown())
        return;
    ++colourStamp_;
    syncContrast();
    updateMeshLevel(); // recolours the decimated copy if it is drawn
    requestRender();
    if (coloring_.displayedColorField() != previous)
        emit colorFieldsChanged();
}

bool SceneView3D::isScalarBarVisible() const {
    return meshShown() && coloring_.isScalarBarVisible();
}

std::string SceneView3D::scalarBarTitle() const {
    return coloring_.scalarBarTitle();
}

QRect SceneView3D::scalarBarRect() const {
    return isScalarBarVisible() ? coloring_.scalarBarRect(deviceSize()) : QRect();
}

long long SceneView3D::displayedFaceCount() const {
    if (showsLevelOfDetail())
        return motionCopy_.copyData()->GetNumberOfPolys();
    return coloring_.faceCount();
}

// -------------------------------------------------------------- overlays

void SceneView3D::setOverlayEnabled(SceneOverlay overlay, bool enabled) {
    overlays_.setEnabled(overlay, enabled);
    ++colourStamp_; // the radial tint is folded into the moving copy's colours
    updateMeshLevel();
    requestRender();
}

bool SceneView3D::isOverlayEnabled(SceneOverlay overlay) const {
    return overlays_.isEnabled(overlay);
}

bool SceneView3D::isOverlayAvailable(SceneOverlay overlay) const {
    return overlays_.isAvailable(overlay);
}

bool SceneView3D::isOverlayShown(SceneOverlay overlay) const {
    return overlays_.isShown(overlay) && meshShown();
}

long long SceneView3D::overlayElementCount(SceneOverlay overlay) const {
    return overlays_.elementCount(overlay);
}

vtkPolyData* SceneView3D::overlayData(SceneOverlay overlay) const {
    return overlays_.data(overlay);
}

// ------------------------------------------------------------ view graph

void SceneView3D::setShowHiddenCurves(bool show) {
    viewGraph_.setShowHiddenCurves(show);
    requestRender();
}

void SceneView3D::setShowSimplifiedCurves(bool show) {
    viewGraph_.setShowSimplifiedCurves(show);
    requestRender();
}

void SceneView3D::setShowViewGraphNodes(bool show) {
    viewGraph_.setShowNodes(show);
    requestRender();
}

void SceneView3D::setChainColoring(ChainColoring coloring) {
    viewGraph_.setChainColoring(coloring);
    requestRender();
}

long long SceneView3D::viewGraphChainsShown(ChainState state) const {
    return viewGraph_.chainsShown(state);
}

long long SceneView3D::viewGraphNodesShown() const {
    return viewGraph_.nodesShown();
}

vtkPolyData* SceneView3D::viewGraphChainData(ChainState state) const {
    return viewGraph_.chainData(state);
}

vtkPolyData* SceneView3D::viewGraphNodeData(bool hidden) const {
    return viewGraph_.nodeData(hidden);
}

// ---------------------------------------------------------- ground truth

void SceneView3D::setGroundTruth(std::shared_ptr<const GroundTruth> truth) {
    groundTruth_.setGroundTruth(std::move(truth));
    requestRender();
}

// ---------------------------------------------------------- control cage

void SceneView3D::setShowControlCage(bool show) {
    cage_.setShown(show);
    requestRender();
}

long long SceneView3D::controlCageEdgesShown() const {
    return cage_.edgesShown();
}

// --------------------------------------------------------------- cameras

void SceneView3D::setAnalysisCamera(const Camera& camera) {
    frustum_.setAnalysisCamera(camera);
    requestRender();
}

void SceneView3D::setViewCamera(const Camera& camera) {
    applyCameraToVtk(camera, renderer()->GetActiveCamera());
    renderer()->ResetCameraClippingRange();
    requestRender();
}

Camera SceneView3D::viewCamera() const {
    const double ratio = devicePixelRatioF();
    Viewport viewport{std::max(1, static_cast<int>(width() * ratio)),
                      std::max(1, static_cast<int>(height() * ratio))};
    return cameraFromVtk(renderer()->GetActiveCamera(), viewport);
}

void SceneView3D::orbit(double azimuthDegrees, double elevationDegrees) {
    vtkCamera* camera = renderer()->GetActiveCamera();
    camera->Azimuth(azimuthDegrees);
    camera->Elevation(elevationDegrees);
    camera->OrthogonalizeViewUp();
    renderer()->ResetCameraClippingRange();
    requestRender();
}

bool SceneView3D::viewMatchesAnalysisCamera() const {
    const std::optional<Camera>& analysis = frustum_.analysisCamera();
    return !analysis || sameView(viewCamera(), *analysis);
}

bool SceneView3D::isFrustumVisible() const {
    return frustum_.isShownFor(viewCamera());
}

void SceneView3D::beforeRender() {
    coloring_.placeScalarBar(deviceSize().height());
    frustum_.setViewCamera(viewCamera());
    renderer()->ResetCameraClippingRange();
    const bool matches = viewMatchesAnalysisCamera();
    if (matches != lastMatch_) {
        lastMatch_ = matches;
        // Queued: listeners must not re-enter the paint.
        QMetaObject::invokeMethod(
            this, [this, matches] { emit viewMatchChanged(matches); }, Qt::QueuedConnection);
    }
}

// ------------------------------------------------------------- selection

Selection SceneView3D::pick(const QPointF& position) const {
    if (!mesh_ || !meshShown())
        return {};
    const double ratio = devicePixelRatioF();
    const QSize size = deviceSize();
    const Vec2 click(position.x() * ratio, position.y() * ratio);
    renderer()->ResetCameraClippingRange();
    vtkNew<vtkCellPicker> picker;
    picker->SetTolerance(0.0);
    picker->PickFromListOn();
    picker->AddPickList(coloring_.meshActor());
    // VTK's display y goes up (VtkOpenGLWidget::setEventPosition flips it
    // the same way).
    if (!picker->Pick(click.x(), size.height() - 1 - click.y(), 0.0, renderer()))
        return {};
    const vtkIdType cell = picker->GetCellId();
    if (cell < 0 || cell >= static_cast<vtkIdType>(mesh_->faceCount()))
        return {};
    const Index f = static_cast<Index>(cell); // meshToPolyData keeps the face order
    // The face's corners in device pixels, as this view's camera sees them.
    const Camera camera = viewCamera();
    const Triangle& t = mesh_->triangle(f);
    std::array<Vec2, 3> corner;
    for (int i = 0; i < 3; ++i) {
        const ProjectedPoint p = camera.project(mesh_->position(t[i]));
        if (!(p.depth > 0.0) || !p.pixel.allFinite())
            return Selection::face(f);
        corner[static_cast<size_t>(i)] = p.pixel;
    }
    return pickWithinFace(*mesh_, f, corner, click, kPickVertexPixels * ratio,
                          kPickEdgePixels * ratio);
}

void SceneView3D::setHighlight(const Selection& selection) {
    highlight_.setSelection(selection);
    requestRender();
}

vtkPolyData* SceneView3D::highlightData() const {
    return highlight_.highlightData();
}

void SceneView3D::frameFace(Index face) {
    if (!mesh_ || face < 0 || face >= mesh_->faceCount())
        return;
    const Triangle& t = mesh_->triangle(face);
    const Vec3 centre =
        (mesh_->position(t[0]) + mesh_->position(t[1]) + mesh_->position(t[2])) / 3.0;
    double radius = 0.0;
    for (int i = 0; i < 3; ++i)
        radius = std::max(radius, (mesh_->position(t[i]) - centre).norm());
    if (!(radius > 0.0))
        radius = 1e-3 * mesh_->boundingBox().diagonal();
    // The face's radius becomes a sixth of the half-height of the view: the
    // face and a few rings of neighbours around it.
    constexpr double kFill = 6.0;
    vtkCamera* camera = renderer()->GetActiveCamera();
    double direction[3];
    camera->GetDirectionOfProjection(direction);
    double distance = camera->GetDistance();
    if (camera->GetParallelProjection())
        camera->SetParallelScale(kFill * radius);
    else
        distance =
            kFill * radius / std::tan(0.5 * camera->GetViewAngle() * std::numbers::pi / 180.0);
    camera->SetFocalPoint(centre.x(), centre.y(), centre.z());
    camera->SetPosition(centre.x() - distance * direction[0], centre.y() - distance * direction[1],
                        centre.z() - distance * direction[2]);
    renderer()->ResetCameraClippingRange();
    requestRender();
}

void SceneView3D::mousePressEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton) {
        leftPressed_ = true;
        pressPosition_ = event->position();
    }
    VtkOpenGLWidget::mousePressEvent(event);
}

void SceneView3D::mouseReleaseEvent(QMouseEvent* event) {
    VtkOpenGLWidget::mouseReleaseEvent(event);
    if (event->button() != Qt::LeftButton || !leftPressed_)
        return;
    leftPressed_ = false;
    if ((event->position() - pressPosition_).manhattanLength() <= kClickSlopPixels)
        emit pickRequested(pick(event->position()));
}

// ------------------------------------------- motion drawing, level of detail

void SceneView3D::setMotionDrawing(bool on) {
    if (on == motionDrawing_)
        return;
    motionDrawing_ = on;
    if (on) {
        stillStyles_.clear();
        for (vtkRenderer* r : {renderer(), overlayRenderer_.Get()}) {
            vtkActorCollection* actors = r->GetActors();
            actors->InitTraversal();
            while (vtkActor* actor = actors->GetNextActor()) {
                vtkProperty* p = actor->GetProperty();
                stillStyles_.push_back(
                    {p, p->GetLineWidth(), p->GetPointSize(), p->GetRenderPointsAsSpheres()});
                p->SetLineWidth(std::min(p->GetLineWidth(), 1.0f));
                p->SetPointSize(std::min(p->GetPointSize(), 3.0f));
                p->RenderPointsAsSpheresOff();
            }
        }
    } else {
        for (const SavedStyle& s : stillStyles_) {
            s.property->SetLineWidth(s.lineWidth);
            s.property->SetPointSize(s.pointSize);
            s.property->SetRenderPointsAsSpheres(s.spheres);
        }
        stillStyles_.clear();
    }
    // A drag on a mesh whose copy is not built yet (the idle delay has not
    // passed) starts the build now; the copy is shown when it arrives.
    if (on && motionMeshWanted())
        requestMotionMesh();
    overlays_.setMotionDrawing(on);
    updateMeshLevel();
    requestRender();
}

void SceneView3D::onInteraction(vtkObject*, unsigned long eventId, void*) {
    setMotionDrawing(eventId == vtkCommand::StartInteractionEvent);
}

void SceneView3D::setLevelOfDetail(bool enabled) {
    if (enabled == lodEnabled_)
        return;
    lodEnabled_ = enabled;
    if (enabled && motionMeshWanted())
        requestMotionMesh();
    updateMeshLevel();
    requestRender();
}

bool SceneView3D::motionMeshWanted() const {
    return lodEnabled_ && mesh_ && mesh_->faceCount() >= kLevelOfDetailMinFaces &&
           motionCopy_.copiedMesh() != mesh_ && lodPending_ != mesh_;
}

bool SceneView3D::levelOfDetailReady() const {
    return mesh_ && motionCopy_.isReady();
}

bool SceneView3D::showsLevelOfDetail() const {
    return motionCopy_.isShown();
}

long long SceneView3D::levelOfDetailFaceCount() const {
    return levelOfDetailReady() ? motionCopy_.faceCount() : 0;
}

double SceneView3D::levelOfDetailSeconds() const {
    return levelOfDetailReady() ? motionCopy_.buildSeconds() : 0.0;
}

void SceneView3D::requestMotionMesh() {
    lodTimer_->stop();
    if (!motionMeshWanted())
        return;
    std::shared_ptr<const TriangleMesh> mesh = mesh_;
    lodPending_ = mesh;
    auto* watcher = new QFutureWatcher<MotionMesh>(this);
    connect(watcher, &QFutureWatcher<MotionMesh>::finished, this, [this, watcher, mesh] {
        watcher->deleteLater();
        if (lodPending_ == mesh)
            lodPending_.reset();
        // A copy of a mesh no longer shown is dropped.
        MotionMesh result = watcher->result();
        if (mesh != mesh_ || !result.data)
            return;
        motionCopy_.setCopy(std::move(result), mesh);
        lodColourStamp_ = colourStamp_ - 1; // colour it before it is shown
        updateMeshLevel();
        if (showsLevelOfDetail())
            requestRender();
        emit levelOfDetailBuilt();
    });
    // A pool of one thread: the build never takes both cores from a
    // running method.
    watcher->setFuture(QtConcurrent::run(
        &lodPool_, [mesh] { return buildMotionMesh(*mesh, kLevelOfDetailFaces); }));
}

void SceneView3D::updateMeshLevel() {
    const bool lod = motionDrawing_ && lodEnabled_ && meshShown() && levelOfDetailReady();
    if (lod && lodColourStamp_ != colourStamp_) {
        lodColourStamp_ = colourStamp_;
        motionCopy_.recolour(coloring_, isOverlayEnabled(SceneOverlay::RadialFaces) &&
                                            isOverlayAvailable(SceneOverlay::RadialFaces));
    }
    coloring_.setStandIn(lod);
    motionCopy_.setShown(lod);
}

} // namespace contour
