#include "SnapshotImages.h"

#include <cstdlib>
#include <stdexcept>

#ifdef CONTOUR_BATCH_HAS_WIDGETS
#include "ImageView2D.h"
#include "PngBytes.h"
#include "SceneView3D.h"
#include "SurfaceFormat.h"

#include <QApplication>
#include <QImage>
#endif

namespace contour::batch {

#ifdef CONTOUR_BATCH_HAS_WIDGETS
// The batch program has no QApplication of its own: one is made here, only
// when pictures are wanted and a display exists (Qt's xcb platform aborts
// without one).
struct SnapshotImages::Gui {
    int argc = 1;
    char name[14] = "contour-batch";
    char* argv[2] = {name, nullptr};
    QApplication application{argc, argv};
};

SnapshotImages::SnapshotImages() {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        unavailableReason_ = "no display (DISPLAY is not set); run under xvfb-run -a to get them";
        return;
    }
    if (!QApplication::instance()) {
        // Before the QApplication, as in the workbench (SurfaceFormat.h).
        setDefaultSurfaceFormat();
        gui_ = std::make_unique<Gui>();
    }
}

SnapshotImages::~SnapshotImages() = default;

std::vector<SnapshotFile> SnapshotImages::render(const Snapshot& snapshot, const Camera& camera) {
    if (!available())
        throw std::logic_error("SnapshotImages::render: " + unavailableReason_);
    const QSize size(camera.viewport.width, camera.viewport.height);
    std::vector<SnapshotFile> files;

    // The 3D view as the workbench first shows a run: from the analysis
    // camera (so no frustum), every overlay on. Never mapped on screen.
    SceneView3D scene;
    scene.setAttribute(Qt::WA_DontShowOnScreen);
    scene.resize(size);
    scene.show();
    scene.setViewCamera(camera);
    scene.setAnalysisCamera(camera);
    scene.setSnapshot(snapshot);
    const std::string png3d = pngBytes(scene.grabImage());
    if (png3d.empty())
        throw std::runtime_error(std::string(snapshotFiles::kPng3d) +
                                 ": cannot write (the 3D view could not be drawn or encoded)");
    files.push_back({snapshotFiles::kPng3d, png3d, {}});

    ImageView2D image;
    image.setAttribute(Qt::WA_DontShowOnScreen);
    image.resize(size);
    image.show();
    image.setScene(snapshot, camera);
    const std::string png2d = pngBytes(image.grab().toImage());
    if (png2d.empty())
        throw std::runtime_error(std::string(snapshotFiles::kPng2d) +
                                 ": cannot write (the 2D view could not be drawn or encoded)");
    files.push_back({snapshotFiles::kPng2d, png2d, {}});
    return files;
}
#else
struct SnapshotImages::Gui {};

SnapshotImages::SnapshotImages()
    : unavailableReason_("this build has no GUI (CONTOUR_BUILD_GUI=OFF), which draws them") {}

SnapshotImages::~SnapshotImages() = default;

std::vector<SnapshotFile> SnapshotImages::render(const Snapshot&, const Camera&) {
    throw std::logic_error("SnapshotImages::render: " + unavailableReason_);
}
#endif

} // namespace contour::batch
