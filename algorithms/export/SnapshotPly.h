#pragma once
// The PLY properties of a snapshot's working mesh, for writePly()
// (MeshWriter.h): its per-vertex and per-face fields (Snapshot::fields), int
// fields as int properties and double fields as double properties, each
// under the field's name, so any method's labels (facing, vbo, label, cusp,
// g, ...) travel with the mesh and read back with readMesh(path, &labels).
// Vector (Vec3) and edge fields have no PLY property of their own and are
// left out, as is a field whose size does not match the mesh or whose name
// is not a valid property name: `skipped` says which and why.
#include "mesh/io/PlyLabels.h"
#include "pipeline/Snapshot.h"

#include <string>
#include <vector>

namespace contour {

struct SnapshotPlyLabels {
    PlyLabels labels;
    std::vector<std::string> skipped; // "name: reason"
};

// Throws std::invalid_argument when the snapshot has no mesh.
SnapshotPlyLabels snapshotPlyLabels(const Snapshot& snapshot);

} // namespace contour
