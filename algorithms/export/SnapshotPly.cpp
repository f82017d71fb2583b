#include "export/SnapshotPly.h"

#include <algorithm>
#include <stdexcept>

namespace contour {

namespace {

// The writer's rules for a property name (MeshWriter.cpp): printable ASCII
// without spaces, not one of the geometry's names.
bool validPropertyName(const std::string& name) {
    if (name.empty() || name == "x" || name == "y" || name == "z" || name == "vertex_indices" ||
        name == "vertex_index")
        return false;
    return std::none_of(name.begin(), name.end(), [](char c) {
        return static_cast<unsigned char>(c) <= ' ' || static_cast<unsigned char>(c) >= 0x7f;
    });
}

} // namespace

SnapshotPlyLabels snapshotPlyLabels(const Snapshot& snapshot) {
    if (!snapshot.mesh)
        throw std::invalid_argument("the snapshot after \"" + snapshot.phaseName +
                                    "\" has no mesh to write");
    const TriangleMesh& mesh = *snapshot.mesh;
    SnapshotPlyLabels out;
    for (const auto& [name, field] : snapshot.fields) {
        if (!field)
            continue;
        if (field->location == FieldLocation::Edge) {
            out.skipped.push_back(name + ": an edge field (PLY has no edge element here)");
            continue;
        }
        const bool atVertex = field->location == FieldLocation::Vertex;
        const size_t expected =
            static_cast<size_t>(atVertex ? mesh.vertexCount() : mesh.faceCount());
        if (field->vectors()) {
            out.skipped.push_back(name + ": a vector field");
            continue;
        }
        if (!validPropertyName(name)) {
            out.skipped.push_back(name + ": not a valid PLY property name");
            continue;
        }
        if (const std::vector<int>* labels = field->labels()) {
            if (labels->size() != expected) {
                out.skipped.push_back(name + ": " + std::to_string(labels->size()) +
                                      " values for " + std::to_string(expected) +
                                      (atVertex ? " vertices" : " faces"));
                continue;
            }
            (atVertex ? out.labels.vertexLabels : out.labels.faceLabels)[name] = *labels;
        } else if (const std::vector<double>* scalars = field->scalars()) {
            if (scalars->size() != expected) {
                out.skipped.push_back(name + ": " + std::to_string(scalars->size()) +
                                      " values for " + std::to_string(expected) +
                                      (atVertex ? " vertices" : " faces"));
                continue;
            }
            (atVertex ? out.labels.vertexScalars : out.labels.faceScalars)[name] = *scalars;
        }
    }
    return out;
}

} // namespace contour
