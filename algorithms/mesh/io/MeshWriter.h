#pragma once
// OBJ and PLY writers. PLY can carry per-vertex and per-face integer labels
// and scalar fields (each becomes a PLY property with its name). Files are
// written to a temporary name and renamed, so a failure leaves nothing
// half-written; failures throw std::runtime_error naming the file.
#include "mesh/io/PlyLabels.h"
#include "mesh/PolygonMesh.h"

#include <string>

namespace contour {

void writeObj(const PolygonMesh& mesh, const std::string& path);
void writeObj(const TriangleMesh& mesh, const std::string& path);
void writePly(const PolygonMesh& mesh, const std::string& path, const PlyLabels& labels = {},
              bool binary = false);
void writePly(const TriangleMesh& mesh, const std::string& path, const PlyLabels& labels = {},
              bool binary = false);

} // namespace contour
