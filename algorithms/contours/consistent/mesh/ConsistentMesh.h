#pragma once
// The per-view, editable triangle mesh of Bénard, Hertzmann & Kass 2014 §6:
// its topology (vertices, faces, half-edges, edge tags), the local operators
// (§6: edge split, face split, flip, vertex shift, valence-3 removal) and
// provenance per face (the phase that created or last changed it). Each
// vertex is a MeshVertex (MeshVertex.h) computed by its VertexEvaluator;
// preimages are interpolated in the appendix-B charts of its DomainCharts.
// The mesh keeps what depends on its faces: the loops over every face
// (parameterOrientations(), centroidDomainFaces()) and their caches.
#include "camera/Camera.h"
#include "contours/consistent/mesh/DomainCharts.h"
#include "contours/consistent/mesh/HalfedgeMap.h"
#include "contours/consistent/mesh/MeshVertex.h"
#include "contours/consistent/mesh/VertexEvaluator.h"
#include "mesh/TriangleMesh.h"
#include "surface/SmoothSurface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace contour::consistent {

// Tags kept on an edge (an unordered vertex pair) between phases.
enum EdgeTag : int {
    kNoTag = 0,
    kCuspEdge = 1,   // an FB edge whose root of g is a cusp (§6.2 d): insert it last
    kRadialEdge = 2, // p-r with p a C vertex and r on p's radial plane (Definition 5)
};

// The triangle's corners rotated so that v comes first (same orientation).
inline Triangle rotatedTo(Triangle t, Index v) {
    while (t[0] != v)
        std::rotate(t.begin(), t.begin() + 1, t.end());
    return t;
}

class ConsistentMesh {
public:
    // chartTolerance: as in DomainCharts' constructor.
    ConsistentMesh(std::shared_ptr<const SmoothSurface> surface, const Camera& camera,
                   double chartTolerance);

    // The appendix-B charts the mesh interpolates its preimages in, and the
    // evaluation of its vertex records at this view's camera.
    const DomainCharts& charts() const { return charts_; }
    const VertexEvaluator& evaluator() const { return evaluator_; }

    const SmoothSurface& surface() const { return charts_.surface(); }
    const std::shared_ptr<const SmoothSurface>& surfacePtr() const { return charts_.surfacePtr(); }
    const Camera& camera() const { return evaluator_.camera(); }

    Index vertexCount() const { return static_cast<Index>(vertices_.size()); }
    Index faceCount() const { return static_cast<Index>(faces_.size()); }
    const MeshVertex& vertex(Index v) const { return vertices_[v]; }
    const std::vector<MeshVertex>& vertices() const { return vertices_; }
    const Triangle& face(Index f) const { return faces_[f]; }
    int facePhase(Index f) const { return facePhase_[f]; }
    const std::vector<Index>& vertexFaces(Index v) const { return vertexFaces_[v]; }

    // The evaluator's (VertexEvaluator.h).
    MeshVertex evaluate(const Preimage& p) const { return evaluator_.evaluate(p); }
    MeshVertex evaluated(const Preimage& p, const SurfacePoint& sp) const {
        return evaluator_.evaluated(p, sp);
    }
    MeshVertex evaluateWithoutCurvature(const Preimage& p) const {
        return evaluator_.evaluateWithoutCurvature(p);
    }

    // Building (initialization and reloading a snapshot).
    Index addVertex(const MeshVertex& v);
    Index addFace(const Triangle& t, int phase);
    void reserve(Index vertices, Index faces);
    // The whole mesh at once, for reloading a snapshot: the same mesh as
    // addVertex() for every vertex then addFace() for every face in order
    // (vertexFaces() in increasing face order). `halfedges`, when given, is
    // halfedges() of a mesh with exactly these faces (copied instead of
    // rebuilt). Replaces everything but the edge tags.
    void assign(std::vector<MeshVertex> vertices, std::vector<Triangle> faces,
                std::vector<int> facePhase, const HalfedgeMap* halfedges);
    // The same with the table shared, not copied: read in place, and copied
    // only when the mesh is first edited (a reloaded snapshot that is only
    // checked never copies it).
    void assignShared(std::vector<MeshVertex> vertices, std::vector<Triangle> faces,
                      std::vector<int> facePhase, std::shared_ptr<const HalfedgeMap> halfedges);
    const HalfedgeMap& halfedges() const { return halfedgeTable(); }
    // The half-edge table as a shared read-only object, without a copy: the
    // mesh goes on reading it, and copies it on its next edit (publish()
    // hands it to the next phase this way).
    std::shared_ptr<const HalfedgeMap> shareHalfedges();

