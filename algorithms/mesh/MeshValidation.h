#pragma once
// Rejects meshes that no contour method can work on: empty meshes, NaN/inf
// coordinates, out-of-range indices, degenerate faces (repeated corner or zero
// area, decided with exact predicates), non-manifold edges and vertices, and
// inconsistently oriented neighbours. Throws MeshError naming `file`, the
// element (e.g. "face 17", "vertex 3", "edge (4, 9)") and the problem.
//
// Vertices used by no face are allowed. Checks run in this order and the
// first failure is reported: empty mesh, coordinates, face sizes and indices,
// degenerate faces, non-manifold or inconsistently oriented edges,
// non-manifold vertices.
#include "mesh/PolygonMesh.h"

#include <string>
#include <vector>

namespace contour {

// Where the elements of a mesh came from, so that errors can point into the
// file. Readers of text formats fill the line numbers; binary readers leave
// them empty and errors then name elements by their 0-based position.
struct MeshSourceMap {
    // Vertex numbers in messages are printed as index + indexBase, so that
    // they match the file (OBJ counts vertices from 1, OFF and PLY from 0).
    int indexBase = 0;
    std::vector<int> vertexLine; // empty, or the line of each vertex
    std::vector<int> faceLine;   // empty, or the line of each face
};

void validatePolygonMesh(const PolygonMesh& mesh, const std::string& file);
void validatePolygonMesh(const PolygonMesh& mesh, const std::string& file,
                         const MeshSourceMap& source);

} // namespace contour
