#include "SceneView3D.h"

#include "FieldLabels.h"
#include "SnapshotToVtk.h"
#include "VtkCameraConversion.h"

#include <QFileInfo>
#include <QMouseEvent>
#include <QTimer>
#include <QtConcurrent>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkCoordinate.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkInteractorObserver.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

namespace contour {

namespace {

void setTableColor(vtkLookupTable* table, vtkIdType index, const SceneColor& color) {
    table->SetTableValue(index, color.r, color.g, color.b, 1.0);
}

void setColor(vtkProperty* property, const SceneColor& color) {
    property->SetColor(color.r, color.g, color.b);
}

// The name of the RGB colour arrays of the view graph layers.
constexpr const char* kViewGraphColorArray = "view_graph_colors";

void insertColor(vtkUnsignedCharArray* colors, const SceneColor& c, double scale = 1.0) {
    const auto byte = [scale](double v) {
        return static_cast<unsigned char>(std::clamp(v * scale, 0.0, 1.0) * 255.0 + 0.5);
    };
    colors->InsertNextTypedTuple(
        std::array<unsigned char, 3>{byte(c.r), byte(c.g), byte(c.b)}.data());
}

constexpr int kChainStateCount = 3;
// Line widths of visible, hidden and simplified chains (ChainState order).
constexpr std::array<float, kChainStateCount> kChainWidths{4.0f, 2.5f, 1.5f};
constexpr float kNodeDotSize = 12.0f;

// A system font with Greek letters for the scalar bar's title (κr), which
// VTK's embedded fonts may lack. Empty when there is none: the text then uses
// VTK's embedded Arial.
QString greekFontFile() {
    static const QString path = [] {
        for (const char* candidate :
             {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
              "/usr/share/fonts/TTF/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"})
            if (QFileInfo::exists(QString::fromLatin1(candidate)))
                return QString::fromLatin1(candidate);
        return QString();
    }();
    return path;
}

void setTextStyle(vtkTextProperty* text, int size) {
    const SceneColor& color = sceneColors::kScalarBarText;
    text->SetColor(color.r, color.g, color.b);
    text->SetFontSize(size);
    text->BoldOff();
    text->ItalicOff();
    text->ShadowOn();
    if (const QString font = greekFontFile(); !font.isEmpty()) {
        text->SetFontFamily(VTK_FONT_FILE);
        text->SetFontFile(font.toLocal8Bit().constData());
    }
}

// The scalar bar's box in normalized viewport coordinates: along the bottom,
// centred (a horizontal bar leaves room for a long title), at least
// kBarMarginPixels above the bottom edge so that the label of the NaN swatch,
// drawn below the bar, fits.
constexpr double kBarLeft = 0.18, kBarBottom = 0.03, kBarWidth = 0.64, kBarHeight = 0.14;
constexpr double kBarMarginPixels = 34.0;

double barBottom(int viewportHeight) {
    return std::max(kBarBottom, kBarMarginPixels / std::max(1, viewportHeight));
}

} // namespace

SceneView3D::SceneView3D(QWidget* parent) : VtkOpenGLWidget(parent) {
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

    // Facing -1, 0, +1 map to table entries 0, 1, 2.
    facingColors_->SetNumberOfTableValues(3);
    facingColors_->SetTableRange(-1.0, 1.0);
    facingColors_->Build();
    setTableColor(facingColors_, 0, sceneColors::kBackFace);
    setTableColor(facingColors_, 1, sceneColors::kEdgeOnFace);
    setTableColor(facingColors_, 2, sceneColors::kFrontFace);
    meshMapper_->SetLookupTable(facingColors_);
    meshMapper_->SetScalarModeToUseCellData();
    meshMapper_->SetColorModeToMapScalars();
    meshMapper_->UseLookupTableScalarRangeOn();
    meshMapper_->ScalarVisibilityOff();
    meshMapper_->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0);
    meshActor_->SetMapper(meshMapper_);
    vtkProperty* meshProperty = meshActor_->GetProperty();
    setColor(meshProperty, sceneColors::kUnclassifiedFace);
    // No specular highlight: shading then only scales a face's colour, so its
    // hue tells front from back everywhere.
    meshProperty->SetAmbient(0.3);
    meshProperty->SetDiffuse(0.7);
    meshProperty->SetSpecular(0.0);
    meshActor_->VisibilityOff();
    ren->AddActor(meshActor_);

    // The decimated copy drawn instead of the mesh while moving: the same
    // lighting and polygon offset, its colours per triangle (direct RGB).
    lodMapper_->SetScalarModeToUseCellData();
    lodMapper_->SetColorModeToDirectScalars();
    lodMapper_->ScalarVisibilityOn();
    lodMapper_->SetRelativeCoincidentTopologyPolygonOffsetParameters(8.0, 100.0);
    lodMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    lodActor_->SetMapper(lodMapper_);
    lodActor_->GetProperty()->DeepCopy(meshProperty);
    lodActor_->VisibilityOff();
    lodActor_->PickableOff();
    ren->AddActor(lodActor_);
    lodPool_.setMaxThreadCount(1);
    lodTimer_ = new QTimer(this);
    lodTimer_->setSingleShot(true);
    lodTimer_->setInterval(kLevelOfDetailDelayMs);
    connect(lodTimer_, &QTimer::timeout, this, &SceneView3D::requestMotionMesh);