    // The face holding the directed edge a -> b, or kInvalidIndex.
    Index faceOfHalfedge(Index a, Index b) const;
    // Every edge once, as (a, b) with a -> b a half-edge of some face (for an
    // interior edge the one with a < b).
    std::vector<std::array<Index, 2>> edges() const;

    // The charts' (DomainCharts.h): appendix-B interpolation of preimages.
    void setVertexRingCharts(bool on) { charts_.setVertexRingCharts(on); }
    std::optional<Preimage> interpolate(const Preimage& a, const Preimage& b, double t) const {
        return charts_.interpolate(a, b, t);
    }
    void interpolate(const Preimage& a, const Preimage& b, std::span<const double> t,
                     std::span<std::optional<Preimage>> out) const {
        charts_.interpolate(a, b, t, out);
    }
    using Segment = DomainCharts::Segment;
    Segment segment(const Preimage& a, const Preimage& b) const { return charts_.segment(a, b); }
    Segment segmentInChart(const Preimage& a, const Preimage& b, int chart) const {
        return charts_.segmentInChart(a, b, chart);
    }
    int interpolationCharts(const Preimage& a, const Preimage& b) const {
        return charts_.interpolationCharts(a, b);
    }
    // Per face, the domain face holding its centroid: u(1/3) from the
    // midpoint of corners 0-1 to corner 2 (interpolate() twice),
    // kInvalidIndex without a common chart. Every face at once.
    std::vector<Index> centroidDomainFaces() const;
    // The charts' (DomainCharts.h).
    std::vector<std::array<Vec2, 3>> chartCoordinates(const std::array<Preimage, 3>& p) const {
        return charts_.chartCoordinates(p);
    }
    bool withinEdgeCharts(const std::array<Preimage, 3>& p) const {
        return charts_.withinEdgeCharts(p);
    }
    std::optional<int> parameterOrientation(const std::array<Preimage, 3>& p) const {
        return charts_.parameterOrientation(p);
    }
    // The charts' parameterOrientation() of face f's corners.
    std::optional<int> parameterOrientation(Index f) const;
    // parameterOrientation(f) for every face, each vertex's preimages found
    // once (faster than face by face; same results).
    std::vector<std::optional<int>> parameterOrientations() const;

    // Edge split (§6, Fig. 16a and 16c): a vertex `v` (already evaluated) is
    // inserted on edge a-b, and both faces on it are split in two. Returns the
    // new vertex.
    Index splitEdge(Index a, Index b, MeshVertex v, int phase);
    // Face split 1 -> 3 (§6.3, Fig. 16d: radial edge insertion): a vertex
    // `v` (already evaluated) is inserted inside face f = a-b-c, which
    // becomes a-b-v (slot f), b-c-v and c-a-v. Returns the new vertex. Fold
    // checks are the caller's (FoldTest.h).
    Index splitFace(Index f, MeshVertex v, int phase);
    // Vertex shift (§6): new preimage, f and n recomputed; the faces around
    // it are marked as changed by `phase`.
    void shiftVertex(Index v, const Preimage& p, VertexLabel label, int phase);
    void setLabel(Index v, VertexLabel label) { vertices_[v].label = label; }
    // Replaces a vertex's whole record (trial moves that are undone, the
    // normal wiggle); the faces around it are marked as changed by `phase`
    // unless phase < 0 (an undo).
    void setVertex(Index v, const MeshVertex& x, int phase);

    // Edge flip (§6, Fig. 16e): faces a-b-c and b-a-d become a-d-c and
    // b-c-d, i.e. edge a-b is replaced by c-d. Returns false (and changes
    // nothing) for a boundary edge or when c-d already is an edge. Tags of
    // a-b are dropped. Fold checks are the caller's (wouldFold-style tests
    // differ per phase).
    bool flipEdge(Index a, Index b, int phase);
    // The vertices opposite edge a-b: {c, d} with a-b-c and b-a-d faces
    // (kInvalidIndex on a boundary side).
    std::array<Index, 2> oppositeVertices(Index a, Index b) const;
    // Vertex deletion (Fig. 16e right): a vertex of valence 3 (interior)
    // whose three faces become one; the vertex is left isolated and removed
    // by compact(). Returns false when v is not an interior valence-3 vertex.
    bool removeValence3Vertex(Index v, int phase);
    // The vertices adjacent to v, in no particular order.
    std::vector<Index> neighbours(Index v) const;
    bool isBoundaryVertex(Index v) const;
    // Drops isolated (deleted) vertices and renumbers; invalidates indices.
    void compact();

