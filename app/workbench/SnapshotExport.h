#pragma once
// File › Export diagnostic snapshot: the window's current
// state written into one folder, all files or none. The report, SVG, PLY and
// session come from export/DiagnosticSnapshot.h (contour-batch
// --snapshot-dir writes the same); this adds the grabs of the two views as
// view-3d.png and view-2d.png.
#include <QString>
#include <QStringList>

class QImage;

namespace contour {

class MainWindow;

struct SnapshotExportResult {
    QStringList written; // paths, in the order written
    QStringList notes;   // what was left out (e.g. PLY fields without a property)
    QString error;       // empty on success; names the file and the reason
    bool ok() const { return error.isEmpty(); }
};

// Needs the window idle with a runner (a mesh open, a method chosen).
SnapshotExportResult exportDiagnosticSnapshot(MainWindow& window, const QString& folder);

} // namespace contour
