#include "BatchRun.h"

#include "BatchCameras.h"
#include "PendingOutputs.h"
#include "SnapshotImages.h"
#include "Summary.h"
#include "export/DiagnosticSnapshot.h"
#include "export/IllustrationSvg.h"
#include "export/JsonReport.h"
#include "export/SnapshotPly.h"
#include "export/SvgWriter.h"
#include "mesh/MeshError.h"
#include "mesh/Orientation.h"
#include "mesh/io/MeshReader.h"
#include "mesh/io/MeshWriter.h"
#include "pipeline/Runner.h"
#include "pipeline/ViewGraph.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

namespace contour::batch {

namespace {

constexpr const char* kToolName = "contour-batch";

// Fails before any work when an output's folder does not exist.
void checkOutputFolders(const BatchOptions& o) {
    for (const std::string& path : {o.svgPath, o.illustrationSvgPath, o.jsonPath, o.writeCameraPath,
                                    o.plyPath, o.snapshotDir}) {
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

// The mesh as read, oriented as --keep-orientation says, and what that did.
std::shared_ptr<const PolygonMesh> loadMesh(const BatchOptions& o, std::string* orientation) {
    try {
        OrientationReport report;
        auto mesh = std::make_shared<const PolygonMesh>(
            orientForContours(readMesh(o.meshPath), o.keepOrientation, report));
        *orientation = orientationMessage(report, "--keep-orientation");
        return mesh;
    } catch (const MeshError& e) {
        throw BatchFailure(e.what());
    } catch (const std::exception& e) {
        throw BatchFailure(o.meshPath + ": " + e.what());
    }
}

// The method's input: the mesh as loaded and its triangulation; what
// loading noted about the mesh's orientation is printed and becomes a note
// of the input (and so of the JSON report's "mesh").
Snapshot readInput(const BatchOptions& o, std::ostream& out) {
    std::string orientation;
    const std::shared_ptr<const PolygonMesh> cage = loadMesh(o, &orientation);
    Snapshot input;
    try {
        input = makeInputSnapshot(cage);
    } catch (const std::exception& e) {
        throw BatchFailure(o.meshPath + ": " + e.what());
    }
    if (!orientation.empty()) {
        input.notes.push_back(o.meshPath + ": " + orientation);
        out << input.notes.back() << "\n";
    }
    return input;
}

// The mesh path a session file records, so it reopens from anywhere.
std::string absoluteMeshPath(const std::string& meshPath) {
    std::error_code error;
    const std::string absolute =
        std::filesystem::absolute(meshPath, error).lexically_normal().string();
    return error ? meshPath : absolute;
}

// The snapshot's two PNGs, drawn by the workbench's views when this build
// and this machine can (SnapshotImages.h); said once when they cannot.
std::unique_ptr<SnapshotImages> snapshotImages(const BatchOptions& o, std::ostream& out) {
    if (o.snapshotDir.empty())
        return nullptr;
    auto images = std::make_unique<SnapshotImages>();
    if (!images->available())
        out << "--snapshot-dir: " << snapshotFiles::kPng3d << " and " << snapshotFiles::kPng2d
            << " not written: " << images->unavailableReason() << "\n";
    return images;
}

// Which view of several a message is about ("" for a single view).
struct ViewName {
    int index = 0;
    bool several = false;

    // "view 3" followed by `separator`, or "".
    std::string prefix(const char* separator) const {
        return several ? "view " + std::to_string(index) + separator : std::string();
    }
    // "03": the two-digit number of per-view file and folder names.
    std::string number() const {
        std::string text = std::to_string(index);
        if (index < 10)
            text.insert(0, 1, '0');
        return text;
    }
};

// Steps the method through the requested phases from one camera, printing
// each phase and the view's totals.
std::unique_ptr<Runner> runView(const BatchOptions& o, const Snapshot& input, const Camera& camera,
                                const ViewName& view, int viewCount, std::ostream& out) {
    const Method& method = *o.method;
    const int phases = o.phases.value_or(static_cast<int>(method.phases.size()));
    printViewHeader(out, view.index, viewCount, camera);
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
            // The mesh is named: a phase may fail on what the mesh is (a
            // conformal map it cannot have, say).
            throw BatchFailure(o.meshPath + ": " + view.prefix(": ") + e.what());
        }
        const int done = runner->completedPhases();
        printPhase(out, method, runner->snapshot(done), runner->snapshot(done - 1));
    }
    printViewTotals(out, runner->current(), camera);
    printMethodSummary(out, {method, camera, runner->snapshots()});
    return runner;
}

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

// What --strict fails on, over every view: violated post-conditions and
// visibility conflicts that are not by design, each with its first example.
struct StrictFindings {
    long long violations = 0;
    std::string firstViolation;
    long long conflicts = 0;
    std::string firstConflict;
};

void countViolations(const std::vector<Snapshot>& snapshots, const ViewName& view,
                     StrictFindings& findings) {
    for (const Snapshot& s : snapshots)
        for (const InvariantCheck& c : s.invariants)
            if (c.violations > 0) {
                if (findings.violations == 0)
                    findings.firstViolation = view.prefix(", ") + s.phaseName + ": " + c.name +
                                              " (" + std::to_string(c.violations) + "x, first " +
                                              c.firstExample + ")";
                findings.violations += c.violations;
            }
}

// A ray test that disagrees with exact QI propagation is a bug or a
// degenerate input: --strict fails on those too (the votes' conflicts are
// expected, see conflictByDesign).
void countConflicts(const Snapshot& last, const ViewName& view, StrictFindings& findings) {
    if (!last.viewGraph)
        return;
    const ViewGraph& graph = *last.viewGraph;
    for (const VisibilityConflict& c : graph.conflicts) {
        if (conflictByDesign(graph, c))
            continue;
        if (findings.conflicts++ == 0)
            findings.firstConflict = view.prefix(", ") + "chain " + std::to_string(c.chain) +
                                     ": propagated QI " + std::to_string(c.propagatedQi) +
                                     ", ray test " + std::to_string(c.rayQi) + " (" + c.reason +
                                     ")";
    }
}

// The SVG's <title>: "<mesh> - <method label>[, view N], after <phase>".
std::string viewTitle(const BatchOptions& o, const ViewName& view, const Snapshot& last) {
    return o.meshPath + " - " + o.method->label +
           (view.several ? ", " + view.prefix("") : std::string()) + ", after " + last.phaseName;
}

// What every view's outputs share.
struct RunOutputs {
    const BatchOptions& options;
    std::string absoluteMesh;
    SnapshotImages* images = nullptr; // with --snapshot-dir only
    PendingOutputs pending;
};

// One view's run, as its outputs need it.
struct ViewRun {
    const Camera& camera;
    const Runner& runner;
    ViewName name;
    std::string title; // the SVG's <title>

