#include "contours/consistent/edits/PatchSearch.h"

#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/edits/RingRetriangulation.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/TriangleQuality.h"
#include "contours/consistent/predicates/TriangulationCost.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

namespace contour::consistent {

namespace {

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
    // A C vertex slid along the contour (contourSlide): x stays on g = 0
    // and joined to both contour neighbours (its CC edges stay).
    bool onContour = false;
    std::array<Index, 2> contourNeighbours{kInvalidIndex, kInvalidIndex};
    // newRadialEnds: x lies on the radial plane of `partner`, a C vertex
    // with fewer than two radial edges, and the edge partner-x becomes
    // radial (x the far end of a new radial edge).
    bool newRadial = false;
    // newRadialCusps: the one cusp without radial edges on the ring
    // (kInvalidIndex: none). Such a patch is searched only as a new radial
    // end of that cusp: the new radial edge lets its valence change.
    Index lockedCusp = kInvalidIndex;
};

// The bounding box of the mesh's vertices and the vertices on each of its
// sides: a vertex on a side may move inside while another one keeps the
// side where it is, so that no move changes the box.
class BoxSides {
public:
    explicit BoxSides(const ConsistentMesh& m) {
        min_ = Vec3::Constant(std::numeric_limits<double>::infinity());
        max_ = -min_;
        for (Index v = 0; v < m.vertexCount(); ++v) {
            min_ = min_.cwiseMin(m.vertex(v).position);
            max_ = max_.cwiseMax(m.vertex(v).position);
        }
        for (Index v = 0; v < m.vertexCount(); ++v)
            for (int d = 0; d < 3; ++d) {
                atMin_[d] += m.vertex(v).position[d] == min_[d];
                atMax_[d] += m.vertex(v).position[d] == max_[d];
            }
    }

    // A vertex at p may leave its place without changing the box.
    bool keeps(const Vec3& p) const {
        for (int d = 0; d < 3; ++d)
            if ((p[d] <= min_[d] && atMin_[d] < 2) || (p[d] >= max_[d] && atMax_[d] < 2))
                return false;
        return true;
    }
    bool inside(const Vec3& p) const {
        for (int d = 0; d < 3; ++d)
            if (!(p[d] > min_[d] && p[d] < max_[d]))
                return false;
        return true;
    }
    // A vertex leaves `from` (for a point inside the box).
    void leave(const Vec3& from) {
        for (int d = 0; d < 3; ++d) {
            atMin_[d] -= from[d] == min_[d];
            atMax_[d] -= from[d] == max_[d];
        }
    }

private:
    Vec3 min_, max_;
    std::array<int, 3> atMin_{0, 0, 0}, atMax_{0, 0, 0};
};

// Growth: the candidate patches around an inconsistent face, in the order
// they are searched. `set` is read at each call: the late moves switch on
// between the passes.
class PatchGrowth {
public:
    PatchGrowth(const ConsistentMesh& m, const PatchSearchSettings& set, const BoxSides& box)
        : m_(m), set_(set), box_(box) {}

    // lateOnly: the face failed every other move already; only its late
    // moves (slides, new radial ends) are searched.
    std::vector<Patch> candidates(Index f, bool lateOnly) const {
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
        return patches;
    }

private:
    const ConsistentMesh& m_;
    const PatchSearchSettings& set_;
    const BoxSides& box_;

    // An edge a patch may have inside: no tag (a radial or cusp edge stays)
    // and not CC (a contour edge stays).
    bool openEdge(Index a, Index b) const {
        return m_.edgeTag(a, b) == kNoTag && !(m_.vertex(a).label == VertexLabel::Contour &&
                                               m_.vertex(b).label == VertexLabel::Contour);
    }

    // Sets p.lockedCusp; false when the ring is too long or has a cusp
    // that must keep its valence.
    bool cornersAllowed(Patch& p) const {
        if (static_cast<int>(p.ring.size()) > set_.maxCorners)
            return false;
        // A corner's valence changes: a cusp keeps the valence 4 of Fig.
        // 18d until it has radial edges (as in edge splitting), unless the
        // move gives it one (newRadialCusps).
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
        p.ring = outline(m_, p.faces);
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
        q.ring = outline(m_, q.faces);
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
            !box_.keeps(x.position))
            return std::nullopt;
        Patch p;
        p.centre = v;
        p.faces = m_.vertexFaces(v);
        p.ring = outline(m_, p.faces);
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

