#include "ImageView2D.h"

#include "SceneColors.h"

#include <QFontMetricsF>
#include <QMouseEvent>
#include <QPaintEvent>
#include <QPainter>
#include <algorithm>
#include <limits>

namespace contour {

namespace {

constexpr double kMargin = 12.0;
constexpr double kGlyphSize = 9.0;    // node glyphs, in screen pixels
constexpr double kVisibleWidth = 2.0; // screen pixels
constexpr double kComparisonHighlightWidth = 9.0;
constexpr double kHiddenWidth = 1.5;     // screen pixels
constexpr double kSimplifiedWidth = 1.0; // screen pixels

QColor curveColor(CurveType type) {
    switch (type) {
    case CurveType::Contour:
        return sceneColors::kContour2D.toQColor();
    case CurveType::Boundary:
        return sceneColors::kBoundary.toQColor();
    case CurveType::SurfaceIntersection:
        return sceneColors::kIntersection.toQColor();
    }
    return Qt::black;
}

QPen linePen(const QColor& color, double width, Qt::PenStyle style) {
    QPen pen(color, width, style);
    pen.setCosmetic(true); // width in screen pixels whatever the scale
    pen.setJoinStyle(Qt::RoundJoin);
    pen.setCapStyle(style == Qt::SolidLine ? Qt::RoundCap : Qt::FlatCap);
    return pen;
}

// A node glyph centred on `c` (widget coordinates), `size` pixels across,
// filled with `color` and outlined in dark grey so that light colours show
// on the white image.
void drawGlyph(QPainter& painter, const QPointF& c, NodeGlyph glyph, const QColor& color,
               double size) {
    const double r = 0.5 * size;
    painter.setPen(QPen(QColor(40, 40, 40), 1.0));
    painter.setBrush(color);
    switch (glyph) {
    case NodeGlyph::Square:
        painter.drawRect(QRectF(c.x() - r, c.y() - r, size, size));
        break;
    case NodeGlyph::Diamond:
        painter.drawPolygon(QPolygonF({c + QPointF(0, -1.3 * r), c + QPointF(1.3 * r, 0),
                                       c + QPointF(0, 1.3 * r), c + QPointF(-1.3 * r, 0)}));
        break;
    case NodeGlyph::TriangleUp:
        painter.drawPolygon(QPolygonF(
            {c + QPointF(-1.2 * r, r), c + QPointF(1.2 * r, r), c + QPointF(0, -1.3 * r)}));
        break;
    case NodeGlyph::TriangleDown:
        painter.drawPolygon(QPolygonF(
            {c + QPointF(-1.2 * r, -r), c + QPointF(1.2 * r, -r), c + QPointF(0, 1.3 * r)}));
        break;
    case NodeGlyph::Circle:
        painter.drawEllipse(c, r, r);
        break;
    case NodeGlyph::Ring:
        painter.setPen(QPen(color, 2.5));
        painter.setBrush(Qt::NoBrush);
        painter.drawEllipse(c, r, r);
        break;
    case NodeGlyph::Cross:
        painter.setPen(QPen(color, 2.5));
        painter.drawLine(c + QPointF(-r, -r), c + QPointF(r, r));
        painter.drawLine(c + QPointF(-r, r), c + QPointF(r, -r));
        break;
    }
}

// Appends the polyline through `points` (each placed by `position`; a
// closed one joins back to its first point) to `path`, projected by
// `camera` into image pixels. A segment is drawn when both ends are in front
// of the eye. Returns the segments appended.
template <class Points, class Position>
int appendProjected(QPainterPath& path, const Camera& camera, const Points& points, bool closed,
                    Position position) {
    const size_t n = points.size();
    if (n == 0)
        return 0;
    const size_t count = closed ? n + 1 : n;
    bool penDown = false;
    int segments = 0;
    for (size_t i = 0; i < count; ++i) {
        const ProjectedPoint p = camera.project(position(points[i % n]));
        if (!(p.depth > 0.0) || !p.pixel.allFinite()) {
            penDown = false;
            continue;
        }
        const QPointF q(p.pixel.x(), p.pixel.y());
        if (penDown) {
            path.lineTo(q);
            ++segments;
        } else {
            path.moveTo(q);
        }
        penDown = true;
    }
    return segments;
}

} // namespace

ImageView2D::ImageView2D(QWidget* parent) : QWidget(parent) {
    loadSceneColors();
    setAttribute(Qt::WA_OpaquePaintEvent);
    setAutoFillBackground(false);
}

void ImageView2D::setScene(const Snapshot& snapshot, const Camera& camera) {
    camera_ = camera;
    paths_.clear();
    int contours = 0, boundaries = 0, others = 0;
    if (snapshot.curves) {
        for (const Polyline& curve : *snapshot.curves) {
            if (curve.points.size() < 2)
                continue;
            ProjectedCurve projected{curve.type, {}};
            appendProjected(projected.path, camera, curve.points, curve.closed,
                            [](const CurvePoint& p) { return p.position; });
            contours += curve.type == CurveType::Contour;
            boundaries += curve.type == CurveType::Boundary;
            others += curve.type == CurveType::SurfaceIntersection;
            paths_.push_back(std::move(projected));
        }
    }
    graph_ = snapshot.viewGraph;
    mesh_ = snapshot.mesh;
    if (graph_) {
        long long visible = 0, hidden = 0;
        for (const ViewChain& chain : graph_->chains) {
            visible += chainState(chain) == ChainState::Visible;
            hidden += chainState(chain) == ChainState::Hidden;
        }
        caption_ = QStringLiteral("%1 — view graph: %2 visible, %3 hidden chains, %4 nodes")
                       .arg(QString::fromStdString(snapshot.phaseName))
                       .arg(visible)
                       .arg(hidden)
                       .arg(graph_->nodes.size());
    } else {
        caption_ = QStringLiteral("%1 — %2 contour, %3 boundary curves")
                       .arg(QString::fromStdString(snapshot.phaseName))
                       .arg(contours)
                       .arg(boundaries);
        if (others > 0)
            caption_ += QStringLiteral(", %1 intersections").arg(others);
    }
    rebuildViewGraph();
    rebuildGroundTruth();
    update();
}

void ImageView2D::clearScene() {
    camera_.reset();
    paths_.clear();
    caption_.clear();
    graph_.reset();
    mesh_.reset();
    comparison_.reset();
    groundTruth_.reset();
    rebuildViewGraph();
    rebuildGroundTruth();
    update();
}

namespace {

QPainterPath pathOf(const std::vector<ImagePolyline>& lines) {
    QPainterPath path;
    for (const ImagePolyline& line : lines) {
        if (line.size() < 2)
            continue;
        path.moveTo(line.front().x(), line.front().y());
        for (std::size_t i = 1; i < line.size(); ++i)
            path.lineTo(line[i].x(), line[i].y());
    }
    return path;
}

} // namespace

void ImageView2D::setComparison(const QString& thisLabel, const QString& otherLabel,
                                const std::vector<ImagePolyline>& otherCurves,
                                const CurveDifference& difference) {
    comparison_ = Comparison{};
    comparison_->thisLabel = thisLabel;
    comparison_->otherLabel = otherLabel;
    comparison_->other = pathOf(otherCurves);
    comparison_->onlyHere = pathOf(difference.onlyInA);
    comparison_->onlyOther = pathOf(difference.onlyInB);
    comparison_->difference = difference;
    update();
}

namespace {

// The distance field's colours, nearest to farthest (ColorBrewer RdYlGn,
// reversed): green within a pixel, red at the cap.
QColor distanceColor(int bin) {
    static const std::array<QColor, ImageView2D::kDistanceBins> ramp{
        QColor(26, 152, 80),   QColor(145, 207, 96), QColor(217, 239, 139),
        QColor(254, 224, 139), QColor(252, 141, 89), QColor(215, 48, 39)};
    return ramp[static_cast<size_t>(std::clamp(bin, 0, ImageView2D::kDistanceBins - 1))];
}

} // namespace

void ImageView2D::setComparisonDetail(const CurveDistanceField& field,
                                      const NodeDifference& nodes) {
    if (!comparison_)
        return;
    comparison_->field = field;
    comparison_->nodes = nodes;
    for (QPainterPath& bin : comparison_->fieldBins)
        bin = QPainterPath();
    for (size_t c = 0; c < field.points.size(); ++c)
        for (size_t i = 1; i < field.points[c].size(); ++i) {
            const double d = 0.5 * (field.distances[c][i - 1] + field.distances[c][i]);
            const int bin =
                field.cap > 0.0 ? static_cast<int>(std::floor(d / field.cap * kDistanceBins)) : 0;
            QPainterPath& path =
                comparison_->fieldBins[static_cast<size_t>(std::clamp(bin, 0, kDistanceBins - 1))];
            path.moveTo(field.points[c][i - 1].x(), field.points[c][i - 1].y());
            path.lineTo(field.points[c][i].x(), field.points[c][i].y());
        }
    update();
}

void ImageView2D::clearComparison() {
    comparison_.reset();
    update();
}

QString ImageView2D::comparisonCaption() const {
    if (!comparison_)
        return {};
    const CurveDifference& d = comparison_->difference;
    return tr("only %1: %2 of %3 px · only %4: %5 of %6 px (farther than %7 px)")
               .arg(comparison_->thisLabel)
               .arg(d.onlyInALength, 0, 'f', 0)
               .arg(d.lengthA, 0, 'f', 0)
               .arg(comparison_->otherLabel)
               .arg(d.onlyInBLength, 0, 'f', 0)
               .arg(d.lengthB, 0, 'f', 0)
               .arg(d.tolerancePixels, 0, 'g', 2) +
           comparisonDetailCaption();
}

QString ImageView2D::comparisonDetailCaption() const {
    QString text;
    if (comparison_->field && comparison_->field->count > 0) {
        const CurveDistanceField& f = *comparison_->field;
        text += tr(" · distance to %1: mean %2, 95 % %3, max %4 px (capped at %5)")
                    .arg(comparison_->otherLabel)
                    .arg(f.mean, 0, 'f', 2)
                    .arg(f.p95, 0, 'f', 2)
                    .arg(f.max, 0, 'f', 2)
                    .arg(f.cap, 0, 'g', 3);
    }
    if (comparison_->nodes) {
        const NodeDifference& n = *comparison_->nodes;
        text += tr(" · curves %1 vs %2 · cusps %3 vs %4 (%5 and %6 unmatched) · T-junctions "
                   "%7 vs %8 (%9 and %10 unmatched)")
                    .arg(n.a.curves)
                    .arg(n.b.curves)
                    .arg(n.a.cusps.size())
                    .arg(n.b.cusps.size())
                    .arg(n.cuspsOnlyInA.size())
                    .arg(n.cuspsOnlyInB.size())
                    .arg(n.a.tJunctions.size())
                    .arg(n.b.tJunctions.size())
                    .arg(n.tJunctionsOnlyInA.size())
                    .arg(n.tJunctionsOnlyInB.size());
    }
    return text;
}

void ImageView2D::paintComparison(QPainter& painter, const QRectF& frame) const {
    painter.save();
    painter.setClipRect(frame);
    const double scale = frame.width() / camera_->viewport.width;
    painter.translate(frame.topLeft());
    painter.scale(scale, scale);
    QColor here = sceneColors::kComparisonOnlyHere.toQColor();
    QColor other = sceneColors::kComparisonOther.toQColor();
    here.setAlphaF(static_cast<float>(sceneColors::kComparisonHighlightOpacity));
    QColor otherHighlight = other;
    otherHighlight.setAlphaF(static_cast<float>(sceneColors::kComparisonHighlightOpacity));
    painter.setPen(linePen(here, kComparisonHighlightWidth, Qt::SolidLine));
    painter.drawPath(comparison_->onlyHere);
    painter.setPen(linePen(otherHighlight, kComparisonHighlightWidth, Qt::SolidLine));
    painter.drawPath(comparison_->onlyOther);
    for (int bin = 0; bin < kDistanceBins; ++bin) {
        painter.setPen(linePen(distanceColor(bin), 2.0, Qt::SolidLine));
        painter.drawPath(comparison_->fieldBins[static_cast<size_t>(bin)]);
    }
    painter.setPen(linePen(other, 1.0, Qt::SolidLine));
    painter.drawPath(comparison_->other);
    painter.restore();
    // Cusps and T-junctions only one side draws, in widget coordinates so
    // the glyphs keep their size.
    if (comparison_->nodes) {
        const NodeDifference& n = *comparison_->nodes;
        const auto at = [&](const Vec2& p) {
            return QPointF(frame.left() + p.x() * scale, frame.top() + p.y() * scale);
        };
        QColor hereMark = sceneColors::kComparisonOnlyHere.toQColor();
        QColor otherMark = sceneColors::kComparisonOther.toQColor();
        for (const Vec2& p : n.cuspsOnlyInA)
            drawGlyph(painter, at(p), NodeGlyph::Ring, hereMark, 11.0);
        for (const Vec2& p : n.cuspsOnlyInB)
            drawGlyph(painter, at(p), NodeGlyph::Ring, otherMark, 11.0);
        for (const Vec2& p : n.tJunctionsOnlyInA)
            drawGlyph(painter, at(p), NodeGlyph::Cross, hereMark, 9.0);
        for (const Vec2& p : n.tJunctionsOnlyInB)
            drawGlyph(painter, at(p), NodeGlyph::Cross, otherMark, 9.0);
    }
    // The lengths, above the viewport size at the bottom, wrapped.
    painter.save();
    const QRectF box(frame.left() + 4.0, frame.bottom() - 58.0, frame.width() - 8.0, 38.0);
    painter.setPen(QColor(30, 30, 30));
    painter.drawText(box, Qt::AlignLeft | Qt::AlignBottom | Qt::TextWordWrap, comparisonCaption());
    painter.restore();
}

void ImageView2D::setGroundTruth(std::shared_ptr<const GroundTruth> truth, int imageCrossings) {
    groundTruth_ = std::move(truth);
    groundTruthCrossings_ = imageCrossings;
    rebuildGroundTruth();
    update();
}

void ImageView2D::clearGroundTruth() {
    groundTruth_.reset();
    rebuildGroundTruth();
    update();
}

void ImageView2D::rebuildGroundTruth() {
    groundTruthPath_ = QPainterPath();
    groundTruthCusps_.clear();
    groundTruthDrawn_ = GroundTruthCounts();
    if (!groundTruth_ || !camera_)
        return;
    const Camera& camera = *camera_;
    for (const GroundTruthLoop& loop : groundTruth_->loops)
        groundTruthDrawn_.loops +=
            appendProjected(groundTruthPath_, camera, loop.points, loop.closed,
                            [](const Vec3& p) { return p; }) > 0;
    for (const GroundTruthCusp& cusp : groundTruth_->cusps) {
        const ProjectedPoint p = camera.project(cusp.position);
        if (!(p.depth > 0.0) || !p.pixel.allFinite())
            continue;
        groundTruthCusps_.push_back(p.pixel);
        ++groundTruthDrawn_.cusps;
    }
}

QString ImageView2D::groundTruthLegend() const {
    if (!groundTruth_)
        return {};
    return tr("ground truth: %1 loops, %2 cusps, %3 crossings (N = %4)")
        .arg(groundTruth_->loops.size())
        .arg(groundTruth_->cusps.size())
        .arg(groundTruthCrossings_)
        .arg(groundTruth_->samples);
}

void ImageView2D::paintGroundTruth(QPainter& painter, const QRectF& frame) const {
    const QColor color = sceneColors::kGroundTruth.toQColor();
    painter.save();
    painter.setClipRect(frame);
    painter.save();
    const double scale = frame.width() / camera_->viewport.width;
    painter.translate(frame.topLeft());
    painter.scale(scale, scale);
    painter.setBrush(Qt::NoBrush);
    painter.setPen(linePen(color, sceneColors::kGroundTruthLineWidth2D, Qt::SolidLine));
    painter.drawPath(groundTruthPath_);
    painter.restore();
    // Rings at a fixed screen size: the method's own cusp glyph stays
    // visible inside.
    painter.setPen(linePen(color, 1.5, Qt::SolidLine));
    painter.setBrush(Qt::NoBrush);
    const double r = 0.5 * sceneColors::kGroundTruthCuspSize2D;
    for (const Vec2& pixel : groundTruthCusps_)
        painter.drawEllipse(toWidget(pixel), r, r);
    painter.restore();
}

void ImageView2D::appendGroundTruthLegend(std::vector<LegendEntry>& entries) const {
    if (!groundTruth_)
        return;
    const QColor color = sceneColors::kGroundTruth.toQColor();
    entries.push_back({LegendEntry::ThinLine, color, NodeGlyph::Ring, groundTruthLegend()});
    if (!groundTruth_->cusps.empty())
        entries.push_back(
            {LegendEntry::SmallRing, color, NodeGlyph::Ring, tr("ground-truth cusp")});
}

QStringList ImageView2D::legendTexts() const {
    QStringList texts;
    for (const LegendEntry& e : legendEntries())
        texts << e.text;
    return texts;
}

void ImageView2D::setShowHiddenCurves(bool show) {
    showHidden_ = show;
    rebuildViewGraph();
    update();
}

void ImageView2D::setShowSimplifiedCurves(bool show) {
    showSimplified_ = show;
    rebuildViewGraph();
    update();
}

void ImageView2D::setShowNodes(bool show) {
    showNodes_ = show;
    rebuildViewGraph();
    update();
}

void ImageView2D::setChainColoring(ChainColoring coloring) {
    coloring_ = coloring;
    update();
}

void ImageView2D::rebuildViewGraph() {
    chains_.clear();
    nodes_.clear();
    drawn_ = Counts();
    if (!graph_ || !camera_)
        return;
    const Camera& camera = *camera_;
    std::vector<DrawnChain> visible, hidden, simplified;
    for (Index c = 0; c < static_cast<Index>(graph_->chains.size()); ++c) {
        const ViewChain& chain = graph_->chains[c];
        const ChainState state = chainState(chain);
        if ((state == ChainState::Hidden && !showHidden_) ||
            (state == ChainState::Simplified && !showSimplified_))
            continue;
        // The builder's pixels when it gave one per point, else the 3D points
        // projected; a segment is drawn when both ends are in front of the eye.
        const bool hasImage =
            chain.image.size() == chain.points.size() && chain.depth.size() == chain.points.size();
        DrawnChain drawn{c, state, {}};
        bool penDown = false;
        int segments = 0;
        for (size_t i = 0; i < chain.points.size(); ++i) {
            Vec2 pixel;
            double depth;
            if (hasImage) {
                pixel = chain.image[i];
                depth = chain.depth[i];
            } else {
                const ProjectedPoint p = camera.project(chain.points[i]);
                pixel = p.pixel;
                depth = p.depth;
            }
            if (!(depth > 0.0) || !pixel.allFinite()) {
                penDown = false;
                continue;
            }
            const QPointF q(pixel.x(), pixel.y());
            if (penDown) {
                drawn.path.lineTo(q);
                ++segments;
            } else {
                drawn.path.moveTo(q);
            }
            penDown = true;
        }
        if (segments == 0)
            continue;
        switch (state) {
        case ChainState::Visible:
            ++drawn_.visible;
            visible.push_back(std::move(drawn));
            break;
        case ChainState::Hidden:
            ++drawn_.hidden;
            hidden.push_back(std::move(drawn));
            break;
        case ChainState::Simplified:
            ++drawn_.simplified;
            simplified.push_back(std::move(drawn));
            break;
        }
    }
    // Painted in this order: what is visible ends up on top.
    for (auto* group : {&hidden, &simplified, &visible})
        for (DrawnChain& d : *group)
            chains_.push_back(std::move(d));

    if (!showNodes_)
        return;
    for (Index n = 0; n < static_cast<Index>(graph_->nodes.size()); ++n) {
        if (!showHidden_ && nodeIsHidden(*graph_, n))
            continue;
        const ProjectedPoint p = camera.project(graph_->nodes[n].position);
        if (!(p.depth > 0.0) || !p.pixel.allFinite())
            continue;
        nodes_.push_back(n);
        ++drawn_.nodes;
        ++drawn_.nodesByType[static_cast<size_t>(graph_->nodes[n].type)];
        drawn_.cuspFolds += graph_->nodes[n].smoothCusp;
        drawn_.singularCuspFolds += graph_->nodes[n].singularCusp;
        drawn_.smallLoopCrossings += graph_->nodes[n].smallLoop;
    }
}

QColor ImageView2D::chainPenColor(const ViewChain& chain) const {
    if (chainState(chain) == ChainState::Simplified)
        return viewGraphColors::kSimplified2D.toQColor();
    if (coloring_ == ChainColoring::ByChain) {
        const Index index = static_cast<Index>(&chain - graph_->chains.data());
        return chainColor(index).toQColor();
    }
    return qiColor(chain.qi, sceneColors::kContour2D).toQColor();
}

QRectF ImageView2D::imageRect() const {
    const QRectF area = QRectF(rect()).adjusted(kMargin, kMargin + 14.0, -kMargin, -kMargin);
    if (!camera_ || area.width() <= 0 || area.height() <= 0)
        return area;
    const double w = camera_->viewport.width, h = camera_->viewport.height;
    const double scale = std::min(area.width() / w, area.height() / h);
    const QSizeF size(w * scale, h * scale);
    return {area.center() - QPointF(0.5 * size.width(), 0.5 * size.height()), size};
}

QPointF ImageView2D::toWidget(const Vec2& imagePixel) const {
    const QRectF frame = imageRect();
    if (!camera_)
        return frame.topLeft();
    const double scale = frame.width() / camera_->viewport.width;
    return frame.topLeft() + QPointF(imagePixel.x() * scale, imagePixel.y() * scale);
}

std::vector<ImageView2D::LegendEntry> ImageView2D::legendEntries() const {
    std::vector<LegendEntry> entries;
    if (!graph_) {
        appendComparisonLegend(entries);
        appendGroundTruthLegend(entries);
        return entries;
    }
    // Only what is drawn: the legend explains the picture.
    std::array<bool, 5> qiShown{}; // unknown, 0, 1, 2, 3+
    for (const DrawnChain& d : chains_) {
        const int qi = graph_->chains[d.chain].qi;
        if (d.state != ChainState::Simplified)
            qiShown[static_cast<size_t>(std::clamp(qi, -1, 3) + 1)] = true;
    }
    if (coloring_ == ChainColoring::ByQi) {
        if (qiShown[1])
            entries.push_back({LegendEntry::Line, sceneColors::kContour2D.toQColor(),
                               NodeGlyph::Square, tr("QI 0 (visible)")});
        const char* names[] = {"QI 1", "QI 2", "QI 3+"};
        for (int qi = 1; qi <= 3; ++qi)
            if (qiShown[static_cast<size_t>(qi + 1)])
                entries.push_back({LegendEntry::DashedLine,
                                   qiColor(qi, sceneColors::kContour2D).toQColor(),
                                   NodeGlyph::Square, tr(names[qi - 1])});
        if (qiShown[0])
            entries.push_back({LegendEntry::DashedLine, viewGraphColors::kUnknownQi.toQColor(),
                               NodeGlyph::Square, tr("QI unknown")});
    } else {
        if (drawn_.visible > 0)
            entries.push_back({LegendEntry::Line, chainColor(0).toQColor(), NodeGlyph::Square,
                               tr("visible (a colour per chain)")});
        if (drawn_.hidden > 0)
            entries.push_back({LegendEntry::DashedLine, chainColor(1).toQColor(), NodeGlyph::Square,
                               tr("hidden")});
    }
    if (drawn_.simplified > 0)
        entries.push_back({LegendEntry::Line, viewGraphColors::kSimplified2D.toQColor(),
                           NodeGlyph::Square, tr("simplified away")});
    for (int t = 0; t < kViewNodeTypeCount; ++t) {
        if (drawn_.nodesByType[static_cast<size_t>(t)] == 0)
            continue;
        const NodeStyle style = nodeStyle(static_cast<ViewNodeType>(t));
        const int count = drawn_.nodesByType[static_cast<size_t>(t)];
        QString label = QStringLiteral("%1 (%2)").arg(tr(style.label)).arg(count);
        // Consistent contours: the smooth surface's cusps and the folds of
        // the near-face fallback next to inconsistent faces, counted apart.
        if (static_cast<ViewNodeType>(t) == ViewNodeType::CurtainFold && drawn_.cuspFolds > 0)
            label = QStringLiteral("%1 (%2 at cusps, %3 by a mesh test)")
                        .arg(tr(style.label))
                        .arg(drawn_.cuspFolds)
                        .arg(count - drawn_.cuspFolds);
        // Cusps at singular points of the surface are stepped by the mesh's
        // one-ring test: the smooth fold does not exist there.
        if (static_cast<ViewNodeType>(t) == ViewNodeType::CurtainFold &&
            drawn_.singularCuspFolds > 0)
            label = QStringLiteral("%1 (%2 at cusps, %3 at singular points, %4 by a mesh test)")
                        .arg(tr(style.label))
                        .arg(drawn_.cuspFolds)
                        .arg(drawn_.singularCuspFolds)
                        .arg(count - drawn_.cuspFolds - drawn_.singularCuspFolds);
        // T-junctions of sub-pixel loops of the polylines (zig-zags next to
        // cusps), counted apart from the crossings of the smooth contour.
        if (static_cast<ViewNodeType>(t) == ViewNodeType::ImageIntersection &&
            drawn_.smallLoopCrossings > 0)
            label = QStringLiteral("%1 (%2, %3 in sub-pixel loops)")
                        .arg(tr(style.label))
                        .arg(count - drawn_.smallLoopCrossings)
                        .arg(drawn_.smallLoopCrossings);
        entries.push_back({LegendEntry::Glyph, style.color.toQColor(), style.glyph, label});
    }
    appendComparisonLegend(entries);
    appendGroundTruthLegend(entries);
    return entries;
}

void ImageView2D::appendComparisonLegend(std::vector<LegendEntry>& entries) const {
    if (!comparison_)
        return;
    QColor here = sceneColors::kComparisonOnlyHere.toQColor();
    QColor other = sceneColors::kComparisonOther.toQColor();
    entries.push_back({LegendEntry::Line, other, NodeGlyph::Square, comparison_->otherLabel});
    here.setAlphaF(static_cast<float>(sceneColors::kComparisonHighlightOpacity));
    other.setAlphaF(static_cast<float>(sceneColors::kComparisonHighlightOpacity));
    entries.push_back({LegendEntry::WideLine, here, NodeGlyph::Square,
                       tr("only %1").arg(comparison_->thisLabel)});
    entries.push_back({LegendEntry::WideLine, other, NodeGlyph::Square,
                       tr("only %1").arg(comparison_->otherLabel)});
    if (comparison_->field) {
        entries.push_back({LegendEntry::Line, distanceColor(0), NodeGlyph::Square,
                           tr("< %1 px from %2")
                               .arg(comparison_->field->cap / kDistanceBins, 0, 'g', 2)
                               .arg(comparison_->otherLabel)});
        entries.push_back({LegendEntry::Line, distanceColor(kDistanceBins - 1), NodeGlyph::Square,
                           tr("≥ %1 px").arg(comparison_->field->cap, 0, 'g', 2)});
    }
    if (comparison_->nodes) {
        const NodeDifference& n = *comparison_->nodes;
        if (!n.cuspsOnlyInA.empty() || !n.cuspsOnlyInB.empty())
            entries.push_back({LegendEntry::Glyph, sceneColors::kComparisonOnlyHere.toQColor(),
                               NodeGlyph::Ring, tr("cusp of one side only")});
        if (!n.tJunctionsOnlyInA.empty() || !n.tJunctionsOnlyInB.empty())
            entries.push_back({LegendEntry::Glyph, sceneColors::kComparisonOnlyHere.toQColor(),
                               NodeGlyph::Cross, tr("T-junction of one side only")});
    }
}

QRectF ImageView2D::legendRect() const {
    const std::vector<LegendEntry> entries = legendEntries();
    if (entries.empty())
        return {};
    const QFontMetricsF metrics(font());
    double textWidth = 0.0;
    for (const LegendEntry& e : entries)
        textWidth = std::max(textWidth, metrics.horizontalAdvance(e.text));
    const double line = metrics.height() + 2.0;
    const QSizeF size(textWidth + 42.0, line * static_cast<double>(entries.size()) + 8.0);
    const QRectF frame = imageRect();
    return {QPointF(frame.right() - size.width() - 6.0, frame.top() + 6.0), size};
}

void ImageView2D::paintViewGraph(QPainter& painter, const QRectF& frame) const {
    painter.save();
    painter.setClipRect(frame);
    const double scale = frame.width() / camera_->viewport.width;
    painter.save();
    painter.translate(frame.topLeft());
    painter.scale(scale, scale);
    painter.setBrush(Qt::NoBrush);
    for (const DrawnChain& d : chains_) {
        const ViewChain& chain = graph_->chains[d.chain];
        switch (d.state) {
        case ChainState::Visible:
            painter.setPen(linePen(chainPenColor(chain), kVisibleWidth, Qt::SolidLine));
            break;
        case ChainState::Hidden:
            painter.setPen(linePen(chainPenColor(chain), kHiddenWidth, Qt::DashLine));
            break;
        case ChainState::Simplified:
            painter.setPen(linePen(chainPenColor(chain), kSimplifiedWidth, Qt::SolidLine));
            break;
        }
        painter.drawPath(d.path);
    }
    painter.restore();
    // Glyphs at a fixed screen size, over the chains.
    for (const Index n : nodes_) {
        const ViewNode& node = graph_->nodes[n];
        const NodeStyle style = nodeStyle(node.type);
        const ProjectedPoint p = camera_->project(node.position);
        drawGlyph(painter, toWidget(p.pixel), style.glyph, style.color.toQColor(), kGlyphSize);
    }
    painter.restore();
}

void ImageView2D::paintLegend(QPainter& painter) const {
    const std::vector<LegendEntry> entries = legendEntries();
    if (entries.empty())
        return;
    const QRectF box = legendRect();
    painter.save();
    painter.setPen(QPen(QColor(120, 120, 120), 1.0));
    painter.setBrush(QColor(255, 255, 255, 225));
    painter.drawRect(box);
    const QFontMetricsF metrics(font());
    const double line = metrics.height() + 2.0;
    double y = box.top() + 4.0;
    for (const LegendEntry& e : entries) {
        const double mid = y + 0.5 * line;
        const QPointF left(box.left() + 6.0, mid), right(box.left() + 32.0, mid);
        switch (e.kind) {
        case LegendEntry::Line:
            painter.setPen(linePen(e.color, kVisibleWidth, Qt::SolidLine));
            painter.drawLine(left, right);
            break;
        case LegendEntry::DashedLine:
            painter.setPen(linePen(e.color, kHiddenWidth, Qt::DashLine));
            painter.drawLine(left, right);
            break;
        case LegendEntry::WideLine:
            painter.setPen(linePen(e.color, kComparisonHighlightWidth, Qt::SolidLine));
            painter.drawLine(left, right);
            break;
        case LegendEntry::ThinLine:
            painter.setPen(linePen(e.color, sceneColors::kGroundTruthLineWidth2D, Qt::SolidLine));
            painter.drawLine(left, right);
            break;
        case LegendEntry::SmallRing: {
            const double r = 0.5 * sceneColors::kGroundTruthCuspSize2D;
            painter.setPen(linePen(e.color, 1.5, Qt::SolidLine));
            painter.setBrush(Qt::NoBrush);
            painter.drawEllipse(0.5 * (left + right), r, r);
            break;
        }
        case LegendEntry::Glyph:
            drawGlyph(painter, 0.5 * (left + right), e.glyph, e.color, kGlyphSize);
            break;
        }
        painter.setPen(QColor(30, 30, 30));
        painter.drawText(QRectF(box.left() + 38.0, y, box.width() - 40.0, line),
                         Qt::AlignLeft | Qt::AlignVCenter, e.text);
        y += line;
    }
    painter.restore();
}

void ImageView2D::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), palette().color(QPalette::Window).darker(115));
    if (!camera_) {
        painter.setPen(palette().color(QPalette::WindowText));
        painter.drawText(rect(), Qt::AlignCenter, tr("Open a mesh to see its contours here"));
        return;
    }
    const QRectF frame = imageRect();
    painter.fillRect(frame, Qt::white);
    painter.setPen(palette().color(QPalette::WindowText));
    painter.drawText(QRectF(kMargin, 2.0, width() - 2 * kMargin, 18.0),
                     Qt::AlignLeft | Qt::AlignVCenter, caption_);

    painter.setRenderHint(QPainter::Antialiasing);
    if (graph_) {
        paintViewGraph(painter, frame);
    } else {
        painter.save();
        painter.setClipRect(frame);
        const double scale = frame.width() / camera_->viewport.width;
        painter.translate(frame.topLeft());
        painter.scale(scale, scale);
        for (const ProjectedCurve& curve : paths_) {
            painter.setPen(linePen(curveColor(curve.type), kVisibleWidth, Qt::SolidLine));
            painter.drawPath(curve.path);
        }
        painter.restore();
    }

    if (comparison_)
        paintComparison(painter, frame);
    if (groundTruth_)
        paintGroundTruth(painter, frame);

    painter.setPen(QPen(QColor(60, 60, 60), 1.0));
    painter.setBrush(Qt::NoBrush);
    painter.drawRect(frame);
    painter.drawText(
        frame.adjusted(4, 2, -4, -2), Qt::AlignRight | Qt::AlignBottom,
        QStringLiteral("%1 × %2").arg(camera_->viewport.width).arg(camera_->viewport.height));
    paintHighlight(painter, frame);
    if (graph_ || comparison_ || groundTruth_)
        paintLegend(painter);
}

