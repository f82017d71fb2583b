#pragma once
// Ring re-triangulation: a patch of faces re-triangulated through the mesh's
// own edits, as Bénard 2014 §6.3 (h) deletes a vertex (Fig. 16e right: flips
// of the edges around a vertex cut off the ears of the target triangulation
// until the vertex has valence 3, then its three faces merge). Used by the
// vertex removal and the patch search of the optimization phase (§6.4
// extensions).
//
// Why planned: ConsistentMesh::flipEdge refuses a flip whose new edge
// already exists (or whose faces are missing); a refusal half-way through a
// sequence would leave the mesh half-edited. The whole sequence is first run
// on a copy of the patch's connectivity, with the same conditions the mesh
// checks (and the same face slots and face orders, so that applying it
// gives exactly the mesh the plan predicted); only a sequence that succeeds
// and ends in the target triangulation is applied.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <map>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace contour::consistent {

class RingRetriangulation {
public:
    // The edits may only touch `patch` (mesh face slots) and the faces they
    // create.
    RingRetriangulation(const ConsistentMesh& m, const std::vector<Index>& patch);

    // ConsistentMesh::splitFace of face slot f: the new vertex gets the index
    // m.vertexCount(); false when f is not a patch face.
    std::optional<Index> splitFace(Index f);
    // ConsistentMesh::flipEdge, with its conditions; false (nothing changed)
    // also when a face of the edge is outside the patch.
    bool flipEdge(Index a, Index b);
    // The conditions of ConsistentMesh::removeValence3Vertex (recorded; the
    // merge is the last edit a plan may hold).
    bool removeValence3Vertex(Index v);

    // The faces around v, in the order the mesh will keep them.
    const std::vector<Index>& vertexFaces(Index v);
    const Triangle& face(Index f) const { return faces_.at(f); }

    // v is joined to every corner of `ring` (counter-clockwise) and `faces`
    // is the target triangulation of the polygon (with or without v's own
    // faces). Flips each edge v-w whose corner w, not in `fan`, is the tip
    // of an ear prev-w-next of `faces`, until v keeps only the `fan`
    // corners (at least three). False when no ear is left or a flip is
    // refused.
    bool cutEars(Index v, std::vector<Index> ring, std::vector<Triangle> faces,
                 const std::vector<Index>& fan);

    // The patch's faces now, with the slots they will have.
    std::vector<Triangle> patchFaces() const;
    // The triangles `target` (any rotation) are exactly the patch's faces.
    bool endsIn(const std::vector<Triangle>& target) const;

    // The planned edits on the mesh (which must be the one planned on,
    // unchanged since); `split` is the record of the new vertex when the
    // plan splits a face. Throws std::logic_error if the mesh refuses an
    // edit the plan accepted (a bug, never valid input).
    void apply(ConsistentMesh& m, const MeshVertex* split, int phase) const;

private:
    struct Edit {
        enum Kind { Split, Flip, Merge } kind;
        Index a, b;
    };
    const ConsistentMesh& m_;
    std::vector<Edit> edits_;
    std::map<Index, Triangle> faces_; // patch slots and new slots
    std::unordered_map<Index, std::vector<Index>> vertexFaces_;
    Index nextFace_, nextVertex_;
    bool merged_ = false;

    Index faceOfHalfedge(Index a, Index b) const;
    bool local(Index f) const { return faces_.count(f) != 0; }
    void detach(Index f);
    void attach(Index f);
};

// Directed edges (a, b) chained into one closed cycle a -> b -> ...,
// starting at the first edge's tail; empty when they do not form a single
// simple cycle of at least three corners (a patch that is not a disc, a
// vertex on the boundary).
std::vector<Index> simpleCycle(const std::vector<std::pair<Index, Index>>& edges);

// The outline of a set of mesh faces, counter-clockwise: its boundary
// half-edges (those whose opposite face is not in the set, in the order of
// the faces and their corners) chained by simpleCycle(); empty when the
// faces do not form a disc.
std::vector<Index> outline(const ConsistentMesh& m, const std::vector<Index>& faces);

} // namespace contour::consistent
