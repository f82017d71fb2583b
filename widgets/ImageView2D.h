#pragma once
// The 2D view: the snapshot's curves projected with the analysis camera into
// its image (Camera::project: x right, y down, origin top-left), fitted into
// the widget with the image's aspect ratio, the image frame drawn.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <QPainterPath>
#include <QWidget>
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
    int curveCount() const { return static_cast<int>(paths_.size()); }
    // Where the analysis camera's image is drawn, in widget coordinates.
    QRectF imageRect() const;
    // Maps a pixel of the analysis camera's image to widget coordinates.
    QPointF toWidget(const Vec2& imagePixel) const;

    QSize sizeHint() const override { return {640, 480}; }
    QSize minimumSizeHint() const override { return {120, 90}; }

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    struct ProjectedCurve {
        CurveType type;
        QPainterPath path; // in image pixels
    };

    std::optional<Camera> camera_;
    std::vector<ProjectedCurve> paths_;
    QString caption_;
};

} // namespace contour
