#pragma once
// Which way a mesh's faces turn. The contour methods take a face whose
// normal (counter-clockwise corners) points away from the eye as back-facing
// (Bénard 2014 §3, docs/dev/conventions.md), so a closed surface whose faces are all oriented
// inward has every contour read as hidden. A closed, consistently oriented component encloses a
// volume whose sign tells which way it is oriented (positive: outward); an open or inconsistently
// oriented component has no such volume, so its orientation cannot be decided and is left as it is.
//
// Components are edge-connected: two faces belong together when they share
// an edge. Precondition of every function: face indices in range (any mesh
// readMesh() returns; validation rejects inconsistent and non-manifold
// meshes, which the report still describes when built in code).
#include "mesh/PolygonMesh.h"

#include <string>
#include <vector>

namespace contour {

struct ComponentOrientation {
    Index faces = 0;     // how many faces it has
    Index firstFace = 0; // its lowest face index
    // No boundary edge: every edge has two faces (or more, see consistent).
    bool closed = false;
    // Every edge with two faces runs once in each direction, and no edge has
    // more than two.
    bool consistent = false;
    // The enclosed volume by the divergence theorem, positive for outward
    // faces; computed for closed, consistent components only (0 otherwise).
    double signedVolume = 0.0;
    // Its faces were reversed (orientOutward).
    bool flipped = false;

    // Closed and consistent: the volume's sign decides the orientation.
    bool decidable() const { return closed && consistent; }
    // Decidable with a negative volume (whether flipped since or not).
    bool inward() const { return decidable() && signedVolume < 0.0; }
    // "closed, outward (signed volume 4.19)", "open: its orientation cannot
    // be decided by volume", ...
    std::string describe() const;
};

struct OrientationReport {
    std::vector<ComponentOrientation> components; // ordered by first face
    std::vector<Index> faceComponent;             // the component of each face

    int decidableCount() const;
    int inwardCount() const;
    int flippedCount() const;
    int openCount() const;
    // Closed but inconsistently oriented or non-manifold.
    int inconsistentCount() const;
    // Something for the user to know: an inward component, or one whose
    // orientation cannot be decided.
    bool hasMessage() const;
};

OrientationReport orientationReport(const PolygonMesh& mesh);

// The mesh with the faces of every inward component reversed; everything
// else (vertex indices, face order, creases, corner sharpness) unchanged, so
// per-vertex and per-face data stay aligned. A face keeps its first corner
// and reverses the others (a b c d -> a d c b), so it triangulates into the
// same triangles. `report`, when given, receives orientationReport(mesh)
// with the reversed components marked flipped.
PolygonMesh orientOutward(const PolygonMesh& mesh, OrientationReport* report = nullptr);

// The mesh as the contour methods get it after loading: orientOutward(mesh),
// or with `keepFileOrientation` the mesh itself. `report` receives the
// report either way.
PolygonMesh orientForContours(const PolygonMesh& mesh, bool keepFileOrientation,
                              OrientationReport& report);

// One line for the user, "" when !report.hasMessage(). `keepSwitch` names
// the option that keeps the file's orientation ("--keep-orientation"), e.g.
// "1 of 1 closed components had inward normals (signed volume -0.31);
// flipped (--keep-orientation keeps them)", or when kept "... have inward
// normals (...); kept as in the file (--keep-orientation): their contours
// will read as hidden". Open and inconsistently oriented components follow
// ("1 open component left as in the file: its orientation cannot be decided
// by volume").
std::string orientationMessage(const OrientationReport& report, const std::string& keepSwitch);

} // namespace contour
