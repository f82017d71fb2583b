// Object File Format: an optional "OFF" keyword (also the COFF, NOFF, CNOFF
// and ST variants, whose extra per-vertex values are skipped), a counts line
// "vertices faces [edges]", one vertex per line, then one face per line as
// "n i1 ... in [colour]". '#' starts a comment. Indices count from 0.
#include "mesh/MeshError.h"
#include "mesh/io/MeshFileSupport.h"
#include "mesh/io/MeshReader.h"

#include <algorithm>
#include <limits>

namespace contour {

namespace {

using meshio::quoted;

constexpr std::int64_t kMaxCount = std::numeric_limits<Index>::max();

std::string lineLocation(int line) {
    return "line " + std::to_string(line);
}

std::string plural(std::int64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Lines with their comments removed; blank lines are skipped.
class OffLines {
public:
    explicit OffLines(std::string_view text) : lines_(text) {}
    bool next(std::string_view& line) {
        std::string_view raw;
        while (lines_.next(raw)) {
            const auto hash = raw.find('#');
            line = hash == std::string_view::npos ? raw : raw.substr(0, hash);
            std::string_view probe = line;
            if (!meshio::nextToken(probe).empty())
                return true;
        }
        return false;
    }
    int lineNumber() const { return lines_.lineNumber(); }

private:
    meshio::LineReader lines_;
};

// "OFF" with the optional ST, C and N prefixes, in that order.
bool isOffKeyword(std::string_view token) {
    if (token.starts_with("ST"))
        token.remove_prefix(2);
    if (token.starts_with("C"))
        token.remove_prefix(1);
    if (token.starts_with("N"))
        token.remove_prefix(1);
    return token == "OFF";
}

std::int64_t parseCount(const std::string& path, int line, std::string_view token, const char* what,
                        const char* whats) {
    std::int64_t value = 0;
    const auto parsed = meshio::parseInt64(token, value);
    if (parsed == meshio::IntParse::NotAnInteger)
        throw MeshError(path, lineLocation(line),
                        std::string("the ") + what + " count " + quoted(token) +
                            " in the header is not a whole number");
    if (parsed == meshio::IntParse::OutOfRange || value > kMaxCount)
        throw MeshError(path, lineLocation(line),
                        std::string("the header announces ") + std::string(token) + " " + whats +
                            ", more than the " + std::to_string(kMaxCount) + " supported");
    if (value < 0)
        throw MeshError(path, lineLocation(line),
                        std::string("the ") + what + " count " + std::string(token) +
                            " in the header is negative");
    return value;
}

} // namespace

PolygonMesh readOff(const std::string& path, MeshSourceMap* source) {
    const meshio::FileData file = meshio::readWholeFile(path);
    const std::string_view data = file.view();
    OffLines lines(data);
    std::string_view line;

    // Header: keyword (optional) and counts.
    if (!lines.next(line))
        throw MeshError(path, "", "the file is empty (an OFF file starts with \"OFF\")");
    std::string_view rest = line;
    std::string_view token = meshio::nextToken(rest);
    std::int64_t probe = 0;
    if (isOffKeyword(token)) {
        const std::string_view after = meshio::nextToken(rest);
        if (after == "BINARY")
            throw MeshError(path, lineLocation(lines.lineNumber()),
                            "binary OFF files are not supported (save it as ASCII OFF, OBJ or "
                            "PLY)");
        if (after.empty()) {
            if (!lines.next(line))
                throw MeshError(path, lineLocation(lines.lineNumber()),
                                "the file ends before the counts line \"vertices faces edges\"");
            rest = line;
        } else {
            rest = std::string_view(after.data(),
                                    static_cast<size_t>(line.data() + line.size() - after.data()));
        }
    } else if (token.ends_with("OFF")) {
        throw MeshError(path, lineLocation(lines.lineNumber()),
                        "the OFF variant " + quoted(token) +
                            " is not supported (expected OFF, COFF, NOFF or CNOFF)");
    } else if (meshio::parseInt64(token, probe) != meshio::IntParse::Ok) {
        throw MeshError(path, lineLocation(lines.lineNumber()),
                        "not an OFF file (it must start with \"OFF\", found " + quoted(token) +
                            ")");
    } else {
        rest = line; // the keyword is optional: this is the counts line
    }
    const int countsLine = lines.lineNumber();
    const std::string_view vertexToken = meshio::nextToken(rest);
    const std::string_view faceToken = meshio::nextToken(rest);
    if (faceToken.empty())
        throw MeshError(path, lineLocation(countsLine),
                        "the counts line must give the numbers of vertices and faces");
    const std::int64_t vertexCount =
        parseCount(path, countsLine, vertexToken, "vertex", "vertices");
    const std::int64_t faceCount = parseCount(path, countsLine, faceToken, "face", "faces");
    // The edge count, when present, is not used.

    PolygonMesh mesh;
    std::vector<int> vertexLines, faceLines;
    // Never trust a count for an allocation: a vertex takes at least 6 bytes.
    const auto plausible = [&](std::int64_t count) {
        return static_cast<size_t>(
            std::min<std::int64_t>(count, static_cast<std::int64_t>(data.size() / 6 + 1)));
    };
    mesh.positions.reserve(plausible(vertexCount));
    vertexLines.reserve(plausible(vertexCount));
    for (std::int64_t v = 0; v < vertexCount; ++v) {
        if (!lines.next(line))
            throw MeshError(path, lineLocation(lines.lineNumber()),
                            "the file ends after " + std::to_string(v) + " of the " +
                                plural(vertexCount, "vertex", "vertices") +
                                " that the header announces");
        rest = line;
        double xyz[3];
        for (int k = 0; k < 3; ++k) {
            token = meshio::nextToken(rest);
            if (token.empty())
                throw MeshError(path, lineLocation(lines.lineNumber()),
                                "vertex " + std::to_string(v) + " needs 3 coordinates, found " +
                                    std::to_string(k));
            if (!meshio::parseDouble(token, xyz[k]))
                throw MeshError(path, lineLocation(lines.lineNumber()),
                                "vertex coordinate " + quoted(token) + " is not a number");
        }
        // Colours, normals or texture coordinates may follow; they are skipped.
        mesh.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
        vertexLines.push_back(lines.lineNumber());
    }

    mesh.offsets.reserve(plausible(faceCount) + 1);
    faceLines.reserve(plausible(faceCount));
    std::vector<Index> corners;
    for (std::int64_t f = 0; f < faceCount; ++f) {
        if (!lines.next(line))
            throw MeshError(path, lineLocation(lines.lineNumber()),
                            "the file ends after " + std::to_string(f) + " of the " +
                                plural(faceCount, "face", "faces") + " that the header announces");
        const int lineNumber = lines.lineNumber();
        rest = line;
        token = meshio::nextToken(rest);
        std::int64_t n = 0;
        if (meshio::parseInt64(token, n) != meshio::IntParse::Ok || n < 0)
            throw MeshError(path, lineLocation(lineNumber),
                            "face " + std::to_string(f) +
                                " must start with its number of corners, "
                                "found " +
                                quoted(token));
        corners.clear();
        for (std::int64_t k = 0; k < n; ++k) {
            token = meshio::nextToken(rest);
            if (token.empty())
                throw MeshError(path, lineLocation(lineNumber),
                                "face " + std::to_string(f) + " announces " +
                                    plural(n, "corner", "corners") + " but lists only " +
                                    std::to_string(k));
            std::int64_t index = 0;
            const auto parsed = meshio::parseInt64(token, index);
            if (parsed == meshio::IntParse::NotAnInteger)
                throw MeshError(path, lineLocation(lineNumber),
                                "face index " + quoted(token) + " is not a whole number");
            if (parsed == meshio::IntParse::OutOfRange || index >= vertexCount)
                throw MeshError(path, lineLocation(lineNumber),
                                "face index " + std::string(token) +
                                    " is out of range (the file has " +
                                    std::to_string(vertexCount) + " vertices)");
            if (index < 0)
                throw MeshError(path, lineLocation(lineNumber),
                                "face index " + std::to_string(index) +
                                    " is negative (OFF vertex indices count from 0)");
            corners.push_back(static_cast<Index>(index));
        }
        // A face colour may follow; it is skipped.
        if (mesh.indices.size() + corners.size() > static_cast<size_t>(kMaxCount))
            throw MeshError(path, lineLocation(lineNumber),
                            "too many face corners (at most " + std::to_string(kMaxCount) +
                                " in all are supported)");
        mesh.addFace(corners);
        faceLines.push_back(lineNumber);
    }
    // Anything after the last face is ignored.
    if (source) {
        source->indexBase = 0;
        source->vertexLine = std::move(vertexLines);
        source->faceLine = std::move(faceLines);
    }
    return mesh;
}

} // namespace contour
