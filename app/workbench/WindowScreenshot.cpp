#include "WindowScreenshot.h"

#include "GroundTruthComputation.h"
#include "MainWindow.h"
#include "contours/Methods.h"

#include <QAction>
#include <QColor>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QImageWriter>
#include <QSet>
#include <QTimer>
#include <algorithm>

namespace contour {

namespace {

// Lets queued events (layouts, the views' repaints) run for `ms`.
void settle(int ms) {
    QEventLoop loop;
    QTimer::singleShot(ms, &loop, &QEventLoop::quit);
    loop.exec();
}

} // namespace

QString screenshotProblem(const QImage& image) {
    if (image.isNull() || image.width() < 2 || image.height() < 2)
        return QStringLiteral("the window could not be grabbed");
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    QSet<QRgb> colours;
    long long dark = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QRgb c = rgb.pixel(x, y);
            if (colours.size() < 64)
                colours.insert(c);
            dark += qRed(c) + qGreen(c) + qBlue(c) < 24;
        }
    if (colours.size() < 2)
        return QStringLiteral("the grabbed window is a single colour");
    const double darkShare =
        static_cast<double>(dark) / (static_cast<double>(rgb.width()) * rgb.height());
    if (darkShare > 0.9)
        return QStringLiteral("the grabbed window is black (the 3D view was not drawn)");
    return {};
}

QString takeWindowScreenshot(MainWindow& window, const ScreenshotRequest& request) {
    if (request.input.isEmpty())
        return QStringLiteral("--screenshot needs a mesh or session file to open");
    if (!request.method.isEmpty()) {
        const std::string name = request.method.toStdString();
        if (const PlannedMethod* planned = findPlannedMethod(name))
            return QStringLiteral("--method %1 (%2): %3")
                .arg(request.method, QString::fromStdString(planned->label),
                     QString::fromStdString(planned->reason));
        if (!window.setMethod(request.method))
            return QStringLiteral("unknown method \"%1\"").arg(request.method);
    }
    if (!window.openFile(request.input))
        return window.lastError();
    QElapsedTimer clock;
    clock.start();
    const auto remaining = [&] {
        return static_cast<int>(std::max<qint64>(1, request.timeoutMs - clock.elapsed()));
    };
    if (!window.waitForIdle(remaining()))
        return QStringLiteral("%1: the method did not finish within %2 s")
            .arg(request.input)
            .arg(request.timeoutMs / 1000);
    // A session stops at the phase it reached: run on to the end.
    if (window.runner() && !window.runner()->atEnd()) {
        window.runToEnd();
        if (!window.waitForIdle(remaining()))
            return QStringLiteral("%1: the method did not finish within %2 s")
                .arg(request.input)
                .arg(request.timeoutMs / 1000);
    }
    if (!window.lastError().isEmpty())
        return window.lastError();
    if (!window.runner() || !window.runner()->atEnd())
        return QStringLiteral("%1: the method did not run to its end").arg(request.input);
    if (request.groundTruth) {
        QAction* toggle = window.groundTruthAction();
        if (!toggle->isEnabled())
            return QStringLiteral("--ground-truth: %1").arg(toggle->toolTip());
        toggle->setChecked(true);
        GroundTruthComputation* truth = window.groundTruth();
        if (!truth->waitForResult(remaining()))
            return QStringLiteral("%1: the ground truth did not finish within %2 s")
                .arg(request.input)
                .arg(request.timeoutMs / 1000);
        if (!truth->error().isEmpty())
            return QStringLiteral("%1: the ground truth failed: %2")
                .arg(request.input, truth->error());
    }
    settle(300); // the views repaint after the last snapshot
    const QImage image = window.grab().toImage();
    if (const QString problem = screenshotProblem(image); !problem.isEmpty())
        return QStringLiteral("%1: %2").arg(request.output, problem);
    QImageWriter writer(request.output, "png");
    if (!writer.write(image))
        return QStringLiteral("%1: cannot write (%2)").arg(request.output, writer.errorString());
    return {};
}

} // namespace contour
