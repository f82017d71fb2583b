// Patch search: compound moves of the optimization phase, not in the paper;
// an extension of Bénard 2014 §6.4 that escapes the fixed
// point of its one-edit-at-a-time local search.
//
// Why: after the §6.4 sweeps (flips, flip pairs, parameter wiggle, edge
// split, vertex removal) re-running them changes nothing. Each of those
// moves changes one thing: one edge, one vertex's position, one split
// point. A face that only becomes consistent when a vertex appears (or
// moves) AND the faces around it are re-connected is out of their reach.
//
// The move: a small patch of faces (a topological disc) around an
// inconsistent face gets one free vertex x, placed at sampled points of
// the patch in parameter space, and the patch is re-triangulated with x
// optimally (fewest inconsistent faces, then the best minimum Bank-Smith
// quality). Two kinds of patch, each also grown by the faces across its
// open boundary edges:
//  - insertion: the face plus its neighbours across its untagged, non-CC
//    edges (also centred on each such neighbour); x is a NEW vertex. This
//    contains the edge split followed by flips of the new vertex's
//    opposite edges (x on an edge) and the 1->3 face split followed by
//    flips (x inside a face).
//  - relocation: the star of a vertex v of the face that vertex removal
//    could remove (not C, not a cusp, no tagged edge, and off the bounding
//    box unless another vertex keeps that side); x is v's new position: a
//    parameter wiggle and flips around v as one move. With
//    patch-radial-ends, the far end r of one radial edge p-r also moves,
//    sampled on p's radial plane only (roots of h_p between lattice
//    points) and kept joined to p, so the edge stays radial (§6.3 g).
//    With patch-contour-slide, a C vertex without tagged edges and with
//    exactly two CC edges also moves, sampled on the contour only (roots
//    of g between lattice points, §6.2) and kept joined to both contour
//    neighbours, so its CC edges stay. Slides are tried only once the
//    other moves are at their fixed point (a second pass; faces whose
//    surroundings did not change search their slides alone), so that they
//    never pre-empt one of those moves.
//  - new radial ends (patch-new-radial-ends): a C vertex p on the patch's
//    boundary with fewer than two radial edges (radial edge insertion,
//    §6.3 g, skipped one, e.g. to avoid a fold) gets one: x (inserted, or
//    a relocated vertex without tagged edges) is sampled on p's radial
//    plane only, kept joined to p, and p-x is tagged radial. Most faces
//    touching such a C vertex on its bare side are F-F-C or B-B-C slivers
//    of the wrong facing; a vertex on p's radial plane gives that side the
//    standard radial triangles of §6.3 h. Late, like the slides.
// Every triangulation of a polygon with one interior point x is a fan of
// x over some of the polygon's corners, the pockets between consecutive
// fan corners triangulated without x: the pockets' best triangulations do
// not depend on x (computed once per patch, by the dynamic programme of
// vertex removal), the fan is chosen per sample by a cyclic dynamic
// programme. The move is judged like every §6.4 move, on the faces it
// changes (LocalEdit): strictly fewer inconsistent faces, every VBO
// defined (no FB edge, no CCC face), no degenerate CC edge, no new CC edge
// (a contour edge the root finding did not make), no CC edge removed, no
// fold in parameter space or 3D. Tagged (radial, cusp) edges and cusps
// never move; C vertices only along the contour.
//
// The torus's last faces are F-F-F faces facing away beyond a cusp's
// radial end, two corners radial ends: a new F vertex inside such a face
// splits its image area and one part still faces away; a radial end slid
// along its radial plane with its star re-triangulated removes them (torus
// 12 -> 0 final inconsistent faces over 26 views with patch-radial-ends,
// on by default: see the parameter).
//
// Placed after vertex removal, before the normal wiggle (which then works
// on what is left). Measured over 26 views (final inconsistent faces, off
// -> on): see the parameter patch-search. After the normal wiggle instead
// it removes less (with 12-corner patches, bob 73 -> 64 there against
// 73 -> 48 here), and running it in both places removed nothing more.
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/edits/RingRetriangulation.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/OptimizationFlip.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/TriangleQuality.h"
#include "contours/consistent/predicates/TriangulationCost.h"
#include "pipeline/FieldNames.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

namespace contour::consistent {

namespace {

struct PatchSettings {
    int rows = 6;         // lattice step 1/rows on every face of the patch
    int maxCorners = 16;  // largest patch polygon
    bool insert = true;   // insertion patches
    bool relocate = true; // relocation patches
    bool grow = true;     // also the patches grown by one layer of faces
    bool cuspEdits = true;
    bool radialEnds = false;      // relocate radial ends along their radial planes
    double radialTolerance = 0.0; // |h_p(r)| of a radial end (a distance)
    bool contourSlide = false;    // relocate C vertices along the contour g = 0
    bool newRadialEnds = false;   // x on the radial plane of a C vertex lacking a radial edge
    bool newRadialCusps = false;  // ... also of a cusp, whose valence then changes
    bool cuspTies = false;        // a cusp's first radial edge also without a gain
    double rootTolerance = 0.0;   // |g| of a slid C vertex (a distance)
};

struct PatchStats {
    long long patches = 0, samples = 0, cancelledSamples = 0, rejected = 0, inserted = 0,
              relocated = 0, skipped = 0, unplanned = 0, slid = 0, newRadial = 0,
              newRadialCusps = 0;
};

using Cost = TriangulationCost;
Cost plus(const Cost& a, const Cost& b) {
    if (!a.valid() || !b.valid())
        return {};
    return {a.inconsistent + b.inconsistent, std::min(a.minQuality, b.minQuality)};
}
const Cost kEmpty{0, std::numeric_limits<double>::infinity()};

// A patch: faces forming a disc, its boundary polygon counter-clockwise and
// the vertex that moves (relocation) or kInvalidIndex (insertion: `seed`
// is the face the new vertex splits first).
struct Patch {
    std::vector<Index> faces;
    std::vector<Index> ring;
    Index centre = kInvalidIndex;
    Index seed = kInvalidIndex;
    bool grown = false;
    // A relocated radial end: the C vertex p of its radial edge (x stays on
    // p's radial plane and joined to p).
    Index partner = kInvalidIndex;
    // A C vertex slid along the contour (patch-contour-slide): x stays on
    // g = 0 and joined to both contour neighbours (its CC edges stay).
    bool onContour = false;
    std::array<Index, 2> contourNeighbours{kInvalidIndex, kInvalidIndex};
    // patch-new-radial-ends: x lies on the radial plane of `partner`, a C
    // vertex with fewer than two radial edges, and the edge partner-x
    // becomes radial (x the far end of a new radial edge).
    bool newRadial = false;
    // patch-new-radial-cusps: the one cusp without radial edges on the ring
    // (kInvalidIndex: none). Such a patch is searched only as a new radial
    // end of that cusp: the new radial edge lets its valence change.
    Index lockedCusp = kInvalidIndex;
};

class PatchSearcher {
public:
    PatchSearcher(ConsistentMesh& m, const PatchSettings& set, int phase)
        : m_(m), set_(set), phase_(phase) {
        boxMin_ = Vec3::Constant(std::numeric_limits<double>::infinity());
        boxMax_ = -boxMin_;
        for (Index v = 0; v < m_.vertexCount(); ++v) {
            boxMin_ = boxMin_.cwiseMin(m_.vertex(v).position);
            boxMax_ = boxMax_.cwiseMax(m_.vertex(v).position);
        }
        for (Index v = 0; v < m_.vertexCount(); ++v)
            for (int d = 0; d < 3; ++d) {
                atMin_[d] += m_.vertex(v).position[d] == boxMin_[d];
                atMax_[d] += m_.vertex(v).position[d] == boxMax_[d];
            }
    }

