#pragma once
// Reading OBJ, OFF and PLY (ASCII and binary little/big endian) into a
// validated PolygonMesh. Every failure throws MeshError (see MeshError.h).
#include "mesh/MeshValidation.h"
#include "mesh/io/PlyLabels.h"
#include "mesh/PolygonMesh.h"

#include <string>

namespace contour {

// Reads by extension (.obj, .off, .ply; case-insensitive), then validates
// with validatePolygonMesh(). Throws MeshError.
PolygonMesh readMesh(const std::string& path);
// The same, also returning the extra PLY vertex and face properties (labels
// stays empty for OBJ and OFF).
PolygonMesh readMesh(const std::string& path, PlyLabels* labels);

// Format-specific readers; they parse but do not validate topology. They do
// reject syntax errors, out-of-range and negative vertex indices, and files
// that end early. When `source` is given it receives where each element came
// from, for validatePolygonMesh() to point into the file.
PolygonMesh readObj(const std::string& path, MeshSourceMap* source = nullptr);
PolygonMesh readOff(const std::string& path, MeshSourceMap* source = nullptr);
PolygonMesh readPly(const std::string& path, MeshSourceMap* source = nullptr);
// Also reads every other scalar property of the vertex and face elements into
// `labels`: integer-typed ones as labels, float-typed ones as scalars (the
// inverse of writePly()). List properties other than the face's vertex list
// and elements other than vertex and face are skipped.
PolygonMesh readPly(const std::string& path, PlyLabels* labels, MeshSourceMap* source = nullptr);

} // namespace contour
