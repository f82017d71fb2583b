// contour-workbench: load a mesh, freeze an analysis camera, pick a contour
// method and step through its phases. Usage: contour-workbench [options]
// [mesh-file | session.cwsession]; --help lists the options.
#include "MainWindow.h"
#include "Resources.h"
#include "SessionController.h"
#include "SurfaceFormat.h"
#include "WindowScreenshot.h"
#include "contours/Methods.h"

#include <QAction>
#include <QApplication>
#include <QCommandLineParser>
#include <QRegularExpression>
#include <QScreen>
#include <QTimer>
#include <cstdio>

namespace {

QString methodNames() {
    QStringList names;
    for (const contour::Method& m : contour::contourMethods())
        names << QString::fromStdString(m.name);
    return names.join(QStringLiteral(", "));
}

// "1400x850" -> QSize; invalid when the text is not two positive integers.
QSize parseSize(const QString& text) {
    static const QRegularExpression form(QStringLiteral("^(\\d{2,5})x(\\d{2,5})$"));
    const QRegularExpressionMatch match = form.match(text.trimmed());
    if (!match.hasMatch())
        return {};
    return {match.captured(1).toInt(), match.captured(2).toInt()};
}

int usageError(const QString& message) {
    std::fprintf(stderr, "contour-workbench: %s\n", qPrintable(message));
    return 2;
}

} // namespace

int main(int argc, char* argv[]) {
    // Before the QApplication: the VTK views need a 3.2 core profile context.
    contour::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("Contour Workbench"));
    QApplication::setApplicationVersion(QStringLiteral(CONTOUR_VERSION));
    QApplication::setOrganizationName(QStringLiteral("contour"));
    QApplication::setWindowIcon(contour::resourceIcon(QStringLiteral("contour-workbench")));

    QCommandLineParser parser;
    parser.setApplicationDescription(
        QStringLiteral("Computes and debugs the occluding contours of a 3D surface: opens a mesh "
                       "(OBJ, OFF, PLY) or a saved session and runs the chosen contour method."));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument(QStringLiteral("file"),
                                 QStringLiteral("A mesh or a session (.cwsession) to open."),
                                 QStringLiteral("[file]"));
    const QCommandLineOption methodOption(
        QStringLiteral("method"),
        QStringLiteral("The contour method to run on the mesh: %1 (a session names its own).")
            .arg(methodNames()),
        QStringLiteral("NAME"));
    const QCommandLineOption screenshotOption(
        QStringLiteral("screenshot"),
        QStringLiteral("Open the file, run the method to its last phase, save a picture of the "
                       "whole window as FILE.png and exit (0, or 1 with a message on failure). "
                       "Needs a display; without one run it under xvfb-run -a -s \"-screen 0 "
                       "1600x1200x24\". Saved window settings are not used."),
        QStringLiteral("FILE.png"));
    const QCommandLineOption sizeOption(
        QStringLiteral("size"),
        QStringLiteral("The window's size, WIDTHxHEIGHT (default: the screen's, or for "
                       "--screenshot the default window size)."),
        QStringLiteral("WxH"));
    const QCommandLineOption groundTruthOption(
        QStringLiteral("ground-truth"),
        QStringLiteral("Turn on View > Overlays > Ground-truth contour: the dense ground truth "
                       "of the smooth contour drawn over both views (the method needs a smooth "
                       "surface). With --screenshot the picture waits for it."));
    parser.addOptions({methodOption, screenshotOption, sizeOption, groundTruthOption});
    parser.process(app); // --help and --version exit here; unknown options too (code 1)

    const QStringList files = parser.positionalArguments();
    if (files.size() > 1)
        return usageError(QStringLiteral("one file at a time (got %1)").arg(files.size()));
    const QString file = files.isEmpty() ? QString() : files.front();
    QSize size;
    if (parser.isSet(sizeOption)) {
        size = parseSize(parser.value(sizeOption));
        if (!size.isValid())
            return usageError(
                QStringLiteral("--size: \"%1\" is not WIDTHxHEIGHT").arg(parser.value(sizeOption)));
    }
    const QString method = parser.value(methodOption);
    if (!method.isEmpty() && !contour::findMethod(method.toStdString())) {
        if (const contour::PlannedMethod* planned =
                contour::findPlannedMethod(method.toStdString()))
            return usageError(QStringLiteral("--method %1 (%2): %3")
                                  .arg(method, QString::fromStdString(planned->label),
                                       QString::fromStdString(planned->reason)));
        return usageError(
            QStringLiteral("unknown method \"%1\" (methods: %2)").arg(method, methodNames()));
    }

    contour::MainWindow window;
    if (parser.isSet(screenshotOption)) {
        if (file.isEmpty())
            return usageError(QStringLiteral("--screenshot needs a mesh or session file"));
        window.setInteractive(false);
        if (size.isValid())
            window.resize(size);
        window.show();
        int status = 1;
        contour::ScreenshotRequest request{file, method, parser.value(screenshotOption)};
        request.groundTruth = parser.isSet(groundTruthOption);
        // Once the window is laid out, so the analysis camera gets the 3D
        // view's size as its viewport.
        QTimer::singleShot(0, &window, [&window, &status, request] {
            const QString problem = contour::takeWindowScreenshot(window, request);
            if (problem.isEmpty())
                status = 0;
            else
                std::fprintf(stderr, "contour-workbench: %s\n", qPrintable(problem));
            QApplication::exit(status);
        });
        QApplication::exec();
        return status;
    }

    // Both views side by side between two docks need room: a first start
    // takes most of the screen (a saved geometry wins below).
    if (size.isValid()) {
        window.resize(size);
    } else if (const QScreen* screen = QGuiApplication::primaryScreen()) {
        const QSize room = screen->availableGeometry().size() * 0.9;
        window.resize(window.size().expandedTo(room));
    }
    // Recent files and the window's geometry and layout persist (QSettings).
    window.sessionController()->setUseSettings(true);
    if (!size.isValid())
        window.sessionController()->restoreWindowSettings();
    if (!method.isEmpty())
        window.setMethod(method);
    if (parser.isSet(groundTruthOption))
        window.groundTruthAction()->setChecked(true);
    window.show();
    if (!file.isEmpty()) {
        // A mesh or a saved session (by suffix). Once the window is laid out, so the analysis
        // camera gets the 3D view's size as its viewport.
        QTimer::singleShot(0, &window, [&window, file] { window.openFile(file); });
    }
    return QApplication::exec();
}