    PatchStats stats;

    // The best patch move around inconsistent face f, applied; false when
    // none leaves fewer inconsistent faces.
    bool improve(Index f) {
        // A face whose surroundings (the vertices within two edges of its
        // corners) did not change since its last search fails again: skip
        // it. A grown relocation patch reaches one edge further; a change
        // there can only make a later move be missed, never a wrong one.
        std::array<Index, 3> key = m_.face(f);
        std::sort(key.begin(), key.end());
        const auto unchangedSince = [&](const std::map<std::array<Index, 3>, long long>& failed) {
            const auto it = failed.find(key);
            if (it == failed.end())
                return false;
            const std::vector<Index> near = nearVertices(f);
            return std::none_of(near.begin(), near.end(), [&](Index v) {
                const auto c = changedAt_.find(v);
                return c != changedAt_.end() && c->second > it->second;
            });
        };
        if (unchangedSince(failedAt_)) {
            // Every other move failed here already: only the late moves
            // (slides of its C vertices, new radial ends) are new, once
            // they are allowed.
            if (!lateMoves() || unchangedSince(slideFailedAt_)) {
                ++stats.skipped;
                return false;
            }
            if (!search(f, true)) {
                slideFailedAt_[key] = moves_;
                return false;
            }
            return true;
        }
        if (!search(f, false)) {
            failedAt_[key] = moves_;
            if (lateMoves())
                slideFailedAt_[key] = moves_;
            return false;
        }
        return true;
    }

    // From now on the late moves are allowed too: C vertices may slide
    // (patch-contour-slide), new radial ends appear (patch-new-radial-ends).
    void allowLateMoves(bool contourSlide, bool newRadialEnds) {
        set_.contourSlide = contourSlide;
        set_.newRadialEnds = newRadialEnds;
    }
    bool lateMoves() const { return set_.contourSlide || set_.newRadialEnds; }

private:
    // lateOnly: the face failed every other move already; only its late
    // moves (slides, new radial ends) are searched.
    bool search(Index f, bool lateOnly) {
        std::vector<Patch> patches;
        if (set_.insert && (!lateOnly || set_.newRadialEnds)) {
            std::vector<Index> centres{f};
            for (int i = 0; i < 3; ++i) {
                const Triangle t = m_.face(f);
                if (openEdge(t[i], t[(i + 1) % 3])) {
                    const Index g = m_.faceOfHalfedge(t[(i + 1) % 3], t[i]);
                    if (g != kInvalidIndex)
                        centres.push_back(g);
                }
            }
            for (Index c : centres)
                if (std::optional<Patch> p = insertionPatch(c)) {
                    std::optional<Patch> q;
                    if (set_.grow && c == f)
                        q = grown(*p);
                    if (set_.newRadialEnds) {
                        addNewRadialPatches(*p, patches, false);
                        // A cusp's fan may need a corner one layer out.
                        if (q)
                            addNewRadialPatches(*q, patches, true);
                    }
                    if (lateOnly)
                        continue;
                    if (q && q->lockedCusp == kInvalidIndex)
                        patches.push_back(std::move(*q));
                    if (p->lockedCusp == kInvalidIndex)
                        patches.push_back(std::move(*p));
                }
        }
        if (set_.relocate)
            for (Index v : m_.face(f)) {
                const bool contour = m_.vertex(v).label == VertexLabel::Contour;
                if (lateOnly && !contour && !set_.newRadialEnds)
                    continue;
                std::optional<Patch> p = relocationPatch(v);
                if (!p)
                    continue;
                std::optional<Patch> q;
                if (set_.grow)
                    q = grown(*p);
                if (set_.newRadialEnds && p->partner == kInvalidIndex && !p->onContour) {
                    addNewRadialPatches(*p, patches, false);
                    if (q)
                        addNewRadialPatches(*q, patches, true);
                }
                if (lateOnly && !p->onContour)
                    continue;
                if (q && q->lockedCusp == kInvalidIndex)
                    patches.push_back(std::move(*q));
                if (p->lockedCusp == kInvalidIndex)
                    patches.push_back(std::move(*p));
            }
        Best best;
        for (const Patch& p : patches)
            search(p, best);
        if (!best.patch)
            return false;
        apply(*best.patch, best.x, *best.edits);
        return true;
    }

    // The corners of f and the vertices within two edges of them.
    std::vector<Index> nearVertices(Index f) const {
        std::vector<Index> out(m_.face(f).begin(), m_.face(f).end());
        for (int hop = 0; hop < 2; ++hop) {
            const size_t n = out.size();
            for (size_t i = 0; i < n; ++i)
                for (Index w : m_.neighbours(out[i]))
                    out.push_back(w);
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        }
        return out;
    }

    ConsistentMesh& m_;
    PatchSettings set_;
    int phase_;
    // Moves applied so far; per vertex, the move that last changed it or
    // its faces; per face (its sorted corners), the move count when its
    // search last failed.
    long long moves_ = 0;
    std::unordered_map<Index, long long> changedAt_;
    std::map<std::array<Index, 3>, long long> failedAt_;
    // The same for the slides of a face's C vertices alone.
    std::map<std::array<Index, 3>, long long> slideFailedAt_;
    Vec3 boxMin_, boxMax_;
    // Vertices on each side of the box: a vertex on it may move inside
    // while another one keeps the side where it is.
    std::array<int, 3> atMin_{0, 0, 0}, atMax_{0, 0, 0};

