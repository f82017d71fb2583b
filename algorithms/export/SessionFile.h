#pragma once
// A workbench session: what reopens the same picture (the mesh, the analysis
// camera, the method, its parameters, the phase reached, and the display
// choices). The workbench saves and opens it (File › Save session…), the
// diagnostic snapshot holds one, and contour-batch --session runs from it.
//
// The file is JSON (suffix .cwsession):
// {
//   "format": "contour-workbench-session", "version": 1,
//   "mesh": path of the mesh file (absolute when saved; a relative path is
//           read relative to the session file's folder),
//   "keep_file_orientation": optional (false when absent), true when the
//           mesh was used as the file orients it, false when its inward
//           closed components were flipped outward (mesh/Orientation.h),
//   "method": method name (contourMethods()),
//   "parameters": {name: value} every parameter of the method (bool,
//                 number or choice string, as ParameterSet::toJson),
//   "preset": optional, {"name": the method's preset the parameters started
//             from ("default" when absent), "changed": {name: value} the
//             parameters that differ from it, for readers (changedFromPreset)},
//   "camera": the analysis camera (Camera::toJson, with its viewport),
//   "view_camera": optional, the 3D view's own camera (Camera::toJson),
//   "phase_reached": phases completed (0 = the input),
//   "phase_name": name of the last completed phase ("input" for 0), for
//                 readers; opening checks it against the method,
//   "display": {key: value} strings the GUI fills (colour field, overlay,
//              view-graph and control-cage toggles, view layout, compared
//              method); other readers ignore it
// }
#include "camera/Camera.h"
#include "pipeline/Method.h"
#include "pipeline/Parameters.h"

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace contour {

inline constexpr const char* kSessionFormat = "contour-workbench-session";
inline constexpr int kSessionVersion = 1;

struct Session {
    std::string meshPath;
    // The mesh as the file orients it (true) or with its inward closed
    // components flipped (false, the default), so reopening gives the same
    // mesh.
    bool keepFileOrientation = false;
    std::string method;
    // As read or as captured: values keep their JSON type (an integer in the
    // file reads as int even for a double parameter); sessionParameters()
    // converts them to the method's schema.
    ParameterSet parameters;
    // The preset the parameters started from, and those that differ from it
    // (setSessionPreset fills both).
    std::string preset = "default";
    ParameterSet presetChanges;
    Camera camera;
    std::optional<Camera> viewCamera;
    int phaseReached = 0;
    std::string phaseName = "input";
    std::map<std::string, std::string> display;
};

nlohmann::json sessionJson(const Session& session);
std::string sessionText(const Session& session);
// Throws std::runtime_error naming the field and the problem (not the file).
Session sessionFromJson(const nlohmann::json& json);

// Writes sessionText() atomically (io/AtomicFile.h); throws
// std::runtime_error naming the file.
void writeSession(const std::string& path, const Session& session);
// Reads and checks a session file; a relative mesh path is resolved against
// the file's folder. Throws std::runtime_error "path: problem".
Session readSession(const std::string& path);

// The session's parameters as a complete, valid set for `method`: defaults
// for the parameters the file lacks (a method that gained parameters since),
// each value converted to the spec's type and checked against its range.
// Names the method does not know are ignored. Both cases are reported in
// `warnings` when given. Throws std::invalid_argument naming the parameter
// for a value of the wrong type or out of range.
ParameterSet sessionParameters(const Session& session, const Method& method,
                               std::vector<std::string>* warnings = nullptr);

// Records `presetName` as the preset the session's parameters started from,
// with the parameters that differ from it. Throws std::invalid_argument when
// the method has no such preset.
void setSessionPreset(Session& session, const Method& method, const std::string& presetName);

// The session's preset when `method` has it, else "default" (reported in
// `warnings`).
std::string sessionPresetName(const Session& session, const Method& method,
                              std::vector<std::string>* warnings = nullptr);

// The number of phases to run to reproduce the session with `method`: the
// phase named "phase_name" when the method has it (phases get inserted as
// methods grow), else "phase_reached" clamped to the method's phase count;
// the fallback is reported in `warnings`.
int sessionPhaseTarget(const Session& session, const Method& method,
                       std::vector<std::string>* warnings = nullptr);

} // namespace contour
