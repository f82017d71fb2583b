#include "ParameterDomainView.h"

#include "DivergingColorMap.h"
#include "pipeline/FieldNames.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace contour {

namespace {

// Margin around the domain, in pixels.
constexpr double kMargin = 12.0;

const std::vector<Vec3>* cornerField(const Snapshot& s, const char* name) {
    return fieldValues<Vec3>(s, name, FieldLocation::Face, s.mesh ? s.mesh->faceCount() : 0);
}

QColor mix(const QColor& a, const QColor& b, double t) {
    t = std::clamp(t, 0.0, 1.0);
    return QColor::fromRgbF(static_cast<float>(a.redF() + t * (b.redF() - a.redF())),
                            static_cast<float>(a.greenF() + t * (b.greenF() - a.greenF())),
                            static_cast<float>(a.blueF() + t * (b.blueF() - a.blueF())));
}

} // namespace

ParameterDomainView::ParameterDomainView(QWidget* parent) : QWidget(parent) {
    setObjectName(QStringLiteral("parameterDomainView"));
    setMinimumSize(200, 200);
    setToolTip(tr("Parameter domain: the uv layout of the Powell-Sabin method (Capouellez et al. "
                  "2023 §5.1). Triangles coloured by the area distortion log(uv area / 3D area) "
                  "(blue smaller, red larger in uv) or, after the fit, by the spline's offset "
                  "from the input; the cut thick red, cones black dots."));
}

void ParameterDomainView::clearScene() {
    triangles_.clear();
    cut_.clear();
    cones_.clear();
    colorField_.clear();
    cache_ = QImage();
    update();
}