    // v may leave its place without changing the bounding box.
    bool boxKeeps(const Vec3& p) const {
        for (int d = 0; d < 3; ++d)
            if ((p[d] <= boxMin_[d] && atMin_[d] < 2) || (p[d] >= boxMax_[d] && atMax_[d] < 2))
                return false;
        return true;
    }
    void leaveBox(const Vec3& from) {
        for (int d = 0; d < 3; ++d) {
            atMin_[d] -= from[d] == boxMin_[d];
            atMax_[d] -= from[d] == boxMax_[d];
        }
    }

    struct Best {
        std::optional<Patch> patch;
        MeshVertex x;
        int gain = 0; // inconsistent faces removed
        double minQuality = -1.0;
        std::optional<RingRetriangulation> edits; // the move, planned
    };
    static constexpr Index kX = std::numeric_limits<Index>::max() - 1;

    bool insideBox(const Vec3& p) const {
        for (int d = 0; d < 3; ++d)
            if (!(p[d] > boxMin_[d] && p[d] < boxMax_[d]))
                return false;
        return true;
    }

    // An edge a patch may have inside: no tag (a radial or cusp edge
    // stays) and not CC (a contour edge stays).
    bool openEdge(Index a, Index b) const {
        return m_.edgeTag(a, b) == kNoTag && !(m_.vertex(a).label == VertexLabel::Contour &&
                                               m_.vertex(b).label == VertexLabel::Contour);
    }

    // The boundary of a set of faces as one counter-clockwise cycle, or
    // empty when it is not a simple cycle (not a disc).
    std::vector<Index> boundary(const std::vector<Index>& faces) const {
        std::vector<std::pair<Index, Index>> half;
        for (Index f : faces) {
            const Triangle t = m_.face(f);
            for (int i = 0; i < 3; ++i) {
                const Index a = t[i], b = t[(i + 1) % 3];
                const Index g = m_.faceOfHalfedge(b, a);
                if (g == kInvalidIndex || std::find(faces.begin(), faces.end(), g) == faces.end())
                    half.emplace_back(a, b);
            }
        }
        return simpleCycle(half);
    }

    // Sets p.lockedCusp; false when the ring is too long or has a cusp
    // that must keep its valence.
    bool cornersAllowed(Patch& p) const {
        if (static_cast<int>(p.ring.size()) > set_.maxCorners)
            return false;
        // A corner's valence changes: a cusp keeps the valence 4 of Fig.
        // 18d until it has radial edges (as in edge splitting), unless the
        // move gives it one (patch-new-radial-cusps).
        p.lockedCusp = kInvalidIndex;
        for (Index w : p.ring) {
            if (!lockedCusp(m_, w, set_.cuspEdits))
                continue;
            if (!set_.newRadialEnds || !set_.newRadialCusps || p.lockedCusp != kInvalidIndex)
                return false;
            p.lockedCusp = w;
        }
        return true;
    }

    std::optional<Patch> insertionPatch(Index c) const {
        Patch p;
        p.seed = c;
        p.faces.push_back(c);
        const Triangle t = m_.face(c);
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            if (!openEdge(a, b))
                continue;
            const Index g = m_.faceOfHalfedge(b, a);
            if (g != kInvalidIndex)
                p.faces.push_back(g);
        }
        p.ring = boundary(p.faces);
        if (p.ring.empty() || !cornersAllowed(p))
            return std::nullopt;
        // A corner of valence 3 with its three faces in the patch is inside
        // it: the fan of x over the ring would have to remove it.
        for (Index g : p.faces)
            for (Index w : m_.face(g))
                if (std::find(p.ring.begin(), p.ring.end(), w) == p.ring.end())
                    return std::nullopt;
        return p;
    }

    // The patch and the faces across its open boundary edges, when that is
    // still a disc whose vertices all lie on its boundary (but the centre)
    // and whose inner edges are all open.
    std::optional<Patch> grown(const Patch& p) const {
        Patch q = p;
        q.grown = true;
        const int k = static_cast<int>(p.ring.size());
        for (int i = 0; i < k; ++i) {
            const Index a = p.ring[i], b = p.ring[(i + 1) % k];
            if (!openEdge(a, b))
                continue;
            const Index g = m_.faceOfHalfedge(b, a);
            if (g != kInvalidIndex && std::find(q.faces.begin(), q.faces.end(), g) == q.faces.end())
                q.faces.push_back(g);
        }
        if (q.faces.size() == p.faces.size())
            return std::nullopt;
        q.ring = boundary(q.faces);
        if (q.ring.empty() || !cornersAllowed(q))
            return std::nullopt;
        for (Index f : q.faces) {
            const Triangle t = m_.face(f);
            for (int i = 0; i < 3; ++i) {
                const Index a = t[i], b = t[(i + 1) % 3];
                if (a != q.centre && std::find(q.ring.begin(), q.ring.end(), a) == q.ring.end())
                    return std::nullopt;
                const Index g = m_.faceOfHalfedge(b, a);
                const bool inner = g != kInvalidIndex &&
                                   std::find(q.faces.begin(), q.faces.end(), g) != q.faces.end();
                if (inner && a != q.centre && b != q.centre && !openEdge(a, b))
                    return std::nullopt;
            }
        }
        return q;
    }

    std::optional<Patch> relocationPatch(Index v) const {
        const MeshVertex& x = m_.vertex(v);
        if (x.label == VertexLabel::Contour)
            return contourPatch(v);
        if (x.cusp || m_.vertexFaces(v).size() < 3 || m_.isBoundaryVertex(v) ||
            !boxKeeps(x.position))
            return std::nullopt;
        Patch p;
        p.centre = v;
        p.faces = m_.vertexFaces(v);
        p.ring = boundary(p.faces);
        if (p.ring.size() != p.faces.size() || !cornersAllowed(p))
            return std::nullopt;
        for (Index w : p.ring) {
            // One radial edge p-v at most: v then slides along p's radial
            // plane, the edge kept (§6.3 g: v stays its far end).
            const int tag = m_.edgeTag(v, w);
            if (tag == kNoTag)
                continue;
            if (!set_.radialEnds || tag != kRadialEdge || p.partner != kInvalidIndex ||
                m_.vertex(w).label != VertexLabel::Contour)
                return std::nullopt;
            p.partner = w;
        }
        return p;
    }

