#include "contours/consistent/edits/CuspEndRetriangulation.h"

#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/edits/RingRetriangulation.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/TriangleQuality.h"

#include <algorithm>
#include <array>
#include <deque>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace contour::consistent {

namespace {

// TriangulationCost with the faces turned over in 3D counted (after the
// inconsistent ones): the disc may keep as many as it had, as the normal
// wiggle lets a face that was turned over stay so.
struct Cost {
    int inconsistent = std::numeric_limits<int>::max();
    int turned = 0;
    double minQuality = -1.0;
    bool valid() const { return inconsistent != std::numeric_limits<int>::max(); }
};
bool better(const Cost& a, const Cost& b) {
    if (!b.valid())
        return a.valid();
    if (!a.valid())
        return false;
    if (a.inconsistent != b.inconsistent)
        return a.inconsistent < b.inconsistent;
    if (a.turned != b.turned)
        return a.turned < b.turned;
    return a.minQuality > b.minQuality;
}
Cost plus(const Cost& a, const Cost& b) {
    if (!a.valid() || !b.valid())
        return {};
    return {a.inconsistent + b.inconsistent, a.turned + b.turned,
            std::min(a.minQuality, b.minQuality)};
}
const Cost kEmpty{0, 0, std::numeric_limits<double>::infinity()};

// The far end of a cusp's radial edge (Fig. 18e).
bool cuspRadialEnd(const ConsistentMesh& m, Index v) {
    for (Index w : m.neighbours(v))
        if (m.vertex(w).cusp && isRadialEdge(m, w, v))
            return true;
    return false;
}

// An edge a disc may have inside: untagged (radial and cusp edges stay),
// not CC (the contour stays) and not at a cusp (a cusp keeps its edges,
// Fig. 18d-e).
bool openEdge(const ConsistentMesh& m, Index a, Index b) {
    return m.edgeTag(a, b) == kNoTag && !m.vertex(a).cusp && !m.vertex(b).cusp &&
           !(m.vertex(a).label == VertexLabel::Contour &&
             m.vertex(b).label == VertexLabel::Contour);
}

struct Disc {
    std::vector<Index> faces; // sorted
    std::vector<Index> ring;  // counter-clockwise outline
};

class DiscSearch {
public:
    explicit DiscSearch(const ConsistentMesh& m) : m_(m), edit_(m) {}

    // Outline of the faces, when they form a disc whose vertices all lie on
    // it.
    std::optional<Disc> disc(const std::vector<Index>& faces) const {
        Disc d{faces, outline(m_, faces)};
        if (d.ring.size() != faces.size() + 2)
            return std::nullopt;
        return d;
    }

    // The best triangulation of the disc's outline (dynamic programme over
    // the polygon), and through `out` its triangles.
    Cost best(const Disc& d, std::vector<Triangle>* out) {
        const int k = static_cast<int>(d.ring.size());
        std::vector<std::vector<Cost>> cost(k, std::vector<Cost>(k));
        std::vector<std::vector<int>> split(k, std::vector<int>(k, -1));
        for (int i = 0; i + 1 < k; ++i)
            cost[i][i + 1] = kEmpty;
        for (int len = 2; len < k; ++len)
            for (int i = 0; i + len < k; ++i) {
                const int j = i + len;
                if (!(i == 0 && j == k - 1) && !diagonal(d, d.ring[i], d.ring[j]))
                    continue;
                for (int s = i + 1; s < j; ++s) {
                    const Cost sub = plus(cost[i][s], cost[s][j]);
                    if (!sub.valid())
                        continue;
                    const Cost c = plus(sub, triangle(d, {d.ring[i], d.ring[s], d.ring[j]}));
                    if (better(c, cost[i][j])) {
                        cost[i][j] = c;
                        split[i][j] = s;
                    }
                }
            }
        if (out) {
            out->clear();
            if (cost[0][k - 1].valid())
                collect(d, split, 0, k - 1, *out);
        }
        return cost[0][k - 1];
    }

