// contour-workbench: load a mesh, freeze an analysis camera, pick a contour
// method and step through its phases. Usage: contour-workbench [mesh-file]
#include "MainWindow.h"
#include "SurfaceFormat.h"

#include <QApplication>
#include <QTimer>

int main(int argc, char* argv[]) {
    // Before the QApplication: the VTK views need a 3.2 core profile context.
    contour::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("Contour Workbench"));
    QApplication::setOrganizationName(QStringLiteral("contour"));

    contour::MainWindow window;
    window.show();
    const QStringList arguments = QApplication::arguments();
    if (arguments.size() > 1) {
        const QString path = arguments.at(1);
        // Once the window is laid out, so the analysis camera gets the 3D
        // view's size as its viewport.
        QTimer::singleShot(0, &window, [&window, path] { window.openMesh(path); });
    }
    return QApplication::exec();
}
