#include "core/AtomicFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace contour {

namespace {
std::string describe(int error) {
    return error != 0 ? std::strerror(error) : "input/output error";
}
} // namespace

void writeFileAtomically(const std::string& path, std::string_view content) {
    if (path.empty())
        throw std::runtime_error("cannot write a file with an empty name");
    const std::string tmp = path + ".tmp";
    errno = 0;
    std::FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file)
        throw std::runtime_error(path + ": cannot write (" + describe(errno) + ")");
    bool failed = false;
    int error = 0;
    const auto note = [&](bool ok) {
        if (!ok && !failed) {
            failed = true;
            error = errno;
        }
    };
    errno = 0;
    note(std::fwrite(content.data(), 1, content.size(), file) == content.size());
    note(std::fflush(file) == 0);
    note(std::fclose(file) == 0);
    if (failed) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot write (" + describe(error) + ")");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        error = errno;
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot move the finished file into place (" +
                                 describe(error) + ")");
    }
}

} // namespace contour
