// readMesh(): picks the reader by extension, then validates.
#include "mesh/io/MeshReader.h"

#include "mesh/MeshError.h"
#include "mesh/io/MeshFileSupport.h"
#include "mesh/MeshValidation.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace contour {

PolygonMesh readMesh(const std::string& path) {
    return readMesh(path, nullptr);
}

PolygonMesh readMesh(const std::string& path, PlyLabels* labels) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    MeshSourceMap source;
    PolygonMesh mesh;
    if (labels)
        *labels = PlyLabels{};
    if (extension == ".obj")
        mesh = readObj(path, &source);
    else if (extension == ".off")
        mesh = readOff(path, &source);
    else if (extension == ".ply")
        mesh = readPly(path, labels, &source);
    else if (extension.empty())
        throw MeshError(path, "",
                        "unknown mesh format: the file name has no extension (expected .obj, "
                        ".off or .ply)");
    else
        throw MeshError(path, "",
                        "unknown mesh format " +
                            meshio::quoted(std::filesystem::path(path).extension().string()) +
                            " (expected .obj, .off or .ply)");
    validatePolygonMesh(mesh, path, source);
    return mesh;
}

} // namespace contour
