#pragma once
// Topological simplification of the visible view graph (Bénard, Hertzmann &
// Kass 2014 §9): small visible chains that make the drawing noisy (tiny
// spurs, specks and loops, chains drawn twice) are hidden. Only
// ViewChain::simplifiedAway is set, so the result is reversible.
#include "pipeline/ViewGraph.h"

namespace contour {

struct SimplificationResult {
    int iterations = 0;
    int chainsHidden = 0;
};

// Bénard 2014 §9, rules (a)-(d), iterated to a fixed point; sets chain.simplifiedAway.
SimplificationResult simplifyViewGraph(ViewGraph& graph, double thresholdPixels);

} // namespace contour
