#pragma once
// The output files of a contour-batch run, gathered while the views run and
// written only once every view has run, so a failed view leaves no output
// behind. Writing is all or nothing too: each file is written atomically,
// and when one fails every file and folder already written is removed.
#include "export/DiagnosticSnapshot.h"

#include <functional>
#include <string>
#include <vector>

namespace contour::batch {

// An output file: its text, or (for meshes, whose writer builds the text
// itself) a function that writes it atomically to the path.
struct PendingFile {
    std::string path;
    std::string content;
    std::function<void(const std::string&)> write;
};

// A diagnostic snapshot folder (--snapshot-dir, a view's sub-folder with
// several views) and its files.
struct PendingSnapshot {
    std::string folder;
    std::vector<SnapshotFile> files;
};

struct PendingOutputs {
    std::vector<PendingFile> files;
    std::vector<PendingSnapshot> snapshots;
};

// Writes the files, then the snapshot folders (creating `snapshotRoot` and
// each folder when missing). Returns the paths written; on a failure removes
// them and the folders it made, and throws BatchFailure.
std::vector<std::string> writePendingOutputs(const PendingOutputs& outputs,
                                             const std::string& snapshotRoot);

} // namespace contour::batch
