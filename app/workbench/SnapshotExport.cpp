#include "SnapshotExport.h"

#include "ImageView2D.h"
#include "MainWindow.h"
#include "PngBytes.h"
#include "SceneView3D.h"
#include "SessionController.h"
#include "export/DiagnosticSnapshot.h"

#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <string>

namespace contour {

SnapshotExportResult exportDiagnosticSnapshot(MainWindow& window, const QString& folder) {
    SnapshotExportResult result;
    const auto fail = [&](const QString& file, const QString& why) {
        result.error =
            QStringLiteral("%1: cannot write (%2)").arg(QDir(folder).filePath(file), why);
        return result;
    };
    QString why;
    const std::optional<Session> session = window.sessionController()->capture(&why);
    const Runner* runner = window.runner();
    if (!session || !runner)
        return fail(QString::fromLatin1(snapshotFiles::kReport),
                    session ? QObject::tr("no method has run") : why);

    DiagnosticSnapshotRun run;
    run.toolName = "contour-workbench";
    run.toolVersion = CONTOUR_VERSION;
    run.meshPath = session->meshPath;
    run.method = &runner->method();
    run.parameters = runner->parameters();
    run.camera = runner->camera();
    run.snapshots = runner->snapshots();
    run.session = *session;
    run.otherFiles = {snapshotFiles::kPng3d, snapshotFiles::kPng2d};
    run.title = QFileInfo(window.meshPath()).fileName().toStdString() + " - " +
                runner->method().label + ", after " + runner->current().phaseName;

    std::vector<SnapshotFile> files;
    // The views as shown: the 3D view from its own camera (with the overlays
    // chosen), the 2D view as drawn on screen.
    const std::string png3d = pngBytes(window.sceneView()->grabImage());
    if (png3d.empty())
        return fail(QString::fromLatin1(snapshotFiles::kPng3d),
                    QObject::tr("the 3D view could not be grabbed or encoded as PNG"));
    const std::string png2d = pngBytes(window.imageView()->grab().toImage());
    if (png2d.empty())
        return fail(QString::fromLatin1(snapshotFiles::kPng2d),
                    QObject::tr("the 2D view could not be grabbed or encoded as PNG"));
    files.push_back({snapshotFiles::kPng3d, png3d, {}});
    files.push_back({snapshotFiles::kPng2d, png2d, {}});
    std::vector<std::string> notes;
    try {
        for (SnapshotFile& file : diagnosticSnapshotFiles(run, &notes))
            files.push_back(std::move(file));
        for (const std::string& path : writeSnapshotFiles(folder.toStdString(), files))
            result.written << QString::fromStdString(path);
    } catch (const std::exception& e) {
        result.written.clear();
        result.error = QString::fromStdString(e.what());
        return result;
    }
    for (const std::string& note : notes)
        result.notes << QString::fromStdString(note);
    return result;
}

} // namespace contour
