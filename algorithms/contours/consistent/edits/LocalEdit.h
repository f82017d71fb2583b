#pragma once
// A local edit of the optimization phase (Bénard 2014 §6.4),
// evaluated before the mesh changes: the faces the edit would leave (a
// flip's two faces, a split's four, a moved vertex's star) and the vertices
// it would move or create. The §6.4 moves are accepted only when they
// reduce the inconsistent faces there, create no fold (parameter space and
// 3D), keep every VBO defined and create no degenerate CC edge; ties go to
// the larger minimum Bank-Smith quality.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/VertexBasedOrientation.h"

#include <utility>
#include <vector>

namespace contour::consistent {

struct LocalScore {
    int inconsistent = 0;    // faces that are not contour-consistent (Definition 2)
    double minQuality = 0.0; // smallest Bank-Smith quality among the faces
};
// a is strictly better than b: fewer inconsistent faces, then a larger
// minimum quality.
bool betterScore(const LocalScore& a, const LocalScore& b);

class LocalEdit {
public:
    explicit LocalEdit(const ConsistentMesh& m) : m_(m) {}

    void clear();
    void addFace(const Triangle& t) { faces_.push_back(t); }
    // Current faces of the mesh, by index (the "before" state, or the star
    // of a vertex that moves).
    void addFaces(const std::vector<Index>& meshFaces);
    // Existing vertex v would take record x (replaces an earlier move of v).
    void moveVertex(Index v, const MeshVertex& x);
    // A vertex the edit creates; its index is past the mesh's vertices.
    Index addVertex(const MeshVertex& x);

    const MeshVertex& vertex(Index v) const;
    const std::vector<Triangle>& faces() const { return faces_; }

    Vbo vbo(const Triangle& t) const;
    bool consistent(const Triangle& t) const;
    LocalScore score() const;
    int inconsistent() const;
    double minQuality() const;
    // A face whose normal points against (or is orthogonal to) the limit
    // normal n(u) of one of its corners, or is degenerate: turned over in 3D.
    bool turnedOver(const Triangle& t) const;
    int turnedOver() const;
    // Every face has a defined VBO (hence no FB edge and no CCC face, notes
    // §6.1 item 3) and none of their CC edges is degenerate (Definition 3,
    // the face across a CC edge taken from the edit or else from the mesh).
    bool labelsValid() const;
    // Every face is counter-clockwise in every common chart (appendix B, no
    // parameter-space fold, docs/dev/invariants.md item 1).
    bool parameterValid() const;
    // Appendix C for vertex v of the edit, judged on the edit's faces around
    // v (what shiftable() of Shiftability.h judges on the mesh, for an edit
    // that also changes v's one-ring): v is not C, rule 2 (no CCC; with
    // labelsValid), rule 3 (at most two zero crossings on the one-ring's
    // outer boundary), rules 1 and 4 (every neighbour interpolable, no
    // fold; with parameterValid).
    bool shiftable(Index v) const;

private:
    const ConsistentMesh& m_;
    std::vector<Triangle> faces_;
    std::vector<std::pair<Index, MeshVertex>> moved_;
    std::vector<MeshVertex> added_;
};

// Faces of the mesh that are not contour-consistent (Definition 2), in
// index order.
std::vector<Index> inconsistentFaces(const ConsistentMesh& m);
// The vertices of those faces, each once, in index order.
std::vector<Index> verticesOf(const ConsistentMesh& m, const std::vector<Index>& faces);

// A cusp keeps the valence 4 of Fig. 18d until radial edges are added
// around it (contourInsertionChecks in phases/PhaseChecks.h): a §6.4 move
// may not change its valence before; with `cuspEdits` off
// (optimization-cusp-edits), any cusp keeps its valence. False for
// kInvalidIndex.
bool lockedCusp(const ConsistentMesh& m, Index w, bool cuspEdits);

} // namespace contour::consistent
