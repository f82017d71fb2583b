#pragma once
// The 3D view of a snapshot, composed of layers (widgets/scene/, one class
// per kind of data, in the manner of 3D Slicer's displayable managers): the
// working mesh coloured by facing, a face label field or a signed scalar
// field with its scalar bar (MeshColoringLayer), the raw curves
// (CurveLayer) or, when the snapshot has a view graph, its chains and nodes
// (ViewGraphLayer), the consistent method's overlays (ConsistentOverlayLayer),
// the control cage (CageLayer), the linked selection (HighlightLayer), the
// analysis camera's frustum when this view's own camera differs from it
// (FrustumLayer), on request the dense ground truth of the smooth contour
// (GroundTruthLayer) and, while the camera moves, a decimated copy of a large
// mesh (MotionCopyLayer). The view owns the renderers, the camera, picking
// and the motion drawing; the API below is what the window and tests call.
#include "DivergingColorMap.h"
#include "MotionMesh.h"
#include "SceneColors.h"
#include "Selection.h"
#include "ViewGraphStyle.h"
#include "VtkOpenGLWidget.h"
#include "camera/Camera.h"
#include "pipeline/FieldNames.h"
#include "pipeline/Snapshot.h"
#include "scene/CageLayer.h"
#include "scene/ConsistentOverlayLayer.h"
#include "scene/CurveLayer.h"
#include "scene/FrustumLayer.h"
#include "scene/GroundTruthLayer.h"
#include "scene/HighlightLayer.h"
#include "scene/MeshColoringLayer.h"
#include "scene/MotionCopyLayer.h"
#include "scene/ViewGraphLayer.h"

#include <QRect>
#include <QThreadPool>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <vtkNew.h>
#include <vtkRenderer.h>

class QTimer;
class vtkPolyData;
class vtkProperty;

namespace contour {

// SceneOverlay and kSceneOverlayCount: scene/ConsistentOverlayLayer.h.

class SceneView3D : public VtkOpenGLWidget {
    Q_OBJECT

public:
    explicit SceneView3D(QWidget* parent = nullptr);
    ~SceneView3D() override;

    // Shows the snapshot's mesh, its colouring (colorField()) and curves. The
    // mesh geometry is only converted again when the snapshot's mesh changes.
    // A tessellated smooth surface is shaded with its exact normals, a plain
    // triangle mesh with flat faces.
    void setSnapshot(const Snapshot& snapshot);
    void clearScene();
    bool hasMesh() const { return static_cast<bool>(mesh_); }
    // The snapshot shown (empty after clearScene()).
    const Snapshot& snapshot() const { return snapshot_; }
    // Whether the faces are currently coloured from a facing field.
    bool showsFacing() const { return coloring_.showsFacing(); }
    // Whether they are coloured by a face label field (labelFields()).
    bool showsFaceLabels() const { return coloring_.showsFaceLabels(); }

    // What to colour the mesh by: fields::kFacing (front/back), a face label
    // field (fields::kVbo, faceLabelFieldNames in SnapshotToVtk.h) or the name
    // of a scalar field (scalarFieldNames). The choice is kept
    // across snapshots; a snapshot without that field is shown by facing
    // (displayedColorField()), and the field is shown again as soon as a
    // snapshot has it (stepping back to the input and forward again, or a
    // re-run after a parameter change, keeps the choice).
    void setColorField(const std::string& field);
    const std::string& colorField() const { return coloring_.colorField(); }
    // fields::kFacing or the label or scalar field actually shown.
    const std::string& displayedColorField() const { return coloring_.displayedColorField(); }
    // The face label fields and the scalar fields of the current snapshot,
    // in selector order.
    const std::vector<std::string>& labelFields() const { return coloring_.labelFields(); }
    const std::vector<std::string>& scalarFields() const { return coloring_.scalarFields(); }
    bool showsScalarField() const { return coloring_.showsScalarField(); }
    // The range of the diverging map of the shown scalar field.
    const SymmetricRange& scalarRange() const { return coloring_.scalarRange(); }
    bool isScalarBarVisible() const;
    std::string scalarBarTitle() const;
    // The scalar bar's box (bar, labels and title) in the grabbed image's
    // device pixels, top-left origin; empty when the bar is hidden.
    QRect scalarBarRect() const;
    int curveCount() const { return curves_.curveCount(); }
    // Whether the mesh is shaded with the smooth surface's normals.
    bool hasSmoothShading() const { return coloring_.hasSmoothShading(); }
    // Triangles in the VTK data shown for the mesh (0 when none).
    long long displayedFaceCount() const;

