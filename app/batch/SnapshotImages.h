#pragma once
// The workbench's two pictures of a snapshot (view-3d.png, view-2d.png) for
// contour-batch --snapshot-dir, so a batch snapshot holds everything the
// workbench's File › Export diagnostic snapshot holds. They are drawn by the workbench's own views (SceneView3D with every
// overlay on, ImageView2D), off screen, from the analysis camera at its
// viewport size. That needs the GUI build and a display (an X server:
// xvfb-run -a is enough); without either, available() is false and
// unavailableReason() says which is missing.
#include "camera/Camera.h"
#include "export/DiagnosticSnapshot.h"
#include "pipeline/Snapshot.h"

#include <memory>
#include <string>
#include <vector>

namespace contour::batch {

class SnapshotImages {
public:
    SnapshotImages();
    ~SnapshotImages();
    SnapshotImages(const SnapshotImages&) = delete;
    SnapshotImages& operator=(const SnapshotImages&) = delete;

    bool available() const { return unavailableReason_.empty(); }
    const std::string& unavailableReason() const { return unavailableReason_; }

    // view-3d.png and view-2d.png of the snapshot. Throws std::runtime_error
    // naming the file when a picture cannot be drawn or encoded.
    std::vector<SnapshotFile> render(const Snapshot& snapshot, const Camera& camera);

private:
    struct Gui;
    std::unique_ptr<Gui> gui_;
    std::string unavailableReason_;
};

} // namespace contour::batch
