#include "export/SessionFile.h"

#include "core/AtomicFile.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace contour {

namespace {

std::runtime_error fieldError(const std::string& field, const std::string& problem) {
    return std::runtime_error("session: \"" + field + "\" " + problem);
}

const nlohmann::json& member(const nlohmann::json& j, const std::string& name) {
    const auto it = j.find(name);
    if (it == j.end())
        throw fieldError(name, "is missing");
    return *it;
}

std::string stringMember(const nlohmann::json& j, const std::string& name) {
    const nlohmann::json& v = member(j, name);
    if (!v.is_string())
        throw fieldError(name, "must be a string");
    return v.get<std::string>();
}

// JSON value -> the parameter value of the same JSON type.
// `field` names it in errors ("parameters.NAME").
ParameterValue rawParameter(const std::string& field, const nlohmann::json& v) {
    if (v.is_boolean())
        return v.get<bool>();
    if (v.is_number_integer()) {
        const long long x = v.get<long long>();
        if (x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max())
            return static_cast<double>(x);
        return static_cast<int>(x);
    }
    if (v.is_number())
        return v.get<double>();
    if (v.is_string())
        return v.get<std::string>();
    throw fieldError(field, "must be a boolean, a number or a string");
}

std::string typeText(ParameterType type) {
    switch (type) {
    case ParameterType::Bool:
        return "true or false";
    case ParameterType::Int:
        return "an integer";
    case ParameterType::Double:
        return "a number";
    case ParameterType::Choice:
        return "a string";
    }
    return "a value";
}

// A raw value converted to the spec's type where that loses nothing (an
// integer for a double, an integral double for an int).
std::optional<ParameterValue> convert(const ParameterSpec& spec, const ParameterValue& raw) {
    switch (spec.type) {
    case ParameterType::Bool:
        if (std::holds_alternative<bool>(raw))
            return raw;
        return std::nullopt;
    case ParameterType::Int:
        if (std::holds_alternative<int>(raw))
            return raw;
        if (const double* d = std::get_if<double>(&raw);
            d && std::floor(*d) == *d && std::abs(*d) < 2.0e9)
            return static_cast<int>(*d);
        return std::nullopt;
    case ParameterType::Double:
        if (const int* i = std::get_if<int>(&raw))
            return static_cast<double>(*i);
        if (std::holds_alternative<double>(raw))
            return raw;
        return std::nullopt;
    case ParameterType::Choice:
        if (std::holds_alternative<std::string>(raw))
            return raw;
        return std::nullopt;
    }
    return std::nullopt;
}

} // namespace

nlohmann::json sessionJson(const Session& s) {
    nlohmann::json j;
    j["format"] = kSessionFormat;
    j["version"] = kSessionVersion;
    j["mesh"] = s.meshPath;
    j["keep_file_orientation"] = s.keepFileOrientation;
    j["method"] = s.method;
    j["parameters"] = s.parameters.toJson();
    j["preset"] = {{"name", s.preset}, {"changed", s.presetChanges.toJson()}};
    j["camera"] = s.camera.toJson();
    if (s.viewCamera)
        j["view_camera"] = s.viewCamera->toJson();
    j["phase_reached"] = s.phaseReached;
    j["phase_name"] = s.phaseName;
    nlohmann::json display = nlohmann::json::object();
    for (const auto& [key, value] : s.display)
        display[key] = value;
    j["display"] = std::move(display);
    return j;
}

std::string sessionText(const Session& session) {
    return sessionJson(session).dump(2) + "\n";
}

