#pragma once
// The command line of contour-batch: declared with CLI11, one flag per method
// parameter generated from the registered methods' schemas (Parameters.h),
// and checked into a BatchOptions.
#include "camera/Camera.h"
#include "pipeline/Method.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour::batch {

// Bad arguments: exit code 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Camera settings given on the command line; each one overrides the default
// framing camera (or is an error with --camera/--views26, see BatchOptions.cpp).
struct CameraOverrides {
    std::optional<Vec3> eye, target, up;
    std::optional<double> fovYDegrees, orthoHeight;
    bool orthographic = false;
    std::optional<int> width, height;
};

struct BatchOptions {
    bool listMethods = false;
    std::string meshPath;
    // --keep-orientation (or a session that kept it): use the mesh as the
    // file orients it; by default inward closed components are flipped
    // (mesh/Orientation.h).
    bool keepOrientation = false;
    const Method* method = nullptr;
    // --preset: the method's preset the parameters start from ("default"
    // unless given; with --session, the session's); parameter flags
    // override it. The JSON report and the session record it.
    std::string preset = "default";
    ParameterSet parameters;
    std::string cameraFile;
    CameraOverrides camera;
    bool views26 = false;
    std::optional<int> phases; // stop after this many phases; all when empty
    std::string svgPath, jsonPath, writeCameraPath, plyPath;
    // --illustration-svg: the drawing for an illustrator (IllustrationSvg.h),
    // with hidden lines when --illustration-hidden.
    std::string illustrationSvgPath;
    bool illustrationHidden = false;
    // --snapshot-dir: per view, the diagnostic snapshot's report.json,
    // view-2d.svg, mesh.ply and session.cwsession (DiagnosticSnapshot.h);
    // with several views one sub-folder per view (view00, ...).
    std::string snapshotDir;
    // --session: the session file the mesh, method, parameters, camera and
    // phase came from (flags may override parameters, --phase, --width,
    // --height, --views26); its camera, and what reading it noted.
    std::string sessionPath;
    std::optional<Camera> sessionCamera;
    std::vector<std::string> sessionWarnings;
    // Exit with code 3 when any phase of any view violated a post-condition
    // (Release builds count violations instead of failing the phase), or when
    // a view graph records a visibility conflict between a ray test and exact
    // propagation (the votes' conflicts of the interpolated and consistent
    // methods are by design and only reported).
    bool strict = false;
};

enum class ParseStatus { Run, Exit };
struct ParseResult {
    ParseStatus status = ParseStatus::Run;
    int exitCode = 0; // when status == Exit (--help, --version)
    BatchOptions options;
};

// Parses argv. Help and version print to stdout and return Exit with code 0.
// Every problem (unknown option, bad number, unknown method, parameter of
// another method, bad value) throws UsageError naming the option.
ParseResult parseBatchOptions(int argc, const char* const* argv);

// "1,2.5,-3" -> Vec3; throws UsageError naming `option` on anything else.
Vec3 parseVec3(const std::string& option, const std::string& text);

} // namespace contour::batch
