#pragma once
// What every benchmark prints about the machine and the process: the load
// average (figures taken on a busy machine say so), a /proc/self/status
// field (resident memory), and where a named model of ../shared/meshes is.
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/Method.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour::bench {

// "1-min 5-min 15-min" from /proc/loadavg, or "unknown".
inline std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return in ? one + " " + five + " " + fifteen : std::string("unknown");
}

// A field of /proc/self/status in kB ("VmRSS", "VmHWM"), or -1 if unreadable.
inline long long statusKb(const std::string& key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key + ":", 0) == 0) {
            std::istringstream fields(line.substr(key.size() + 1));
            long long kb = -1;
            fields >> kb;
            return kb;
        }
    return -1;
}

// `dir`/`name` with the first mesh extension that exists as a file.
inline std::optional<std::filesystem::path> findMeshFile(const std::filesystem::path& dir,
                                                         const std::string& name) {
    for (const char* extension : {".obj", ".off", ".ply"}) {
        const std::filesystem::path p = dir / (name + extension);
        std::error_code error;
        if (std::filesystem::is_regular_file(p, error))
            return p;
    }
    return std::nullopt;
}

// Writing 5 to clear_refs resets VmHWM to the current RSS (Linux >= 4.0), so
// each mesh gets its own peak. False when the kernel refuses.
inline bool resetPeakRss() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return static_cast<bool>(out);
}

inline std::string csvEscape(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (const char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

inline std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                cells.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                cells.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            cells.emplace_back();
        } else if (c != '\r') {
            cells.back() += c;
        }
    }
    return cells;
}

// ConTesse's published rows: Input -> Runtime (seconds per view).
inline std::map<std::string, double> readPublished(const std::string& path) {
    std::map<std::string, double> rows;
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line))
        return rows;
    const std::vector<std::string> header = splitCsvLine(line);
    const auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        return it == header.end() ? -1 : static_cast<int>(it - header.begin());
    };
    const int input = column("Input"), runtime = column("Runtime");
    if (input < 0 || runtime < 0)
        return rows;
    while (std::getline(in, line)) {
        const std::vector<std::string> cells = splitCsvLine(line);
        if (static_cast<int>(cells.size()) <= std::max(input, runtime))
            continue;
        try {
            rows[cells[static_cast<size_t>(input)]] =
                std::stod(cells[static_cast<size_t>(runtime)]);
        } catch (const std::exception&) {
        }
    }
    return rows;
}

// The published row for a mesh file name: the same name, else the only row
// named NAME_something (pawn -> pawn_open), else the only row whose name
// starts the file's name followed by '_' (AngelaFace_000150 -> AngelaFace).
inline std::optional<std::string> matchPublished(const std::map<std::string, double>& rows,
                                                 const std::string& name) {
    if (rows.count(name))
        return name;
    std::vector<std::string> candidates;
    for (const auto& [row, runtime] : rows)
        if (row.rfind(name + "_", 0) == 0)
            candidates.push_back(row);
    if (candidates.size() == 1)
        return candidates.front();
    candidates.clear();
    for (const auto& [row, runtime] : rows)
        if (name.rfind(row + "_", 0) == 0)
            candidates.push_back(row);
    if (candidates.size() == 1)
        return candidates.front();
    return std::nullopt;
}

// The method's defaults with every --set PARAM=VALUE applied; throws on an
// unknown parameter or a value its type refuses.
inline ParameterSet parametersWithSettings(const Method& method,
                                           const std::vector<std::string>& settings) {
    ParameterSet parameters = ParameterSet::defaults(method.parameters);
    for (const std::string& setting : settings) {
        const size_t eq = setting.find('=');
        const std::string name = setting.substr(0, eq);
        const auto spec = std::find_if(method.parameters.begin(), method.parameters.end(),
                                       [&](const ParameterSpec& p) { return p.name == name; });
        if (eq == std::string::npos || spec == method.parameters.end())
            throw std::runtime_error("--set " + setting + ": no such parameter");
        parameters.set(name, parseParameter(*spec, setting.substr(eq + 1)));
    }
    return parameters;
}

// A benchmark input: "shape:NAME[:RES]" a procedural shape (resolution 12
// by default), otherwise the mesh file `dir`/NAME.{obj,off,ply}; null when
// that file is absent.
inline std::shared_ptr<const PolygonMesh> loadBenchInput(const std::string& name,
                                                         const std::filesystem::path& dir) {
    if (name.rfind("shape:", 0) == 0) {
        const std::string spec = name.substr(6);
        const size_t colon = spec.find(':');
        const int resolution = colon == std::string::npos ? 12 : std::stoi(spec.substr(colon + 1));
        return std::make_shared<const PolygonMesh>(
            makeProceduralShape(spec.substr(0, colon), resolution));
    }
    const std::optional<std::filesystem::path> file = findMeshFile(dir, name);
    if (!file)
        return nullptr;
    return std::make_shared<const PolygonMesh>(readMesh(file->string()));
}

} // namespace contour::bench
