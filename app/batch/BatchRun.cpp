#include "BatchRun.h"

#include "SnapshotImages.h"
#include "Summary.h"
#include "export/DiagnosticSnapshot.h"
#include "export/JsonReport.h"
#include "export/SnapshotPly.h"
#include "export/SvgWriter.h"
#include "core/AtomicFile.h"
#include "mesh/MeshError.h"
#include "mesh/io/MeshReader.h"
#include "mesh/io/MeshWriter.h"
#include "pipeline/Runner.h"
#include "pipeline/ViewGraph.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <ostream>
#include <vector>

namespace contour::batch {

namespace {

// The default view: from the front-right, a little above (a 3/4 view).
const Vec3 kDefaultViewDirection(1.0, 0.5, 2.0);

Camera readCameraFile(const BatchOptions& o) {
    Camera camera;
    try {
        camera = Camera::readJson(o.cameraFile);
    } catch (const std::exception& e) {
        throw BatchFailure(e.what());
    }
    if (o.camera.width)
        camera.viewport.width = *o.camera.width;
    if (o.camera.height)
        camera.viewport.height = *o.camera.height;
    return camera;
}

std::shared_ptr<const PolygonMesh> loadMesh(const std::string& path) {
    try {
        return std::make_shared<const PolygonMesh>(readMesh(path));
    } catch (const MeshError& e) {
        throw BatchFailure(e.what());
    } catch (const std::exception& e) {
        throw BatchFailure(path + ": " + e.what());
    }
}

// Projection settings that apply to every camera, also the 26 views.
void applyProjection(const CameraOverrides& c, Camera& camera) {
    if (c.orthographic)
        camera.projection = Projection::Orthographic;
    if (c.fovYDegrees)
        camera.fovYDegrees = *c.fovYDegrees;
    if (c.orthoHeight)
        camera.orthoHeight = *c.orthoHeight;
}

std::vector<Camera> placeCameras(const BatchOptions& o, const BoundingBox& box,
                                 const Camera* fromFile) {
    Viewport viewport;
    viewport.width = o.camera.width.value_or(viewport.width);
    viewport.height = o.camera.height.value_or(viewport.height);
    std::vector<Camera> cameras;
    if (o.views26) {
        cameras = Camera::views26(box, viewport);
        for (size_t i = 0; i < cameras.size(); ++i) {
            applyProjection(o.camera, cameras[i]);
            if (const std::string problem = cameras[i].validate(); !problem.empty())
                throw BatchFailure(o.meshPath + ": view " + std::to_string(i) +
                                   " of the 26-view protocol has no valid camera (" + problem +
                                   "); is the mesh flat?");
        }
        return cameras;
    }
    if (fromFile)
        return {*fromFile};
    Camera camera = Camera::framing(box, kDefaultViewDirection, viewport);
    if (o.camera.eye)
        camera.eye = *o.camera.eye;
    if (o.camera.target)
        camera.target = *o.camera.target;
    if (o.camera.up) {
        camera.up = *o.camera.up;
    } else {
        // Without --up, keep the default up away from the viewing direction.
        const Vec3 view = camera.target - camera.eye;
        const double length = view.norm();
        if (length > 0.0 && view.cross(camera.up).norm() < 1e-6 * length)
            camera.up = Vec3(0, 0, 1);
    }
    applyProjection(o.camera, camera);
    if (const std::string problem = camera.validate(); !problem.empty())
        throw UsageError("camera: " + problem);
    return {camera};
}

// Fails before any work when an output's folder does not exist.
void checkOutputFolders(const BatchOptions& o) {
    for (const std::string& path :
         {o.svgPath, o.jsonPath, o.writeCameraPath, o.plyPath, o.snapshotDir}) {
        if (path.empty())
            continue;
        std::filesystem::path folder = std::filesystem::path(path).parent_path();
        if (folder.empty())
            folder = ".";
        std::error_code error;
        if (!std::filesystem::is_directory(folder, error))
            throw BatchFailure(path + ": cannot write (the folder " + folder.string() +
                               " does not exist)");
    }
}

// An output to write once every view has run: its text, or (for meshes,
// whose writer builds the text itself) a function that writes it atomically.
struct PendingFile {
    std::string path;
    std::string content;
    std::function<void(const std::string&)> write;
};

// Conflicts the methods produce on purpose: a vote overriding propagation
// (Bénard 2014 §8.4, reason "consistent-vote") and the interpolated
// contours' heuristic votes (tutorial §6.2.4), whose disagreements with a
// direct ray test are what that method shows. Everything else (exact
// propagation vs a ray test) should never happen.
bool conflictByDesign(const ViewGraph& graph, const VisibilityConflict& conflict) {
    if (conflict.reason == "consistent-vote")
        return true;
    if (conflict.chain < 0 || conflict.chain >= static_cast<Index>(graph.chains.size()))
        return false;
    switch (graph.chains[static_cast<size_t>(conflict.chain)].decidedBy) {
    case VisibilityRule::MajorityVote:
    case VisibilityRule::AmbiguityCusps:
    case VisibilityRule::AmbiguityShortChain:
    case VisibilityRule::AmbiguityBoundary:
    case VisibilityRule::CuspConsistency:
    case VisibilityRule::AmbiguousInvisible:
    case VisibilityRule::HeuristicVote:
        return true;
    default:
        return false;
    }
}

// A diagnostic snapshot to write once every view has run.
struct PendingSnapshot {
    std::string folder;
    std::vector<SnapshotFile> files;
};

SvgOptions svgOptions(const std::string& title) {
    SvgOptions options;
    options.title = title;
    return options;
}

} // namespace

std::string viewOutputPath(const std::string& path, int view) {
    const std::filesystem::path p(path);
    // Two digits; built without `"0" + string`, which GCC 12 flags (-Wrestrict).
    std::string number = std::to_string(view);
    if (view < 10)
        number.insert(0, 1, '0');
    std::filesystem::path name = p.stem();
    name += "_view" + number;
    name += p.extension();
    return (p.parent_path() / name).string();
}

int runBatch(const BatchOptions& o, std::ostream& out) {
    checkOutputFolders(o);
    std::unique_ptr<Camera> fileCamera;
    if (!o.cameraFile.empty())
        fileCamera = std::make_unique<Camera>(readCameraFile(o));
    if (o.sessionCamera) {
        fileCamera = std::make_unique<Camera>(*o.sessionCamera);
        if (o.camera.width)
            fileCamera->viewport.width = *o.camera.width;
        if (o.camera.height)
            fileCamera->viewport.height = *o.camera.height;
        for (const std::string& warning : o.sessionWarnings)
            out << "session: " << warning << "\n";
    }

    const std::shared_ptr<const PolygonMesh> cage = loadMesh(o.meshPath);
    Snapshot input;
    try {
        input = makeInputSnapshot(cage);
    } catch (const std::exception& e) {
        throw BatchFailure(o.meshPath + ": " + e.what());
    }
    const std::vector<Camera> cameras =
        placeCameras(o, input.mesh->boundingBox(), fileCamera.get());

    const Method& method = *o.method;
    const int phases = o.phases.value_or(static_cast<int>(method.phases.size()));
    printRunHeader(out, o.meshPath, input, method, o.parameters);

    JsonReport report("contour-batch", CONTOUR_VERSION, o.meshPath, input, method, o.parameters);
    std::vector<PendingFile> files;
    std::vector<PendingSnapshot> snapshots;
    std::string absoluteMesh;
    {
        std::error_code error;
        absoluteMesh = std::filesystem::absolute(o.meshPath, error).lexically_normal().string();
        if (error)
            absoluteMesh = o.meshPath;
    }
    long long violations = 0;
    std::string firstViolation;
    long long conflicts = 0;
    std::string firstConflict;
    const bool several = cameras.size() > 1;
    // The snapshot's two PNGs, drawn by the workbench's views when this build
    // and this machine can (SnapshotImages.h); said once when they cannot.
    std::unique_ptr<SnapshotImages> images;
    if (!o.snapshotDir.empty()) {
        images = std::make_unique<SnapshotImages>();
        if (!images->available())
            out << "--snapshot-dir: " << snapshotFiles::kPng3d << " and " << snapshotFiles::kPng2d
                << " not written: " << images->unavailableReason() << "\n";
    }
    for (size_t v = 0; v < cameras.size(); ++v) {
        const Camera& camera = cameras[v];
        const int view = static_cast<int>(v);
        printViewHeader(out, view, static_cast<int>(cameras.size()), camera);
        std::unique_ptr<Runner> runner;
        try {
            runner = std::make_unique<Runner>(method, input, camera, o.parameters);
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
        while (runner->completedPhases() < phases) {
            try {
                runner->step();
            } catch (const std::exception& e) {
                out.flush();
                throw BatchFailure((several ? "view " + std::to_string(view) + ": " : "") +
                                   e.what());
            }
            const int done = runner->completedPhases();
            printPhase(out, method, runner->snapshot(done), runner->snapshot(done - 1));
        }
        printViewTotals(out, runner->current(), camera);
        for (const Snapshot& s : runner->snapshots())
            for (const InvariantCheck& c : s.invariants)
                if (c.violations > 0) {
                    if (violations == 0)
                        firstViolation = (several ? "view " + std::to_string(view) + ", " : "") +
                                         s.phaseName + ": " + c.name + " (" +
                                         std::to_string(c.violations) + "x, first " +
                                         c.firstExample + ")";
                    violations += c.violations;
                }
        // A ray test that disagrees with exact QI propagation is a bug or a
        // degenerate input: --strict fails on those too (the votes' conflicts
        // are expected, see conflictByDesign).
        if (const auto& graph = runner->current().viewGraph)
            for (const VisibilityConflict& c : graph->conflicts) {
                if (conflictByDesign(*graph, c))
                    continue;
                if (conflicts++ == 0)
                    firstConflict = (several ? "view " + std::to_string(view) + ", " : "") +
                                    "chain " + std::to_string(c.chain) + ": propagated QI " +
                                    std::to_string(c.propagatedQi) + ", ray test " +
                                    std::to_string(c.rayQi) + " (" + c.reason + ")";
            }
        report.addView(camera, runner->snapshots());
        const std::string title = o.meshPath + " - " + method.label +
                                  (several ? ", view " + std::to_string(view) : "") + ", after " +
                                  runner->current().phaseName;
        if (!o.svgPath.empty())
            files.push_back({several ? viewOutputPath(o.svgPath, view) : o.svgPath,
                             svgDocument(runner->current(), camera, svgOptions(title)),
                             {}});
        if (!o.writeCameraPath.empty())
            files.push_back({several ? viewOutputPath(o.writeCameraPath, view) : o.writeCameraPath,
                             camera.toJson().dump(2) + "\n",
                             {}});
        if (!o.snapshotDir.empty()) {
            DiagnosticSnapshotRun run;
            run.toolName = "contour-batch";
            run.toolVersion = CONTOUR_VERSION;
            run.meshPath = o.meshPath;
            run.method = &method;
            run.parameters = o.parameters;
            run.camera = camera;
            run.snapshots = runner->snapshots();
            run.title = title;
            run.session.meshPath = absoluteMesh;
            run.session.method = method.name;
            run.session.parameters = o.parameters;
            run.session.camera = camera;
            run.session.phaseReached = runner->completedPhases();
            run.session.phaseName = runner->current().phaseName;
            std::vector<std::string> notes;
            PendingSnapshot snapshot;
            std::string number = std::to_string(view);
            if (view < 10)
                number.insert(0, 1, '0');
            snapshot.folder =
                several ? (std::filesystem::path(o.snapshotDir) / ("view" + number)).string()
                        : o.snapshotDir;
            if (images->available()) {
                try {
                    snapshot.files = images->render(runner->current(), camera);
                } catch (const std::exception& e) {
                    throw BatchFailure(snapshot.folder + "/" + e.what());
                }
                run.otherFiles = {snapshotFiles::kPng3d, snapshotFiles::kPng2d};
            }
            for (SnapshotFile& file : diagnosticSnapshotFiles(run, &notes))
                snapshot.files.push_back(std::move(file));
            if (v == 0)
                for (const std::string& note : notes)
                    out << "  --snapshot-dir: " << note << "\n";
            snapshots.push_back(std::move(snapshot));
        }
        if (!o.plyPath.empty()) {
            const Snapshot& last = runner->current();
            if (!last.mesh)
                throw BatchFailure(o.plyPath + ": the snapshot after " + last.phaseName +
                                   " has no mesh to write");
            auto labels = std::make_shared<const SnapshotPlyLabels>(snapshotPlyLabels(last));
            if (v == 0) // the same fields in every view
                for (const std::string& skipped : labels->skipped)
                    out << "  --ply leaves out field " << skipped << "\n";
            files.push_back({several ? viewOutputPath(o.plyPath, view) : o.plyPath,
                             {},
                             [mesh = last.mesh, labels](const std::string& path) {
                                 writePly(*mesh, path, labels->labels);
                             }});
        }
    }
    if (!o.jsonPath.empty())
        files.push_back({o.jsonPath, report.text(), {}});

    std::vector<std::string> written;
    std::vector<std::filesystem::path> createdFolders;
    try {
        for (const PendingFile& file : files) {
            if (file.write)
                file.write(file.path);
            else
                writeFileAtomically(file.path, file.content);
            written.push_back(file.path);
        }
        for (const PendingSnapshot& snapshot : snapshots) {
            // The snapshot folder (and a view's sub-folder) is made here, and
            // removed again on failure.
            for (const std::filesystem::path& folder :
                 {std::filesystem::path(o.snapshotDir), std::filesystem::path(snapshot.folder)}) {
                std::error_code error;
                if (std::filesystem::create_directory(folder, error))
                    createdFolders.push_back(folder);
                else if (error)
                    throw std::runtime_error(snapshot.folder + ": cannot create the folder (" +
                                             error.message() + ")");
            }
            for (const std::string& path : writeSnapshotFiles(snapshot.folder, snapshot.files))
                written.push_back(path);
        }
    } catch (const std::exception& e) {
        // Leave no partial set of outputs behind either.
        for (const std::string& path : written)
            std::remove(path.c_str());
        for (auto it = createdFolders.rbegin(); it != createdFolders.rend(); ++it) {
            std::error_code ignored;
            std::filesystem::remove(*it, ignored); // only if empty
        }
        throw BatchFailure(e.what());
    }
    printWritten(out, written);
    if (o.strict && (violations > 0 || conflicts > 0)) {
        out.flush();
        if (violations > 0)
            std::cerr << "contour-batch: --strict: " << violations
                      << " post-conditions violated; first: " << firstViolation << "\n";
        if (conflicts > 0)
            std::cerr << "contour-batch: --strict: " << conflicts
                      << " visibility conflicts (a ray test disagrees with exact propagation); "
                         "first: "
                      << firstConflict << "\n";
        return 3;
    }
    return 0;
}

} // namespace contour::batch