    // CurveType 0 contour, 1 boundary, 2 surface intersection.
    curveColors_->SetNumberOfTableValues(3);
    curveColors_->SetTableRange(0.0, 2.0);
    curveColors_->Build();
    setTableColor(curveColors_, 0, sceneColors::kContour3D);
    setTableColor(curveColors_, 1, sceneColors::kBoundary);
    setTableColor(curveColors_, 2, sceneColors::kIntersection);
    curveMapper_->SetLookupTable(curveColors_);
    curveMapper_->SetScalarModeToUseCellData();
    curveMapper_->SetColorModeToMapScalars();
    curveMapper_->UseLookupTableScalarRangeOn();
    curveMapper_->ScalarVisibilityOn();
    curveMapper_->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
    // The same over a scalar field, whose map has red in it: black contours.
    curveColorsOverField_->SetNumberOfTableValues(3);
    curveColorsOverField_->SetTableRange(0.0, 2.0);
    curveColorsOverField_->Build();
    setTableColor(curveColorsOverField_, 0, sceneColors::kContourOverField);
    setTableColor(curveColorsOverField_, 1, sceneColors::kBoundary);
    setTableColor(curveColorsOverField_, 2, sceneColors::kIntersection);
    curveActor_->SetMapper(curveMapper_);
    curveActor_->GetProperty()->SetLineWidth(4.0f);
    curveActor_->GetProperty()->LightingOff();
    curveActor_->VisibilityOff();
    ren->AddActor(curveActor_);

    fillDivergingLookupTable(fieldColors_, 1.0);
    scalarBar_->SetLookupTable(fieldColors_);
    scalarBar_->SetOrientationToHorizontal();
    scalarBar_->SetNumberOfLabels(5); // -m, -m/2, 0, m/2, m
    scalarBar_->SetLabelFormat("%-#6.3g");
    scalarBar_->SetMaximumNumberOfColors(kDivergingTableSize);
    scalarBar_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    scalarBar_->GetPositionCoordinate()->SetValue(kBarLeft, kBarBottom);
    scalarBar_->GetPosition2Coordinate()->SetValue(kBarWidth, kBarHeight);
    scalarBar_->UnconstrainedFontSizeOn();
    scalarBar_->SetBarRatio(0.3);
    setTextStyle(scalarBar_->GetTitleTextProperty(), 16);
    setTextStyle(scalarBar_->GetLabelTextProperty(), 13);
    setTextStyle(scalarBar_->GetAnnotationTextProperty(), 13);
    scalarBar_->SetNanAnnotation("NaN");
    scalarBar_->DrawNanAnnotationOff();
    scalarBar_->PickableOff();
    scalarBar_->VisibilityOff();
    ren->AddActor2D(scalarBar_);

    // VBO -1, 0, +1 map to table entries 0, 1, 2: B, undefined, F.
    labelColors_->SetNumberOfTableValues(3);
    labelColors_->SetTableRange(-1.0, 1.0);
    labelColors_->Build();
    setTableColor(labelColors_, 0, sceneColors::kBackFace);
    setTableColor(labelColors_, 1, sceneColors::kUndefinedVbo);
    setTableColor(labelColors_, 2, sceneColors::kFrontFace);

    // Overlays. What must be seen wherever it is goes on a second layer,
    // which clears the depth buffer and keeps the colours below.
    renderWindow()->SetNumberOfLayers(2);
    overlayRenderer_->SetLayer(1);
    overlayRenderer_->InteractiveOff();
    overlayRenderer_->SetActiveCamera(ren->GetActiveCamera());
    renderWindow()->AddRenderer(overlayRenderer_);
    for (OverlayLayer& layer : overlays_) {
        layer.mapper->ScalarVisibilityOff();
        layer.actor->SetMapper(layer.mapper);
        layer.actor->VisibilityOff();
        layer.actor->PickableOff();
    }
    {
        OverlayLayer& outlines = overlays_[static_cast<int>(SceneOverlay::InconsistentFaces)];
        vtkProperty* property = outlines.actor->GetProperty();
        setColor(property, sceneColors::kInconsistentOutline);
        property->SetLineWidth(static_cast<float>(sceneColors::kInconsistentOutlineWidth));
        property->LightingOff();
        overlayRenderer_->AddActor(outlines.actor);
    }
    {
        // Standard radial 1 and other radial 0 map to table entries 1 and 0.
        radialColors_->SetNumberOfTableValues(2);
        radialColors_->SetTableRange(0.0, 1.0);
        radialColors_->Build();
        setTableColor(radialColors_, 0, sceneColors::kRadialTint);
        setTableColor(radialColors_, 1, sceneColors::kStandardRadialTint);
        OverlayLayer& tint = overlays_[static_cast<int>(SceneOverlay::RadialFaces)];
        tint.mapper->SetLookupTable(radialColors_);
        tint.mapper->SetScalarModeToUseCellData();
        tint.mapper->SetColorModeToMapScalars();
        tint.mapper->UseLookupTableScalarRangeOn();
        tint.mapper->ScalarVisibilityOn();
        // In front of the mesh (pushed back by 2, 4), behind the lines.
        tint.mapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(0.0, 0.0);
        vtkProperty* property = tint.actor->GetProperty();
        property->SetOpacity(sceneColors::kRadialTintOpacity);
        property->SetAmbient(0.3);
        property->SetDiffuse(0.7);
        property->SetSpecular(0.0);
        ren->AddActor(tint.actor);
    }
    {
        OverlayLayer& edges = overlays_[static_cast<int>(SceneOverlay::RadialEdges)];
        edges.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
        vtkProperty* property = edges.actor->GetProperty();
        setColor(property, sceneColors::kRadialEdge);
        property->SetLineWidth(static_cast<float>(sceneColors::kRadialEdgeWidth));
        property->LightingOff();
        ren->AddActor(edges.actor);
    }
    {
        // Round dots pulled in front of the curves they lie on.
        OverlayLayer& contour = overlays_[static_cast<int>(SceneOverlay::ContourVertices)];
        contour.mapper->SetRelativeCoincidentTopologyPointOffsetParameter(-120.0);
        vtkProperty* property = contour.actor->GetProperty();
        setColor(property, sceneColors::kContourVertex);
        property->SetPointSize(static_cast<float>(sceneColors::kContourVertexSize));
        property->RenderPointsAsSpheresOn();
        property->LightingOff();
        ren->AddActor(contour.actor);
    }
    {
        // Large squares: a different glyph from the C vertices' dots.
        OverlayLayer& cusps = overlays_[static_cast<int>(SceneOverlay::Cusps)];
        vtkProperty* property = cusps.actor->GetProperty();
        setColor(property, sceneColors::kCuspVertex);
        property->SetPointSize(static_cast<float>(sceneColors::kCuspVertexSize));
        property->LightingOff();
        overlayRenderer_->AddActor(cusps.actor);
    }