    // Overlays: a choice kept across snapshots (all enabled at first); an
    // overlay is drawn when it is enabled and the snapshot has its fields.
    void setOverlayEnabled(SceneOverlay overlay, bool enabled);
    bool isOverlayEnabled(SceneOverlay overlay) const;
    bool isOverlayAvailable(SceneOverlay overlay) const;
    bool isOverlayShown(SceneOverlay overlay) const;
    // Elements in the overlay's VTK data (outlined faces, tinted faces, C
    // vertices, cusps, radial edges); 0 when it is not available.
    long long overlayElementCount(SceneOverlay overlay) const;
    // The overlay's VTK data, or null when it is not available.
    vtkPolyData* overlayData(SceneOverlay overlay) const;

    // View graph display: choices kept across snapshots, applied when the
    // snapshot has a view graph.
    bool hasViewGraph() const { return viewGraph_.hasViewGraph(); }
    void setShowHiddenCurves(bool show);
    bool showsHiddenCurves() const { return viewGraph_.showsHiddenCurves(); }
    void setShowSimplifiedCurves(bool show);
    bool showsSimplifiedCurves() const { return viewGraph_.showsSimplifiedCurves(); }
    void setShowViewGraphNodes(bool show);
    bool showsViewGraphNodes() const { return viewGraph_.showsNodes(); }
    void setChainColoring(ChainColoring coloring);
    ChainColoring chainColoring() const { return viewGraph_.chainColoring(); }
    // Chains in `state` drawn now (0 when that layer is off or there is no
    // view graph), node dots drawn now (both kinds), and their VTK data
    // (null without a view graph): the nodes on a visible chain, or with
    // `hidden` those whose chains are all hidden.
    long long viewGraphChainsShown(ChainState state) const;
    long long viewGraphNodesShown() const;
    vtkPolyData* viewGraphChainData(ChainState state) const;
    vtkPolyData* viewGraphNodeData(bool hidden = false) const;

    // The dense ground truth of the smooth contour (the application computes
    // it for the analysis camera), drawn on the surface while the snapshot
    // has a mesh; kept across snapshots until cleared or replaced.
    void setGroundTruth(std::shared_ptr<const GroundTruth> truth);
    void clearGroundTruth() { setGroundTruth(nullptr); }
    bool hasGroundTruth() const { return groundTruth_.hasGroundTruth(); }
    // Loops and cusps drawn now, and their VTK data (null without one).
    long long groundTruthLoopsShown() const { return groundTruth_.loopsShown(); }
    long long groundTruthCuspsShown() const { return groundTruth_.cuspsShown(); }
    vtkPolyData* groundTruthLoopData() const { return groundTruth_.loopData(); }
    vtkPolyData* groundTruthCuspData() const { return groundTruth_.cuspData(); }

    // The camera the method runs with; drawn as a frustum when it differs
    // from this view's camera.
    void setAnalysisCamera(const Camera& camera);
    const std::optional<Camera>& analysisCamera() const { return frustum_.analysisCamera(); }

    // Sets this view's VTK camera from an analysis camera.
    void setViewCamera(const Camera& camera);
    // This view's VTK camera as an analysis camera whose viewport is the
    // view's size in device pixels ("set analysis camera from this view").
    Camera viewCamera() const;
    // Rotates this view's camera about its focal point (degrees), as a
    // trackball drag does.
    void orbit(double azimuthDegrees, double elevationDegrees);

    // Linked selection (Selection.h). What a click at `position` (widget
    // coordinates) hits on the mesh (a cell picker on the mesh actor, nearest
    // surface along the ray): the vertex of the hit face within
    // kPickVertexPixels of the click (less on small faces), else its edge
    // within kPickEdgePixels, else the face; nothing off the mesh.
    Selection pick(const QPointF& position) const;
    static constexpr double kPickVertexPixels = 6.0; // widget pixels
    static constexpr double kPickEdgePixels = 4.0;
    // A press and release further apart than this is a drag (an orbit).
    static constexpr double kClickSlopPixels = 4.0;
    // Draws the selected element over everything in sceneColors::kSelection:
    // a face's outline, a vertex's dot, an edge, or a view-graph chain.
    void setHighlight(const Selection& selection);
    const Selection& highlight() const { return highlight_.selection(); }
    // The highlight's VTK data (null when nothing is drawn).
    vtkPolyData* highlightData() const;
    // Zooms this view's camera onto the face, keeping its viewing direction
    // (the analysis camera does not change).
    void frameFace(Index face);