void ParameterDomainView::setSnapshot(const Snapshot& s) {
    triangles_.clear();
    cut_.clear();
    cones_.clear();
    colorField_.clear();
    const auto* uv0 = cornerField(s, fields::kCornerUv0);
    const auto* uv1 = cornerField(s, fields::kCornerUv1);
    const auto* uv2 = cornerField(s, fields::kCornerUv2);
    if (!s.mesh || !uv0 || !uv1 || !uv2) {
        cache_ = QImage();
        update();
        return;
    }
    const TriangleMesh& mesh = *s.mesh;
    const std::array<const std::vector<Vec3>*, 3> uv{uv0, uv1, uv2};
    const auto* faceValues =
        fieldValues<double>(s, fields::kLogAreaRatio, FieldLocation::Face, mesh.faceCount());
    const auto* vertexValues =
        fieldValues<double>(s, fields::kFitOffset, FieldLocation::Vertex, mesh.vertexCount());
    colorField_ = faceValues     ? QString::fromLatin1(fields::kLogAreaRatio)
                  : vertexValues ? QString::fromLatin1(fields::kFitOffset)
                                 : QString();
    diverging_ = faceValues != nullptr;
    triangles_.resize(mesh.faceCount());
    min_ = Vec2::Constant(std::numeric_limits<double>::infinity());
    max_ = -min_;
    std::vector<double> values(mesh.faceCount(), 0.0);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        UvTriangle& t = triangles_[f];
        for (int c = 0; c < 3; ++c) {
            t.uv[c] = (*uv[c])[f].head<2>();
            min_ = min_.cwiseMin(t.uv[c]);
            max_ = max_.cwiseMax(t.uv[c]);
        }
        if (faceValues)
            t.value = (*faceValues)[f];
        else if (vertexValues)
            t.value = ((*vertexValues)[mesh.triangle(f)[0]] + (*vertexValues)[mesh.triangle(f)[1]] +
                       (*vertexValues)[mesh.triangle(f)[2]]) /
                      3.0;
        values[f] = t.value;
    }
    if (diverging_) {
        const SymmetricRange range = symmetricRange(values);
        low_ = range.low();
        high_ = range.high();
    } else {
        low_ = 0.0;
        high_ = values.empty() ? 1.0 : *std::max_element(values.begin(), values.end());
        if (!(high_ > 0.0))
            high_ = 1.0;
    }
    // The cut: cut_edge on the layout's mesh, patch_edge 3 on the spline's
    // tessellation; both uv images of each cut edge are drawn.
    const auto* cutEdge =
        fieldValues<int>(s, fields::kCutEdge, FieldLocation::Edge, mesh.edgeCount());
    const auto* patchEdge =
        fieldValues<int>(s, fields::kPatchEdge, FieldLocation::Edge, mesh.edgeCount());
    for (Index h = 0; h < mesh.halfedgeCount(); ++h) {
        const Index e = mesh.edge(h);
        const bool isCut = (cutEdge && (*cutEdge)[e] != 0) || (patchEdge && (*patchEdge)[e] == 3);
        if (!isCut)
            continue;
        const Index f = TriangleMesh::face(h);
        cut_.push_back({triangles_[f].uv[h % 3], triangles_[f].uv[(h % 3 + 1) % 3]});
    }
    if (const auto* cone =
            fieldValues<int>(s, fields::kCone, FieldLocation::Vertex, mesh.vertexCount()))
        for (Index h = 0; h < mesh.halfedgeCount(); ++h)
            if ((*cone)[mesh.from(h)] != 0)
                cones_.push_back(triangles_[TriangleMesh::face(h)].uv[h % 3]);
    // One dot per distinct uv image of a cone (corners repeat them).
    std::sort(cones_.begin(), cones_.end(), [](const Vec2& a, const Vec2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    cones_.erase(std::unique(cones_.begin(), cones_.end(),
                             [](const Vec2& a, const Vec2& b) { return (a - b).norm() < 1e-12; }),
                 cones_.end());
    renderCache();
    update();
}

QColor ParameterDomainView::colorOf(double value) const {
    if (colorField_.isEmpty())
        return QColor(220, 220, 220);
    if (!std::isfinite(value))
        return QColor(128, 128, 128);
    const QColor low(59, 76, 192), middle(221, 221, 221), high(180, 4, 38);
    if (diverging_) {
        const double t = (value - low_) / (high_ - low_);
        return t < 0.5 ? mix(low, middle, 2.0 * t) : mix(middle, high, 2.0 * t - 1.0);
    }
    return mix(QColor(240, 240, 240), high, value / high_);
}

void ParameterDomainView::renderCache() {
    if (triangles_.empty() || width() <= 0 || height() <= 0) {
        cache_ = QImage();
        return;
    }
    cache_ = QImage(size() * devicePixelRatioF(), QImage::Format_ARGB32_Premultiplied);
    cache_.setDevicePixelRatio(devicePixelRatioF());
    cache_.fill(Qt::white);
    const Vec2 extent = (max_ - min_).cwiseMax(Vec2::Constant(1e-300));
    const double scale =
        std::min((width() - 2 * kMargin) / extent.x(), (height() - 2 * kMargin) / extent.y());
    const Vec2 offset(0.5 * (width() - scale * extent.x()), 0.5 * (height() - scale * extent.y()));
    const auto toWidget = [&](const Vec2& uv) {
        const Vec2 q = (uv - min_) * scale + offset;
        return QPointF(q.x(), height() - q.y()); // v up
    };
    QPainter painter(&cache_);
    // Outlines only while they do not drown the colours.
    const bool outline = triangles_.size() * 40.0 < static_cast<double>(width()) * height() / 10.0;
    // Without outlines, antialiased fills would leave seams between
    // neighbours unless each is also stroked in its colour; aliased fills
    // tile the plane exactly, at a fraction of the cost (a spline's drawing
    // tessellation has tens of thousands of triangles, redrawn per view).
    painter.setRenderHint(QPainter::Antialiasing, outline);
    painter.setPen(outline ? QPen(QColor(90, 90, 90), 0.0) : QPen(Qt::NoPen));
    for (const UvTriangle& t : triangles_) {
        const QPointF points[3] = {toWidget(t.uv[0]), toWidget(t.uv[1]), toWidget(t.uv[2])};
        painter.setBrush(colorOf(t.value));
        painter.drawPolygon(points, 3);
    }
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(QPen(QColor(200, 0, 0), 2.0));
    for (const Segment& s : cut_)
        painter.drawLine(toWidget(s.a), toWidget(s.b));
    painter.setPen(Qt::NoPen);
    painter.setBrush(Qt::black);
    for (const Vec2& c : cones_)
        painter.drawEllipse(toWidget(c), 4.0, 4.0);
}

QString ParameterDomainView::caption() const {
    if (triangles_.empty())
        return tr("no uv layout in this phase");
    QString text = tr("uv layout: %1 triangles, %2 cut edge sides, %3 cone images")
                       .arg(triangles_.size())
                       .arg(cut_.size())
                       .arg(cones_.size());
    if (colorField_ == QLatin1String(fields::kLogAreaRatio))
        text += tr("\ncolour: log(uv area / 3D area) against the mean, blue %1 to red %2")
                    .arg(low_, 0, 'g', 3)
                    .arg(high_, 0, 'g', 3);
    else if (!colorField_.isEmpty())
        text += tr("\ncolour: %1, white 0 to red %2").arg(colorField_).arg(high_, 0, 'g', 3);
    return text;
}

void ParameterDomainView::resizeEvent(QResizeEvent* event) {
    QWidget::resizeEvent(event);
    renderCache();
}

void ParameterDomainView::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), Qt::white);
    if (!cache_.isNull())
        painter.drawImage(QPointF(0, 0), cache_);
    painter.setPen(Qt::black);
    painter.drawText(rect().adjusted(6, 4, -6, -4), Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap,
                     caption());
}

} // namespace contour