    // View graph: chains on the scene, depth-tested and pulled towards the
    // viewer like the curves; nodes over everything, like the cusps. Colours
    // are per cell (chains) or per point (nodes), set by recolourViewGraph().
    for (int i = 0; i < kChainStateCount; ++i) {
        ViewGraphLayer& layer = chainLayers_[static_cast<size_t>(i)];
        layer.mapper->SetScalarModeToUseCellData();
        layer.mapper->SetColorModeToDirectScalars();
        layer.mapper->ScalarVisibilityOn();
        layer.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
        layer.actor->SetMapper(layer.mapper);
        layer.actor->GetProperty()->SetLineWidth(kChainWidths[static_cast<size_t>(i)]);
        layer.actor->GetProperty()->LightingOff();
        layer.actor->VisibilityOff();
        layer.actor->PickableOff();
        ren->AddActor(layer.actor);
    }
    for (ViewGraphLayer& layer : nodeLayers_) {
        layer.mapper->SetScalarModeToUsePointData();
        layer.mapper->SetColorModeToDirectScalars();
        layer.mapper->ScalarVisibilityOn();
        layer.actor->SetMapper(layer.mapper);
        layer.actor->GetProperty()->SetPointSize(kNodeDotSize);
        layer.actor->GetProperty()->RenderPointsAsSpheresOn();
        layer.actor->GetProperty()->LightingOff();
        layer.actor->VisibilityOff();
        layer.actor->PickableOff();
    }
    overlayRenderer_->AddActor(nodeLayers_[0].actor);
    // Nodes on hidden chains only: with those chains, pulled in front of the
    // surface they lie on.
    nodeLayers_[1].mapper->SetRelativeCoincidentTopologyPointOffsetParameter(-120.0);
    ren->AddActor(nodeLayers_[1].actor);

    // The selection's highlight, over everything like the inconsistent
    // outlines.
    highlightActor_->SetMapper(highlightMapper_);
    highlightMapper_->ScalarVisibilityOff();
    setColor(highlightActor_->GetProperty(), sceneColors::kSelection);
    highlightActor_->GetProperty()->SetLineWidth(
        static_cast<float>(sceneColors::kSelectionLineWidth));
    highlightActor_->GetProperty()->SetPointSize(
        static_cast<float>(sceneColors::kSelectionPointSize));
    highlightActor_->GetProperty()->RenderPointsAsSpheresOn();
    highlightActor_->GetProperty()->LightingOff();
    highlightActor_->VisibilityOff();
    highlightActor_->PickableOff();
    overlayRenderer_->AddActor(highlightActor_);

    cageActor_->SetMapper(cageMapper_);
    setColor(cageActor_->GetProperty(), sceneColors::kControlCage);
    cageActor_->GetProperty()->SetLineWidth(1.0f);
    cageActor_->GetProperty()->LightingOff();
    cageActor_->VisibilityOff();
    cageActor_->PickableOff();
    ren->AddActor(cageActor_);

    if (vtkInteractorObserver* style = interactor()->GetInteractorStyle()) {
        interactionObservers_ = {
            style->AddObserver(vtkCommand::StartInteractionEvent, this,
                               &SceneView3D::onInteraction),
            style->AddObserver(vtkCommand::EndInteractionEvent, this, &SceneView3D::onInteraction)};
    }

    frustumActor_->SetMapper(frustumMapper_);
    setColor(frustumActor_->GetProperty(), sceneColors::kFrustum);
    frustumActor_->GetProperty()->SetLineWidth(1.5f);
    frustumActor_->GetProperty()->LightingOff();
    frustumActor_->VisibilityOff();
    frustumActor_->PickableOff();
    ren->AddActor(frustumActor_);
}

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
    if (on && lodEnabled_ && mesh_ && mesh_->faceCount() >= kLevelOfDetailMinFaces &&
        lodMesh_ != mesh_ && lodPending_ != mesh_)
        requestMotionMesh();
    updateOverlayVisibility();
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
    if (enabled && mesh_ && mesh_->faceCount() >= kLevelOfDetailMinFaces && lodMesh_ != mesh_ &&
        lodPending_ != mesh_)
        requestMotionMesh();
    updateMeshLevel();
    requestRender();
}

bool SceneView3D::levelOfDetailReady() const {
    return mesh_ && lod_.data && lodMesh_ == mesh_;
}

