// Topological simplification (Bénard, Hertzmann & Kass 2014 §9, Fig. 24).
//
// Definitions used here (the paper states them in one paragraph):
// - node classes count visible chains only (ViewGraph::nodeClass): dead-end
//   1, connector 2, junction 3 or more; a chain that starts and ends at the
//   same node counts twice there;
// - a candidate is a maximal run of visible chains joined at connector nodes
//   (so no junction inside), or a closed chain, whose summed image length is
//   below the threshold; an open chain end without a node counts as a
//   dead-end;
// - rule (d) "overlapped in 2D by another chain": every sample point of the
//   run (its image points plus points every kSampleSpacing pixels) lies
//   within kOverlapPixels of a visible chain outside the run.
// Candidates are taken shortest first and each one is re-checked against
// the current graph just before it is hidden, so one hide can change the
// class of a node used by the next candidate; passes repeat until one
// changes nothing (the fixed point of §9).
#include "visibility/TopologicalSimplification.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace contour {

namespace {

constexpr double kOverlapPixels = 1.0; // "overlapped in 2D": within a pixel
constexpr double kSampleSpacing = 0.5; // sampling of a run for rule (d)

enum class Rule { None, JunctionDeadEnd, DeadEndDeadEnd, Loop, Overlapped };

struct Run {
    std::vector<Index> chains;
    Index startNode = kInvalidIndex; // kInvalidIndex: an open end without a node
    Index endNode = kInvalidIndex;
    bool closed = false; // a loop through connectors only, or a closed chain
    double length = 0.0;
};

// Visible-chain neighbourhood of a node: the other chain end when the node is
// a connector (exactly two visible chain ends), else nothing.
Index otherVisibleChain(const ViewGraph& g, Index node, Index chain, bool* twice) {
    Index other = kInvalidIndex;
    int count = 0;
    for (Index c : g.nodes[node].chains) {
        if (!g.chains[c].visible())
            continue;
        ++count;
        if (c != chain)
            other = c;
    }
    *twice = false;
    if (count != 2)
        return kInvalidIndex;
    if (other == kInvalidIndex) { // the chain itself, at both of its ends
        *twice = true;
        return chain;
    }
    return other;
}

// The node at the far end of `chain` when entering it at `node`.
Index farNode(const ViewChain& c, Index node) {
    return c.startNode == node ? c.endNode : c.startNode;
}

// The maximal run of visible chains through connector nodes containing
// `seed` (a visible chain).
Run runThrough(const ViewGraph& g, Index seed) {
    Run run;
    const ViewChain& s = g.chains[seed];
    run.chains.push_back(seed);
    if (s.closed || (s.startNode == kInvalidIndex && s.endNode == kInvalidIndex)) {
        run.closed = s.closed;
        run.length = s.lengthPixels;
        return run;
    }
    // Walk from one end of the seed, then from the other.
    std::unordered_set<Index> inRun{seed};
    std::vector<Index> before; // chains walked from the start side, nearest first
    auto walk = [&](Index node, Index chain, std::vector<Index>& out) -> Index {
        // Returns the run's end node on this side, or kInvalidIndex (open end).
        while (node != kInvalidIndex) {
            bool twice = false;
            const Index next = otherVisibleChain(g, node, chain, &twice);
            if (next == kInvalidIndex || twice)
                return node; // dead-end or junction (or a self-loop at a connector)
            if (inRun.count(next)) {
                run.closed = true; // back to the run: a loop through connectors
                return node;
            }
            inRun.insert(next);
            out.push_back(next);
            node = farNode(g.chains[next], node);
            chain = next;
        }
        return kInvalidIndex;
    };
    run.startNode = walk(s.startNode, seed, before);
    if (run.closed) {
        run.endNode = run.startNode;
        run.chains.insert(run.chains.end(), before.begin(), before.end());
    } else {
        std::vector<Index> after;
        run.endNode = walk(s.endNode, seed, after);
        run.chains.assign(before.rbegin(), before.rend());
        run.chains.push_back(seed);
        run.chains.insert(run.chains.end(), after.begin(), after.end());
    }
    for (Index c : run.chains)
        run.length += g.chains[c].lengthPixels;
    return run;
}

ViewNodeClass endClass(const ViewGraph& g, Index node) {
    return node == kInvalidIndex ? ViewNodeClass::DeadEnd : g.nodeClass(node);
}

// A uniform grid of every chain's image segments, to find nearby chains.
class SegmentGrid {
public:
    explicit SegmentGrid(const ViewGraph& g) : g_(g) {
        for (Index c = 0; c < static_cast<Index>(g.chains.size()); ++c)
            for (size_t i = 0; i + 1 < g.chains[c].image.size(); ++i) {
                const Vec2 &a = g.chains[c].image[i], &b = g.chains[c].image[i + 1];
                const Vec2 lo = (a.cwiseMin(b).array() - kOverlapPixels).matrix();
                const Vec2 hi = (a.cwiseMax(b).array() + kOverlapPixels).matrix();
                for (long x = cell(lo.x()); x <= cell(hi.x()); ++x)
                    for (long y = cell(lo.y()); y <= cell(hi.y()); ++y)
                        cells_[key(x, y)].push_back({c, static_cast<Index>(i)});
            }
    }

