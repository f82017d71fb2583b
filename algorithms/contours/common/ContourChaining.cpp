#include "contours/common/ContourChaining.h"

#include <algorithm>

namespace contour {

std::vector<Chain> chainSegments(const std::vector<ChainSegment>& segments, Index nodeCount) {
    // Node -> incident segments, in compressed row form.
    std::vector<Index> start(static_cast<size_t>(nodeCount) + 1, 0);
    for (const ChainSegment& s : segments) {
        ++start[s.nodeA + 1];
        ++start[s.nodeB + 1];
    }
    for (Index v = 0; v < nodeCount; ++v)
        start[v + 1] += start[v];
    std::vector<Index> incident(start.back());
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index i = 0; i < static_cast<Index>(segments.size()); ++i) {
        incident[fill[segments[i].nodeA]++] = i;
        incident[fill[segments[i].nodeB]++] = i;
    }
    const auto degree = [&](Index v) {
        return start[v + 1] - start[v];
    };

    std::vector<char> used(segments.size(), 0);
    std::vector<Chain> chains;
    const auto walk = [&](Index node, Index segment, Chain& chain) {
        chain.nodes.push_back(node);
        while (segment != kInvalidIndex && !used[segment]) {
            used[segment] = 1;
            chain.segments.push_back(segment);
            const ChainSegment& s = segments[segment];
            node = s.nodeA == node ? s.nodeB : s.nodeA;
            chain.nodes.push_back(node);
            segment = kInvalidIndex;
            if (degree(node) != 2)
                break;
            for (Index k = start[node]; k < start[node + 1]; ++k)
                if (!used[incident[k]])
                    segment = incident[k];
        }
    };

    // Open chains first: start at every node whose degree is not 2.
    for (Index v = 0; v < nodeCount; ++v) {
        if (degree(v) == 2 || degree(v) == 0)
            continue;
        for (Index k = start[v]; k < start[v + 1]; ++k) {
            if (used[incident[k]])
                continue;
            Chain chain;
            walk(v, incident[k], chain);
            chains.push_back(std::move(chain));
        }
    }
    // What is left runs through degree-2 nodes only: closed loops.
    std::vector<Index> order(segments.size());
    for (Index i = 0; i < static_cast<Index>(order.size()); ++i)
        order[i] = i;
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
        return std::min(segments[a].nodeA, segments[a].nodeB) <
               std::min(segments[b].nodeA, segments[b].nodeB);
    });
    for (Index i : order) {
        if (used[i])
            continue;
        Chain chain;
        const Index v = std::min(segments[i].nodeA, segments[i].nodeB);
        walk(v, i, chain);
        chain.closed = chain.nodes.size() > 2 && chain.nodes.front() == chain.nodes.back();
        if (chain.closed)
            chain.nodes.pop_back();
        chains.push_back(std::move(chain));
    }
    return chains;
}

} // namespace contour
