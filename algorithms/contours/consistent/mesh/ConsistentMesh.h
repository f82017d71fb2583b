#pragma once
// The per-view, editable triangle mesh of Bénard, Hertzmann & Kass 2014 §6
// (Bénard 2014 §4, §6): every vertex i stores a preimage u_i on the smooth
// surface's domain, its position f(u_i), its limit normal n(u_i), g(u_i) =
// (c - f) · n (eq. 1), the radial curvature and a label F / B / C. Local
// operators only (§6: edge split, vertex shift); provenance per vertex
// (initial / inserted / shifted, and the phase that last changed it) and per
// face (the phase that created or last changed it).
//
// Preimage interpolation follows appendix B: a point on a domain
// edge or corner has one preimage per domain face around it; two preimages
// are interpolated in a face that holds both, or, when they lie in
// edge-adjacent faces, in one face's chart extended across the shared edge
// (SmoothSurface::transferAcrossEdge), the result mapped back into a face that
// contains it. When no such chart exists the interpolation fails (nullopt) and
// the caller cancels the operation and counts it; nothing is guessed.
#include "camera/Camera.h"
#include "contours/consistent/mesh/HalfedgeMap.h"
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

// R_S at a vertex (Bénard 2014 §4): sign of g, or C for an inserted root.
enum class VertexLabel : std::int8_t { Back = -1, Contour = 0, Front = 1 };
enum class Provenance : std::int8_t { Initial = 0, Inserted = 1, Shifted = 2, Wiggled = 3 };

// Tags kept on an edge (an unordered vertex pair) between phases.
enum EdgeTag : int {
    kNoTag = 0,
    kCuspEdge = 1,   // an FB edge whose root of g is a cusp (§6.2 d): insert it last
    kRadialEdge = 2, // p-r with p a C vertex and r on p's radial plane (Definition 5)
};

VertexLabel labelFromG(double g);

// The triangle's corners rotated so that v comes first (same orientation).
inline Triangle rotatedTo(Triangle t, Index v) {
    while (t[0] != v)
        std::rotate(t.begin(), t.begin() + 1, t.end());
    return t;
}

struct MeshVertex {
    Preimage preimage;
    Vec3 position = Vec3::Zero(); // f(u)
    Vec3 normal = Vec3::Zero();   // n(u), unit
    double g = 0.0;               // (c - f(u)) · n(u)
    double radialCurvature = 0.0; // SurfaceFields.h convention, NaN where undefined
    // Only the final normal wiggle (§6.4) moves a vertex off the
    // surface: position = f(u) + normalOffset * n(u).
    double normalOffset = 0.0;
    bool cusp = false; // a C vertex inserted at a cusp (g = 0 and κr = 0, §6.2 d)
    VertexLabel label = VertexLabel::Contour;
    Provenance provenance = Provenance::Initial;
    int phase = 0; // the phase index that created or last changed the vertex
};

class ConsistentMesh {
public:
    // chartTolerance: how far (in domain parameters) a preimage may be from a
    // domain edge and still count as lying on it (so that it also has a
    // preimage in the neighbouring face), and how far outside a face an
    // interpolated preimage may land and still count as inside.
    ConsistentMesh(std::shared_ptr<const SmoothSurface> surface, const Camera& camera,
                   double chartTolerance);

    const SmoothSurface& surface() const { return *surface_; }
    const std::shared_ptr<const SmoothSurface>& surfacePtr() const { return surface_; }
    const Camera& camera() const { return camera_; }

    Index vertexCount() const { return static_cast<Index>(vertices_.size()); }
    Index faceCount() const { return static_cast<Index>(faces_.size()); }
    const MeshVertex& vertex(Index v) const { return vertices_[v]; }
    const std::vector<MeshVertex>& vertices() const { return vertices_; }
    const Triangle& face(Index f) const { return faces_[f]; }
    int facePhase(Index f) const { return facePhase_[f]; }
    const std::vector<Index>& vertexFaces(Index v) const { return vertexFaces_[v]; }

    // Evaluates f, n, g and the radial curvature at p; the label is sign(g).
    MeshVertex evaluate(const Preimage& p) const;
    // evaluate(p) given sp = surface().evaluate(p), already computed (the
    // initialization's tessellation evaluated every vertex).
    MeshVertex evaluated(const Preimage& p, const SurfacePoint& sp) const;
    // The same without the radial curvature (NaN): what the label and the
    // facing of a candidate need. Every other field has evaluate()'s exact
    // value, so evaluate() of a chosen candidate gives the same record.
    MeshVertex evaluateWithoutCurvature(const Preimage& p) const;

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

