// Stanford PLY, ASCII and binary (little and big endian). The vertex element
// needs scalar x, y, z properties of any type; the face element needs a list
// property "vertex_indices" (or "vertex_index") of any count and index type.
// Other properties, lists and elements are skipped, or for vertex and face
// scalars read into PlyLabels when asked. Indices count from 0.
#include "mesh/MeshError.h"
#include "mesh/io/MeshFileSupport.h"
#include "mesh/io/MeshReader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace contour {

namespace {

using meshio::quoted;

constexpr std::int64_t kMaxCount = std::numeric_limits<Index>::max();

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

std::optional<PlyType> typeFromName(std::string_view name) {
    if (name == "char" || name == "int8")
        return PlyType::Int8;
    if (name == "uchar" || name == "uint8")
        return PlyType::UInt8;
    if (name == "short" || name == "int16")
        return PlyType::Int16;
    if (name == "ushort" || name == "uint16")
        return PlyType::UInt16;
    if (name == "int" || name == "int32")
        return PlyType::Int32;
    if (name == "uint" || name == "uint32")
        return PlyType::UInt32;
    if (name == "float" || name == "float32")
        return PlyType::Float32;
    if (name == "double" || name == "float64")
        return PlyType::Float64;
    return std::nullopt;
}

std::size_t sizeOf(PlyType type) {
    switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
        return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
        return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
        return 4;
    case PlyType::Float64:
        return 8;
    }
    return 1;
}

bool isIntegerType(PlyType type) {
    return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32; // of the items, for a list
    bool isList = false;
    PlyType countType = PlyType::UInt8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    int line = 0;

    bool fixedSize() const {
        return std::none_of(properties.begin(), properties.end(),
                            [](const PlyProperty& p) { return p.isList; });
    }
    std::size_t rowSize() const { // of a fixed-size row
        std::size_t size = 0;
        for (const PlyProperty& p : properties)
            size += sizeOf(p.type);
        return size;
    }
    // Fewest bytes a binary row can take.
    std::size_t minRowSize() const {
        std::size_t size = 0;
        for (const PlyProperty& p : properties)
            size += p.isList ? sizeOf(p.countType) : sizeOf(p.type);
        return size;
    }
};

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t dataStart = 0; // byte offset of the first element row
    int lastLine = 0;          // of end_header
};

std::string lineLocation(int line) {
    return "line " + std::to_string(line);
}

std::string plural(std::uint64_t n, const std::string& element) {
    if (element == "vertex")
        return std::to_string(n) + (n == 1 ? " vertex" : " vertices");
    if (element == "face")
        return std::to_string(n) + (n == 1 ? " face" : " faces");
    return std::to_string(n) + " \"" + element + "\" element" + (n == 1 ? "" : "s");
}