    // Edge tags (unordered vertex pairs).
    int edgeTag(Index a, Index b) const;
    void setEdgeTag(Index a, Index b, int tag);
    void addEdgeTag(Index a, Index b, int tag) { setEdgeTag(a, b, edgeTag(a, b) | tag); }
    const std::unordered_map<std::uint64_t, int>& edgeTags() const { return edgeTags_; }

    // The immutable mesh a snapshot publishes (positions f(u_i)).
    std::shared_ptr<const TriangleMesh> toTriangleMesh() const;

    // Every vertex's preimages in every domain face around it (appendix B),
    // flattened: vertex v's are reps[offsets[v] .. offsets[v + 1]). Used by
    // the loops over every face (parameterOrientations(),
    // centroidDomainFaces()); computed on first use and kept until a vertex
    // is added, moved or renumbered. Not safe to call from several threads
    // at once (it fills the cache).
    struct VertexPreimages {
        std::vector<size_t> offsets;
        std::vector<Preimage> reps;
        std::span<const Preimage> of(Index v) const {
            const auto i = static_cast<size_t>(v);
            return {reps.data() + offsets[i], offsets[i + 1] - offsets[i]};
        }
    };
    std::shared_ptr<const VertexPreimages> vertexPreimages() const;
    // The table if it is computed and current, else null (never computes it).
    std::shared_ptr<const VertexPreimages> currentVertexPreimages() const;
    // Reuses a table computed for a mesh with the same vertex preimages
    // (reloading a snapshot).
    void adoptVertexPreimages(std::shared_ptr<const VertexPreimages> table) {
        preimageTable_ = std::move(table);
    }

    // What parameterOrientations() and centroidDomainFaces() computed per
    // face (each depends only on the face's three preimages, in order), kept
    // until the face or one of its corners' preimages changes, so that a
    // phase that edits a few faces recomputes only those (publish() calls
    // both for every face). kUnknown where not computed; orientation
    // kNoChart where the corners have no common chart.
    static constexpr std::int8_t kOrientationUnknown = 2, kOrientationNoChart = 3;
    static constexpr Index kDomainFaceUnknown = -2;
    struct FaceCaches {
        double chartTolerance = 0.0;
        std::vector<std::int8_t> orientation;
        std::vector<Index> domainFace;
    };
    FaceCaches faceCaches() const;
    // Reuses the caches of a mesh with exactly these faces and vertex
    // preimages (reloading a snapshot); ignored when the chart tolerance or
    // the face count differs.
    void adoptFaceCaches(const FaceCaches& caches);

private:
    DomainCharts charts_;
    VertexEvaluator evaluator_;
    std::vector<MeshVertex> vertices_;
    std::vector<Triangle> faces_;
    std::vector<int> facePhase_;
    std::vector<std::vector<Index>> vertexFaces_;
    // The half-edge table: sharedHalfedges_ when set (read-only, shared with
    // a snapshot), else halfedgeFace_ (copied from the shared one on the
    // first edit).
    HalfedgeMap halfedgeFace_;
    std::shared_ptr<const HalfedgeMap> sharedHalfedges_;
    const HalfedgeMap& halfedgeTable() const {
        return sharedHalfedges_ ? *sharedHalfedges_ : halfedgeFace_;
    }
    HalfedgeMap& ownHalfedges();
    std::unordered_map<std::uint64_t, int> edgeTags_;
    mutable std::shared_ptr<const VertexPreimages> preimageTable_;
    mutable std::vector<std::int8_t> orientationCache_;
    mutable std::vector<Index> domainFaceCache_;
    // Marks the faces around v unknown in the caches above.
    void forgetFacesOf(Index v);
    void forgetFace(Index f);
    // Sizes the caches to the faces (new slots unknown).
    void sizeFaceCaches() const;
    // vertexPreimages() when it is current or worth building for
    // `unknownFaces` faces, else null.
    std::shared_ptr<const VertexPreimages> tableFor(size_t unknownFaces) const;

    static std::uint64_t key(Index a, Index b) {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
               static_cast<std::uint32_t>(b);
    }
    static std::uint64_t undirectedKey(Index a, Index b) { return a < b ? key(a, b) : key(b, a); }

public:
    static std::array<Index, 2> edgeFromKey(std::uint64_t k) {
        return {static_cast<Index>(k >> 32), static_cast<Index>(k & 0xffffffffu)};
    }

private:
    void attachFace(Index f);
    void detachFace(Index f);
};

} // namespace contour::consistent
