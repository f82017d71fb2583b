#include "BatchOptions.h"

#include "BatchRun.h"
#include "contours/Methods.h"
#include "export/SessionFile.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

namespace contour::batch {

namespace {

constexpr int kMaxViewportSide = 65536;

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t");
    if (a == std::string::npos)
        return {};
    const size_t b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
    std::string out;
    for (const std::string& item : items)
        out += (out.empty() ? "" : separator) + item;
    return out;
}

std::string numberText(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

// One flag per parameter name, shared by the methods that declare it.
struct ParameterFlag {
    const ParameterSpec* spec = nullptr; // of the first method that declares it
    std::vector<std::string> methods;
    std::string value;
    CLI::Option* option = nullptr;
};

std::string typeName(const ParameterSpec& spec) {
    switch (spec.type) {
    case ParameterType::Bool:
        return "BOOL";
    case ParameterType::Int:
        return "INT";
    case ParameterType::Double:
        return "NUMBER";
    case ParameterType::Choice:
        return "{" + join(spec.choices, ",") + "}";
    }
    return "VALUE";
}

std::string flagHelp(const ParameterFlag& flag) {
    const ParameterSpec& spec = *flag.spec;
    std::string help = spec.help;
    if (spec.type == ParameterType::Int || spec.type == ParameterType::Double)
        help += " Range [" + numberText(spec.minimum) + ", " + numberText(spec.maximum) + "].";
    if (spec.type == ParameterType::Bool)
        help += " true or false.";
    std::vector<std::string> defaults;
    for (const std::string& methodName : flag.methods) {
        const ParameterSpec* own = findMethod(methodName)->parameter(spec.name);
        defaults.push_back(methodName + ", default " + toString(own->defaultValue));
    }
    return help + " [" + join(defaults, "; ") + "]";
}

// "--preset" help: each method's presets.
std::string presetHelp() {
    std::string help = "Start from a preset of the method's parameters (parameter flags "
                       "override it; with --session it replaces the session's parameters):";
    for (const Method& m : contourMethods()) {
        std::vector<std::string> names;
        for (const ParameterPreset& p : m.presets)
            names.push_back(p.name);
        help += " " + m.name + ": " + join(names, ", ") + ";";
    }
    help.back() = '.';
    return help + " --list-methods describes them. Default: default.";
}

std::vector<std::string> methodNames() {
    std::vector<std::string> names;
    for (const Method& m : contourMethods())
        names.push_back(m.name);
    return names;
}

std::vector<std::string> plannedNames() {
    std::vector<std::string> names;
    for (const PlannedMethod& m : plannedMethods())
        names.push_back(m.name);
    return names;
}

const Method* resolveMethod(const std::string& name) {
    if (const Method* method = findMethod(name))
        return method;
    if (const PlannedMethod* planned = findPlannedMethod(name))
        throw UsageError("--method " + name + " (" + planned->label + "): " + planned->reason);
    throw UsageError("--method: unknown method \"" + name +
                     "\"; available: " + join(methodNames(), ", ") +
                     " (planned, not implemented yet: " + join(plannedNames(), ", ") + ")");
}

} // namespace

Vec3 parseVec3(const std::string& option, const std::string& text) {
    std::vector<std::string> parts;
    std::string current;
    for (const char c : text) {
        if (c == ',') {
            parts.push_back(current);
            current.clear();
        } else {
            current += c;
        }
    }
    parts.push_back(current);
    const auto bad = [&]() {
        return UsageError(option + ": \"" + text + "\" is not three comma-separated numbers x,y,z");
    };
    if (parts.size() != 3)
        throw bad();
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
        const std::string part = trim(parts[static_cast<size_t>(i)]);
        double x = 0.0;
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
        if (part.empty() || ec != std::errc() || end != part.data() + part.size() ||
            !std::isfinite(x))
            throw bad();
        v[i] = x;
    }
    return v;
}