PlyHeader parseHeader(const std::string& path, std::string_view data) {
    meshio::LineReader lines(data);
    std::string_view line;
    if (!lines.next(line) || line.substr(0, line.find_last_not_of(" \t") + 1) != "ply")
        throw MeshError(path, data.empty() ? "" : "line 1",
                        data.empty() ? "the file is empty (a PLY file starts with \"ply\")"
                                     : "not a PLY file (it must start with a line \"ply\")");
    PlyHeader header;
    bool haveFormat = false;
    while (true) {
        if (!lines.next(line))
            throw MeshError(path, lineLocation(lines.lineNumber()),
                            "the file ends inside the header (no \"end_header\" line)");
        const int lineNumber = lines.lineNumber();
        auto fail = [&](const std::string& problem) {
            throw MeshError(path, lineLocation(lineNumber), problem);
        };
        std::string_view rest = line;
        const std::string_view keyword = meshio::nextToken(rest);
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info")
            continue;
        if (keyword == "end_header") {
            header.dataStart = static_cast<std::size_t>(lines.position() - data.data());
            header.lastLine = lineNumber;
            break;
        }
        if (keyword == "format") {
            const std::string_view name = meshio::nextToken(rest);
            if (name == "ascii")
                header.format = PlyFormat::Ascii;
            else if (name == "binary_little_endian")
                header.format = PlyFormat::BinaryLittleEndian;
            else if (name == "binary_big_endian")
                header.format = PlyFormat::BinaryBigEndian;
            else
                fail("unknown PLY format " + quoted(name) +
                     " (expected ascii, binary_little_endian or binary_big_endian)");
            haveFormat = true;
        } else if (keyword == "element") {
            const std::string_view name = meshio::nextToken(rest);
            const std::string_view countToken = meshio::nextToken(rest);
            if (name.empty() || countToken.empty())
                fail("an element line must be \"element <name> <count>\"");
            std::int64_t count = 0;
            const auto parsed = meshio::parseInt64(countToken, count);
            if (parsed == meshio::IntParse::NotAnInteger)
                fail("the count " + quoted(countToken) + " of element " + quoted(name) +
                     " is not a whole number");
            if (parsed == meshio::IntParse::OutOfRange)
                fail("the count " + std::string(countToken) + " of element " + quoted(name) +
                     " is too large");
            if (count < 0)
                fail("the count " + std::string(countToken) + " of element " + quoted(name) +
                     " is negative");
            for (const PlyElement& e : header.elements)
                if (e.name == name)
                    fail("element " + quoted(name) + " is declared twice");
            if ((name == "vertex" || name == "face") && count > kMaxCount)
                fail("the header announces " +
                     plural(static_cast<std::uint64_t>(count), std::string(name)) +
                     ", more than the " + std::to_string(kMaxCount) + " supported");
            header.elements.push_back(
                {std::string(name), static_cast<std::uint64_t>(count), {}, lineNumber});
        } else if (keyword == "property") {
            if (header.elements.empty())
                fail("a property line comes before any element line");
            PlyProperty property;
            std::string_view typeName = meshio::nextToken(rest);
            if (typeName == "list") {
                property.isList = true;
                const std::string_view countName = meshio::nextToken(rest);
                const auto countType = typeFromName(countName);
                if (!countType)
                    fail("unknown list count type " + quoted(countName));
                if (!isIntegerType(*countType))
                    fail("the list count type " + quoted(countName) + " is not an integer type");
                property.countType = *countType;
                typeName = meshio::nextToken(rest);
            }
            const auto type = typeFromName(typeName);
            if (!type)
                fail("unknown property type " + quoted(typeName) +
                     " (expected char, uchar, short, ushort, int, uint, float or double)");
            property.type = *type;
            const std::string_view name = meshio::nextToken(rest);
            if (name.empty())
                fail("the property has no name");
            PlyElement& element = header.elements.back();
            for (const PlyProperty& p : element.properties)
                if (p.name == name)
                    fail("property " + quoted(name) + " of element " + quoted(element.name) +
                         " is declared twice");
            property.name = std::string(name);
            element.properties.push_back(std::move(property));
        } else if (keyword == "ply") {
            fail("a second \"ply\" line inside the header");
        } else {
            fail("unknown header line " + quoted(keyword) +
                 " (expected format, element, property, comment or end_header)");
        }
    }
    if (!haveFormat)
        throw MeshError(path, lineLocation(header.lastLine), "the header has no \"format\" line");
    return header;
}

// Reads the values of rows, in ASCII or binary; errors name the row.
class RowReader {
public:
    RowReader(const std::string& path, std::string_view data, const PlyHeader& header)
        : path_(path), format_(header.format),
          tokens_(data.substr(header.dataStart), header.lastLine + 1, false),
          p_(reinterpret_cast<const unsigned char*>(data.data()) + header.dataStart),
          end_(reinterpret_cast<const unsigned char*>(data.data()) + data.size()) {
        swap_ = (format_ == PlyFormat::BinaryLittleEndian) !=
                (std::endian::native == std::endian::little);
    }