    // The disc's faces as they are.
    Cost current(const Disc& d) {
        Cost c = kEmpty;
        edit_.clear();
        for (Index f : d.faces) {
            const Triangle& t = m_.face(f);
            c = plus(c, {edit_.consistent(t) ? 0 : 1, edit_.turnedOver(t) ? 1 : 0,
                         bankSmithQuality(m_.vertex(t[0]).position, m_.vertex(t[1]).position,
                                          m_.vertex(t[2]).position)});
        }
        return c;
    }

private:
    const ConsistentMesh& m_;
    LocalEdit edit_;

    static bool inside(const std::vector<Index>& faces, Index f) {
        return f != kInvalidIndex && std::binary_search(faces.begin(), faces.end(), f);
    }

    // A diagonal a-b: not an edge of the mesh outside the disc, not at a
    // cusp (a cusp keeps its valence, Fig. 18d-e), neither CC nor FB.
    bool diagonal(const Disc& d, Index a, Index b) const {
        const Index f1 = m_.faceOfHalfedge(a, b), f2 = m_.faceOfHalfedge(b, a);
        if ((f1 != kInvalidIndex || f2 != kInvalidIndex) &&
            !(inside(d.faces, f1) && inside(d.faces, f2)))
            return false;
        if (m_.vertex(a).cusp || m_.vertex(b).cusp)
            return false;
        const int la = static_cast<int>(m_.vertex(a).label),
                  lb = static_cast<int>(m_.vertex(b).label);
        return !(la == 0 && lb == 0) && la * lb >= 0;
    }

    // A triangle of the re-triangulation: defined VBO, not turned over in
    // 3D, counter-clockwise in every common chart, and no degenerate CC edge
    // with the face beyond the outline (Definition 3).
    Cost triangle(const Disc& d, const Triangle& t) {
        const Vbo vbo = edit_.vbo(t);
        if (vbo == Vbo::Undefined)
            return {};
        const std::optional<int> o = m_.parameterOrientation(
            {m_.vertex(t[0]).preimage, m_.vertex(t[1]).preimage, m_.vertex(t[2]).preimage});
        if (!o || *o <= 0)
            return {};
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            if (m_.vertex(a).label != VertexLabel::Contour ||
                m_.vertex(b).label != VertexLabel::Contour)
                continue;
            const Index beyond = m_.faceOfHalfedge(b, a);
            if (beyond != kInvalidIndex && !inside(d.faces, beyond) &&
                isDegenerateEdge(m_.vertex(a).label, m_.vertex(b).label, vbo,
                                 edit_.vbo(m_.face(beyond))))
                return {};
        }
        return {edit_.consistent(t) ? 0 : 1, edit_.turnedOver(t) ? 1 : 0,
                bankSmithQuality(m_.vertex(t[0]).position, m_.vertex(t[1]).position,
                                 m_.vertex(t[2]).position)};
    }

    void collect(const Disc& d, const std::vector<std::vector<int>>& split, int i, int j,
                 std::vector<Triangle>& out) const {
        if (j - i < 2)
            return;
        const int s = split[i][j];
        out.push_back({d.ring[i], d.ring[s], d.ring[j]});
        collect(d, split, i, s, out);
        collect(d, split, s, j, out);
    }
};

// The inner edges of the plan's current faces, sorted (a state of the
// breadth-first search over flips).
std::vector<std::array<Index, 2>> innerEdges(const RingRetriangulation& r,
                                             const std::vector<Index>& slots) {
    std::vector<std::array<Index, 2>> all;
    for (Index f : slots) {
        const Triangle& t = r.face(f);
        for (int i = 0; i < 3; ++i)
            all.push_back({std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])});
    }
    std::sort(all.begin(), all.end());
    std::vector<std::array<Index, 2>> inner;
    for (size_t i = 0; i + 1 < all.size(); ++i)
        if (all[i] == all[i + 1])
            inner.push_back(all[i]);
    return inner;
}

