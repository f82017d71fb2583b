#pragma once
// Reading OBJ, OFF and PLY (ASCII and binary little/big endian) into a
// validated PolygonMesh. Every failure throws MeshError (see MeshError.h).
#include "mesh/PolygonMesh.h"

#include <string>

namespace contour {

// Reads by extension (.obj, .off, .ply; case-insensitive), then validates
// with validatePolygonMesh(). Throws MeshError.
PolygonMesh readMesh(const std::string& path);

// Format-specific readers; they parse but do not validate topology.
PolygonMesh readObj(const std::string& path);
PolygonMesh readOff(const std::string& path);
PolygonMesh readPly(const std::string& path);

} // namespace contour