    // Whether p lies within kOverlapPixels of a visible chain not in `exclude`.
    bool covered(const Vec2& p, const std::unordered_set<Index>& exclude) const {
        const auto it = cells_.find(key(cell(p.x()), cell(p.y())));
        if (it == cells_.end())
            return false;
        for (const auto& [c, i] : it->second) {
            if (exclude.count(c) || !g_.chains[c].visible())
                continue;
            const Vec2 &a = g_.chains[c].image[i], &b = g_.chains[c].image[i + 1];
            const Vec2 ab = b - a;
            const double len2 = ab.squaredNorm();
            const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
            if ((a + t * ab - p).norm() <= kOverlapPixels)
                return true;
        }
        return false;
    }

private:
    static constexpr double kCell = 4.0;
    static long cell(double x) { return static_cast<long>(std::floor(x / kCell)); }
    static long long key(long x, long y) {
        return (static_cast<long long>(x) << 32) ^ static_cast<long long>(y & 0xffffffffL);
    }
    const ViewGraph& g_;
    std::unordered_map<long long, std::vector<std::pair<Index, Index>>> cells_;
};

bool overlapped(const ViewGraph& g, const Run& run, const SegmentGrid& grid) {
    const std::unordered_set<Index> exclude(run.chains.begin(), run.chains.end());
    bool any = false;
    for (Index c : run.chains) {
        const std::vector<Vec2>& im = g.chains[c].image;
        for (size_t i = 0; i < im.size(); ++i) {
            any = true;
            if (!grid.covered(im[i], exclude))
                return false;
            if (i + 1 == im.size())
                break;
            const double len = (im[i + 1] - im[i]).norm();
            const int steps = static_cast<int>(std::ceil(len / kSampleSpacing));
            for (int k = 1; k < steps; ++k)
                if (!grid.covered(im[i] + (im[i + 1] - im[i]) * (double(k) / steps), exclude))
                    return false;
        }
    }
    return any; // a run without image points is never "overlapped"
}

// Which of §9's rules hides this run now (Rule::None if it is no candidate).
Rule ruleFor(const ViewGraph& g, const Run& run, double threshold, const SegmentGrid& grid) {
    if (!(run.length < threshold))
        return Rule::None;
    if (run.closed || (run.startNode != kInvalidIndex && run.startNode == run.endNode))
        return Rule::Loop; // (c): a vertex to itself
    const ViewNodeClass a = endClass(g, run.startNode), b = endClass(g, run.endNode);
    if (a == ViewNodeClass::DeadEnd && b == ViewNodeClass::DeadEnd)
        return Rule::DeadEndDeadEnd; // (b)
    if ((a == ViewNodeClass::DeadEnd && b == ViewNodeClass::Junction) ||
        (a == ViewNodeClass::Junction && b == ViewNodeClass::DeadEnd))
        return Rule::JunctionDeadEnd; // (a)
    if (overlapped(g, run, grid))
        return Rule::Overlapped; // (d)
    return Rule::None;
}

} // namespace

SimplificationResult simplifyViewGraph(ViewGraph& graph, double thresholdPixels) {
    SimplificationResult result;
    if (!(thresholdPixels > 0.0))
        return result;
    const SegmentGrid grid(graph); // geometry does not change; visibility is read live
    for (;;) {
        ++result.iterations;
        // Every candidate run of this pass, shortest first.
        std::vector<Run> runs;
        std::vector<std::uint8_t> seen(graph.chains.size(), 0);
        for (Index c = 0; c < static_cast<Index>(graph.chains.size()); ++c) {
            if (seen[c] || !graph.chains[c].visible())
                continue;
            Run run = runThrough(graph, c);
            for (Index r : run.chains)
                seen[r] = 1;
            if (run.length < thresholdPixels)
                runs.push_back(std::move(run));
        }
        std::stable_sort(runs.begin(), runs.end(),
                         [](const Run& a, const Run& b) { return a.length < b.length; });
        int hidden = 0;
        for (const Run& candidate : runs) {
            // Re-check against the current graph: an earlier hide of this pass
            // may have changed the run or its end classes.
            bool allVisible = true;
            for (Index c : candidate.chains)
                allVisible = allVisible && graph.chains[c].visible();
            if (!allVisible)
                continue;
            const Run now = runThrough(graph, candidate.chains.front());
            if (ruleFor(graph, now, thresholdPixels, grid) == Rule::None)
                continue;
            for (Index c : now.chains)
                graph.chains[c].simplifiedAway = true;
            result.chainsHidden += static_cast<int>(now.chains.size());
            ++hidden;
        }
        if (hidden == 0)
            break;
    }
    return result;
}

} // namespace contour
