#include "mesh/io/MeshFileSupport.h"

#include "mesh/MeshError.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <stdexcept>
#include <system_error>

namespace contour::meshio {

namespace {
struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

std::string errnoText(int error) {
    return std::strerror(error);
}
} // namespace

FileData readWholeFile(const std::string& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status))
        throw MeshError(path, "",
                        "cannot open the file (" + (ec ? ec.message() : errnoText(ENOENT)) + ")");
    if (std::filesystem::is_directory(status))
        throw MeshError(path, "", "cannot open the file (it is a directory)");
    if (!std::filesystem::is_regular_file(status))
        throw MeshError(path, "", "cannot open the file (it is not a regular file)");
    File file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw MeshError(path, "", "cannot open the file (" + errnoText(errno) + ")");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec)
        throw MeshError(path, "", "cannot read the file (" + ec.message() + ")");
    std::unique_ptr<char[]> bytes;
    try {
        bytes.reset(new char[size + 1]); // + 1: never a zero-length array
    } catch (const std::bad_alloc&) {
        throw MeshError(path, "",
                        "the file is too large to load (" + std::to_string(size) + " bytes)");
    }
    const std::size_t got = size == 0 ? 0 : std::fread(bytes.get(), 1, size, file.get());
    if (got != size && std::ferror(file.get()))
        throw MeshError(path, "", "cannot read the file (" + errnoText(errno) + ")");
    return FileData(std::move(bytes), got); // got < size: the file shrank while we read it
}

std::string quoted(std::string_view token, std::size_t limit) {
    static const char hex[] = "0123456789abcdef";
    std::string out = "\"";
    for (std::size_t i = 0; i < token.size() && i < limit; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
            out += static_cast<char>(c);
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    if (token.size() > limit)
        out += "...";
    return out + "\"";
}

bool parseDouble(std::string_view token, double& value) {
    const char* first = token.data();
    const char* last = first + token.size();
    if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+')
        ++first;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ptr != last)
        return false;
    if (ec == std::errc())
        return true;
    if (ec != std::errc::result_out_of_range)
        return false;
    // from_chars leaves the value alone on overflow and underflow; strtod
    // gives +-HUGE_VAL (inf) and 0 or a denormal, as any other reader would.
    const std::string copy(first, last);
    value = std::strtod(copy.c_str(), nullptr);
    return true;
}

IntParse parseInt64(std::string_view token, std::int64_t& value) {
    const char* first = token.data();
    const char* last = first + token.size();
    if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+')
        ++first;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range)
        return IntParse::OutOfRange;
    if (ec != std::errc() || ptr != last)
        return IntParse::NotAnInteger;
    return IntParse::Ok;
}

void appendDouble(std::string& out, double value) {
    char buffer[32];
    const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, ec == std::errc() ? ptr : buffer);
}

void appendInt(std::string& out, std::int64_t value) {
    char buffer[24];
    const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, ec == std::errc() ? ptr : buffer);
}

bool LineReader::next(std::string_view& line) {
    if (p_ >= end_)
        return false;
    const char* start = p_;
    while (p_ < end_ && *p_ != '\n' && *p_ != '\r')
        ++p_;
    line = std::string_view(start, static_cast<std::size_t>(p_ - start));
    if (p_ < end_) {
        if (*p_ == '\r' && p_ + 1 < end_ && p_[1] == '\n')
            ++p_;
        ++p_;
    }
    ++line_;
    return true;
}

std::string_view nextToken(std::string_view& rest) {
    std::size_t i = 0;
    while (i < rest.size() && isBlank(rest[i]))
        ++i;
    std::size_t j = i;
    while (j < rest.size() && !isBlank(rest[j]))
        ++j;
    const std::string_view token = rest.substr(i, j - i);
    rest.remove_prefix(j);
    return token;
}

void Tokenizer::skipBlanks(bool crossLines) {
    while (p_ < end_) {
        const char c = *p_;
        if (isBlank(c)) {
            ++p_;
        } else if (c == '\n' || c == '\r') {
            if (!crossLines)
                return;
            if (c == '\r' && p_ + 1 < end_ && p_[1] == '\n')
                ++p_;
            ++p_;
            ++line_;
        } else if (c == '#' && comments_) {
            while (p_ < end_ && *p_ != '\n' && *p_ != '\r')
                ++p_;
        } else {
            return;
        }
    }
}

std::string_view Tokenizer::next() {
    skipBlanks(true);
    const char* start = p_;
    while (p_ < end_ && !isBlank(*p_) && *p_ != '\n' && *p_ != '\r' && !(comments_ && *p_ == '#'))
        ++p_;
    tokenLine_ = line_;
    return {start, static_cast<std::size_t>(p_ - start)};
}

bool Tokenizer::moreOnLine() {
    skipBlanks(false);
    return p_ < end_ && *p_ != '\n' && *p_ != '\r';
}

void Tokenizer::skipLine() {
    while (p_ < end_ && *p_ != '\n' && *p_ != '\r')
        ++p_;
}

} // namespace contour::meshio
