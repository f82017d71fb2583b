#pragma once
// The parameter-domain view: the uv layout of a snapshot that has one (the
// Powell-Sabin method's fields corner_uv_0..2, Capouellez et al. 2023 §5.1),
// each triangle filled by a field of the layout (the area distortion
// log(uv area / 3D area), or the fitted spline's offset from the input),
// the cut drawn thick and the cones as dots. The view is drawn with the
// domain's aspect ratio, v up; it is hidden by the window when the snapshot
// has no layout.
#include "pipeline/Snapshot.h"

#include <QImage>
#include <QString>
#include <QWidget>
#include <vector>

namespace contour {

class ParameterDomainView : public QWidget {
    Q_OBJECT

public:
    explicit ParameterDomainView(QWidget* parent = nullptr);

    void setSnapshot(const Snapshot& snapshot);
    void clearScene();

    // What the next paint draws.
    bool hasLayout() const { return !triangles_.empty(); }
    int triangleCount() const { return static_cast<int>(triangles_.size()); }
    int cutSegmentCount() const { return static_cast<int>(cut_.size()); }
    int coneCount() const { return static_cast<int>(cones_.size()); }
    // The field the triangles are coloured by ("" for none) and its range.
    const QString& colorField() const { return colorField_; }
    double colorLow() const { return low_; }
    double colorHigh() const { return high_; }
    QString caption() const;

    QSize sizeHint() const override { return {420, 420}; }

protected:
    void paintEvent(QPaintEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;

private:
    struct UvTriangle {
        std::array<Vec2, 3> uv;
        double value = 0.0;
    };
    struct Segment {
        Vec2 a, b;
    };
    QColor colorOf(double value) const;
    void renderCache();

    std::vector<UvTriangle> triangles_;
    std::vector<Segment> cut_;
    std::vector<Vec2> cones_;
    Vec2 min_ = Vec2::Zero(), max_ = Vec2::Ones();
    QString colorField_;
    bool diverging_ = true;
    double low_ = 0.0, high_ = 1.0;
    QImage cache_; // the triangles and the cut, redrawn on resize or new data
};

} // namespace contour
