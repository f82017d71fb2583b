#include "export/DiagnosticSnapshot.h"

#include "core/AtomicFile.h"
#include "export/JsonReport.h"
#include "export/SnapshotPly.h"
#include "export/SvgWriter.h"
#include "mesh/io/MeshWriter.h"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace contour {

namespace fs = std::filesystem;

std::vector<SnapshotFile> diagnosticSnapshotFiles(const DiagnosticSnapshotRun& run,
                                                  std::vector<std::string>* notes) {
    if (!run.method)
        throw std::invalid_argument("diagnostic snapshot: no method");
    if (run.snapshots.empty())
        throw std::invalid_argument("diagnostic snapshot: no snapshot");
    const Snapshot& last = run.snapshots.back();
    std::vector<SnapshotFile> files;

    JsonReport report(run.toolName, run.toolVersion, run.meshPath, run.snapshots.front(),
                      *run.method, run.parameters, sessionPresetName(run.session, *run.method));
    report.addView(run.camera, run.snapshots);
    nlohmann::json json = report.json();
    nlohmann::json names = nlohmann::json::array();
    for (const char* name : {snapshotFiles::kReport, snapshotFiles::kSvg, snapshotFiles::kPly,
                             snapshotFiles::kSession})
        names.push_back(name);
    for (const std::string& name : run.otherFiles)
        names.push_back(name);
    json["snapshot"] = {{"phase_reached", static_cast<int>(run.snapshots.size()) - 1},
                        {"phase_name", last.phaseName},
                        {"files", std::move(names)}};
    files.push_back({snapshotFiles::kReport, json.dump(2) + "\n", {}});

    SvgOptions svg;
    svg.title = run.title;
    files.push_back({snapshotFiles::kSvg, svgDocument(last, run.camera, svg), {}});

    if (last.mesh) {
        auto labels = std::make_shared<const SnapshotPlyLabels>(snapshotPlyLabels(last));
        if (notes)
            for (const std::string& skipped : labels->skipped)
                notes->push_back(std::string(snapshotFiles::kPly) + " leaves out field " + skipped);
        files.push_back({snapshotFiles::kPly, {}, [mesh = last.mesh, labels](const std::string& p) {
                             writePly(*mesh, p, labels->labels);
                         }});
    } else if (notes) {
        notes->push_back(std::string(snapshotFiles::kPly) + " not written: the snapshot after " +
                         last.phaseName + " has no mesh");
    }
    files.push_back({snapshotFiles::kSession, sessionText(run.session), {}});
    return files;
}

namespace {

std::string cannotWrite(const fs::path& path, const std::string& reason) {
    return path.string() + ": cannot write (" + reason + ")";
}

// Replaces the temporary folder by the destination in a writer's message, so
// it names the file the user asked for.
std::string retarget(std::string message, const fs::path& staging, const fs::path& folder) {
    const std::string from = staging.string();
    const std::string to = folder.string();
    for (size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at + to.size()))
        message.replace(at, from.size(), to);
    return message;
}

fs::path stagingName(const fs::path& folder) {
    static std::atomic<unsigned> counter{0};
    const auto ticks = std::chrono::steady_clock::now().time_since_epoch().count();
    return folder / (".contour-snapshot-" + std::to_string(ticks) + "-" +
                     std::to_string(counter++) + ".tmp");
}

} // namespace

std::vector<std::string> writeSnapshotFiles(const std::string& folderText,
                                            const std::vector<SnapshotFile>& files) {
    if (files.empty())
        return {};
    const fs::path folder(folderText);
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw std::runtime_error(
            cannotWrite(folder / files.front().name,
                        "the folder " + folder.string() + " does not exist or is not a folder"));
    const fs::path staging = stagingName(folder);
    if (!fs::create_directory(staging, ec) || ec)
        throw std::runtime_error(
            cannotWrite(folder / files.front().name,
                        "cannot create a temporary folder in " + folder.string() + ": " +
                            (ec ? ec.message() : std::string("it already exists"))));
    const auto discardStaging = [&] {
        std::error_code ignored;
        fs::remove_all(staging, ignored);
    };

    // 1. Every file, complete, in the temporary folder.
    for (const SnapshotFile& file : files) {
        const fs::path path = staging / file.name;
        try {
            if (file.write)
                file.write(path.string());
            else
                writeFileAtomically(path.string(), file.content);
        } catch (const std::exception& e) {
            discardStaging();
            throw std::runtime_error(retarget(e.what(), staging, folder));
        }
    }

    // 2. Each into place; an existing file of the same name is kept aside
    // until every rename has succeeded.
    struct Moved {
        fs::path destination;
        fs::path backup; // empty: nothing was there
    };
    std::vector<Moved> moved;
    const auto rollBack = [&] {
        std::error_code ignored;
        for (auto it = moved.rbegin(); it != moved.rend(); ++it) {
            fs::remove(it->destination, ignored);
            if (!it->backup.empty())
                fs::rename(it->backup, it->destination, ignored);
        }
        discardStaging();
    };
    std::vector<std::string> written;
    for (const SnapshotFile& file : files) {
        const fs::path destination = folder / file.name;
        Moved m{destination, {}};
        const fs::file_status status = fs::symlink_status(destination, ec);
        if (fs::is_directory(status)) {
            rollBack();
            throw std::runtime_error(
                cannotWrite(destination, "a folder of that name is in the way"));
        }
        if (fs::exists(status)) {
            m.backup = staging / (".previous-" + file.name);
            fs::rename(destination, m.backup, ec);
            if (ec) {
                const std::string reason = ec.message();
                rollBack();
                throw std::runtime_error(
                    cannotWrite(destination, "cannot move the existing file aside: " + reason));
            }
        }
        fs::rename(staging / file.name, destination, ec);
        if (ec) {
            const std::string reason = ec.message();
            if (!m.backup.empty()) {
                std::error_code ignored;
                fs::rename(m.backup, destination, ignored);
            }
            rollBack();
            throw std::runtime_error(cannotWrite(destination, reason));
        }
        moved.push_back(m);
        written.push_back(destination.string());
    }
    discardStaging();
    return written;
}

} // namespace contour