    void beginRow(const PlyElement& element, std::uint64_t row) {
        element_ = &element;
        row_ = row;
    }
    std::size_t remainingBytes() const { return static_cast<std::size_t>(end_ - p_); }
    bool binary() const { return format_ != PlyFormat::Ascii; }
    void skipBytes(std::size_t n) { p_ += n; }

    double read(PlyType type, const std::string& property) {
        if (format_ == PlyFormat::Ascii)
            return readAscii(type, property);
        const std::size_t size = sizeOf(type);
        if (remainingBytes() < size)
            ranOut();
        unsigned char b[8];
        std::memcpy(b, p_, size);
        p_ += size;
        if (swap_)
            std::reverse(b, b + size);
        switch (type) {
        case PlyType::Int8:
            return load<std::int8_t>(b);
        case PlyType::UInt8:
            return load<std::uint8_t>(b);
        case PlyType::Int16:
            return load<std::int16_t>(b);
        case PlyType::UInt16:
            return load<std::uint16_t>(b);
        case PlyType::Int32:
            return load<std::int32_t>(b);
        case PlyType::UInt32:
            return load<std::uint32_t>(b);
        case PlyType::Float32:
            return load<float>(b);
        case PlyType::Float64:
            return load<double>(b);
        }
        return 0.0;
    }

    // A list count or an index: a whole number (of any type).
    std::int64_t readWhole(PlyType type, const std::string& property, const char* what) {
        const double value = read(type, property);
        if (!(std::abs(value) < 9.0e15) || value != std::floor(value)) {
            std::string text;
            meshio::appendDouble(text, value);
            fail(std::string(what) + " " + text + " is not a whole number");
        }
        return static_cast<std::int64_t>(value);
    }

    void skipList(const PlyProperty& property) {
        const std::int64_t n = readWhole(property.countType, property.name, "the list length");
        if (n < 0)
            fail("list " + quoted(property.name) + " has a negative length " + std::to_string(n));
        if (binary()) {
            const std::size_t size = sizeOf(property.type);
            if (static_cast<std::uint64_t>(n) > remainingBytes() / size)
                ranOut();
            p_ += static_cast<std::size_t>(n) * size;
        } else {
            for (std::int64_t i = 0; i < n; ++i)
                read(property.type, property.name);
        }
    }

    [[noreturn]] void fail(const std::string& problem) const {
        throw MeshError(path_, location(), problem);
    }
    [[noreturn]] void ranOut() const {
        fail(std::string("the file ends in the middle of this ") +
             (element_->name == "vertex" || element_->name == "face" ? element_->name : "element") +
             (binary() ? " (binary data ran out" : " (values ran out") + "; the header announces " +
             plural(element_->count, element_->name) + ")");
    }
    std::string location() const {
        std::string where = element_->name + " " + std::to_string(row_);
        if (!binary())
            return "line " + std::to_string(tokens_.line()) + " (" + where + ")";
        return where;
    }
    int line() const { return binary() ? 0 : tokens_.line(); }

private:
    template <class T> static double load(const unsigned char* bytes) {
        T value;
        std::memcpy(&value, bytes, sizeof value);
        return static_cast<double>(value);
    }

    double readAscii(PlyType type, const std::string& property) {
        const std::string_view token = tokens_.next();
        if (token.empty())
            ranOut();
        double value = 0.0;
        if (isIntegerType(type)) {
            std::int64_t whole = 0;
            if (meshio::parseInt64(token, whole) == meshio::IntParse::Ok)
                return static_cast<double>(whole);
        }
        if (!meshio::parseDouble(token, value))
            fail("the value " + quoted(token) + " of property " + quoted(property) +
                 " is not a number");
        return value;
    }

    const std::string& path_;
    PlyFormat format_;
    meshio::Tokenizer tokens_;
    const unsigned char* p_;
    const unsigned char* end_;
    bool swap_ = false;
    const PlyElement* element_ = nullptr;
    std::uint64_t row_ = 0;
};