    // True when the frustum is drawn (decided before each render).
    bool isFrustumVisible() const;
    // Lighter drawing while the camera moves (the interactor style's
    // start/end interaction events, or a caller such as a benchmark): every
    // line 1 px wide, points as small squares instead of spheres, the
    // translucent radial tint hidden. Software rendering spends most of an
    // orbit frame on wide lines, sphere points and the tint (README,
    // bench_workbench). Off restores every actor's own style.
    void setMotionDrawing(bool on);
    bool motionDrawing() const { return motionDrawing_; }
    // Level of detail while moving (MotionMesh.h, as ParaView does): for a
    // mesh of at least kLevelOfDetailMinFaces faces a decimated copy of
    // about kLevelOfDetailFaces triangles is built on a worker thread once
    // the snapshot has been shown for kLevelOfDetailDelayMs (or at the first
    // drag). While motionDrawing() it is drawn instead of the mesh, each
    // triangle in the colour of the face it stands for (facing, VBO or the
    // scalar field, with the radial tint folded in); every overlay, curve
    // and the view graph are still drawn from the exact data. Until the copy
    // is ready the full mesh is drawn; when the motion ends the full mesh is
    // drawn again (the very same picture as before). On by default.
    static constexpr Index kLevelOfDetailMinFaces = 50000;
    static constexpr Index kLevelOfDetailFaces = 25000;
    static constexpr int kLevelOfDetailDelayMs = 300;
    void setLevelOfDetail(bool enabled);
    bool levelOfDetailEnabled() const { return lodEnabled_; }
    // True when the decimated copy of the current mesh is built.
    bool levelOfDetailReady() const;
    // True when the decimated copy is drawn now instead of the mesh.
    bool showsLevelOfDetail() const;
    // Triangles of the copy and the wall time its build took (0 when none).
    long long levelOfDetailFaceCount() const;
    double levelOfDetailSeconds() const;
    // The control cage (Snapshot::cage) as a wireframe, off by default.
    void setShowControlCage(bool show);
    bool showsControlCage() const { return cage_.isShown(); }
    // Cage edges drawn (0 while hidden or without a cage).
    long long controlCageEdgesShown() const;
    // True when this view's camera shows the analysis camera's view.
    bool viewMatchesAnalysisCamera() const;

signals:
    // The list of scalar fields or the displayed colouring changed.
    void colorFieldsChanged();
    // Which overlays the snapshot has fields for changed.
    void overlaysChanged();
    // The frustum appeared or disappeared (the view left or joined the
    // analysis camera).
    void viewMatchChanged(bool matches);
    // setSnapshot() or clearScene() changed the snapshot shown.
    void snapshotChanged();
    // A left click without drag: what pick() found there (possibly nothing).
    void pickRequested(const Selection& selection);
    // The decimated copy of the current mesh has been built.
    void levelOfDetailBuilt();

protected:
    void beforeRender() override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;

private:
    // The layers' state after a change of the colouring: the curves and the
    // chains coloured by QI follow it (black over a scalar field).
    void syncContrast();
    // Level of detail while moving (setLevelOfDetail). meshShown() says
    // whether a mesh is displayed, by the full actor or by the copy.
    bool meshShown() const { return coloring_.meshData() != nullptr; }
    void requestMotionMesh();
    bool motionMeshWanted() const;
    // Shows the copy or the full mesh, as motion drawing asks.
    void updateMeshLevel();
    void onInteraction(vtkObject* caller, unsigned long eventId, void* callData);

    // The layers, in drawing order (SceneLayer.h).
    MeshColoringLayer coloring_;
    MotionCopyLayer motionCopy_;
    CurveLayer curves_;
    ConsistentOverlayLayer overlays_;
    ViewGraphLayer viewGraph_;
    GroundTruthLayer groundTruth_;
    HighlightLayer highlight_;
    CageLayer cage_;
    FrustumLayer frustum_;
    // Layer 1 over the scene, sharing its camera: what is drawn over
    // everything (inconsistent outlines, cusps, nodes on visible chains, the
    // highlight).
    vtkNew<vtkRenderer> overlayRenderer_;

    struct SavedStyle {
        vtkProperty* property; // owned by its actor, which a layer keeps
        float lineWidth;
        float pointSize;
        bool spheres;
    };
    std::vector<SavedStyle> stillStyles_; // while motionDrawing_
    bool motionDrawing_ = false;
    std::array<unsigned long, 2> interactionObservers_{};
    std::shared_ptr<const TriangleMesh> lodPending_; // the mesh being decimated
    QThreadPool lodPool_;
    QTimer* lodTimer_ = nullptr;
    bool lodEnabled_ = true;
    // Bumped when the colouring or the overlays change, to recolour the
    // copy only then.
    unsigned long colourStamp_ = 0;
    unsigned long lodColourStamp_ = 0;

    std::shared_ptr<const TriangleMesh> mesh_;
    Snapshot snapshot_;
    bool lastMatch_ = true;
    // The press that may become a click.
    QPointF pressPosition_;
    bool leftPressed_ = false;
};

} // namespace contour