bool SceneView3D::showsLevelOfDetail() const {
    return lodActor_->GetVisibility() != 0;
}

long long SceneView3D::levelOfDetailFaceCount() const {
    return levelOfDetailReady() ? lod_.data->GetNumberOfPolys() : 0;
}

double SceneView3D::levelOfDetailSeconds() const {
    return levelOfDetailReady() ? lod_.seconds : 0.0;
}

void SceneView3D::requestMotionMesh() {
    lodTimer_->stop();
    if (!mesh_ || !lodEnabled_ || mesh_->faceCount() < kLevelOfDetailMinFaces ||
        lodMesh_ == mesh_ || lodPending_ == mesh_)
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
        lod_ = std::move(result);
        lodMesh_ = mesh;
        lodMapper_->SetInputData(lod_.data);
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
    if (lod && lodColourStamp_ != colourStamp_)
        recolourMotionMesh();
    meshActor_->SetVisibility(meshShown() && !lod);
    lodActor_->SetVisibility(lod);
}

void SceneView3D::recolourMotionMesh() {
    lodColourStamp_ = colourStamp_;
    vtkPolyData* lod = lod_.data;
    const std::vector<Index>& source = lod_.sourceFaces;
    const auto count = static_cast<vtkIdType>(source.size());
    // Shaded like the mesh: smooth when the mesh has the surface's normals.
    lod->GetPointData()->SetNormals(shownNormals_ ? lod_.normals.Get() : nullptr);

    // What the mesh mapper colours a face by (updateColoring()): a cell
    // array, or a vertex field whose mean over the face stands for it.
    vtkDataArray* values = nullptr;
    bool perVertex = false;
    if (meshMapper_->GetScalarVisibility()) {
        switch (meshMapper_->GetScalarMode()) {
        case VTK_SCALAR_MODE_USE_CELL_DATA:
            values = meshData_->GetCellData()->GetScalars();
            break;
        case VTK_SCALAR_MODE_USE_CELL_FIELD_DATA:
            values = meshData_->GetCellData()->GetArray(meshMapper_->GetArrayName());
            break;
        case VTK_SCALAR_MODE_USE_POINT_FIELD_DATA:
            values = meshData_->GetPointData()->GetArray(meshMapper_->GetArrayName());
            perVertex = true;
            break;
        default:
            break;
        }
    }
    vtkScalarsToColors* table = meshMapper_->GetLookupTable();
    double plain[3];
    meshActor_->GetProperty()->GetColor(plain);

    // The translucent radial tint folded into the colours (the tint actor
    // is hidden while moving): the same blend, one opaque triangle.
    const bool tint = isOverlayEnabled(SceneOverlay::RadialFaces) &&
                      isOverlayAvailable(SceneOverlay::RadialFaces);
    const auto faceLabels = [this](const char* name) -> const std::vector<int>* {
        const Field* field = snapshot_.field(name);
        if (!field || field->location != FieldLocation::Face || !field->labels() ||
            static_cast<Index>(field->labels()->size()) != mesh_->faceCount())
            return nullptr;
        return field->labels();
    };
    const std::vector<int>* radial = tint ? faceLabels(fields::kRadial) : nullptr;
    const std::vector<int>* standard = tint ? faceLabels(fields::kStandardRadial) : nullptr;
    const double opacity = sceneColors::kRadialTintOpacity;

    auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
    colors->SetName("motion_colors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(count);
    unsigned char* out = colors->GetPointer(0);
    for (vtkIdType c = 0; c < count; ++c) {
        const Index f = source[static_cast<size_t>(c)];
        std::array<double, 3> rgb{plain[0], plain[1], plain[2]};
        if (values && table) {
            double value = 0.0;
            if (perVertex) {
                const Triangle& t = mesh_->triangle(f);
                for (int i = 0; i < 3; ++i)
                    value += values->GetComponent(t[i], 0) / 3.0;
            } else {
                value = values->GetComponent(f, 0);
            }
            const unsigned char* mapped = table->MapValue(value);
            for (int k = 0; k < 3; ++k)
                rgb[k] = mapped[k] / 255.0;
        }
        const bool isStandard = standard && (*standard)[f] != 0;
        if (isStandard || (radial && (*radial)[f] != 0)) {
            const SceneColor& t =
                isStandard ? sceneColors::kStandardRadialTint : sceneColors::kRadialTint;
            const std::array<double, 3> tintRgb{t.r, t.g, t.b};
            for (int k = 0; k < 3; ++k)
                rgb[k] = (1.0 - opacity) * rgb[k] + opacity * tintRgb[k];
        }
        for (int k = 0; k < 3; ++k)
            *out++ = static_cast<unsigned char>(std::clamp(rgb[k], 0.0, 1.0) * 255.0 + 0.5);
    }
    lod->GetCellData()->SetScalars(colors);
    lod->Modified();
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

void SceneView3D::setSnapshot(const Snapshot& snapshot) {
    if (!snapshot.mesh) {
        clearScene();
        return;
    }
    if (snapshot.mesh != mesh_) {
        mesh_ = snapshot.mesh;
        meshData_ = meshToPolyData(*mesh_);
        meshMapper_->SetInputData(meshData_);
        // The decimated copy of the previous mesh is of no use any more; the
        // new one is built once the window has been idle for a moment, so
        // that stepping through phases does not queue a build per phase.
        lod_ = {};
        lodMesh_.reset();
        lodMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
        if (mesh_->faceCount() >= kLevelOfDetailMinFaces && lodEnabled_)
            lodTimer_->start();
        else
            lodTimer_->stop();
        shownFieldValues_.reset();
        shownArrayName_.clear();
        shownNormals_.reset();
        updateFrustum();
    }
    snapshot_ = snapshot;
    const auto normals = snapshot.fields.find(fields::kVertexNormal);
    const std::shared_ptr<const Field> normalField =
        normals == snapshot.fields.end() ? nullptr : normals->second;
    if (normalField != shownNormals_ || !normalField) {
        if (vtkSmartPointer<vtkDoubleArray> smooth = smoothSurfaceNormals(snapshot)) {
            meshData_->GetPointData()->SetNormals(smooth);
            shownNormals_ = normalField;
        } else {
            meshData_->GetPointData()->SetNormals(nullptr);
            shownNormals_.reset();
        }
    }
    if (vtkSmartPointer<vtkIntArray> facing = facingToCellArray(snapshot))
        meshData_->GetCellData()->SetScalars(facing);
    else
        meshData_->GetCellData()->RemoveArray(kVtkFacingArray);
    updateColoring();
    updateOverlays();
    updateMeshLevel();

    if (snapshot.curves != curves_) {
        curves_ = snapshot.curves;
        static const std::vector<Polyline> none;
        const std::vector<Polyline>& curves = curves_ ? *curves_ : none;
        curveMapper_->SetInputData(curvesToPolyData(curves));
        curveCount_ = static_cast<int>(curves.size());
    }
    if (snapshot.cage != shownCage_) {
        shownCage_ = snapshot.cage;
        if (shownCage_)
            cageMapper_->SetInputData(cageToPolyData(*shownCage_));
    }
    cageActor_->SetVisibility(showCage_ && shownCage_);
    updateViewGraph();
    updateHighlight();
    requestRender();
    emit snapshotChanged();
}

void SceneView3D::setShowControlCage(bool show) {
    showCage_ = show;
    cageActor_->SetVisibility(showCage_ && shownCage_);
    requestRender();
}

long long SceneView3D::controlCageEdgesShown() const {
    vtkPolyData* cage = cageMapper_->GetInput();
    return cageActor_->GetVisibility() && cage ? cage->GetNumberOfLines() : 0;
}

void SceneView3D::setColorField(const std::string& field) {
    colorField_ = field.empty() ? std::string(fields::kFacing) : field;
    if (!meshData_)
        return;
    updateColoring();
    updateMeshLevel(); // recolours the decimated copy if it is drawn
    requestRender();
}

void SceneView3D::updateColoring() {
    ++colourStamp_;
    const std::string previousField = displayedField_;
    const std::vector<std::string> previousFields = scalarFields_;
    const std::vector<std::string> previousLabels = labelFields_;
    scalarFields_ = meshData_ ? scalarFieldNames(snapshot_) : std::vector<std::string>{};
    labelFields_ = meshData_ ? faceLabelFieldNames(snapshot_) : std::vector<std::string>{};
    const auto lists = [this](const std::vector<std::string>& names) {
        return std::find(names.begin(), names.end(), colorField_) != names.end();
    };
    showsScalar_ = meshData_ && lists(scalarFields_);
    showsLabels_ = meshData_ && !showsScalar_ && lists(labelFields_);
    displayedField_ = showsScalar_ || showsLabels_ ? colorField_ : std::string(fields::kFacing);

    const auto removeShownArray = [this] {
        if (meshData_ && !shownArrayName_.empty()) {
            meshData_->GetPointData()->RemoveArray(shownArrayName_.c_str());
            meshData_->GetCellData()->RemoveArray(shownArrayName_.c_str());
        }
        shownArrayName_.clear();
        shownFieldValues_.reset();
    };

    if (showsScalar_) {
        const std::shared_ptr<const Field>& field = snapshot_.fields.at(displayedField_);
        if (field != shownFieldValues_) {
            removeShownArray();
            FieldLocation location = FieldLocation::Vertex;
            vtkSmartPointer<vtkDoubleArray> values =
                scalarFieldToArray(snapshot_, displayedField_, &location);
            if (location == FieldLocation::Face)
                meshData_->GetCellData()->AddArray(values);
            else
                meshData_->GetPointData()->AddArray(values);
            shownArrayName_ = displayedField_;
            shownFieldValues_ = field;
            scalarRange_ = symmetricRange(std::span<const double>(
                values->GetPointer(0), static_cast<size_t>(values->GetNumberOfTuples())));
            fillDivergingLookupTable(fieldColors_, scalarRange_.halfWidth);
        }
        if (field->location == FieldLocation::Face) {
            meshMapper_->SetScalarModeToUseCellFieldData();
            meshMapper_->InterpolateScalarsBeforeMappingOff();
        } else {
            // Interpolating the scalar (not the colour) across a triangle
            // keeps the map's colours exact inside it.
            meshMapper_->SetScalarModeToUsePointFieldData();
            meshMapper_->InterpolateScalarsBeforeMappingOn();
        }
        meshMapper_->SelectColorArray(displayedField_.c_str());
        meshMapper_->SetLookupTable(fieldColors_);
        meshMapper_->ScalarVisibilityOn();
        showsFacing_ = false;
        curveMapper_->SetLookupTable(curveColorsOverField_);
        scalarBar_->SetTitle(fieldDisplayName(displayedField_).c_str());
        scalarBar_->SetDrawNanAnnotation(scalarRange_.nanCount > 0);
        scalarBar_->VisibilityOn();
    } else if (showsLabels_) {
        const std::shared_ptr<const Field>& field = snapshot_.fields.at(displayedField_);
        if (field != shownFieldValues_) {
            removeShownArray();
            meshData_->GetCellData()->AddArray(faceLabelsToCellArray(snapshot_, displayedField_));
            shownArrayName_ = displayedField_;
            shownFieldValues_ = field;
        }
        meshMapper_->SetScalarModeToUseCellFieldData();
        meshMapper_->InterpolateScalarsBeforeMappingOff();
        meshMapper_->SelectColorArray(displayedField_.c_str());
        meshMapper_->SetLookupTable(labelColors_);
        meshMapper_->ScalarVisibilityOn();
        showsFacing_ = false;
        curveMapper_->SetLookupTable(curveColors_);
        scalarBar_->VisibilityOff();
    } else {
        removeShownArray();
        showsFacing_ = meshData_ && meshData_->GetCellData()->GetArray(kVtkFacingArray);
        meshMapper_->SetScalarModeToUseCellData();
        meshMapper_->InterpolateScalarsBeforeMappingOff();
        meshMapper_->SetLookupTable(facingColors_);
        meshMapper_->SetScalarVisibility(showsFacing_);
        curveMapper_->SetLookupTable(curveColors_);
        scalarBar_->VisibilityOff();
    }
    if (meshData_)
        meshData_->Modified();
    // Visible chains coloured by QI follow the curves' colour.
    recolourViewGraph();
    if (displayedField_ != previousField || scalarFields_ != previousFields ||
        labelFields_ != previousLabels)
        emit colorFieldsChanged();
}

void SceneView3D::updateOverlays() {
    ++colourStamp_;
    std::array<bool, kSceneOverlayCount> wasAvailable{};
    for (int i = 0; i < kSceneOverlayCount; ++i)
        wasAvailable[i] = static_cast<bool>(overlays_[i].data);
    std::array<vtkSmartPointer<vtkPolyData>, kSceneOverlayCount> converted{};
    if (meshData_) {
        converted[static_cast<int>(SceneOverlay::InconsistentFaces)] =
            inconsistentFaceOutlines(snapshot_);
        converted[static_cast<int>(SceneOverlay::RadialFaces)] = radialFacesToPolyData(snapshot_);
        converted[static_cast<int>(SceneOverlay::ContourVertices)] =
            markedVerticesToPolyData(snapshot_, fields::kLabel, 0);
        converted[static_cast<int>(SceneOverlay::Cusps)] =
            markedVerticesToPolyData(snapshot_, fields::kCusp, 1);
        converted[static_cast<int>(SceneOverlay::RadialEdges)] =
            markedEdgesToPolyData(snapshot_, fields::kRadialEdge);
    }
    // The tint shares the mesh's points: shade it like the mesh.
    if (vtkPolyData* tint = converted[static_cast<int>(SceneOverlay::RadialFaces)])
        tint->GetPointData()->SetNormals(meshData_->GetPointData()->GetNormals());
    bool changed = false;
    for (int i = 0; i < kSceneOverlayCount; ++i) {
        OverlayLayer& layer = overlays_[i];
        layer.data = converted[i];
        layer.mapper->SetInputData(layer.data ? layer.data.Get()
                                              : vtkSmartPointer<vtkPolyData>::New().Get());
        changed |= wasAvailable[i] != static_cast<bool>(layer.data);
    }
    updateOverlayVisibility();
    if (changed)
        emit overlaysChanged();
}

void SceneView3D::updateOverlayVisibility() {
    for (int i = 0; i < kSceneOverlayCount; ++i)
        overlays_[i].actor->SetVisibility(isOverlayShown(static_cast<SceneOverlay>(i)));
}

void SceneView3D::setOverlayEnabled(SceneOverlay overlay, bool enabled) {
    overlays_[static_cast<int>(overlay)].enabled = enabled;
    ++colourStamp_; // the radial tint is folded into the moving copy's colours
    updateMeshLevel();
    updateOverlayVisibility();
    requestRender();
}

bool SceneView3D::isOverlayEnabled(SceneOverlay overlay) const {
    return overlays_[static_cast<int>(overlay)].enabled;
}

bool SceneView3D::isOverlayAvailable(SceneOverlay overlay) const {
    return static_cast<bool>(overlays_[static_cast<int>(overlay)].data);
}

bool SceneView3D::isOverlayShown(SceneOverlay overlay) const {
    if (motionDrawing_ && overlay == SceneOverlay::RadialFaces)
        return false;
    return isOverlayEnabled(overlay) && isOverlayAvailable(overlay) && meshShown();
}

long long SceneView3D::overlayElementCount(SceneOverlay overlay) const {
    vtkPolyData* poly = overlays_[static_cast<int>(overlay)].data;
    if (!poly)
        return 0;
    return poly->GetNumberOfVerts() + poly->GetNumberOfLines() + poly->GetNumberOfPolys();
}

vtkPolyData* SceneView3D::overlayData(SceneOverlay overlay) const {
    return overlays_[static_cast<int>(overlay)].data;
}

bool SceneView3D::isScalarBarVisible() const {
    return meshShown() && scalarBar_->GetVisibility();
}

std::string SceneView3D::scalarBarTitle() const {
    const char* title = scalarBar_->GetTitle();
    return title ? title : "";
}

QRect SceneView3D::scalarBarRect() const {
    if (!isScalarBarVisible())
        return {};
    const QSize size = deviceSize();
    const int left = static_cast<int>(kBarLeft * size.width());
    const int right = static_cast<int>((kBarLeft + kBarWidth) * size.width());
    const double y = barBottom(size.height());
    const int bottom = size.height() - static_cast<int>(y * size.height());
    const int top = size.height() - static_cast<int>((y + kBarHeight) * size.height());
    return QRect(QPoint(left, top), QPoint(right - 1, bottom - 1));
}

void SceneView3D::updateViewGraph() {
    const bool had = static_cast<bool>(graph_);
    const std::shared_ptr<const ViewGraph> graph = meshData_ ? snapshot_.viewGraph : nullptr;
    const bool changed = graph != graph_;
    graph_ = graph;
    const auto setData = [](ViewGraphLayer& layer, vtkSmartPointer<vtkPolyData> poly) {
        layer.data = std::move(poly);
        layer.mapper->SetInputData(layer.data ? layer.data.Get()
                                              : vtkSmartPointer<vtkPolyData>::New().Get());
    };
    if (changed) {
        for (int i = 0; i < kChainStateCount; ++i)
            setData(chainLayers_[static_cast<size_t>(i)],
                    graph_ ? viewChainsToPolyData(*graph_, static_cast<ChainState>(i)) : nullptr);
        for (int hidden = 0; hidden < 2; ++hidden)
            setData(nodeLayers_[static_cast<size_t>(hidden)],
                    graph_ ? viewNodesToPolyData(*graph_, hidden != 0) : nullptr);
    }
    recolourViewGraph();
    updateViewGraphVisibility();
    if (had != static_cast<bool>(graph_))
        emit overlaysChanged();
}

void SceneView3D::recolourViewGraph() {
    if (!graph_)
        return;
    // Over a scalar field (which has red in it) visible chains are black,
    // like the curves.
    const SceneColor& visible =
        showsScalar_ ? sceneColors::kContourOverField : sceneColors::kContour3D;
    for (int i = 0; i < kChainStateCount; ++i) {
        vtkPolyData* chains = chainLayers_[static_cast<size_t>(i)].data;
        if (!chains)
            continue;
        const auto state = static_cast<ChainState>(i);
        auto* indices =
            vtkIntArray::SafeDownCast(chains->GetCellData()->GetArray(kVtkChainIndexArray));
        auto* qis = vtkIntArray::SafeDownCast(chains->GetCellData()->GetArray(kVtkChainQiArray));
        auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
        colors->SetName(kViewGraphColorArray);
        colors->SetNumberOfComponents(3);
        for (vtkIdType c = 0; c < chains->GetNumberOfLines(); ++c) {
            if (state == ChainState::Simplified)
                insertColor(colors, viewGraphColors::kSimplified3D);
            else if (coloring_ == ChainColoring::ByChain)
                insertColor(colors, chainColor(indices->GetValue(c)),
                            state == ChainState::Hidden ? viewGraphColors::kHiddenDarken : 1.0);
            else
                insertColor(colors, qiColor(qis->GetValue(c), visible));
        }
        chains->GetCellData()->AddArray(colors);
        chains->GetCellData()->SetActiveScalars(kViewGraphColorArray);
        chains->Modified();
    }
    for (const ViewGraphLayer& layer : nodeLayers_) {
        vtkPolyData* nodes = layer.data;
        if (!nodes)
            continue;
        auto* types = vtkIntArray::SafeDownCast(nodes->GetPointData()->GetArray(kVtkNodeTypeArray));
        auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
        colors->SetName(kViewGraphColorArray);
        colors->SetNumberOfComponents(3);
        for (vtkIdType n = 0; n < nodes->GetNumberOfPoints(); ++n)
            insertColor(colors, nodeStyle(static_cast<ViewNodeType>(types->GetValue(n))).color);
        nodes->GetPointData()->AddArray(colors);
        nodes->GetPointData()->SetActiveScalars(kViewGraphColorArray);
        nodes->Modified();
    }
}

void SceneView3D::updateViewGraphVisibility() {
    curveActor_->SetVisibility(meshShown() && curveCount_ > 0 && !graph_);
    for (int i = 0; i < kChainStateCount; ++i)
        chainLayers_[static_cast<size_t>(i)].actor->SetVisibility(
            viewGraphChainsShown(static_cast<ChainState>(i)) > 0);
    for (int hidden = 0; hidden < 2; ++hidden) {
        const ViewGraphLayer& layer = nodeLayers_[static_cast<size_t>(hidden)];
        layer.actor->SetVisibility(graph_ && layer.data && showNodes_ && (!hidden || showHidden_) &&
                                   meshShown());
    }
}

long long SceneView3D::viewGraphChainsShown(ChainState state) const {
    const ViewGraphLayer& layer = chainLayers_[static_cast<size_t>(state)];
    if (!graph_ || !layer.data || !meshShown())
        return 0;
    if ((state == ChainState::Hidden && !showHidden_) ||
        (state == ChainState::Simplified && !showSimplified_))
        return 0;
    return layer.data->GetNumberOfLines();
}

long long SceneView3D::viewGraphNodesShown() const {
    long long shown = 0;
    for (const ViewGraphLayer& layer : nodeLayers_)
        if (layer.actor->GetVisibility())
            shown += layer.data->GetNumberOfVerts();
    return shown;
}

vtkPolyData* SceneView3D::viewGraphChainData(ChainState state) const {
    return chainLayers_[static_cast<size_t>(state)].data;
}

vtkPolyData* SceneView3D::viewGraphNodeData(bool hidden) const {
    return nodeLayers_[hidden ? 1 : 0].data;
}

void SceneView3D::setShowHiddenCurves(bool show) {
    showHidden_ = show;
    updateViewGraphVisibility();
    requestRender();
}

void SceneView3D::setShowSimplifiedCurves(bool show) {
    showSimplified_ = show;
    updateViewGraphVisibility();
    requestRender();
}

void SceneView3D::setShowViewGraphNodes(bool show) {
    showNodes_ = show;
    updateViewGraphVisibility();
    requestRender();
}

void SceneView3D::setChainColoring(ChainColoring coloring) {
    coloring_ = coloring;
    recolourViewGraph();
    requestRender();
}

long long SceneView3D::displayedFaceCount() const {
    if (showsLevelOfDetail())
        return lod_.data->GetNumberOfPolys();
    return meshData_ ? meshData_->GetNumberOfPolys() : 0;
}

void SceneView3D::clearScene() {
    mesh_.reset();
    meshData_ = nullptr;
    snapshot_ = Snapshot();
    shownFieldValues_.reset();
    shownArrayName_.clear();
    shownNormals_.reset();
    updateColoring();
    updateOverlays();
    curves_.reset();
    curveCount_ = 0;
    showsFacing_ = false;
    lod_ = {};
    lodMesh_.reset();
    lodTimer_->stop();
    lodMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    updateMeshLevel();
    curveActor_->VisibilityOff();
    updateViewGraph();
    frustumActor_->VisibilityOff();
    shownCage_.reset();
    cageActor_->VisibilityOff();
    updateHighlight();
    requestRender();
    emit snapshotChanged();
}

void SceneView3D::setAnalysisCamera(const Camera& camera) {
    analysisCamera_ = camera;
    updateFrustum();
    requestRender();
}

void SceneView3D::updateFrustum() {
    if (!analysisCamera_)
        return;
    const Camera& camera = *analysisCamera_;
    // The image rectangle through the target; orthographic boxes reach to the
    // far side of the mesh.
    double depth = (camera.target - camera.eye).norm();
    if (camera.isOrthographic() && mesh_)
        depth += 0.5 * mesh_->boundingBox().diagonal();
    frustumMapper_->SetInputData(frustumToPolyData(camera, depth));
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
    return !analysisCamera_ || sameView(viewCamera(), *analysisCamera_);
}

bool SceneView3D::isFrustumVisible() const {
    return mesh_ && analysisCamera_ && !viewMatchesAnalysisCamera();
}

void SceneView3D::beforeRender() {
    scalarBar_->GetPositionCoordinate()->SetValue(kBarLeft, barBottom(deviceSize().height()));
    const bool visible = isFrustumVisible();
    frustumActor_->SetVisibility(visible);
    renderer()->ResetCameraClippingRange();
    const bool matches = viewMatchesAnalysisCamera();
    if (matches != lastMatch_) {
        lastMatch_ = matches;
        // Queued: listeners must not re-enter the paint.
        QMetaObject::invokeMethod(
            this, [this, matches] { emit viewMatchChanged(matches); }, Qt::QueuedConnection);
    }
}

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
    picker->AddPickList(meshActor_);
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

vtkPolyData* SceneView3D::highlightData() const {
    return highlightData_;
}

void SceneView3D::setHighlight(const Selection& selection) {
    highlight_ = selection;
    updateHighlight();
    requestRender();
}

void SceneView3D::updateHighlight() {
    highlightData_ = nullptr;
    if (mesh_ && meshData_ && selectionExists(snapshot_, highlight_)) {
        auto points = vtkSmartPointer<vtkPoints>::New();
        auto lines = vtkSmartPointer<vtkCellArray>::New();
        auto verts = vtkSmartPointer<vtkCellArray>::New();
        const auto addPoint = [&](const Vec3& p) {
            return points->InsertNextPoint(p.x(), p.y(), p.z());
        };
        switch (highlight_.kind) {
        case SelectionKind::Face: {
            const Triangle& t = mesh_->triangle(highlight_.id);
            const std::array<vtkIdType, 4> ids{addPoint(mesh_->position(t[0])),
                                               addPoint(mesh_->position(t[1])),
                                               addPoint(mesh_->position(t[2])), 0};
            lines->InsertNextCell(4, ids.data());
            break;
        }
        case SelectionKind::Vertex: {
            const vtkIdType id = addPoint(mesh_->position(highlight_.id));
            verts->InsertNextCell(1, &id);
            break;
        }
        case SelectionKind::Edge: {
            const Index h = mesh_->edgeHalfedge(highlight_.id);
            const std::array<vtkIdType, 2> ids{addPoint(mesh_->position(mesh_->from(h))),
                                               addPoint(mesh_->position(mesh_->to(h)))};
            lines->InsertNextCell(2, ids.data());
            break;
        }
        case SelectionKind::Chain: {
            const ViewChain& chain =
                snapshot_.viewGraph->chains[static_cast<size_t>(highlight_.id)];
            std::vector<vtkIdType> ids;
            for (const Vec3& p : chain.points)
                ids.push_back(addPoint(p));
            if (ids.size() >= 2)
                lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
            else if (ids.size() == 1)
                verts->InsertNextCell(1, ids.data());
            break;
        }
        case SelectionKind::None:
            break;
        }
        if (points->GetNumberOfPoints() > 0) {
            highlightData_ = vtkSmartPointer<vtkPolyData>::New();
            highlightData_->SetPoints(points);
            highlightData_->SetLines(lines);
            highlightData_->SetVerts(verts);
        }
    }
    highlightMapper_->SetInputData(highlightData_ ? highlightData_.Get()
                                                  : vtkSmartPointer<vtkPolyData>::New().Get());
    highlightActor_->SetVisibility(highlightData_ && meshShown());
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

} // namespace contour