    // patch-new-radial-ends: the variants of patch p whose free vertex x is
    // sampled on the radial plane of a ring corner w that lacks a radial
    // edge (roots of h_w, as for a relocated radial end), with x joined to
    // w and the edge w-x tagged radial once the move is applied. A ring
    // with a cusp without radial edges gives only that cusp's variant;
    // cuspsOnly: only cusps' variants (grown patches).
    void addNewRadialPatches(const Patch& p, std::vector<Patch>& out, bool cuspsOnly) const {
        for (Index w : p.ring)
            if (missingRadialEdge(w) && (p.lockedCusp == kInvalidIndex || p.lockedCusp == w) &&
                (!cuspsOnly || m_.vertex(w).cusp)) {
                Patch r = p;
                r.partner = w;
                r.newRadial = true;
                out.push_back(std::move(r));
            }
    }

    // A C vertex with fewer than two radial edges: §6.3 g gives every C
    // vertex two, but an insertion that would fold is skipped (Fig. 17),
    // and the faces on that side stay inconsistent. A cusp (two radial
    // edges on its outside region, Fig. 18e) only with
    // patch-new-radial-cusps: radial insertion skips a cusp whose outside
    // region it cannot identify, and its valence-4 fan (Fig. 18d) can then
    // have too few corners on one side to wrap around the cusp's image.
    bool missingRadialEdge(Index w) const {
        const MeshVertex& x = m_.vertex(w);
        if (x.label != VertexLabel::Contour || (x.cusp && !set_.newRadialCusps))
            return false;
        int radial = 0;
        for (Index u : m_.neighbours(w))
            radial += (m_.edgeTag(w, u) & kRadialEdge) != 0;
        return radial < 2;
    }

    // A C vertex v that may slide along the contour: not a cusp (its place
    // is the joint root of g and the radial curvature), no tagged edge (a
    // radial edge p-r stays on v's radial plane only while v stays), and
    // exactly two C neighbours, its CC edges, which the fan keeps.
    std::optional<Patch> contourPatch(Index v) const {
        const MeshVertex& x = m_.vertex(v);
        if (!set_.contourSlide || x.cusp || m_.vertexFaces(v).size() < 3 ||
            m_.isBoundaryVertex(v) || !boxKeeps(x.position))
            return std::nullopt;
        Patch p;
        p.centre = v;
        p.onContour = true;
        p.faces = m_.vertexFaces(v);
        p.ring = boundary(p.faces);
        if (p.ring.size() != p.faces.size() || !cornersAllowed(p))
            return std::nullopt;
        int contour = 0;
        for (Index w : p.ring) {
            if (m_.edgeTag(v, w) != kNoTag)
                return std::nullopt;
            if (m_.vertex(w).label != VertexLabel::Contour)
                continue;
            if (contour == 2)
                return std::nullopt;
            p.contourNeighbours[static_cast<size_t>(contour++)] = w;
        }
        if (contour != 2)
            return std::nullopt;
        return p;
    }

    // The diagonal ring[i]-ring[j] of a re-triangulation: not an edge of
    // the mesh outside the patch, and neither a new CC edge nor an FB edge.
    bool diagonalAllowed(const Patch& p, Index a, Index b) const {
        const Index f1 = m_.faceOfHalfedge(a, b), f2 = m_.faceOfHalfedge(b, a);
        const auto inPatch = [&](Index f) {
            return std::find(p.faces.begin(), p.faces.end(), f) != p.faces.end();
        };
        if (f1 != kInvalidIndex || f2 != kInvalidIndex) {
            // An interior edge of the patch may stay (it is removed and put
            // back by the flips that apply the move).
            if (!(f1 != kInvalidIndex && f2 != kInvalidIndex && inPatch(f1) && inPatch(f2)))
                return false;
        }
        const int la = static_cast<int>(m_.vertex(a).label),
                  lb = static_cast<int>(m_.vertex(b).label);
        return !(la == 0 && lb == 0) && la * lb >= 0;
    }

    // A triangle of the re-triangulation: defined VBO and, when `full`, not
    // turned over in 3D and counter-clockwise in every common chart.
    Cost triangle(const LocalEdit& e, const Triangle& t, bool full) const {
        if (e.vbo(t) == Vbo::Undefined)
            return {};
        if (full) {
            if (e.turnedOver(t))
                return {};
            const std::optional<int> o = m_.parameterOrientation(
                {e.vertex(t[0]).preimage, e.vertex(t[1]).preimage, e.vertex(t[2]).preimage});
            if (!o || *o <= 0)
                return {};
        }
        // The quality only breaks ties between full triangulations.
        return {e.consistent(t) ? 0 : 1,
                full ? bankSmithQuality(e.vertex(t[0]).position, e.vertex(t[1]).position,
                                        e.vertex(t[2]).position)
                     : 0.0};
    }

    // Pockets: best[i][len] triangulates the ring's chain i .. i+len
    // (indices modulo k) closed by the diagonal ring[i]-ring[i+len];
    // len = 1 is a ring edge (no face).
    struct Pockets {
        std::vector<std::vector<Cost>> best;
        std::vector<std::vector<int>> split;
    };
    Pockets pockets(const Patch& p, const LocalEdit& e, bool full) const {
        const int k = static_cast<int>(p.ring.size());
        Pockets out;
        out.best.assign(k, std::vector<Cost>(k));
        out.split.assign(k, std::vector<int>(k, -1));
        for (int i = 0; i < k; ++i)
            out.best[i][1] = kEmpty;
        for (int len = 2; len <= k - 2; ++len)
            for (int i = 0; i < k; ++i) {
                const int j = (i + len) % k;
                if (!diagonalAllowed(p, p.ring[i], p.ring[j]))
                    continue;
                for (int s = 1; s < len; ++s) {
                    const Cost sub = plus(out.best[i][s], out.best[(i + s) % k][len - s]);
                    if (!sub.valid())
                        continue;
                    const Cost c =
                        plus(sub, triangle(e, {p.ring[i], p.ring[(i + s) % k], p.ring[j]}, full));
                    if (better(c, out.best[i][len])) {
                        out.best[i][len] = c;
                        out.split[i][len] = s;
                    }
                }
            }
        return out;
    }

