#include "PendingOutputs.h"

#include "BatchRun.h"
#include "core/AtomicFile.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace contour::batch {

namespace fs = std::filesystem;

namespace {

// Creates `folder` unless it exists; remembers it when made here.
void makeFolder(const fs::path& folder, const std::string& snapshotFolder,
                std::vector<fs::path>& created) {
    std::error_code error;
    if (fs::create_directory(folder, error))
        created.push_back(folder);
    else if (error)
        throw std::runtime_error(snapshotFolder + ": cannot create the folder (" + error.message() +
                                 ")");
}

void removeWritten(const std::vector<std::string>& written, const std::vector<fs::path>& created) {
    for (const std::string& path : written)
        std::remove(path.c_str());
    for (auto it = created.rbegin(); it != created.rend(); ++it) {
        std::error_code ignored;
        fs::remove(*it, ignored); // only if empty
    }
}

} // namespace

std::vector<std::string> writePendingOutputs(const PendingOutputs& outputs,
                                             const std::string& snapshotRoot) {
    std::vector<std::string> written;
    std::vector<fs::path> createdFolders;
    try {
        for (const PendingFile& file : outputs.files) {
            if (file.write)
                file.write(file.path);
            else
                writeFileAtomically(file.path, file.content);
            written.push_back(file.path);
        }
        for (const PendingSnapshot& snapshot : outputs.snapshots) {
            // The snapshot folder and a view's sub-folder are made here, and
            // removed again on failure.
            makeFolder(snapshotRoot, snapshot.folder, createdFolders);
            makeFolder(snapshot.folder, snapshot.folder, createdFolders);
            for (const std::string& path : writeSnapshotFiles(snapshot.folder, snapshot.files))
                written.push_back(path);
        }
    } catch (const std::exception& e) {
        // Leave no partial set of outputs behind either.
        removeWritten(written, createdFolders);
        throw BatchFailure(e.what());
    }
    return written;
}

} // namespace contour::batch