Session sessionFromJson(const nlohmann::json& j) {
    if (!j.is_object())
        throw std::runtime_error("session: expected a JSON object");
    if (stringMember(j, "format") != kSessionFormat)
        throw fieldError("format", std::string("must be \"") + kSessionFormat + "\"");
    const nlohmann::json& version = member(j, "version");
    if (!version.is_number_integer() || version.get<long long>() < 1)
        throw fieldError("version", "must be a positive integer");
    if (version.get<long long>() > kSessionVersion)
        throw fieldError("version", std::to_string(version.get<long long>()) +
                                        " is newer than this program reads (" +
                                        std::to_string(kSessionVersion) + ")");
    Session s;
    s.meshPath = stringMember(j, "mesh");
    if (s.meshPath.empty())
        throw fieldError("mesh", "is empty");
    if (j.contains("keep_file_orientation")) {
        if (!j["keep_file_orientation"].is_boolean())
            throw fieldError("keep_file_orientation", "must be true or false");
        s.keepFileOrientation = j["keep_file_orientation"].get<bool>();
    }
    s.method = stringMember(j, "method");
    const nlohmann::json& parameters = member(j, "parameters");
    if (!parameters.is_object())
        throw fieldError("parameters", "must be an object {name: value}");
    for (const auto& [name, value] : parameters.items())
        s.parameters.set(name, rawParameter("parameters." + name, value));
    if (j.contains("preset")) {
        const nlohmann::json& preset = j["preset"];
        if (!preset.is_object())
            throw fieldError("preset", "must be an object {\"name\", \"changed\"}");
        s.preset = stringMember(preset, "name");
        if (s.preset.empty())
            throw fieldError("preset.name", "is empty");
        if (preset.contains("changed")) {
            const nlohmann::json& changed = preset["changed"];
            if (!changed.is_object())
                throw fieldError("preset.changed", "must be an object {name: value}");
            for (const auto& [name, value] : changed.items())
                s.presetChanges.set(name, rawParameter("preset.changed." + name, value));
        }
    }
    try {
        s.camera = Camera::fromJson(member(j, "camera"));
        if (j.contains("view_camera"))
            s.viewCamera = Camera::fromJson(j["view_camera"]);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("session: ") + e.what());
    }
    if (const std::string problem = s.camera.validate(); !problem.empty())
        throw fieldError("camera", "is not usable: " + problem);
    if (s.viewCamera && !s.viewCamera->validate().empty())
        throw fieldError("view_camera", "is not usable: " + s.viewCamera->validate());
    const nlohmann::json& phase = member(j, "phase_reached");
    if (!phase.is_number_integer() || phase.get<long long>() < 0 || phase.get<long long>() > 100000)
        throw fieldError("phase_reached", "must be a non-negative integer");
    s.phaseReached = phase.get<int>();
    if (j.contains("phase_name")) {
        if (!j["phase_name"].is_string())
            throw fieldError("phase_name", "must be a string");
        s.phaseName = j["phase_name"].get<std::string>();
    }
    if (j.contains("display")) {
        const nlohmann::json& display = j["display"];
        if (!display.is_object())
            throw fieldError("display", "must be an object {key: string}");
        for (const auto& [key, value] : display.items()) {
            if (!value.is_string())
                throw fieldError("display." + key, "must be a string");
            s.display[key] = value.get<std::string>();
        }
    }
    return s;
}

void writeSession(const std::string& path, const Session& session) {
    writeFileAtomically(path, sessionText(session));
}

Session readSession(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(path + ": cannot open the session file");
    std::ostringstream text;
    text << in.rdbuf();
    Session s;
    try {
        s = sessionFromJson(nlohmann::json::parse(text.str()));
    } catch (const nlohmann::json::parse_error& e) {
        throw std::runtime_error(path + ": not a JSON file (" + e.what() + ")");
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    const std::filesystem::path mesh(s.meshPath);
    if (mesh.is_relative())
        s.meshPath = (std::filesystem::path(path).parent_path() / mesh).lexically_normal().string();
    return s;
}

ParameterSet sessionParameters(const Session& session, const Method& method,
                               std::vector<std::string>* warnings) {
    ParameterSet out = ParameterSet::defaults(method.parameters);
    for (const ParameterSpec& spec : method.parameters) {
        if (!session.parameters.has(spec.name)) {
            if (warnings)
                warnings->push_back("parameter " + spec.name +
                                    " is not in the session: using its default " +
                                    toString(spec.defaultValue));
            continue;
        }
        const ParameterValue& raw = session.parameters.value(spec.name);
        const std::optional<ParameterValue> value = convert(spec, raw);
        if (!value)
            throw std::invalid_argument("parameter " + spec.name + ": \"" + toString(raw) +
                                        "\" must be " + typeText(spec.type));
        out.set(spec.name, *value);
    }
    for (const auto& [name, value] : session.parameters.values())
        if (!method.parameter(name) && warnings)
            warnings->push_back("parameter " + name + " is not a parameter of method " +
                                method.name + ": ignored");
    const std::vector<std::string> problems = validateParameters(method.parameters, out);
    if (!problems.empty())
        throw std::invalid_argument(problems.front());
    return out;
}

void setSessionPreset(Session& session, const Method& method, const std::string& presetName) {
    const ParameterPreset* preset = method.preset(presetName);
    if (!preset)
        throw std::invalid_argument("session: method " + method.name + " has no preset \"" +
                                    presetName + "\"");
    session.preset = preset->name;
    session.presetChanges = changedFromPreset(method.parameters, *preset, session.parameters);
}

std::string sessionPresetName(const Session& session, const Method& method,
                              std::vector<std::string>* warnings) {
    if (method.preset(session.preset))
        return session.preset;
    if (warnings)
        warnings->push_back("method " + method.name + " has no preset \"" + session.preset +
                            "\": the parameters are taken as changed from \"default\"");
    return "default";
}

int sessionPhaseTarget(const Session& session, const Method& method,
                       std::vector<std::string>* warnings) {
    const int count = static_cast<int>(method.phases.size());
    if (session.phaseReached == 0 || session.phaseName == "input")
        return 0;
    if (const int named = method.phaseIndex(session.phaseName) + 1; named > 0) {
        if (named != session.phaseReached && warnings)
            warnings->push_back("phase \"" + session.phaseName + "\" is now phase " +
                                std::to_string(named) + " of method " + method.name +
                                " (the session says " + std::to_string(session.phaseReached) +
                                "): running to it by name");
        return named;
    }
    const int target = std::min(session.phaseReached, count);
    if (warnings)
        warnings->push_back("method " + method.name + " has no phase named \"" + session.phaseName +
                            "\": running to phase " + std::to_string(target));
    return target;
}

} // namespace contour