    // newRadialEnds: the variants of patch p whose free vertex x is sampled
    // on the radial plane of a ring corner w that lacks a radial edge (roots
    // of h_w, as for a relocated radial end), with x joined to w and the
    // edge w-x tagged radial once the move is applied. A ring with a cusp
    // without radial edges gives only that cusp's variant; cuspsOnly: only
    // cusps' variants (grown patches).
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
    // edges on its outside region, Fig. 18e) only with newRadialCusps:
    // radial insertion skips a cusp whose outside region it cannot
    // identify, and its valence-4 fan (Fig. 18d) can then have too few
    // corners on one side to wrap around the cusp's image.
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
            m_.isBoundaryVertex(v) || !box_.keeps(x.position))
            return std::nullopt;
        Patch p;
        p.centre = v;
        p.onContour = true;
        p.faces = m_.vertexFaces(v);
        p.ring = outline(m_, p.faces);
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
};

// Re-triangulation of one patch around x: the pockets (the ring's chains
// closed by a diagonal, triangulated without x, independent of x) and the
// fan of x over the ring's corners that, with the pockets under it, costs
// least.
class PatchTriangulation {
public:
    // Pockets: best[i][len] triangulates the ring's chain i .. i+len
    // (indices modulo k) closed by the diagonal ring[i]-ring[i+len];
    // len = 1 is a ring edge (no face).
    struct Pockets {
        std::vector<std::vector<Cost>> best;
        std::vector<std::vector<int>> split;
    };

    PatchTriangulation(const ConsistentMesh& m, const Patch& p) : m_(m), p_(p) {}

    // full: also the 3D and parameter-space orientation of every triangle
    // and the quality (else the labels alone, a lower bound).
    Pockets pockets(const LocalEdit& e, bool full) const {
        const int k = static_cast<int>(p_.ring.size());
        Pockets out;
        out.best.assign(k, std::vector<Cost>(k));
        out.split.assign(k, std::vector<int>(k, -1));
        for (int i = 0; i < k; ++i)
            out.best[i][1] = kEmpty;
        for (int len = 2; len <= k - 2; ++len)
            for (int i = 0; i < k; ++i) {
                const int j = (i + len) % k;
                if (!diagonalAllowed(p_.ring[i], p_.ring[j]))
                    continue;
                for (int s = 1; s < len; ++s) {
                    const Cost sub = plus(out.best[i][s], out.best[(i + s) % k][len - s]);
                    if (!sub.valid())
                        continue;
                    const Cost c = plus(
                        sub, triangle(e, {p_.ring[i], p_.ring[(i + s) % k], p_.ring[j]}, full));
                    if (better(c, out.best[i][len])) {
                        out.best[i][len] = c;
                        out.split[i][len] = s;
                    }
                }
            }
        return out;
    }