    void collect(const Patch& p, const Pockets& q, int i, int len,
                 std::vector<Triangle>& out) const {
        if (len < 2)
            return;
        const int k = static_cast<int>(p.ring.size());
        const int s = q.split[i][len];
        out.push_back({p.ring[i], p.ring[(i + s) % k], p.ring[(i + len) % k]});
        collect(p, q, i, s, out);
        collect(p, q, (i + s) % k, len - s, out);
    }

    // Best fan of x (vertex xi of e) over the ring, with the pockets q:
    // cost and, through `fan`, the fan corners (ring indices, increasing).
    Cost bestFan(const Patch& p, const LocalEdit& e, Index xi, const Pockets& q, bool full,
                 std::vector<int>* fan) const {
        const int k = static_cast<int>(p.ring.size());
        // seg[i][len]: fan face x-ring[i]-ring[i+len] and the pocket under it.
        std::vector<std::vector<Cost>> seg(k, std::vector<Cost>(k));
        // A radial end's partner, a slid C vertex's contour neighbours stay
        // joined to x: no fan face passes over them.
        std::vector<int> required;
        for (Index w : {p.partner, p.contourNeighbours[0], p.contourNeighbours[1]})
            if (const auto at = std::find(p.ring.begin(), p.ring.end(), w); at != p.ring.end())
                required.push_back(static_cast<int>(at - p.ring.begin()));
        for (int i = 0; i < k; ++i)
            for (int len = 1; len <= k - 2; ++len) {
                if (!q.best[i][len].valid())
                    continue;
                if (std::any_of(required.begin(), required.end(), [&](int r) {
                        return (r - i + k) % k > 0 && (r - i + k) % k < len;
                    }))
                    continue;
                seg[i][len] =
                    plus(q.best[i][len], triangle(e, {xi, p.ring[i], p.ring[(i + len) % k]}, full));
            }
        Cost best;
        std::vector<int> bestFan;
        // The first fan corner is the smallest ring index s0; dp over the
        // offset d from s0 and the number of fan faces so far (capped at 3:
        // x needs three neighbours).
        for (int s0 = 0; s0 < k; ++s0) {
            const int span = k - s0; // offsets 0 .. span-1 stay at or after s0
            std::vector<std::array<Cost, 4>> dp(span);
            std::vector<std::array<int, 4>> from(span, {-1, -1, -1, -1});
            dp[0][0] = kEmpty;
            for (int d = 1; d < span; ++d)
                for (int e0 = 0; e0 < d; ++e0) {
                    const Cost& s = seg[(s0 + e0) % k][d - e0];
                    if (!s.valid())
                        continue;
                    for (int c = 0; c < 4; ++c) {
                        if (!dp[e0][c].valid())
                            continue;
                        const int c2 = std::min(c + 1, 3);
                        const Cost t = plus(dp[e0][c], s);
                        if (better(t, dp[d][c2])) {
                            dp[d][c2] = t;
                            from[d][c2] = e0 * 4 + c;
                        }
                    }
                }
            for (int d = 1; d < span; ++d) {
                const int close = k - d;
                if (close > k - 2)
                    continue;
                const Cost& s = seg[(s0 + d) % k][close];
                for (int c = 2; c < 4; ++c) {
                    const Cost t = plus(dp[d][c], s);
                    if (!better(t, best))
                        continue;
                    best = t;
                    if (fan) {
                        bestFan.clear();
                        int dd = d, cc = c;
                        while (dd > 0) {
                            bestFan.push_back(s0 + dd);
                            const int f = from[dd][cc];
                            dd = f / 4;
                            cc = f % 4;
                        }
                        bestFan.push_back(s0);
                        std::reverse(bestFan.begin(), bestFan.end());
                    }
                }
            }
        }
        if (fan)
            *fan = bestFan;
        return best;
    }

    // Lattice points of step 1/rows on the patch's faces (corners and the
    // patch's own boundary excluded), and v's current position for a
    // relocation (the flips alone).
    std::vector<Preimage> samplePoints(const Patch& p) {
        if (p.partner != kInvalidIndex || p.onContour)
            return rootSamples(p);
        std::vector<Preimage> out;
        if (p.centre != kInvalidIndex)
            out.push_back(m_.vertex(p.centre).preimage);
        // Grown patches have three times the faces: a coarser lattice.
        const int n = p.grown ? std::max(2, set_.rows - 2) : set_.rows;
        const auto onBoundary = [&](Index a, Index b) {
            const Index g = m_.faceOfHalfedge(b, a);
            return g == kInvalidIndex ||
                   std::find(p.faces.begin(), p.faces.end(), g) == p.faces.end();
        };
        for (Index f : p.faces) {
            const Triangle t = m_.face(f);
            const Preimage &p0 = m_.vertex(t[0]).preimage, &p1 = m_.vertex(t[1]).preimage,
                           &p2 = m_.vertex(t[2]).preimage;
            const bool b01 = onBoundary(t[0], t[1]), b12 = onBoundary(t[1], t[2]),
                       b20 = onBoundary(t[2], t[0]);
            for (int row = 1; row <= n; ++row) {
                const double level = static_cast<double>(row) / n;
                const std::optional<Preimage> ra = m_.interpolate(p0, p1, level);
                const std::optional<Preimage> rb = m_.interpolate(p0, p2, level);
                for (int j = 0; j <= row; ++j) {
                    // j = 0 lies on edge 0-1, j = row on 0-2, row = n on 1-2.
                    if ((j == 0 && b01) || (j == row && b20) || (row == n && b12))
                        continue;
                    if (row == n && (j == 0 || j == row))
                        continue;
                    // Points on an interior edge are sampled from one side.
                    if (j == 0 && t[0] > t[1])
                        continue;
                    if (j == row && t[2] > t[0])
                        continue;
                    if (row == n && t[1] > t[2])
                        continue;
                    if (!ra || !rb) {
                        ++stats.cancelledSamples;
                        continue;
                    }
                    const std::optional<Preimage> u =
                        j == 0     ? ra
                        : j == row ? rb
                                   : m_.interpolate(*ra, *rb, static_cast<double>(j) / row);
                    if (u)
                        out.push_back(*u);
                    else
                        ++stats.cancelledSamples;
                }
            }
        }
        return out;
    }