ParseResult parseBatchOptions(int argc, const char* const* argv) {
    ParseResult result;
    BatchOptions& o = result.options;

    CLI::App app{"Runs a contour method on a mesh from one or more cameras, headless, and "
                 "writes the curves as SVG and a JSON report of every phase.",
                 "contour-batch"};
    app.set_version_flag("--version", std::string("contour-batch ") + CONTOUR_VERSION);
    app.get_formatter()->column_width(40);

    std::string methodName = "mesh";
    std::string eyeText, targetText, upText;
    double fov = 0.0, orthoHeight = 0.0;
    int width = 800, height = 600, phases = 0;

    app.add_flag("--list-methods", o.listMethods,
                 "List the methods, their phases and parameters, then exit.");
    CLI::Option* meshOption =
        app.add_option("--mesh", o.meshPath, "Mesh to read (.obj, .off, .ply). Required.")
            ->type_name("FILE");
    app.add_flag("--keep-orientation", o.keepOrientation,
                 "Use the mesh as the file orients its faces. By default each closed component "
                 "whose faces are oriented inward (negative signed volume) is flipped outward, "
                 "since its contours would all read as hidden; a line says which were flipped "
                 "or kept.");
    CLI::Option* sessionOption =
        app.add_option("--session", o.sessionPath,
                       "Run what a workbench session file (.cwsession) holds: its mesh, method, "
                       "parameters, analysis camera, phase reached and whether it kept the "
                       "file's orientation. Parameter flags, --phase, --width, --height and "
                       "--views26 override it; --keep-orientation keeps the file's orientation "
                       "even when the session flipped it.")
            ->type_name("FILE");
    CLI::Option* methodOption =
        app.add_option("--method", methodName,
                       "Contour method: " + join(methodNames(), ", ") +
                           " (planned, not implemented yet: " + join(plannedNames(), ", ") + ").")
            ->type_name("NAME")
            ->capture_default_str();
    CLI::Option* presetOption =
        app.add_option("--preset", o.preset, presetHelp())->type_name("NAME");
    app.add_option("--phase", phases,
                   "Stop after N phases (0 = the input only). Default: run every phase.")
        ->type_name("N");

    const std::string cameraGroup = "Camera (default: a 3/4 view framing the mesh)";
    CLI::Option* cameraFile = app.add_option("--camera", o.cameraFile,
                                             "Read the camera from a JSON file (Camera::toJson).")
                                  ->type_name("FILE")
                                  ->group(cameraGroup);
    CLI::Option* eye = app.add_option("--eye", eyeText, "Camera position.")
                           ->type_name("X,Y,Z")
                           ->group(cameraGroup);
    CLI::Option* target = app.add_option("--target", targetText,
                                         "Point looked at (default: the bounding-box centre).")
                              ->type_name("X,Y,Z")
                              ->group(cameraGroup);
    CLI::Option* up = app.add_option("--up", upText, "Up direction (default 0,1,0).")
                          ->type_name("X,Y,Z")
                          ->group(cameraGroup);
    CLI::Option* fovOption =
        app.add_option("--fov", fov, "Vertical field of view in degrees, perspective (default 60).")
            ->type_name("DEG")
            ->group(cameraGroup);
    CLI::Option* ortho = app.add_flag("--ortho", o.camera.orthographic, "Orthographic projection.")
                             ->group(cameraGroup);
    CLI::Option* orthoHeightOption =
        app.add_option("--ortho-height", orthoHeight,
                       "World-space height of an orthographic view (default: the bounding-box "
                       "diagonal).")
            ->type_name("H")
            ->group(cameraGroup);
    app.add_flag("--views26", o.views26,
                 "Run the 26 views of the test protocol; outputs get a _viewNN suffix "
                 "(00-25) before their extension, the JSON report holds all 26 views.")
        ->group(cameraGroup);
    CLI::Option* widthOption = app.add_option("--width", width, "Viewport width in pixels.")
                                   ->type_name("PX")
                                   ->capture_default_str()
                                   ->group(cameraGroup);
    CLI::Option* heightOption = app.add_option("--height", height, "Viewport height in pixels.")
                                    ->type_name("PX")
                                    ->capture_default_str()
                                    ->group(cameraGroup);

    const std::string outputGroup = "Output (written only when every step succeeds)";
    app.add_option("--svg", o.svgPath,
                   "Write the curves as SVG (the view graph's visible/hidden layers and node "
                   "markers when the method ran its visibility phase).")
        ->type_name("FILE")
        ->group(outputGroup);
    app.add_option("--illustration-svg", o.illustrationSvgPath,
                   "Write the clean drawing as SVG: visible strokes chained through the view "
                   "graph, tapered at curtain folds and dead ends, no node glyphs, one Inkscape "
                   "layer per curve type.")
        ->type_name("FILE")
        ->group(outputGroup);
    app.add_flag("--illustration-hidden", o.illustrationHidden,
                 "With --illustration-svg: also draw the hidden lines, dashed, in a layer of "
                 "their own.")
        ->group(outputGroup);
    app.add_flag("--strict", o.strict,
                 "Exit with code 3 when any post-condition of any phase is violated, or when "
                 "a ray test disagrees with exact QI propagation (visibility conflicts of the "
                 "votes are only reported); the outputs are still written.");
    app.add_option("--json", o.jsonPath, "Write the JSON report.")
        ->type_name("FILE")
        ->group(outputGroup);
    app.add_option("--write-camera", o.writeCameraPath, "Write the camera used as JSON.")
        ->type_name("FILE")
        ->group(outputGroup);
    app.add_option("--snapshot-dir", o.snapshotDir,
                   "Write per view the diagnostic snapshot the workbench exports: report.json, "
                   "view-2d.svg, mesh.ply, session.cwsession, and with a display (xvfb-run -a "
                   "will do) view-3d.png and view-2d.png drawn by the workbench's views, into "
                   "DIR (created if missing; with several views into DIR/view00, ...).")
        ->type_name("DIR")
        ->group(outputGroup);
    app.add_option("--ply", o.plyPath,
                   "Write the working mesh of the last snapshot computed (after --phase N when "
                   "given) as ASCII PLY, with every int and double vertex and face field of the "
                   "snapshot as a property of the same name (vector and edge fields are left "
                   "out).")
        ->type_name("FILE")
        ->group(outputGroup);

    // One flag per parameter of every registered method (the CLI flags are
    // generated from the schema), listed under the group of the first method
    // that declares it.
    std::map<std::string, ParameterFlag> flags;
    std::vector<std::string> flagOrder;
    for (const Method& method : contourMethods())
        for (const ParameterSpec& spec : method.parameters) {
            auto [it, inserted] = flags.try_emplace(spec.name);
            if (inserted) {
                it->second.spec = &spec;
                flagOrder.push_back(spec.name);
            }
            it->second.methods.push_back(method.name);
        }
    for (const std::string& name : flagOrder) {
        ParameterFlag& flag = flags.at(name);
        flag.option = app.add_option("--" + name, flag.value, flagHelp(flag))
                          ->type_name(typeName(*flag.spec))
                          ->group("Parameters: " + flag.spec->group);
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() != 0)
            throw UsageError(e.what());
        result.status = ParseStatus::Exit; // --help or --version
        result.exitCode = app.exit(e);
        return result;
    }
    if (o.listMethods)
        return result;
    Session session;
    if (sessionOption->count() > 0) {
        for (CLI::Option* option : {meshOption, methodOption, cameraFile, eye, target, up,
                                    fovOption, ortho, orthoHeightOption})
            if (option->count() > 0)
                throw UsageError("--session cannot be combined with " + option->get_name() +
                                 " (the session names the mesh, method and camera)");
        try {
            session = readSession(o.sessionPath);
        } catch (const std::exception& e) {
            throw BatchFailure(e.what());
        }
        o.meshPath = session.meshPath;
        o.keepOrientation = o.keepOrientation || session.keepFileOrientation;
        methodName = session.method;
        o.sessionCamera = session.camera;
    }
    if (o.meshPath.empty())
        throw UsageError("--mesh is required (the mesh file to read)");

    o.method = resolveMethod(methodName);
    o.parameters = ParameterSet::defaults(o.method->parameters);
    if (o.sessionCamera) {
        try {
            o.parameters = sessionParameters(session, *o.method, &o.sessionWarnings);
        } catch (const std::invalid_argument& e) {
            throw BatchFailure(o.sessionPath + ": " + e.what());
        }
        if (app.count("--phase") == 0)
            o.phases = sessionPhaseTarget(session, *o.method, &o.sessionWarnings);
        if (presetOption->count() == 0)
            o.preset = sessionPresetName(session, *o.method, &o.sessionWarnings);
    }
    const ParameterPreset* preset = o.method->preset(o.preset);
    if (!preset) {
        std::vector<std::string> names;
        for (const ParameterPreset& p : o.method->presets)
            names.push_back(p.name);
        throw UsageError("--preset: method " + o.method->name + " has no preset \"" + o.preset +
                         "\"; its presets: " + join(names, ", "));
    }
    if (presetOption->count() > 0 || !o.sessionCamera)
        o.parameters = presetValues(o.method->parameters, *preset);
    for (const std::string& name : flagOrder) {
        const ParameterFlag& flag = flags.at(name);
        if (flag.option->count() == 0)
            continue;
        const ParameterSpec* spec = o.method->parameter(name);
        if (!spec) {
            std::vector<std::string> own;
            for (const ParameterSpec& s : o.method->parameters)
                own.push_back("--" + s.name);
            throw UsageError("--" + name + " is a parameter of method " + join(flag.methods, ", ") +
                             ", not of method " + o.method->name + " (" + o.method->name +
                             " takes: " + (own.empty() ? "no parameters" : join(own, ", ")) + ")");
        }
        try {
            o.parameters.set(name, parseParameter(*spec, flag.value));
        } catch (const std::invalid_argument& e) {
            // "parameter NAME: PROBLEM" -> "--NAME: PROBLEM"
            std::string problem = e.what();
            const std::string prefix = "parameter " + name + ": ";
            if (problem.rfind(prefix, 0) == 0)
                problem.erase(0, prefix.size());
            throw UsageError("--" + name + ": " + problem);
        }
    }

    // Camera options: a file, or flags that override the default framing.
    for (CLI::Option* option : {eye, target, up, fovOption, ortho, orthoHeightOption})
        if (cameraFile->count() > 0 && option->count() > 0)
            throw UsageError("--camera cannot be combined with " + option->get_name() +
                             " (edit the camera file instead)");
    for (CLI::Option* option : {cameraFile, eye, target, up})
        if (o.views26 && option->count() > 0)
            throw UsageError("--views26 cannot be combined with " + option->get_name() +
                             " (the protocol places the 26 cameras)");
    if (ortho->count() > 0 && fovOption->count() > 0)
        throw UsageError("--fov applies to perspective cameras, not with --ortho");
    if (orthoHeightOption->count() > 0 && ortho->count() == 0)
        throw UsageError("--ortho-height needs --ortho");
    if (eye->count() > 0)
        o.camera.eye = parseVec3("--eye", eyeText);
    if (target->count() > 0)
        o.camera.target = parseVec3("--target", targetText);
    if (up->count() > 0)
        o.camera.up = parseVec3("--up", upText);
    if (fovOption->count() > 0) {
        if (!(fov > 0.0 && fov < 180.0))
            throw UsageError("--fov: " + numberText(fov) + " is not in (0, 180) degrees");
        o.camera.fovYDegrees = fov;
    }
    if (orthoHeightOption->count() > 0) {
        if (!(orthoHeight > 0.0 && std::isfinite(orthoHeight)))
            throw UsageError("--ortho-height: " + numberText(orthoHeight) + " is not positive");
        o.camera.orthoHeight = orthoHeight;
    }
    for (const auto& [option, value] : {std::pair{widthOption, width}, {heightOption, height}})
        if (option->count() > 0 && (value < 1 || value > kMaxViewportSide))
            throw UsageError(option->get_name() + ": " + std::to_string(value) +
                             " pixels is not in [1, " + std::to_string(kMaxViewportSide) + "]");
    // A camera file or session keeps its viewport unless --width/--height say
    // otherwise (the 26 views of a session take the session's viewport).
    const bool ownViewport = cameraFile->count() > 0 || o.sessionCamera;
    if (widthOption->count() > 0 || !ownViewport)
        o.camera.width = width;
    else if (o.sessionCamera && o.views26)
        o.camera.width = o.sessionCamera->viewport.width;
    if (heightOption->count() > 0 || !ownViewport)
        o.camera.height = height;
    else if (o.sessionCamera && o.views26)
        o.camera.height = o.sessionCamera->viewport.height;
    if (app.count("--phase") > 0) {
        const size_t available = o.method->phases.size();
        if (phases < 0 || static_cast<size_t>(phases) > available)
            throw UsageError("--phase: " + std::to_string(phases) + " is not in [0, " +
                             std::to_string(available) + "]: method " + o.method->name + " has " +
                             std::to_string(available) + " phases");
        o.phases = phases;
    }

    // "out/snap/" -> "out/snap": its parent folder must exist.
    while (o.snapshotDir.size() > 1 && o.snapshotDir.back() == '/')
        o.snapshotDir.pop_back();
    // Two outputs with one name would overwrite each other.
    const std::vector<std::pair<std::string, std::string>> outputs{
        {"--svg", o.svgPath},   {"--illustration-svg", o.illustrationSvgPath},
        {"--json", o.jsonPath}, {"--write-camera", o.writeCameraPath},
        {"--ply", o.plyPath},   {"--snapshot-dir", o.snapshotDir}};
    for (size_t i = 0; i < outputs.size(); ++i)
        for (size_t j = i + 1; j < outputs.size(); ++j)
            if (!outputs[i].second.empty() && outputs[i].second == outputs[j].second)
                throw UsageError(outputs[i].first + " and " + outputs[j].first +
                                 " name the same file " + outputs[i].second);
    return result;
}

} // namespace contour::batch