    // Best fan of x (vertex xi of e) over the ring, with the pockets q:
    // cost and, through `fan`, the fan corners (ring indices, increasing).
    Cost bestFan(const LocalEdit& e, Index xi, const Pockets& q, bool full,
                 std::vector<int>* fan) const {
        const int k = static_cast<int>(p_.ring.size());
        // seg[i][len]: fan face x-ring[i]-ring[i+len] and the pocket under it.
        std::vector<std::vector<Cost>> seg(k, std::vector<Cost>(k));
        // A radial end's partner, a slid C vertex's contour neighbours stay
        // joined to x: no fan face passes over them.
        std::vector<int> required;
        for (Index w : {p_.partner, p_.contourNeighbours[0], p_.contourNeighbours[1]})
            if (const auto at = std::find(p_.ring.begin(), p_.ring.end(), w); at != p_.ring.end())
                required.push_back(static_cast<int>(at - p_.ring.begin()));
        for (int i = 0; i < k; ++i)
            for (int len = 1; len <= k - 2; ++len) {
                if (!q.best[i][len].valid())
                    continue;
                if (std::any_of(required.begin(), required.end(), [&](int r) {
                        return (r - i + k) % k > 0 && (r - i + k) % k < len;
                    }))
                    continue;
                seg[i][len] = plus(q.best[i][len],
                                   triangle(e, {xi, p_.ring[i], p_.ring[(i + len) % k]}, full));
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

    // The triangles of the fan (corners as bestFan gives them) over the
    // pockets q: each fan face x-ring[i]-ring[j], then its pocket.
    std::vector<Triangle> faces(Index xi, const Pockets& q, const std::vector<int>& fan) const {
        std::vector<Triangle> out;
        const int k = static_cast<int>(p_.ring.size());
        for (size_t n = 0; n < fan.size(); ++n) {
            const int i = fan[n], j = fan[(n + 1) % fan.size()];
            const int len = (j - i + k) % k;
            out.push_back({xi, p_.ring[i], p_.ring[j]});
            collect(q, i, len, out);
        }
        return out;
    }

private:
    const ConsistentMesh& m_;
    const Patch& p_;

    // The diagonal a-b of a re-triangulation: not an edge of the mesh
    // outside the patch, and neither a new CC edge nor an FB edge.
    bool diagonalAllowed(Index a, Index b) const {
        const Index f1 = m_.faceOfHalfedge(a, b), f2 = m_.faceOfHalfedge(b, a);
        const auto inPatch = [&](Index f) {
            return std::find(p_.faces.begin(), p_.faces.end(), f) != p_.faces.end();
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

    void collect(const Pockets& q, int i, int len, std::vector<Triangle>& out) const {
        if (len < 2)
            return;
        const int k = static_cast<int>(p_.ring.size());
        const int s = q.split[i][len];
        out.push_back({p_.ring[i], p_.ring[(i + s) % k], p_.ring[(i + len) % k]});
        collect(q, i, s, out);
        collect(q, (i + s) % k, len - s, out);
    }
};

// Where x is tried in a patch: points of the lattice of step 1/rows on the
// patch's faces, or, when x must stay on a radial plane or on the contour,
// the roots between consecutive lattice points. Counts the points and roots
// that could not be placed (no chart, no converged root).
class PatchSamples {
public:
    PatchSamples(const ConsistentMesh& m, const PatchSearchSettings& set, long long& cancelled)
        : m_(m), set_(set), cancelled_(cancelled) {}

    // The lattice points (corners and the patch's own boundary excluded),
    // and v's current position for a relocation (the flips alone).
    std::vector<Preimage> of(const Patch& p) {
        if (p.partner != kInvalidIndex || p.onContour)
            return roots(p);
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
                        ++cancelled_;
                        continue;
                    }
                    const std::optional<Preimage> u =
                        j == 0     ? ra
                        : j == row ? rb
                                   : m_.interpolate(*ra, *rb, static_cast<double>(j) / row);
                    if (u)
                        out.push_back(*u);
                    else
                        ++cancelled_;
                }
            }
        }
        return out;
    }

private:
    const ConsistentMesh& m_;
    const PatchSearchSettings& set_;
    long long& cancelled_;

    // A radial end's samples: its place, and the roots of h_p (p its
    // partner) between consecutive lattice points of each row on the
    // patch's faces (bisection to the radial tolerance), so that x stays on
    // p's radial plane. A slid C vertex's: the roots of g instead, so that
    // x stays on the contour.
    std::vector<Preimage> roots(const Patch& p) {
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
                    ++cancelled_;
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
        ++cancelled_;
        return std::nullopt;
    }
};

// The search around one face at a time: its candidates (PatchGrowth), each
// evaluated at its samples (PatchSamples, PatchTriangulation), the best
// move planned and applied; and the memory of where it failed.
class PatchSearcher {
public:
    // Starts with the late moves off (allowLateMoves()).
    PatchSearcher(ConsistentMesh& m, const PatchSearchSettings& settings, int phase)
        : m_(m), settings_(settings), set_(withoutLateMoves(settings)), phase_(phase), box_(m),
          growth_(m, set_, box_), samples_(m, set_, stats.cancelledSamples) {}
    PatchSearcher(const PatchSearcher&) = delete;
    PatchSearcher& operator=(const PatchSearcher&) = delete;

    PatchSearchStats stats;

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
            if (!lateMoves() || unchangedSince(lateFailedAt_)) {
                ++stats.skipped;
                return false;
            }
            if (!search(f, true)) {
                lateFailedAt_[key] = moves_;
                return false;
            }
            return true;
        }
        if (!search(f, false)) {
            failedAt_[key] = moves_;
            if (lateMoves())
                lateFailedAt_[key] = moves_;
            return false;
        }
        return true;
    }

    // From now on the late moves of the settings are allowed too: C
    // vertices may slide (contourSlide), new radial ends appear
    // (newRadialEnds).
    void allowLateMoves() {
        set_.contourSlide = settings_.contourSlide;
        set_.newRadialEnds = settings_.newRadialEnds;
    }