    // A radial end's samples: its place, and the roots of h_p (p its
    // partner) between consecutive lattice points of each row on the
    // patch's faces (bisection to the radial tolerance), so that x stays on
    // p's radial plane. A slid C vertex's: the roots of g instead, so that
    // x stays on the contour.
    std::vector<Preimage> rootSamples(const Patch& p) {
        // An insertion has no current place; a new radial end's current
        // place is off its partner's radial plane.
        std::vector<Preimage> out;
        if (p.centre != kInvalidIndex && !p.newRadial)
            out.push_back(m_.vertex(p.centre).preimage);
        const Index partner = p.partner;
        const auto h = [&](const Preimage& u) {
            const MeshVertex x = m_.evaluateWithoutCurvature(u);
            return partner == kInvalidIndex
                       ? x.g
                       : radialPlaneDistance(m_.camera(), m_.vertex(partner), x.position);
        };
        const double tolerance =
            partner == kInvalidIndex ? set_.rootTolerance : set_.radialTolerance;
        const int n = p.grown ? std::max(2, set_.rows - 2) : set_.rows;
        for (Index f : p.faces) {
            const Triangle t = m_.face(f);
            const Preimage &p0 = m_.vertex(t[0]).preimage, &p1 = m_.vertex(t[1]).preimage,
                           &p2 = m_.vertex(t[2]).preimage;
            for (int row = 1; row <= n; ++row) {
                const double level = static_cast<double>(row) / n;
                const std::optional<Preimage> ra = m_.interpolate(p0, p1, level);
                const std::optional<Preimage> rb = m_.interpolate(p0, p2, level);
                if (!ra || !rb) {
                    ++stats.cancelledSamples;
                    continue;
                }
                std::optional<Preimage> prev;
                double hPrev = 0.0;
                for (int j = 0; j <= row; ++j) {
                    const std::optional<Preimage> u =
                        j == 0     ? ra
                        : j == row ? rb
                                   : m_.interpolate(*ra, *rb, static_cast<double>(j) / row);
                    if (!u) {
                        prev.reset();
                        continue;
                    }
                    const double hu = h(*u);
                    if (prev && (hu < 0.0) != (hPrev < 0.0))
                        if (std::optional<Preimage> root =
                                planeRoot(*prev, hPrev, *u, h, tolerance))
                            out.push_back(*root);
                    prev = u;
                    hPrev = hu;
                }
            }
        }
        return out;
    }

    // The zero of h (h_p or g) between a and b (h(a) = ha, opposite signs
    // at the ends), halving the parameter interval.
    template <class H>
    std::optional<Preimage> planeRoot(const Preimage& a, double ha, const Preimage& b, const H& h,
                                      double tolerance) {
        BisectionOptions search;
        search.step = BisectionStep::Midpoint;
        search.sign = BisectionSign::Negative;
        search.maxIterations = 60;
        search.tolerance = tolerance;
        BisectionResult<Preimage> r =
            bisect([&](double along) { return m_.interpolate(a, b, along); }, h,
                   {0.0, 1.0, ha, -ha}, search);
        if (r.outcome == BisectionOutcome::Converged)
            return std::move(r.last);
        ++stats.cancelledSamples;
        return std::nullopt;
    }

    void search(const Patch& p, Best& best) {
        ++stats.patches;
        LocalEdit before(m_);
        before.addFaces(p.faces);
        const int now = before.inconsistent();
        if (now == 0)
            return;
        LocalEdit plain(m_);
        const Pockets cheap = pockets(p, plain, false);
        std::optional<Pockets> full;
        LocalEdit e(m_);
        for (const Preimage& u : samplePoints(p)) {
            ++stats.samples;
            MeshVertex x = m_.evaluateWithoutCurvature(u);
            if (p.onContour) {
                // A root of g (or v's own place): v stays C.
                if (!(std::abs(x.g) <= set_.rootTolerance))
                    continue;
                x.label = VertexLabel::Contour;
            } else if (x.label == VertexLabel::Contour) {
                continue;
            }
            if (!insideBox(x.position))
                continue;
            e.clear();
            Index xi;
            if (p.centre != kInvalidIndex) {
                e.moveVertex(p.centre, x);
                xi = p.centre;
            } else {
                xi = e.addVertex(x);
            }
            // Labels only first: a lower bound that most samples fail.
            const Cost bound = bestFan(p, e, xi, cheap, false, nullptr);
            // patch-new-radial-cusp-ties: a cusp's first radial edge is worth
            // a move that removes nothing (a tie-break, see the parameter).
            const int minGain = set_.cuspTies && p.lockedCusp != kInvalidIndex ? 0 : 1;
            if (!bound.valid() || now - bound.inconsistent < std::max(best.gain, minGain))
                continue;
            if (!full)
                full = pockets(p, plain, true);
            std::vector<int> fan;
            const Cost c = bestFan(p, e, xi, *full, true, &fan);
            if (!c.valid())
                continue;
            const int gain = now - c.inconsistent;
            if (gain < minGain || gain < best.gain ||
                (gain == best.gain && !(c.minQuality > best.minQuality)))
                continue;
            // The whole edit: degenerate CC edges across the patch's
            // boundary, and every face once more.
            std::vector<Triangle> faces;
            const int k = static_cast<int>(p.ring.size());
            for (size_t n = 0; n < fan.size(); ++n) {
                const int i = fan[n], j = fan[(n + 1) % fan.size()];
                const int len = (j - i + k) % k;
                faces.push_back({xi, p.ring[i], p.ring[j]});
                collect(p, *full, i, len, faces);
            }
            LocalEdit after(m_);
            if (p.centre != kInvalidIndex)
                after.moveVertex(p.centre, x);
            else
                after.addVertex(x);
            for (const Triangle& t : faces)
                after.addFace(t);
            // A polygon of k corners and one interior vertex: k faces.
            if (static_cast<int>(faces.size()) != k || after.inconsistent() != c.inconsistent ||
                !after.labelsValid() || !after.parameterValid() || after.turnedOver() > 0) {
                ++stats.rejected;
                continue;
            }
            for (Triangle& t : faces)
                for (Index& w : t)
                    if (w == xi)
                        w = kX;
            std::vector<Index> corners;
            for (int i : fan)
                corners.push_back(p.ring[i]);
            std::optional<RingRetriangulation> edits = plan(p, corners, faces);
            if (!edits) {
                ++stats.unplanned;
                continue;
            }
            best.patch = p;
            best.x = x;
            best.gain = gain;
            best.minQuality = c.minQuality;
            best.edits.reset();
            best.edits.emplace(std::move(*edits));
        }
    }