const PlyElement* findElement(const PlyHeader& header, const char* name) {
    for (const PlyElement& e : header.elements)
        if (e.name == name)
            return &e;
    return nullptr;
}

PolygonMesh readPlyImpl(const std::string& path, PlyLabels* labels, MeshSourceMap* source) {
    const meshio::FileData file = meshio::readWholeFile(path);
    const std::string_view data = file.view();
    const PlyHeader header = parseHeader(path, data);
    if (labels)
        *labels = PlyLabels{};

    // What the vertex and face elements must hold.
    const PlyElement* vertexElement = findElement(header, "vertex");
    if (!vertexElement)
        throw MeshError(path, lineLocation(header.lastLine),
                        "the header declares no \"vertex\" element");
    int coordinate[3] = {-1, -1, -1}; // property index of x, y, z
    for (size_t i = 0; i < vertexElement->properties.size(); ++i) {
        const PlyProperty& p = vertexElement->properties[i];
        const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
        if (axis < 0)
            continue;
        if (p.isList)
            throw MeshError(path, lineLocation(vertexElement->line),
                            "vertex property " + p.name + " is a list, not a number");
        coordinate[axis] = static_cast<int>(i);
    }
    for (int axis = 0; axis < 3; ++axis)
        if (coordinate[axis] < 0)
            throw MeshError(path, lineLocation(vertexElement->line),
                            std::string("the vertex element has no \"") + "xyz"[axis] +
                                "\" property");
    const PlyElement* faceElement = findElement(header, "face");
    int indexList = -1;
    if (faceElement) {
        for (size_t i = 0; i < faceElement->properties.size() && indexList < 0; ++i) {
            const PlyProperty& p = faceElement->properties[i];
            if (p.isList && (p.name == "vertex_indices" || p.name == "vertex_index"))
                indexList = static_cast<int>(i);
        }
        if (indexList < 0)
            throw MeshError(path, lineLocation(faceElement->line),
                            "the face element has no \"vertex_indices\" list property");
    }

    const auto vertexCount = static_cast<std::int64_t>(vertexElement->count);
    PolygonMesh mesh;
    std::vector<int> vertexLines, faceLines;
    RowReader reader(path, data, header);
    for (const PlyElement& element : header.elements) {
        if (element.properties.empty() || element.count == 0)
            continue; // rows without properties take no room
        const bool isVertex = &element == vertexElement;
        const bool isFace = &element == faceElement;
        // Never allocate by a count alone: a row takes at least minRowSize
        // bytes (binary) or one byte per value (ASCII).
        const std::size_t rowBytes =
            reader.binary() ? element.minRowSize() : 2 * element.properties.size();
        const auto plausibleRows = static_cast<std::size_t>(std::min<std::uint64_t>(
            element.count, reader.remainingBytes() / std::max<std::size_t>(rowBytes, 1) + 1));
        if (reader.binary() && element.fixedSize() && !isVertex && !isFace) {
            // Skip in one step; name the row where the data runs out.
            const std::size_t size = element.rowSize();
            const std::uint64_t available = reader.remainingBytes() / size;
            if (available < element.count) {
                reader.beginRow(element, available);
                reader.ranOut();
            }
            reader.skipBytes(static_cast<std::size_t>(element.count) * size);
            continue;
        }

        // Where each property goes: a coordinate, the index list, a label or nowhere.
        std::vector<std::vector<int>*> labelTarget(element.properties.size(), nullptr);
        std::vector<std::vector<double>*> scalarTarget(element.properties.size(), nullptr);
        if (labels && (isVertex || isFace)) {
            for (size_t i = 0; i < element.properties.size(); ++i) {
                const PlyProperty& p = element.properties[i];
                if (p.isList || (isVertex && (static_cast<int>(i) == coordinate[0] ||
                                              static_cast<int>(i) == coordinate[1] ||
                                              static_cast<int>(i) == coordinate[2])))
                    continue;
                if (isIntegerType(p.type)) {
                    auto& target =
                        isVertex ? labels->vertexLabels[p.name] : labels->faceLabels[p.name];
                    target.reserve(plausibleRows);
                    labelTarget[i] = &target;
                } else {
                    auto& target =
                        isVertex ? labels->vertexScalars[p.name] : labels->faceScalars[p.name];
                    target.reserve(plausibleRows);
                    scalarTarget[i] = &target;
                }
            }
        }
        if (isVertex) {
            mesh.positions.reserve(plausibleRows);
            if (!reader.binary())
                vertexLines.reserve(plausibleRows);
        }
        if (isFace) {
            mesh.offsets.reserve(plausibleRows + 1);
            mesh.indices.reserve(3 * plausibleRows);
            if (!reader.binary())
                faceLines.reserve(plausibleRows);
        }

        std::vector<Index> corners;
        for (std::uint64_t row = 0; row < element.count; ++row) {
            reader.beginRow(element, row);
            Vec3 position = Vec3::Zero();
            int line = 0;
            for (size_t i = 0; i < element.properties.size(); ++i) {
                const PlyProperty& p = element.properties[i];
                if (isFace && static_cast<int>(i) == indexList) {
                    const std::int64_t n =
                        reader.readWhole(p.countType, p.name, "the corner count");
                    line = reader.line();
                    if (n < 0)
                        reader.fail("the face has a negative corner count " + std::to_string(n));
                    if (reader.binary() &&
                        static_cast<std::uint64_t>(n) > reader.remainingBytes() / sizeOf(p.type))
                        reader.ranOut();
                    if (mesh.indices.size() + static_cast<std::uint64_t>(n) >
                        static_cast<std::uint64_t>(kMaxCount))
                        reader.fail("too many face corners (at most " + std::to_string(kMaxCount) +
                                    " in all are supported)");
                    corners.clear();
                    for (std::int64_t k = 0; k < n; ++k) {
                        const std::int64_t index = reader.readWhole(p.type, p.name, "face index");
                        if (index < 0)
                            reader.fail("face index " + std::to_string(index) +
                                        " is negative (PLY vertex indices count from 0)");
                        if (index >= vertexCount)
                            reader.fail("face index " + std::to_string(index) +
                                        " is out of range (the file has " +
                                        std::to_string(vertexCount) + " vertices)");
                        corners.push_back(static_cast<Index>(index));
                    }
                } else if (p.isList) {
                    reader.skipList(p);
                } else {
                    const double value = reader.read(p.type, p.name);
                    if (isVertex) {
                        for (int axis = 0; axis < 3; ++axis)
                            if (static_cast<int>(i) == coordinate[axis]) {
                                position[axis] = value;
                                line = reader.line();
                            }
                    }
                    if (labelTarget[i])
                        labelTarget[i]->push_back(
                            static_cast<int>(static_cast<std::int64_t>(value)));
                    else if (scalarTarget[i])
                        scalarTarget[i]->push_back(value);
                }
            }
            if (isVertex) {
                mesh.positions.push_back(position);
                if (!reader.binary())
                    vertexLines.push_back(line);
            } else if (isFace) {
                mesh.addFace(corners);
                if (!reader.binary())
                    faceLines.push_back(line);
            }
        }
    }
    // Anything after the last element is ignored.
    if (source) {
        source->indexBase = 0;
        source->vertexLine = std::move(vertexLines);
        source->faceLine = std::move(faceLines);
    }
    return mesh;
}

} // namespace

PolygonMesh readPly(const std::string& path, MeshSourceMap* source) {
    return readPlyImpl(path, nullptr, source);
}

PolygonMesh readPly(const std::string& path, PlyLabels* labels, MeshSourceMap* source) {
    return readPlyImpl(path, labels, source);
}

} // namespace contour
