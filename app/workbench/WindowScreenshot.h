#pragma once
// contour-workbench --screenshot: opens a mesh or a session in the window,
// runs the method to its last phase (and, when asked, the ground truth of the
// smooth contour), waits until no phase runs and the views have drawn, grabs the whole window
// (QWidget::grab includes the VTK views' QOpenGLWidget) and writes it as a PNG. Used for the
// README's picture.
#include <QImage>
#include <QString>

namespace contour {

class MainWindow;

struct ScreenshotRequest {
    QString input;  // a mesh or a session file (MainWindow::openFile)
    QString method; // empty: the window's method (or the session's)
    QString output; // the PNG to write
    // Turn on View › Overlays › Ground-truth contour and wait for it.
    bool groundTruth = false;
    int timeoutMs = 600000;
};

// Runs the request in `window` (shown, not interactive); returns an empty
// string on success, else what went wrong, naming the file or the method.
QString takeWindowScreenshot(MainWindow& window, const ScreenshotRequest& request);

// Why `image` is not a usable picture of the window (null, or a single
// colour, or nearly all black: the GL views were not grabbed); empty when it
// is.
QString screenshotProblem(const QImage& image);

} // namespace contour