private:
    struct Best {
        std::optional<Patch> patch;
        MeshVertex x;
        int gain = 0; // inconsistent faces removed
        double minQuality = -1.0;
        std::optional<RingRetriangulation> edits; // the move, planned
    };
    static constexpr Index kX = std::numeric_limits<Index>::max() - 1;

    static PatchSearchSettings withoutLateMoves(PatchSearchSettings s) {
        s.contourSlide = false;
        s.newRadialEnds = false;
        return s;
    }
    bool lateMoves() const { return set_.contourSlide || set_.newRadialEnds; }

    ConsistentMesh& m_;
    const PatchSearchSettings settings_; // as asked
    PatchSearchSettings set_;            // as allowed so far
    int phase_;
    BoxSides box_;
    PatchGrowth growth_;
    PatchSamples samples_;
    // Moves applied so far; per vertex, the move that last changed it or
    // its faces; per face (its sorted corners), the move count when its
    // search last failed.
    long long moves_ = 0;
    std::unordered_map<Index, long long> changedAt_;
    std::map<std::array<Index, 3>, long long> failedAt_;
    // The same for the late moves of a face alone.
    std::map<std::array<Index, 3>, long long> lateFailedAt_;

    bool search(Index f, bool lateOnly) {
        Best best;
        for (const Patch& p : growth_.candidates(f, lateOnly))
            evaluate(p, best);
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

    // Evaluation and acceptance: x at each sample of p, the patch
    // re-triangulated around it (a lower bound from the labels first, then
    // the full cost), the whole edit checked and planned; `best` keeps the
    // largest gain, ties to the larger minimum quality.
    void evaluate(const Patch& p, Best& best) {
        ++stats.patches;
        LocalEdit before(m_);
        before.addFaces(p.faces);
        const int now = before.inconsistent();
        if (now == 0)
            return;
        const PatchTriangulation triangulation(m_, p);
        LocalEdit plain(m_);
        const PatchTriangulation::Pockets cheap = triangulation.pockets(plain, false);
        std::optional<PatchTriangulation::Pockets> full;
        LocalEdit e(m_);
        for (const Preimage& u : samples_.of(p)) {
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
            if (!box_.inside(x.position))
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
            const Cost bound = triangulation.bestFan(e, xi, cheap, false, nullptr);
            // cuspTies: a cusp's first radial edge is worth a move that
            // removes nothing (a tie-break, see the parameter).
            const int minGain = set_.cuspTies && p.lockedCusp != kInvalidIndex ? 0 : 1;
            if (!bound.valid() || now - bound.inconsistent < std::max(best.gain, minGain))
                continue;
            if (!full)
                full = triangulation.pockets(plain, true);
            std::vector<int> fan;
            const Cost c = triangulation.bestFan(e, xi, *full, true, &fan);
            if (!c.valid())
                continue;
            const int gain = now - c.inconsistent;
            if (gain < minGain || gain < best.gain ||
                (gain == best.gain && !(c.minQuality > best.minQuality)))
                continue;
            // The whole edit: degenerate CC edges across the patch's
            // boundary, and every face once more.
            std::vector<Triangle> faces = triangulation.faces(xi, *full, fan);
            const int k = static_cast<int>(p.ring.size());
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
            box_.leave(m_.vertex(xi).position);
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

} // namespace

PatchSearchResult searchPatches(ConsistentMesh& m, const PatchSearchSettings& settings, int phase,
                                const std::function<void()>& checkCancelled) {
    PatchSearcher searcher(m, settings, phase);
    const auto improve = [&](Index f) {
        return searcher.improve(f);
    };
    PatchSearchResult result;
    OptimizationTally& tally = result.faces;
    sweepInconsistent(m, settings.maxSweeps, false, tally, improve, checkCancelled);
    // The late moves only once the other moves are at their fixed point, so
    // that a slide or a new radial end never pre-empts one of them (in
    // competition with them, they left some views one face worse at the
    // method's end).
    if (settings.contourSlide || settings.newRadialEnds) {
        searcher.allowLateMoves();
        OptimizationTally more;
        sweepInconsistent(m, settings.maxSweeps, false, more, improve, checkCancelled);
        tally.tried += more.tried;
        tally.accepted += more.accepted;
        tally.sweeps += more.sweeps;
        tally.sweepLimitHit = more.sweepLimitHit;
    }
    result.moves = searcher.stats;
    return result;
}

} // namespace contour::consistent