    // The path of a per-view output: `path` itself for a single view.
    std::string outputPath(const std::string& path) const {
        return name.several ? viewOutputPath(path, name.index) : path;
    }
};

void addSvg(RunOutputs& r, const ViewRun& v) {
    SvgOptions options;
    options.title = v.title;
    r.pending.files.push_back(
        {v.outputPath(r.options.svgPath), svgDocument(v.runner.current(), v.camera, options), {}});
}

void addIllustrationSvg(RunOutputs& r, const ViewRun& v) {
    IllustrationOptions options;
    options.title = v.title;
    options.drawHidden = r.options.illustrationHidden;
    r.pending.files.push_back({v.outputPath(r.options.illustrationSvgPath),
                               illustrationSvgDocument(v.runner.current(), v.camera, options),
                               {}});
}

void addCameraFile(RunOutputs& r, const ViewRun& v) {
    r.pending.files.push_back(
        {v.outputPath(r.options.writeCameraPath), v.camera.toJson().dump(2) + "\n", {}});
}

void addDiagnosticSnapshot(RunOutputs& r, const ViewRun& v, std::ostream& out) {
    const BatchOptions& o = r.options;
    const Method& method = *o.method;
    DiagnosticSnapshotRun run;
    run.toolName = kToolName;
    run.toolVersion = CONTOUR_VERSION;
    run.meshPath = o.meshPath;
    run.method = &method;
    run.parameters = o.parameters;
    run.camera = v.camera;
    run.snapshots = v.runner.snapshots();
    run.title = v.title;
    run.session.meshPath = r.absoluteMesh;
    run.session.keepFileOrientation = o.keepOrientation;
    run.session.method = method.name;
    run.session.parameters = o.parameters;
    setSessionPreset(run.session, method, o.preset);
    run.session.camera = v.camera;
    run.session.phaseReached = v.runner.completedPhases();
    run.session.phaseName = v.runner.current().phaseName;
    PendingSnapshot snapshot;
    snapshot.folder =
        v.name.several
            ? (std::filesystem::path(o.snapshotDir) / ("view" + v.name.number())).string()
            : o.snapshotDir;
    if (r.images->available()) {
        try {
            snapshot.files = r.images->render(v.runner.current(), v.camera);
        } catch (const std::exception& e) {
            throw BatchFailure(snapshot.folder + "/" + e.what());
        }
        run.otherFiles = {snapshotFiles::kPng3d, snapshotFiles::kPng2d};
    }
    std::vector<std::string> notes;
    for (SnapshotFile& file : diagnosticSnapshotFiles(run, &notes))
        snapshot.files.push_back(std::move(file));
    if (v.name.index == 0) // the same notes in every view
        for (const std::string& note : notes)
            out << "  --snapshot-dir: " << note << "\n";
    r.pending.snapshots.push_back(std::move(snapshot));
}

void addPly(RunOutputs& r, const ViewRun& v, std::ostream& out) {
    const std::string& plyPath = r.options.plyPath;
    const Snapshot& last = v.runner.current();
    if (!last.mesh)
        throw BatchFailure(plyPath + ": the snapshot after " + last.phaseName +
                           " has no mesh to write");
    auto labels = std::make_shared<const SnapshotPlyLabels>(snapshotPlyLabels(last));
    if (v.name.index == 0) // the same fields in every view
        for (const std::string& skipped : labels->skipped)
            out << "  --ply leaves out field " << skipped << "\n";
    r.pending.files.push_back(
        {v.outputPath(plyPath), {}, [mesh = last.mesh, labels](const std::string& path) {
             writePly(*mesh, path, labels->labels);
         }});
}

// The per-view outputs the options ask for, in a fixed order: SVG, illustration SVG, camera,
// snapshot folder, PLY.
void addViewOutputs(RunOutputs& r, const ViewRun& v, std::ostream& out) {
    const BatchOptions& o = r.options;
    if (!o.svgPath.empty())
        addSvg(r, v);
    if (!o.illustrationSvgPath.empty())
        addIllustrationSvg(r, v);
    if (!o.writeCameraPath.empty())
        addCameraFile(r, v);
    if (!o.snapshotDir.empty())
        addDiagnosticSnapshot(r, v, out);
    if (!o.plyPath.empty())
        addPly(r, v, out);
}

// 3 when --strict finds a violated post-condition or a conflict (said on
// stderr), else 0.
int strictExitCode(const BatchOptions& o, const StrictFindings& f, std::ostream& out) {
    if (!o.strict || (f.violations == 0 && f.conflicts == 0))
        return 0;
    out.flush();
    if (f.violations > 0)
        std::cerr << "contour-batch: --strict: " << f.violations
                  << " post-conditions violated; first: " << f.firstViolation << "\n";
    if (f.conflicts > 0)
        std::cerr << "contour-batch: --strict: " << f.conflicts
                  << " visibility conflicts (a ray test disagrees with exact propagation); "
                     "first: "
                  << f.firstConflict << "\n";
    return 3;
}

} // namespace

std::string viewOutputPath(const std::string& path, int view) {
    const std::filesystem::path p(path);
    std::filesystem::path name = p.stem();
    name += "_view" + ViewName{view, true}.number();
    name += p.extension();
    return (p.parent_path() / name).string();
}

int runBatch(const BatchOptions& o, std::ostream& out) {
    checkOutputFolders(o);
    const std::optional<Camera> given = givenCamera(o, out);
    const Snapshot input = readInput(o, out);
    const std::vector<Camera> cameras = placeCameras(o, input.mesh->boundingBox(), given);
    const Method& method = *o.method;
    printRunHeader(out, o.meshPath, input, method, o.parameters);

    JsonReport report(kToolName, CONTOUR_VERSION, o.meshPath, input, method, o.parameters,
                      o.preset);
    const std::unique_ptr<SnapshotImages> images = snapshotImages(o, out);
    RunOutputs outputs{o, absoluteMeshPath(o.meshPath), images.get(), {}};
    StrictFindings findings;
    const int viewCount = static_cast<int>(cameras.size());
    for (int index = 0; index < viewCount; ++index) {
        const Camera& camera = cameras[static_cast<size_t>(index)];
        const ViewName view{index, viewCount > 1};
        const std::unique_ptr<Runner> runner = runView(o, input, camera, view, viewCount, out);
        countViolations(runner->snapshots(), view, findings);
        countConflicts(runner->current(), view, findings);
        report.addView(camera, runner->snapshots());
        addViewOutputs(outputs, {camera, *runner, view, viewTitle(o, view, runner->current())},
                       out);
    }
    if (!o.jsonPath.empty())
        outputs.pending.files.push_back({o.jsonPath, report.text(), {}});

    printWritten(out, writePendingOutputs(outputs.pending, o.snapshotDir));
    return strictExitCode(o, findings, out);
}

} // namespace contour::batch
