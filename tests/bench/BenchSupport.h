#pragma once
// What every benchmark prints about the machine and the process: the load
// average (figures taken on a busy machine say so), a /proc/self/status
// field (resident memory), and where a named model of ../shared/meshes is.
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

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

} // namespace contour::bench
