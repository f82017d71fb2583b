// contour-shapes: writes the procedural shapes (mesh/ProceduralShapes.h) as
// OBJ files, e.g. to regenerate samples/:
//   contour-shapes --out samples
#include "mesh/io/MeshWriter.h"
#include "mesh/ProceduralShapes.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// Resolutions used when --resolution is not given: a few thousand faces per
// shape, enough to resolve the bumps of the bumpy torus, small enough for the
// repository.
const std::map<std::string, int>& defaultResolutions() {
    static const std::map<std::string, int> resolutions = {
        {"sphere", 48},      {"ellipsoid", 48}, {"torus", 48},
        {"bumpy-torus", 64}, {"saddle", 32},    {"two-spheres", 48},
    };
    return resolutions;
}

// Accepts the file-name spelling too: "bumpy_torus" is "bumpy-torus".
std::string canonicalName(std::string name) {
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}

std::string fileName(std::string name) {
    std::replace(name.begin(), name.end(), '-', '_');
    return name + ".obj";
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Writes the procedural test shapes of Contour Workbench as OBJ files."};
    std::string out = "samples";
    std::vector<std::string> shapes;
    int resolution = 0;
    app.add_option("--out", out, "Output folder (created if missing)")->capture_default_str();
    std::string known, knownWithResolutions;
    for (const std::string& name : contour::proceduralShapeNames()) {
        known += (known.empty() ? "" : ", ") + name;
        knownWithResolutions += (knownWithResolutions.empty() ? "" : ", ") + name +
                                " (default resolution " +
                                std::to_string(defaultResolutions().at(name)) + ")";
    }
    app.add_option("--shape", shapes,
                   "Shape to write, repeatable; default all of: " + knownWithResolutions);
    app.add_option("--resolution", resolution,
                   "Segments around the main circle (sphere, torus) or along each side "
                   "(saddle); default per shape, see --shape")
        ->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);

    try {
        if (shapes.empty())
            shapes = contour::proceduralShapeNames();
        for (std::string& name : shapes) {
            const std::string requested = name;
            name = canonicalName(name);
            if (defaultResolutions().count(name) == 0)
                throw std::invalid_argument("unknown shape \"" + requested + "\" (known: " + known +
                                            ")");
        }
        std::filesystem::create_directories(out);
        for (const std::string& name : shapes) {
            const int n = resolution > 0 ? resolution : defaultResolutions().at(name);
            const contour::PolygonMesh mesh = contour::makeProceduralShape(name, n);
            // Checks the shape is a valid, consistently oriented manifold.
            const contour::TriangleMesh triangles = mesh.triangulate();
            const std::string path = (std::filesystem::path(out) / fileName(name)).string();
            contour::writeObj(mesh, path);
            std::printf("%s: %s, resolution %d, %d vertices, %d faces (%d triangles)\n",
                        path.c_str(), name.c_str(), n, mesh.vertexCount(), mesh.faceCount(),
                        triangles.faceCount());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "contour-shapes: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