// Flips turning the disc's faces into `target`, planned breadth first (a
// disc of at most a few faces has few triangulations); nothing when the
// mesh would refuse every sequence.
std::optional<RingRetriangulation> plan(const ConsistentMesh& m, const Disc& d,
                                        const std::vector<Triangle>& target) {
    std::deque<RingRetriangulation> queue{RingRetriangulation(m, d.faces)};
    std::set<std::vector<std::array<Index, 2>>> seen{innerEdges(queue.front(), d.faces)};
    constexpr size_t kMaxStates = 5000;
    while (!queue.empty() && seen.size() < kMaxStates) {
        RingRetriangulation r = std::move(queue.front());
        queue.pop_front();
        if (r.endsIn(target))
            return r;
        for (const auto& [a, b] : innerEdges(r, d.faces)) {
            RingRetriangulation next = r;
            if (!next.flipEdge(a, b))
                continue;
            if (seen.insert(innerEdges(next, d.faces)).second)
                queue.push_back(std::move(next));
        }
    }
    return std::nullopt;
}

} // namespace

CuspEndRetriangulationCounts retriangulateAtCuspEnds(const PhaseContext& ctx, ConsistentMesh& m,
                                                     int maxFaces, int phase) {
    CuspEndRetriangulationCounts counts;
    if (maxFaces <= 0)
        return counts;
    // Passes over the faces still inconsistent, while one gains (a disc
    // applied may open another).
    for (int pass = 0; pass < 100; ++pass) {
        bool progress = false;
        for (Index f : inconsistentFaces(m)) {
            ctx.checkCancelled();
            if (f >= m.faceCount() || faceIsConsistent(m, f))
                continue;
            const Triangle t = m.face(f);
            if (std::none_of(t.begin(), t.end(), [&](Index v) { return cuspRadialEnd(m, v); }))
                continue;
            ++counts.faces;
            DiscSearch search(m);
            // Connected sets of faces holding f, grown one face at a time
            // across open edges, smallest first.
            std::set<std::vector<Index>> seen;
            std::vector<std::vector<Index>> layer{{f}};
            std::optional<Disc> bestDisc;
            std::vector<Triangle> bestFaces;
            int bestGain = 0;
            double bestQuality = -1.0;
            for (int size = 1; size <= maxFaces && !layer.empty(); ++size) {
                std::set<std::vector<Index>> next;
                for (const std::vector<Index>& faces : layer) {
                    if (const std::optional<Disc> d = search.disc(faces)) {
                        std::vector<Triangle> tris;
                        const Cost now = search.current(*d);
                        const Cost c = search.best(*d, &tris);
                        if (c.valid() && c.turned <= now.turned) {
                            const int gain = now.inconsistent - c.inconsistent;
                            if (gain > bestGain ||
                                (gain == bestGain && gain > 0 && c.minQuality > bestQuality)) {
                                bestGain = gain;
                                bestQuality = c.minQuality;
                                bestDisc = d;
                                bestFaces = tris;
                            }
                        }
                    }
                    if (size == maxFaces)
                        continue;
                    for (Index g : faces) {
                        const Triangle u = m.face(g);
                        for (int i = 0; i < 3; ++i) {
                            const Index a = u[i], b = u[(i + 1) % 3];
                            const Index h = m.faceOfHalfedge(b, a);
                            if (h == kInvalidIndex || !openEdge(m, a, b) ||
                                std::binary_search(faces.begin(), faces.end(), h))
                                continue;
                            std::vector<Index> grown = faces;
                            grown.insert(std::upper_bound(grown.begin(), grown.end(), h), h);
                            if (seen.insert(grown).second)
                                next.insert(std::move(grown));
                        }
                    }
                }
                layer.assign(next.begin(), next.end());
            }
            if (!bestDisc)
                continue;
            const std::optional<RingRetriangulation> edits = plan(m, *bestDisc, bestFaces);
            if (!edits)
                continue;
            edits->apply(m, nullptr, phase);
            ++counts.applied;
            progress = true;
        }
        if (!progress)
            break;
    }
    return counts;
}

} // namespace contour::consistent