Vec2 ImageView2D::toImage(const QPointF& widgetPoint) const {
    const QRectF frame = imageRect();
    if (!camera_ || frame.width() <= 0.0)
        return Vec2::Zero();
    const double scale = frame.width() / camera_->viewport.width;
    const QPointF p = (widgetPoint - frame.topLeft()) / scale;
    return {p.x(), p.y()};
}

Selection ImageView2D::pick(const QPointF& position) const {
    if (!camera_)
        return {};
    const QRectF frame = imageRect();
    if (!frame.contains(position))
        return {};
    const double scale = frame.width() / camera_->viewport.width;
    const Vec2 click = toImage(position);
    // Node glyphs are drawn over the chains: a drawn node that stands on a
    // mesh vertex (a cusp, a boundary curtain fold) picks that vertex.
    if (graph_) {
        Index bestVertex = kInvalidIndex;
        double bestDistance = kPickPixels / scale;
        for (const Index n : nodes_) {
            const ViewNode& node = graph_->nodes[static_cast<size_t>(n)];
            // Where the glyph is drawn (rebuildViewGraph).
            const double distance = (camera_->project(node.position).pixel - click).norm();
            if (node.meshVertex != kInvalidIndex && distance <= bestDistance) {
                bestDistance = distance;
                bestVertex = node.meshVertex;
            }
        }
        if (bestVertex != kInvalidIndex && mesh_ && bestVertex < mesh_->vertexCount())
            return Selection::vertex(bestVertex);
    }
    // Chains: the nearest drawn polyline, in widget pixels.
    Index bestChain = kInvalidIndex;
    double bestDistance = kPickPixels / scale;
    for (const DrawnChain& d : chains_) {
        QPointF previous;
        for (int i = 0; i < d.path.elementCount(); ++i) {
            const QPainterPath::Element e = d.path.elementAt(i);
            const QPointF point(e.x, e.y);
            if (e.isLineTo()) {
                const Vec2 a(previous.x(), previous.y()), b(point.x(), point.y());
                const Vec2 ab = b - a;
                const double s = ab.squaredNorm() > 0.0
                                     ? std::clamp((click - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                                     : 0.0;
                const double distance = (a + s * ab - click).norm();
                // Later chains are painted on top: ties go to them.
                if (distance <= bestDistance) {
                    bestDistance = distance;
                    bestChain = d.chain;
                }
            }
            previous = point;
        }
    }
    if (bestChain != kInvalidIndex)
        return Selection::chain(bestChain);
    // Faces: the nearest one (depth interpolated at the click) whose
    // projection holds the click.
    if (!mesh_)
        return {};
    const Camera& camera = *camera_;
    std::vector<ProjectedPoint> projected(static_cast<size_t>(mesh_->vertexCount()));
    for (Index v = 0; v < mesh_->vertexCount(); ++v)
        projected[static_cast<size_t>(v)] = camera.project(mesh_->position(v));
    Index bestFace = kInvalidIndex;
    double bestDepth = std::numeric_limits<double>::infinity();
    for (Index f = 0; f < mesh_->faceCount(); ++f) {
        const Triangle& t = mesh_->triangle(f);
        const ProjectedPoint& a = projected[static_cast<size_t>(t[0])];
        const ProjectedPoint& b = projected[static_cast<size_t>(t[1])];
        const ProjectedPoint& c = projected[static_cast<size_t>(t[2])];
        if (!(a.depth > 0.0 && b.depth > 0.0 && c.depth > 0.0))
            continue;
        const Vec2 ab = b.pixel - a.pixel, ac = c.pixel - a.pixel, ap = click - a.pixel;
        const double det = ab.x() * ac.y() - ab.y() * ac.x();
        if (!(std::abs(det) > 0.0))
            continue;
        const double s = (ap.x() * ac.y() - ap.y() * ac.x()) / det;
        const double r = (ab.x() * ap.y() - ab.y() * ap.x()) / det;
        if (s < 0.0 || r < 0.0 || s + r > 1.0)
            continue;
        const double depth = (1.0 - s - r) * a.depth + s * b.depth + r * c.depth;
        if (depth < bestDepth) {
            bestDepth = depth;
            bestFace = f;
        }
    }
    if (bestFace == kInvalidIndex)
        return {};
    // Its vertex or edge when the click is near one, as in the 3D view.
    const Triangle& t = mesh_->triangle(bestFace);
    std::array<Vec2, 3> corners;
    for (size_t i = 0; i < 3; ++i)
        corners[i] = projected[static_cast<size_t>(t[i])].pixel;
    return pickWithinFace(*mesh_, bestFace, corners, click, kPickVertexPixels / scale,
                          kPickEdgePixels / scale);
}

void ImageView2D::setHighlight(const Selection& selection) {
    highlight_ = selection;
    update();
}

void ImageView2D::paintHighlight(QPainter& painter, const QRectF& frame) const {
    if (highlight_.isEmpty() || !camera_)
        return;
    const Camera& camera = *camera_;
    const QColor color = sceneColors::kSelection.toQColor();
    const double width = sceneColors::kSelectionLineWidth;
    // Widget point of a 3D point, or nothing behind the eye.
    const auto widgetPoint = [&](const Vec3& p) -> std::optional<QPointF> {
        const ProjectedPoint q = camera.project(p);
        if (!(q.depth > 0.0) || !q.pixel.allFinite())
            return std::nullopt;
        return toWidget(q.pixel);
    };
    painter.save();
    painter.setClipRect(frame);
    painter.setBrush(Qt::NoBrush);
    painter.setPen(linePen(color, width, Qt::SolidLine));
    const Index id = highlight_.id;
    switch (highlight_.kind) {
    case SelectionKind::Face:
        if (mesh_ && id >= 0 && id < mesh_->faceCount()) {
            const Triangle& t = mesh_->triangle(id);
            QPolygonF polygon;
            for (int i = 0; i < 3; ++i)
                if (const auto p = widgetPoint(mesh_->position(t[i])))
                    polygon << *p;
            if (polygon.size() == 3) {
                QColor fill = color;
                fill.setAlpha(90);
                painter.setBrush(fill);
                painter.drawPolygon(polygon);
            }
        }
        break;
    case SelectionKind::Vertex:
        if (mesh_ && id >= 0 && id < mesh_->vertexCount())
            if (const auto p = widgetPoint(mesh_->position(id)))
                painter.drawEllipse(*p, 6.0, 6.0);
        break;
    case SelectionKind::Edge:
        if (mesh_ && id >= 0 && id < mesh_->edgeCount()) {
            const Index h = mesh_->edgeHalfedge(id);
            const auto a = widgetPoint(mesh_->position(mesh_->from(h)));
            const auto b = widgetPoint(mesh_->position(mesh_->to(h)));
            if (a && b)
                painter.drawLine(*a, *b);
        }
        break;
    case SelectionKind::Chain:
        for (const DrawnChain& d : chains_)
            if (d.chain == id) {
                const double scale = frame.width() / camera.viewport.width;
                painter.translate(frame.topLeft());
                painter.scale(scale, scale);
                painter.setPen(linePen(color, width + 2.0, Qt::SolidLine));
                painter.drawPath(d.path);
                break;
            }
        break;
    case SelectionKind::None:
        break;
    }
    painter.restore();
}

void ImageView2D::mousePressEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton) {
        leftPressed_ = true;
        pressPosition_ = event->position();
        event->accept();
        return;
    }
    QWidget::mousePressEvent(event);
}

void ImageView2D::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton || !leftPressed_) {
        QWidget::mouseReleaseEvent(event);
        return;
    }
    leftPressed_ = false;
    event->accept();
    if ((event->position() - pressPosition_).manhattanLength() <= kClickSlopPixels)
        emit pickRequested(pick(event->position()));
}

} // namespace contour
