#pragma once
// The 2D view: the snapshot's curves projected with the analysis camera into
// its image (Camera::project: x right, y down, origin top-left), fitted into
// the widget with the image's aspect ratio, the image frame drawn.
//
// When the snapshot has a view graph (Snapshot::viewGraph, set by a method's
// visibility phase) its chains are drawn instead of the raw curves: visible
// chains solid, hidden ones (QI > 0 or unknown) dashed and optional, chains
// hidden by topological simplification left out (or very faint, optional),
// coloured by QI or by chain (ViewGraphStyle.h), with one glyph per node type
// and a legend of what is drawn. On request, the dense ground truth of the
// smooth contour is drawn over it (setGroundTruth).
#include "Selection.h"
#include "ViewGraphStyle.h"
#include "camera/Camera.h"
#include "export/CurveComparison.h"
#include "pipeline/Snapshot.h"
#include "reference/DenseGroundTruth.h"

#include <QPainterPath>
#include <QStringList>
#include <QWidget>
#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace contour {

class ImageView2D : public QWidget {
    Q_OBJECT

public:
    explicit ImageView2D(QWidget* parent = nullptr);

    void setScene(const Snapshot& snapshot, const Camera& camera);
    void clearScene();

    const std::optional<Camera>& camera() const { return camera_; }
    // The snapshot's raw curves (whether or not a view graph replaces them).
    int curveCount() const { return static_cast<int>(paths_.size()); }
    // Where the analysis camera's image is drawn, in widget coordinates.
    QRectF imageRect() const;
    // Maps a pixel of the analysis camera's image to widget coordinates.
    QPointF toWidget(const Vec2& imagePixel) const;

    // View graph display: choices kept across snapshots.
    void setShowHiddenCurves(bool show);
    bool showsHiddenCurves() const { return showHidden_; }
    void setShowSimplifiedCurves(bool show);
    bool showsSimplifiedCurves() const { return showSimplified_; }
    void setShowNodes(bool show);
    bool showsNodes() const { return showNodes_; }
    void setChainColoring(ChainColoring coloring);
    ChainColoring chainColoring() const { return coloring_; }

    // What the next paint draws: whether the view graph replaces the raw
    // curves, how many of its chains are drawn solid (visible), dashed
    // (hidden) and faint (simplified away), and how many node glyphs, in all
    // and per ViewNodeType.
    bool showsViewGraph() const { return static_cast<bool>(graph_); }
    int visibleChainsDrawn() const { return drawn_.visible; }
    int hiddenChainsDrawn() const { return drawn_.hidden; }
    int simplifiedChainsDrawn() const { return drawn_.simplified; }
    int nodeGlyphsDrawn() const { return drawn_.nodes; }
    int nodeGlyphsDrawn(ViewNodeType type) const {
        return drawn_.nodesByType[static_cast<size_t>(type)];
    }
    // The legend's box in widget coordinates (empty without a view graph).
    QRectF legendRect() const;

    // Comparison with a second method (the caller computes
    // the difference with compareCurves): the other method's drawn curves
    // thin on top, the parts only one method draws highlighted underneath,
    // and a caption with the lengths. Kept until cleared or replaced.
    void setComparison(const QString& thisLabel, const QString& otherLabel,
                       const std::vector<ImagePolyline>& otherCurves,
                       const CurveDifference& difference);
    // With the comparison: the distance from this method's drawn curves to
    // the other's as a field along them (coloured from kDistanceRamp, 0 to
    // the field's cap), the cusps and T-junctions only one side draws
    // (rings and squares) and both sides' counts in the caption.
    void setComparisonDetail(const CurveDistanceField& field, const NodeDifference& nodes);
    const CurveDistanceField* comparisonDistances() const {
        return comparison_ && comparison_->field ? &*comparison_->field : nullptr;
    }
    const NodeDifference* comparisonNodes() const {
        return comparison_ && comparison_->nodes ? &*comparison_->nodes : nullptr;
    }
    // Segments of the distance field drawn, per colour bin (0 nearest).
    static constexpr int kDistanceBins = 6;
    void clearComparison();
    bool showsComparison() const { return comparison_.has_value(); }
    // The difference shown, or null.
    const CurveDifference* comparison() const {
        return comparison_ ? &comparison_->difference : nullptr;
    }
    // The comparison caption's text (empty without a comparison).
    QString comparisonCaption() const;

    // The dense ground truth of the smooth contour for this view's camera
    // (reference/DenseGroundTruth.h; the application computes it): every
    // loop as a thin sceneColors::kGroundTruth line over the drawing,
    // visible or not (the oracle knows no visibility), its cusps as small
    // rings, and a legend entry with its counts and lattice. Kept, and
    // projected again with each new camera, until cleared or replaced;
    // clearScene() clears it.
    void setGroundTruth(std::shared_ptr<const GroundTruth> truth, int imageCrossings);
    void clearGroundTruth();
    bool showsGroundTruth() const { return static_cast<bool>(groundTruth_); }
    // Loops and cusp rings the next paint draws (0 without a ground truth).
    int groundTruthLoopsDrawn() const { return groundTruthDrawn_.loops; }
    int groundTruthCuspsDrawn() const { return groundTruthDrawn_.cusps; }
    // "ground truth: L loops, C cusps, X crossings (N = n)", empty without.
    QString groundTruthLegend() const;
    // The texts of the legend's entries, top to bottom.
    QStringList legendTexts() const;

