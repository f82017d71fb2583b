#pragma once
// Chains curve segments that share endpoints into polylines. Written by hand:
// it is a walk over a graph whose nodes are mesh elements, which no library
// offers in this form.
#include "pipeline/Snapshot.h"

#include <vector>

namespace contour {

// A segment between two nodes (mesh vertices or mesh edges, by id), coming
// from mesh element `element`.
struct ChainSegment {
    Index nodeA, nodeB;
    Index element;
};

struct Chain {
    std::vector<Index> nodes;    // n+1 nodes for an open chain of n segments, n for a closed one
    std::vector<Index> segments; // indices into the input segment list, in order
    bool closed = false;
};

// Chains segments through nodes of degree 2; a chain stops at nodes of any
// other degree (ends of open curves, or bifurcations where three or more
// segments meet). Each segment is used exactly once. Closed chains start at
// their smallest node, so the result is deterministic.
std::vector<Chain> chainSegments(const std::vector<ChainSegment>& segments, Index nodeCount);

} // namespace contour