    // Appendix B also names the chart of a regular domain vertex's one-ring
    // (four quads, one per quadrant): with this on, two preimages in faces
    // that share only such a corner have a common chart too (the second
    // face's coordinates carried across two edges, both ways round the
    // corner agreeing). Off: a face and its edge neighbours only.
    void setVertexRingCharts(bool on) { vertexRingCharts_ = on; }
    // Appendix B: u(t) = (1 - t) u_a + t u_b in a common chart.
    std::optional<Preimage> interpolate(const Preimage& a, const Preimage& b, double t) const;
    // The same for several t (out[i] at t[i]): the charts of a and b are
    // found once.
    void interpolate(const Preimage& a, const Preimage& b, std::span<const double> t,
                     std::span<std::optional<Preimage>> out) const;
    // interpolate(a, b, t) for t chosen one at a time (a bisection): a's and
    // b's preimages around them (appendix B) are found once, so at(t) is
    // interpolate(a, b, t) without that search (the same results).
    class Segment;
    Segment segment(const Preimage& a, const Preimage& b) const;
    // Per face, the domain face holding its centroid: u(1/3) from the
    // midpoint of corners 0-1 to corner 2 (interpolate() twice),
    // kInvalidIndex without a common chart. Every face at once.
    std::vector<Index> centroidDomainFaces() const;
    // The three preimages' coordinates in every common chart: the domain
    // faces holding all three, or else the faces whose chart extended across
    // their edges holds all three; empty when there is none.
    std::vector<std::array<Vec2, 3>> chartCoordinates(const std::array<Preimage, 3>& p) const;
    // Whether p[0] shares a face or edge-adjacent faces with p[1] and with
    // p[2], and the three lie in one face's chart extended across its edges:
    // the charts without setVertexRingCharts. A move that must not straddle
    // a regular corner asks this (contour insertion's snap rule).
    bool withinEdgeCharts(const std::array<Preimage, 3>& p) const;
    // Sign of the face's orientation in parameter space (+1 counter-clockwise,
    // the domain's orientation; -1 a fold; 0 degenerate), the worst over all
    // common charts, or nullopt when the corners have no common chart.
    std::optional<int> parameterOrientation(const std::array<Preimage, 3>& p) const;
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
    std::shared_ptr<const SmoothSurface> surface_;
    Camera camera_;
    double tolerance_;
    bool vertexRingCharts_ = false;
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
    int cornerCount(Index domainFace) const { return surface_->isQuad(domainFace) ? 4 : 3; }
    bool onDomainEdge(const Preimage& p, int edge) const;
    bool onAnyDomainEdge(const Preimage& p) const;
    bool insideWithTolerance(const Preimage& p) const;
    Preimage clampIntoFace(Preimage p) const;
    // A few preimages without a heap allocation in the common case (a domain
    // corner of valence <= kInline); the hot loops call equivalents() for
    // every interpolation and every face orientation.
    class Preimages {
    public:
        static constexpr int kInline = 12;
        void push_back(const Preimage& p);
        size_t size() const { return static_cast<size_t>(size_); }
        const Preimage& operator[](size_t i) const { return data()[i]; }
        const Preimage* begin() const { return data(); }
        const Preimage* end() const { return data() + size_; }

    private:
        const Preimage* data() const { return heap_.empty() ? inline_.data() : heap_.data(); }
        std::array<Preimage, kInline> inline_;
        std::vector<Preimage> heap_;
        int size_ = 0;
    };
    // Every preimage of the same surface point (one per domain face around a
    // domain edge or corner the point lies on), p first.
    Preimages equivalents(const Preimage& p) const;
    using PreimageSpan = std::span<const Preimage>;
    static PreimageSpan span(const Preimages& p) { return {p.begin(), p.size()}; }
    // interpolate() given both preimages' equivalents().
    std::optional<Preimage> interpolateIn(PreimageSpan ra, PreimageSpan rb, double t) const;
    // p expressed in the chart of `face` (p's face, or an edge neighbour).
    std::optional<Vec2> inChart(PreimageSpan reps, Index face) const;
    // The same without the regular-corner charts.
    std::optional<Vec2> inEdgeChart(PreimageSpan reps, Index face) const;
    // r in the chart of `face` when the two faces share only a regular
    // corner (setVertexRingCharts), else nullopt.
    std::optional<Preimage> acrossRegularCorner(const Preimage& r, Index face) const;
    // Calls visit(coordinates) for every common chart of the three
    // preimages, in the order chartCoordinates() lists them; reps are their
    // equivalents().
    template <typename Visit>
    void forEachChart(const std::array<PreimageSpan, 3>& reps, Visit visit) const;
    template <typename Visit>
    void forEachChart(const std::array<Preimage, 3>& p, Visit visit) const;
};

class ConsistentMesh::Segment {
public:
    std::optional<Preimage> at(double t) const {
        return a_.face == b_.face ? m_->interpolate(a_, b_, t)
                                  : m_->interpolateIn(span(ra_), span(rb_), t);
    }

private:
    friend class ConsistentMesh;
    Segment(const ConsistentMesh& m, const Preimage& a, const Preimage& b) : m_(&m), a_(a), b_(b) {
        if (a.face != b.face) {
            ra_ = m.equivalents(a);
            rb_ = m.equivalents(b);
        }
    }
    const ConsistentMesh* m_;
    Preimage a_, b_;
    Preimages ra_, rb_;
};

inline ConsistentMesh::Segment ConsistentMesh::segment(const Preimage& a, const Preimage& b) const {
    return {*this, a, b};
}

} // namespace contour::consistent
