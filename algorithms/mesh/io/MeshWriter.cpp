// OBJ and PLY writers. The whole file is built in memory, then written to
// path + ".tmp" and renamed (io/AtomicFile.h), so a failure leaves nothing
// half-written. Numbers are written in their shortest exact form, so a mesh
// reads back bit for bit.
#include "mesh/io/MeshWriter.h"

#include "core/AtomicFile.h"

#include "mesh/io/MeshFileSupport.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace contour {

namespace {

// A read-only view of either mesh type for the writers.
struct FaceSource {
    std::span<const Vec3> positions;
    Index faceCount = 0;
    std::span<const Index> (*face)(const void* mesh, Index f) = nullptr;
    const void* mesh = nullptr;
    std::span<const Index> operator()(Index f) const { return face(mesh, f); }
};

FaceSource facesOf(const PolygonMesh& mesh) {
    return {mesh.positions, mesh.faceCount(),
            [](const void* m, Index f) { return static_cast<const PolygonMesh*>(m)->face(f); },
            &mesh};
}

FaceSource facesOf(const TriangleMesh& mesh) {
    return {mesh.positions(), mesh.faceCount(),
            [](const void* m, Index f) {
                const Triangle& t = static_cast<const TriangleMesh*>(m)->triangle(f);
                return std::span<const Index>(t.data(), t.size());
            },
            &mesh};
}

void writeObjImpl(const FaceSource& mesh, const std::string& path) {
    std::string out = "# written by Contour Workbench\n";
    out.reserve(out.size() + 40 * mesh.positions.size() + 24 * static_cast<size_t>(mesh.faceCount));
    for (const Vec3& p : mesh.positions) {
        out += "v ";
        meshio::appendDouble(out, p.x());
        out += ' ';
        meshio::appendDouble(out, p.y());
        out += ' ';
        meshio::appendDouble(out, p.z());
        out += '\n';
    }
    for (Index f = 0; f < mesh.faceCount; ++f) {
        out += 'f';
        for (const Index v : mesh(f)) {
            out += ' ';
            meshio::appendInt(out, std::int64_t{v} + 1);
        }
        out += '\n';
    }
    writeFileAtomically(path, out);
}

template <class T> void appendBinary(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
        std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

void checkName(const std::string& path, const std::string& what, const std::string& name) {
    const bool bad =
        name.empty() || std::any_of(name.begin(), name.end(), [](char c) {
            return static_cast<unsigned char>(c) <= ' ' || static_cast<unsigned char>(c) >= 0x7f;
        });
    if (bad)
        throw std::runtime_error(path + ": cannot write the " + what + " " + meshio::quoted(name) +
                                 ": a PLY property name must be non-empty printable ASCII without "
                                 "spaces");
    if (name == "x" || name == "y" || name == "z" || name == "vertex_indices" ||
        name == "vertex_index")
        throw std::runtime_error(path + ": cannot write the " + what + " " + meshio::quoted(name) +
                                 ": the name is reserved for the geometry");
}

template <class Map>
void checkSizes(const std::string& path, const char* what, const Map& values, size_t expected,
                const char* elements) {
    for (const auto& [name, column] : values) {
        checkName(path, what, name);
        if (column.size() != expected)
            throw std::runtime_error(path + ": cannot write the " + what + " " +
                                     meshio::quoted(name) + ": it has " +
                                     std::to_string(column.size()) + " values but the mesh has " +
                                     std::to_string(expected) + " " + elements);
    }
}

void checkLabels(const std::string& path, const PlyLabels& labels, size_t vertices, size_t faces) {
    checkSizes(path, "vertex label", labels.vertexLabels, vertices, "vertices");
    checkSizes(path, "vertex scalar", labels.vertexScalars, vertices, "vertices");
    checkSizes(path, "face label", labels.faceLabels, faces, "faces");
    checkSizes(path, "face scalar", labels.faceScalars, faces, "faces");
    for (const auto& [name, column] : labels.vertexLabels)
        if (labels.vertexScalars.count(name))
            throw std::runtime_error(path + ": cannot write the vertex property " +
                                     meshio::quoted(name) + ": it is both a label and a scalar");
    for (const auto& [name, column] : labels.faceLabels)
        if (labels.faceScalars.count(name))
            throw std::runtime_error(path + ": cannot write the face property " +
                                     meshio::quoted(name) + ": it is both a label and a scalar");
}

void writePlyImpl(const FaceSource& mesh, const std::string& path, const PlyLabels& labels,
                  bool binary) {
    const size_t vertexCount = mesh.positions.size();
    const auto faceCount = static_cast<size_t>(mesh.faceCount);
    checkLabels(path, labels, vertexCount, faceCount);
    size_t maxCorners = 0;
    for (Index f = 0; f < mesh.faceCount; ++f)
        maxCorners = std::max(maxCorners, mesh(f).size());

    std::string out = "ply\nformat ";
    out += binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
    out += "comment written by Contour Workbench\n";
    out += "element vertex " + std::to_string(vertexCount) + "\n";
    out += "property double x\nproperty double y\nproperty double z\n";
    for (const auto& [name, column] : labels.vertexLabels)
        out += "property int " + name + "\n";
    for (const auto& [name, column] : labels.vertexScalars)
        out += "property double " + name + "\n";
    out += "element face " + std::to_string(faceCount) + "\n";
    out += maxCorners <= 255 ? "property list uchar int vertex_indices\n"
                             : "property list int int vertex_indices\n";
    for (const auto& [name, column] : labels.faceLabels)
        out += "property int " + name + "\n";
    for (const auto& [name, column] : labels.faceScalars)
        out += "property double " + name + "\n";
    out += "end_header\n";

    const size_t perVertex = labels.vertexLabels.size() + labels.vertexScalars.size();
    const size_t perFace = labels.faceLabels.size() + labels.faceScalars.size();
    out.reserve(out.size() + vertexCount * (binary ? 24 + 8 * perVertex : 60 + 12 * perVertex) +
                faceCount * (binary ? 13 + 8 * perFace : 24 + 12 * perFace));

    // Values of a row, in header order: labels, then scalars.
    auto writeExtras = [&](const auto& ints, const auto& reals, size_t row) {
        for (const auto& [name, column] : ints) {
            if (binary) {
                appendBinary<std::int32_t>(out, column[row]);
            } else {
                out += ' ';
                meshio::appendInt(out, column[row]);
            }
        }
        for (const auto& [name, column] : reals) {
            if (binary) {
                appendBinary<double>(out, column[row]);
            } else {
                out += ' ';
                meshio::appendDouble(out, column[row]);
            }
        }
    };
    for (size_t v = 0; v < vertexCount; ++v) {
        const Vec3& p = mesh.positions[v];
        if (binary) {
            appendBinary<double>(out, p.x());
            appendBinary<double>(out, p.y());
            appendBinary<double>(out, p.z());
        } else {
            meshio::appendDouble(out, p.x());
            out += ' ';
            meshio::appendDouble(out, p.y());
            out += ' ';
            meshio::appendDouble(out, p.z());
        }
        writeExtras(labels.vertexLabels, labels.vertexScalars, v);
        if (!binary)
            out += '\n';
    }
    for (size_t f = 0; f < faceCount; ++f) {
        const auto face = mesh(static_cast<Index>(f));
        if (binary) {
            if (maxCorners <= 255)
                appendBinary<std::uint8_t>(out, static_cast<std::uint8_t>(face.size()));
            else
                appendBinary<std::int32_t>(out, static_cast<std::int32_t>(face.size()));
            for (const Index v : face)
                appendBinary<std::int32_t>(out, v);
        } else {
            meshio::appendInt(out, static_cast<std::int64_t>(face.size()));
            for (const Index v : face) {
                out += ' ';
                meshio::appendInt(out, v);
            }
        }
        writeExtras(labels.faceLabels, labels.faceScalars, f);
        if (!binary)
            out += '\n';
    }
    writeFileAtomically(path, out);
}

} // namespace

void writeObj(const PolygonMesh& mesh, const std::string& path) {
    writeObjImpl(facesOf(mesh), path);
}

void writeObj(const TriangleMesh& mesh, const std::string& path) {
    writeObjImpl(facesOf(mesh), path);
}

void writePly(const PolygonMesh& mesh, const std::string& path, const PlyLabels& labels,
              bool binary) {
    writePlyImpl(facesOf(mesh), path, labels, binary);
}

void writePly(const TriangleMesh& mesh, const std::string& path, const PlyLabels& labels,
              bool binary) {
    writePlyImpl(facesOf(mesh), path, labels, binary);
}

} // namespace contour
