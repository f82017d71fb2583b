#include "ImageView2D.h"

#include "SceneColors.h"

#include <QPaintEvent>
#include <QPainter>
#include <algorithm>

namespace contour {

namespace {

constexpr double kMargin = 12.0;

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

} // namespace

ImageView2D::ImageView2D(QWidget* parent) : QWidget(parent) {
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
            // A segment is drawn when both ends are in front of the eye.
            bool penDown = false;
            const size_t n = curve.points.size();
            const size_t count = curve.closed ? n + 1 : n;
            for (size_t i = 0; i < count; ++i) {
                const ProjectedPoint p = camera.project(curve.points[i % n].position);
                if (!(p.depth > 0.0) || !p.pixel.allFinite()) {
                    penDown = false;
                    continue;
                }
                const QPointF q(p.pixel.x(), p.pixel.y());
                if (penDown)
                    projected.path.lineTo(q);
                else
                    projected.path.moveTo(q);
                penDown = true;
            }
            contours += curve.type == CurveType::Contour;
            boundaries += curve.type == CurveType::Boundary;
            others += curve.type == CurveType::SurfaceIntersection;
            paths_.push_back(std::move(projected));
        }
    }
    caption_ = QStringLiteral("%1 — %2 contour, %3 boundary curves")
                   .arg(QString::fromStdString(snapshot.phaseName))
                   .arg(contours)
                   .arg(boundaries);
    if (others > 0)
        caption_ += QStringLiteral(", %1 intersections").arg(others);
    update();
}

void ImageView2D::clearScene() {
    camera_.reset();
    paths_.clear();
    caption_.clear();
    update();
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
    painter.save();
    painter.setClipRect(frame);
    const double scale = frame.width() / camera_->viewport.width;
    painter.translate(frame.topLeft());
    painter.scale(scale, scale);
    for (const ProjectedCurve& curve : paths_) {
        QPen pen(curveColor(curve.type), 2.0);
        pen.setCosmetic(true); // width in screen pixels whatever the scale
        pen.setJoinStyle(Qt::RoundJoin);
        pen.setCapStyle(Qt::RoundCap);
        painter.setPen(pen);
        painter.drawPath(curve.path);
    }
    painter.restore();

    painter.setPen(QPen(QColor(60, 60, 60), 1.0));
    painter.setBrush(Qt::NoBrush);
    painter.drawRect(frame);
    painter.drawText(
        frame.adjusted(4, 2, -4, -2), Qt::AlignRight | Qt::AlignBottom,
        QStringLiteral("%1 × %2").arg(camera_->viewport.width).arg(camera_->viewport.height));
}

} // namespace contour
