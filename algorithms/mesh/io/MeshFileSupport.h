#pragma once
// Shared plumbing of the mesh readers and writers (internal to mesh/): whole-
// file reading, atomic writing, number parsing without iostreams, a text
// tokenizer that tracks line numbers, and quoting of untrusted bytes for
// error messages.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace contour::meshio {

// The bytes of a whole file (not zero-filled first: large files load fast).
class FileData {
public:
    FileData() = default;
    FileData(std::unique_ptr<char[]> bytes, std::size_t size)
        : bytes_(std::move(bytes)), size_(size) {}
    std::string_view view() const { return {bytes_.get(), size_}; }
    operator std::string_view() const { return view(); }
    const char* data() const { return bytes_.get(); }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

private:
    std::unique_ptr<char[]> bytes_;
    std::size_t size_ = 0;
};

// The whole file in memory. Throws MeshError "cannot open ..." naming it.
FileData readWholeFile(const std::string& path);

// `token` in double quotes, non-printable bytes as \xNN, cut after `limit`
// bytes: safe to put garbage input into a message.
std::string quoted(std::string_view token, std::size_t limit = 24);

// Parse the whole token, nothing else; false when it is not a number.
// Overflowing reals become +-inf, underflowing ones 0 (as strtod does).
bool parseDouble(std::string_view token, double& value);
enum class IntParse { Ok, NotAnInteger, OutOfRange };
IntParse parseInt64(std::string_view token, std::int64_t& value);

// Appends the shortest text that reads back as exactly `value`.
void appendDouble(std::string& out, double value);
void appendInt(std::string& out, std::int64_t value);

inline bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\v' || c == '\f';
}

// Splits a text buffer into lines; "\n", "\r\n" and a lone "\r" all end a line.
class LineReader {
public:
    explicit LineReader(std::string_view text) : p_(text.data()), end_(text.data() + text.size()) {}
    // The next line without its terminator; false at the end of the text.
    bool next(std::string_view& line);
    int lineNumber() const { return line_; } // of the line last returned, from 1
    const char* position() const { return p_; }

private:
    const char* p_;
    const char* end_;
    int line_ = 0;
};

// The next blank-separated token of `rest` (which is advanced past it), or an
// empty view when only blanks are left.
std::string_view nextToken(std::string_view& rest);

// Whitespace-separated tokens of a whole buffer, with the line of each;
// '#' starts a comment up to the end of the line when `comments` is set.
class Tokenizer {
public:
    Tokenizer(std::string_view text, int firstLine, bool comments)
        : p_(text.data()), end_(text.data() + text.size()), line_(firstLine), comments_(comments) {}
    // The next token, or an empty view at the end of the text.
    std::string_view next();
    // Whether another token follows on the line of the last token.
    bool moreOnLine();
    // Skips the rest of the line of the last token.
    void skipLine();
    int line() const { return tokenLine_; } // line of the last token returned
    int currentLine() const { return line_; }

private:
    void skipBlanks(bool crossLines);
    const char* p_;
    const char* end_;
    int line_;
    int tokenLine_ = 0;
    bool comments_;
};

} // namespace contour::meshio