    // Linked selection (Selection.h). What a click at `position` (widget
    // coordinates) hits: the mesh vertex of the nearest drawn view-graph node
    // within kPickPixels (nodes with a vertex: cusps, boundary folds), else
    // the nearest drawn chain within kPickPixels, else the front-most mesh
    // face under the click (projected with the analysis camera), narrowed to
    // its vertex or edge near the click as in the 3D view (pickWithinFace),
    // else nothing.
    Selection pick(const QPointF& position) const;
    static constexpr double kPickPixels = 5.0;
    static constexpr double kPickVertexPixels = 6.0; // widget pixels
    static constexpr double kPickEdgePixels = 4.0;
    // A press and release further apart than this is not a click.
    static constexpr double kClickSlopPixels = 4.0;
    // Draws the selected element in sceneColors::kSelection over the
    // picture: a face's projected outline, a vertex's ring, an edge, a
    // chain.
    void setHighlight(const Selection& selection);
    const Selection& highlight() const { return highlight_; }

    QSize sizeHint() const override { return {640, 480}; }
    QSize minimumSizeHint() const override { return {120, 90}; }

signals:
    // A left click: what pick() found there (possibly nothing).
    void pickRequested(const Selection& selection);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;

private:
    struct ProjectedCurve {
        CurveType type;
        QPainterPath path; // in image pixels
    };
    struct DrawnChain {
        Index chain;
        ChainState state;
        QPainterPath path; // in image pixels
    };
    struct Counts {
        int visible = 0, hidden = 0, simplified = 0, nodes = 0;
        std::array<int, kViewNodeTypeCount> nodesByType{};
        int cuspFolds = 0; // curtain folds at the smooth surface's cusps (ViewNode::smoothCusp)
        int singularCuspFolds =
            0; // ... at cusp vertices on singular points (ViewNode::singularCusp)
        int smallLoopCrossings = 0; // T-junctions of sub-pixel loops (ViewNode::smallLoop)
    };
    struct LegendEntry {
        enum Kind { Line, DashedLine, WideLine, ThinLine, SmallRing, Glyph } kind;
        QColor color;
        NodeGlyph glyph = NodeGlyph::Square;
        QString text;
    };

    // Projects the view graph's chains and decides what is drawn.
    void rebuildViewGraph();
    QColor chainPenColor(const ViewChain& chain) const;
    std::vector<LegendEntry> legendEntries() const;
    void paintViewGraph(QPainter& painter, const QRectF& frame) const;
    void paintLegend(QPainter& painter) const;
    void paintHighlight(QPainter& painter, const QRectF& frame) const;
    // The analysis camera's pixel under a widget point.
    Vec2 toImage(const QPointF& widgetPoint) const;

    struct Comparison {
        QString thisLabel, otherLabel;
        QPainterPath other, onlyHere, onlyOther; // in image pixels
        CurveDifference difference;
        std::optional<CurveDistanceField> field;
        std::array<QPainterPath, kDistanceBins> fieldBins; // by distance, nearest first
        std::optional<NodeDifference> nodes;
    };
    void paintComparison(QPainter& painter, const QRectF& frame) const;
    void appendComparisonLegend(std::vector<LegendEntry>& entries) const;
    QString comparisonDetailCaption() const;
    std::optional<Comparison> comparison_;

    // Projects the ground truth's loops and cusps with the camera.
    void rebuildGroundTruth();
    void paintGroundTruth(QPainter& painter, const QRectF& frame) const;
    void appendGroundTruthLegend(std::vector<LegendEntry>& entries) const;
    std::shared_ptr<const GroundTruth> groundTruth_;
    int groundTruthCrossings_ = 0;
    QPainterPath groundTruthPath_;       // in image pixels
    std::vector<Vec2> groundTruthCusps_; // image pixels of the cusps in front of the eye
    struct GroundTruthCounts {
        int loops = 0, cusps = 0;
    } groundTruthDrawn_;

    std::optional<Camera> camera_;
    std::vector<ProjectedCurve> paths_;
    QString caption_;

    std::shared_ptr<const ViewGraph> graph_;
    std::vector<DrawnChain> chains_; // hidden first, then simplified, then visible
    std::vector<Index> nodes_;       // the nodes drawn
    Counts drawn_;
    bool showHidden_ = true;
    bool showSimplified_ = false;
    bool showNodes_ = true;
    ChainColoring coloring_ = ChainColoring::ByQi;

    // Linked selection.
    std::shared_ptr<const TriangleMesh> mesh_;
    Selection highlight_;
    QPointF pressPosition_;
    bool leftPressed_ = false;
};

} // namespace contour