    // The move through the mesh's own edits: x enters (a 1->3 split of the
    // seed face, then flips of the seed's edges join it to every corner) or
    // v moves to x; then, as vertex removal deletes a vertex (§6.3 h), each
    // flip of an edge x-w cuts off an ear prev-w-next of a pocket until x's
    // ring is the chosen fan. Planned on a copy of the patch: nullopt when
    // the mesh would refuse an edit (e.g. a flip whose new edge exists
    // outside the patch) or the edits do not end in `faces` (x as kX).
    std::optional<RingRetriangulation> plan(const Patch& p, const std::vector<Index>& fan,
                                            std::vector<Triangle> faces) const {
        RingRetriangulation r(m_, p.faces);
        Index xi = p.centre;
        if (xi == kInvalidIndex) {
            const std::optional<Index> x = r.splitFace(p.seed);
            if (!x)
                return std::nullopt;
            xi = *x;
        }
        // x joined to every corner: flip the edges of x's link that are
        // inside the patch (the vertex across is a corner x does not reach
        // yet) until its link is the patch's boundary.
        const int k = static_cast<int>(p.ring.size());
        const auto ringEdge = [&](Index a, Index b) {
            for (int i = 0; i < k; ++i)
                if (p.ring[i] == a && p.ring[(i + 1) % k] == b)
                    return true;
            return false;
        };
        for (int guard = 0; static_cast<int>(r.vertexFaces(xi).size()) < k; ++guard) {
            if (guard > 4 * k)
                return std::nullopt;
            bool flipped = false;
            for (Index g : r.vertexFaces(xi)) {
                const Triangle t = rotatedTo(r.face(g), xi);
                if (ringEdge(t[1], t[2]))
                    continue;
                if (!r.flipEdge(t[1], t[2]))
                    return std::nullopt;
                flipped = true;
                break;
            }
            if (!flipped)
                return std::nullopt;
        }
        for (Triangle& t : faces)
            for (Index& w : t)
                if (w == kX)
                    w = xi;
        if (!r.cutEars(xi, p.ring, faces, fan) || !r.endsIn(faces))
            return std::nullopt;
        return r;
    }

    // The planned move on the mesh.
    void apply(const Patch& p, const MeshVertex& x, const RingRetriangulation& edits) {
        MeshVertex full = m_.evaluate(x.preimage);
        if (p.onContour)
            full.label = VertexLabel::Contour;
        Index xi;
        if (p.centre != kInvalidIndex) {
            full.provenance = Provenance::Wiggled;
            xi = p.centre;
            leaveBox(m_.vertex(xi).position);
            m_.setVertex(xi, full, phase_);
            edits.apply(m_, nullptr, phase_);
            ++stats.relocated;
            if (p.newRadial) {
                m_.setEdgeTag(p.partner, xi, kRadialEdge);
                ++stats.newRadial;
                stats.newRadialCusps += m_.vertex(p.partner).cusp;
            }
            stats.slid += p.onContour;
        } else {
            full.provenance = Provenance::Inserted;
            xi = m_.vertexCount();
            edits.apply(m_, &full, phase_);
            ++stats.inserted;
            if (p.newRadial) {
                m_.setEdgeTag(p.partner, xi, kRadialEdge);
                ++stats.newRadial;
                stats.newRadialCusps += m_.vertex(p.partner).cusp;
            }
        }
        ++moves_;
        changedAt_[xi] = moves_;
        for (Index w : p.ring)
            changedAt_[w] = moves_;
    }
};

// The phase's parameters, read once per run.
struct PatchSearchOptions {
    bool enabled = false; // patch-search
    int maxSweeps = 0;    // patch-max-sweeps
    int rows = 0, maxCorners = 0;
    bool relocate = false, grow = false, radialEnds = false, contourSlide = false,
         newRadialEnds = false, newRadialCusps = false, cuspTies = false;
    CuspEditOptions cusps;
    RadialEdgeOptions radial;
    ContourRootOptions root;
    static PatchSearchOptions read(const ParameterSet& p) {
        PatchSearchOptions o;
        o.enabled = p.getBool("patch-search");
        o.maxSweeps = p.getInt("patch-max-sweeps");
        o.rows = p.getInt("patch-rows");
        o.maxCorners = p.getInt("patch-max-corners");
        o.relocate = p.getBool("patch-relocate");
        o.grow = p.getBool("patch-grow");
        o.radialEnds = p.getBool("patch-radial-ends");
        o.contourSlide = p.getBool("patch-contour-slide");
        o.newRadialEnds = p.getBool("patch-new-radial-ends");
        o.newRadialCusps = p.getBool("patch-new-radial-cusps");
        o.cuspTies = p.getBool("patch-new-radial-cusp-ties");
        o.cusps = CuspEditOptions::read(p);
        o.radial = RadialEdgeOptions::read(p);
        o.root = ContourRootOptions::read(p);
        return o;
    }
};

void runPatchSearch(const PhaseContext& ctx, Snapshot& s) {
    const PatchSearchOptions options = PatchSearchOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    PatchSettings set;
    set.rows = options.rows;
    set.maxCorners = options.maxCorners;
    set.relocate = options.relocate;
    set.grow = options.grow;
    set.cuspEdits = options.cusps.cuspEdits;
    set.radialEnds = options.radialEnds;
    set.radialTolerance = options.radial.rootTolerance * sceneScale(m);
    set.contourSlide = options.contourSlide;
    set.newRadialEnds = options.newRadialEnds;
    set.newRadialCusps = options.newRadialCusps;
    set.cuspTies = options.cuspTies;
    // Half the bound the |g| post-condition checks, as contour insertion.
    set.rootTolerance = 0.5 * options.root.tolerance * sceneScale(m);
    const bool enabled = options.enabled;
    const int maxSweeps = options.maxSweeps;
    OptimizationTally tally;
    PatchSearcher searcher(
        m,
        [&] {
            PatchSettings first = set;
            first.contourSlide = false;
            first.newRadialEnds = false;
            return first;
        }(),
        s.phaseIndex);
    if (enabled) {
        sweepInconsistent(ctx, m, maxSweeps, false, tally,
                          [&](Index f) { return searcher.improve(f); });
        // C vertices slide only once the other moves are at their fixed
        // point: a slide never pre-empts one of them (killeroo view 13 ended
        // one face worse after the normal wiggle when slides competed). New
        // radial ends likewise (with the other moves, killeroo view 8 ended
        // one face worse; late, 10 views 158 -> 154, none worse).
        if (set.contourSlide || set.newRadialEnds) {
            searcher.allowLateMoves(set.contourSlide, set.newRadialEnds);
            OptimizationTally more;
            sweepInconsistent(ctx, m, maxSweeps, false, more,
                              [&](Index f) { return searcher.improve(f); });
            tally.tried += more.tried;
            tally.accepted += more.accepted;
            tally.sweeps += more.sweeps;
            tally.sweepLimitHit = more.sweepLimitHit;
        }
    } else
        tally.before = static_cast<long long>(inconsistentFaces(m).size());
    publish(s, m);
    publishTally(s, tally, counters::kFacesTried, counters::kFacesAccepted, "patch-max-sweeps");
    const PatchStats& st = searcher.stats;
    s.setCounter(counters::kPatchesSearched, static_cast<double>(st.patches));
    s.setCounter(counters::kPatchSamples, static_cast<double>(st.samples));
    s.setCounter(counters::kSamplesWithoutAChart, static_cast<double>(st.cancelledSamples));
    s.setCounter(counters::kRejectedDegenerateCCEdgeOrFold, static_cast<double>(st.rejected));
    s.setCounter(counters::kVerticesInserted, static_cast<double>(st.inserted));
    s.setCounter(counters::kVerticesRelocated, static_cast<double>(st.relocated));
    s.setCounter(counters::kCVerticesSlidAlongTheContour, static_cast<double>(st.slid));
    s.setCounter(counters::kNewRadialEdges, static_cast<double>(st.newRadial));
    s.setCounter(counters::kNewRadialEdgesAtCusps, static_cast<double>(st.newRadialCusps));
    s.setCounter(counters::kFacesSkippedNothingChangedNearThem, static_cast<double>(st.skipped));
    s.setCounter(counters::kMovesSkippedTheMeshWouldRefuseAnEdit,
                 static_cast<double>(st.unplanned));
    if (!enabled)
        s.notes.push_back("patch search is off (patch-search = false): mesh passed through");
}

std::vector<InvariantCheck> checkPatchSearch(const PhaseContext& ctx, const Snapshot& s) {
    // After the normal wiggle, vertices sit off the surface, where h_p is
    // no longer evaluated at f(u) (as for the normal wiggle's own checks).
    bool onSurface = true;
    if (const Field* offset = s.field(fields::kNormalOffset); offset && offset->scalars())
        for (double a : *offset->scalars())
            onSurface = onSurface && a == 0.0;
    return optimizationChecks(ctx, s, onSurface);
}

} // namespace

