#pragma once
// A diagnostic snapshot: the files that describe one state of one run (a
// method on a mesh from one camera, up to the phase reached), written
// together into one folder, all or nothing. The workbench's File › Export
// diagnostic snapshot adds the two PNG grabs of its views to the files made
// here; contour-batch --snapshot-dir adds the same two pictures drawn by the
// same views off screen (app/batch/SnapshotImages.h), when it has a display.
//
// Files (fixed names, so scripts find them):
//   report.json       JsonReport with this one view: mesh, method, parameters,
//                     camera, every phase up to the one reached (time,
//                     counters, post-conditions, notes), totals, curves, the
//                     view graph, and what the method adds
//                     (MethodOutputs.h); plus
//                     "snapshot": {"phase_reached", "phase_name", "files"}
//   view-2d.svg       the curves or view graph as the camera sees them
//                     (SvgWriter.h)
//   mesh.ply          the working mesh with every int and double vertex and
//                     face field as a property (SnapshotPly.h)
//   session.cwsession the session that reopens this state (SessionFile.h)
//   view-3d.png, view-2d.png   the 3D and 2D views (made by the caller)
#include "camera/Camera.h"
#include "export/SessionFile.h"
#include "pipeline/Method.h"
#include "pipeline/Snapshot.h"

#include <functional>
#include <string>
#include <vector>

namespace contour {

namespace snapshotFiles {
inline constexpr const char* kReport = "report.json";
inline constexpr const char* kSvg = "view-2d.svg";
inline constexpr const char* kPly = "mesh.ply";
inline constexpr const char* kSession = "session.cwsession";
inline constexpr const char* kPng3d = "view-3d.png";
inline constexpr const char* kPng2d = "view-2d.png";
} // namespace snapshotFiles

// One file of a snapshot: its name in the folder and its bytes, or (for a
// writer that makes its own text, like writePly) a function writing it to a
// given path.
struct SnapshotFile {
    std::string name;
    std::string content;
    std::function<void(const std::string& path)> write;
};

struct DiagnosticSnapshotRun {
    std::string toolName;
    std::string toolVersion;
    std::string meshPath;
    const Method* method = nullptr;
    ParameterSet parameters;
    Camera camera;
    // Runner::snapshots() up to the state exported: [0] the input, [i] after
    // phase i.
    std::vector<Snapshot> snapshots;
    Session session;
    std::string title; // the SVG's <title>
    // Names of files the caller adds to the folder (the workbench's PNGs),
    // listed in the report's "snapshot" object with the four made here.
    std::vector<std::string> otherFiles;
};

// The report, SVG, PLY and session files of a run. `notes` (when given)
// receives what was left out (PLY fields without a property). Throws
// std::invalid_argument when the run has no method or no snapshot.
std::vector<SnapshotFile> diagnosticSnapshotFiles(const DiagnosticSnapshotRun& run,
                                                  std::vector<std::string>* notes = nullptr);

// Writes the files into `folder` (which must exist), all or nothing: every
// file goes into a temporary folder inside `folder` first; once all are
// complete each is renamed into place (a file of the same name already there
// is kept aside and put back if a later rename fails). On any failure
// nothing new is left in `folder` and std::runtime_error says which file and
// why ("<folder>/<name>: cannot write (<reason>)"). Returns the paths
// written.
std::vector<std::string> writeSnapshotFiles(const std::string& folder,
                                            const std::vector<SnapshotFile>& files);

} // namespace contour
