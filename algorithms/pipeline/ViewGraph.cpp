#include "pipeline/ViewGraph.h"

namespace contour {

const char* toString(ViewNodeType type) {
    switch (type) {
    case ViewNodeType::CurtainFold:
        return "curtain-fold";
    case ViewNodeType::BoundaryCurtainFold:
        return "boundary-curtain-fold";
    case ViewNodeType::ImageIntersection:
        return "image-intersection";
    case ViewNodeType::ContourBoundaryJunction:
        return "contour-boundary-junction";
    case ViewNodeType::Bifurcation:
        return "bifurcation";
    case ViewNodeType::SurfaceIntersectionEnd:
        return "surface-intersection-end";
    case ViewNodeType::CurveEnd:
        return "curve-end";
    case ViewNodeType::HiddenFoldCrossing:
        return "hidden-fold-crossing";
    }
    return "unknown";
}

const char* toString(ViewNodeClass nodeClass) {
    switch (nodeClass) {
    case ViewNodeClass::Hidden:
        return "hidden";
    case ViewNodeClass::DeadEnd:
        return "dead-end";
    case ViewNodeClass::Connector:
        return "connector";
    case ViewNodeClass::Junction:
        return "junction";
    }
    return "unknown";
}

const char* toString(VisibilityRule rule) {
    switch (rule) {
    case VisibilityRule::Unknown:
        return "unknown";
    case VisibilityRule::RayTest:
        return "ray-test";
    case VisibilityRule::Propagation:
        return "propagation";
    case VisibilityRule::ImageIntersection:
        return "image-intersection";
    case VisibilityRule::CurtainFold:
        return "curtain-fold";
    case VisibilityRule::ConcaveContour:
        return "concave-contour";
    case VisibilityRule::BackFace:
        return "back-face";
    case VisibilityRule::MajorityVote:
        return "majority-vote";
    case VisibilityRule::AmbiguityCusps:
        return "ambiguity-cusps";
    case VisibilityRule::AmbiguityShortChain:
        return "ambiguity-short-chain";
    case VisibilityRule::AmbiguityBoundary:
        return "ambiguity-boundary";
    case VisibilityRule::CuspConsistency:
        return "cusp-consistency";
    case VisibilityRule::AmbiguousInvisible:
        return "ambiguous-invisible";
    case VisibilityRule::HeuristicVote:
        return "heuristic-vote";
    }
    return "unknown";
}

ViewNodeClass ViewGraph::nodeClass(Index node) const {
    int visibleCount = 0;
    for (Index c : nodes[node].chains)
        if (chains[c].visible())
            ++visibleCount;
    if (visibleCount == 0)
        return ViewNodeClass::Hidden;
    if (visibleCount == 1)
        return ViewNodeClass::DeadEnd;
    if (visibleCount == 2)
        return ViewNodeClass::Connector;
    return ViewNodeClass::Junction;
}

ViewChainTally ViewGraph::chainTally() const {
    ViewChainTally t;
    for (const ViewChain& chain : chains) {
        t.visible += chain.visible();
        t.hidden += !chain.visible() && !chain.simplifiedAway;
        t.simplified += chain.simplifiedAway;
        t.ambiguous += chain.ambiguous;
        t.conflicting += chain.conflict;
        if (chain.simplifiedAway)
            t.simplifiedLengthPixels += chain.lengthPixels;
    }
    return t;
}

double ViewGraph::visibleLengthPixels() const {
    double length = 0.0;
    for (const ViewChain& c : chains)
        if (c.visible())
            length += c.lengthPixels;
    return length;
}

double ViewGraph::hiddenLengthPixels() const {
    double length = 0.0;
    for (const ViewChain& c : chains)
        if (!c.visible())
            length += c.lengthPixels;
    return length;
}

} // namespace contour