void addPatchSearchPhase(Method& m) {
    m.parameters.push_back(
        {"patch-search",
         "Patch search: on",
         "Not in the paper (extends §6.4 past the fixed point of its one-edit moves): a "
         "new or moved vertex anywhere in a small patch around an inconsistent face, the "
         "patch re-triangulated around it, kept when the patch has strictly fewer "
         "inconsistent faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-rows",
         "Patch search: lattice rows",
         "With patch-search (not in the paper): the free vertex is sampled on the "
         "lattice of step 1/rows on every face of the patch. Cost grows with rows².",
         ParameterType::Int,
         6,
         1,
         64,
         {}});
    m.parameters.push_back(
        {"patch-max-corners",
         "Patch search: largest patch",
         "With patch-search (not in the paper): patches whose boundary has more corners "
         "are skipped (the re-triangulation is cubic in it).",
         ParameterType::Int,
         16,
         4,
         32,
         {}});
    m.parameters.push_back(
        {"patch-relocate",
         "Patch search: relocate vertices",
         "With patch-search (not in the paper): also move a vertex of the face over its "
         "whole star, the star re-triangulated (a wiggle and flips as one move). Off: "
         "new vertices only.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-radial-ends",
         "Patch search: relocate radial ends",
         "With patch-search (not in the paper): also relocate the far end r of a radial "
         "edge p-r over its star, kept on p's radial plane (within "
         "radial-root-tolerance) and joined to p, the star re-triangulated.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-contour-slide",
         "Patch search: slide C vertices",
         "With patch-search (not in the paper): also slide a C vertex (no cusp, no "
         "tagged edge, two CC edges) over its star along the contour (a root of g, §6.2 "
         "e), joined to both contour neighbours, the star re-triangulated.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-ends",
         "Patch search: new radial ends",
         "With patch-search (not in the paper): also put the free vertex on the radial "
         "plane of a C vertex p of the patch boundary that has fewer than two radial "
         "edges, joined to p as a new radial edge (the edge §6.3 g did not insert).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-cusps",
         "Patch search: new radial ends at cusps",
         "With patch-search and patch-new-radial-ends (not in the paper): a cusp with "
         "fewer than two radial edges may get one too, which changes its valence (Fig. "
         "18d keeps it 4 only until the cusp has radial edges, Fig. 18e).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-cusp-ties",
         "Patch search: a cusp's first radial edge on a tie",
         "With patch-search and patch-new-radial-cusps (not in the paper): a new radial "
         "end at a cusp without radial edges is accepted when the patch keeps as many "
         "inconsistent faces, not only fewer (it adds the radial edge Fig. 18e gives "
         "every cusp).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-grow",
         "Patch search: grown patches",
         "With patch-search (not in the paper): also try each patch grown by the faces "
         "across its open boundary edges (a wider choice of re-triangulations).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-max-sweeps",
         "Patch search: sweeps",
         "With patch-search (not in the paper): largest number of sweeps over the "
         "inconsistent faces.",
         ParameterType::Int,
         20,
         1,
         10000,
         {}});
    m.addPhase(
        {"patch-search",
         "Extension of §6.4 (not in the paper): around each inconsistent face, one free vertex "
         "(new, or a non-C vertex of the face) sampled over a small patch in parameter space, "
         "the patch re-triangulated around it (fewest inconsistent faces, then the best "
         "minimum Bank-Smith quality), accepted when the patch has strictly fewer inconsistent "
         "faces; no fold, every VBO defined, no new or removed CC edge, no degenerate CC edge, "
         "tagged edges unchanged, C vertices moved only along the contour "
         "(patch-contour-slide), a new radial edge only from a C vertex that lacks one "
         "(patch-new-radial-ends).",
         runPatchSearch, checkPatchSearch});
}

} // namespace contour::consistent
