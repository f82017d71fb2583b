// contour-workbench: load a mesh, freeze an analysis camera, pick a contour
// method and step through its phases. Usage: contour-workbench [mesh-file |
// session.cwsession]
#include "MainWindow.h"
#include "Resources.h"
#include "SessionController.h"
#include "SurfaceFormat.h"

#include <QApplication>
#include <QScreen>
#include <QTimer>

int main(int argc, char* argv[]) {
    // Before the QApplication: the VTK views need a 3.2 core profile context.
    contour::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("Contour Workbench"));
    QApplication::setOrganizationName(QStringLiteral("contour"));
    QApplication::setWindowIcon(contour::resourceIcon(QStringLiteral("contour-workbench")));

    contour::MainWindow window;
    // Both views side by side between two docks need room: a first start
    // takes most of the screen (a saved geometry wins below).
    if (const QScreen* screen = QGuiApplication::primaryScreen()) {
        const QSize room = screen->availableGeometry().size() * 0.9;
        window.resize(window.size().expandedTo(room));
    }
    // Recent files and the window's geometry and layout persist (QSettings).
    window.sessionController()->setUseSettings(true);
    window.sessionController()->restoreWindowSettings();
    window.show();
    const QStringList arguments = QApplication::arguments();
    if (arguments.size() > 1) {
        const QString path = arguments.at(1);
        // A mesh or a saved session (by suffix). Once the window is laid out, so the analysis
        // camera gets the 3D view's size as its viewport.
        QTimer::singleShot(0, &window, [&window, path] { window.openFile(path); });
    }
    return QApplication::exec();
}
