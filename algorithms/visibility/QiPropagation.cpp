#include "visibility/QiPropagation.h"

#include "visibility/RayCaster.h"
#include "visibility/ViewGraphBuilder.h"

#include <algorithm>
#include <deque>
#include <string>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

// qi[to] = qi[from] + delta, decided by `rule`.
struct Link {
    Index to;
    int delta;
    VisibilityRule rule;
    Index node; // the node the link crosses
};

std::vector<std::vector<Link>> links(const ViewGraph& graph) {
    std::vector<std::vector<Link>> adjacency(graph.chains.size());
    Index at = 0; // the node being linked
    auto link = [&](Index a, Index b, int delta, VisibilityRule rule) {
        if (a == kInvalidIndex || b == kInvalidIndex)
            return;
        adjacency[a].push_back({b, delta, rule, at});
        adjacency[b].push_back({a, -delta, rule, at});
    };
    for (; at < static_cast<Index>(graph.nodes.size()); ++at) {
        const ViewNode& node = graph.nodes[at];
        switch (node.type) {
        case ViewNodeType::ImageIntersection:
        case ViewNodeType::HiddenFoldCrossing:
            // Tutorial §4.7: the near curve keeps its QI across the crossing;
            // the far curve's occluded side is +2 behind a contour, +1
            // behind a boundary.
            link(node.nearChains[0], node.nearChains[1], 0, VisibilityRule::Propagation);
            link(node.farChains[0], node.farChains[1], node.qiStep,
                 VisibilityRule::ImageIntersection);
            break;
        case ViewNodeType::CurtainFold:
        case ViewNodeType::BoundaryCurtainFold:
            // Tutorial §4.7: the far (occluded) edge of a curtain fold is at
            // least one deeper than the near one; the step counts the
            // one-ring faces that overlap it.
            if (node.chains.size() == 2) {
                link(node.nearChains[0], node.farChains[1], node.qiStep,
                     VisibilityRule::CurtainFold);
                break;
            }
            [[fallthrough]];
        case ViewNodeType::ContourBoundaryJunction:
        case ViewNodeType::Bifurcation:
            // Tutorial §4.7: at other multi-curve vertices, the QI
            // differences come from local overlap tests.
            if (node.localOccluders.size() == node.chains.size())
                for (size_t i = 1; i < node.chains.size(); ++i)
                    link(node.chains[0], node.chains[i],
                         node.localOccluders[i] - node.localOccluders[0],
                         VisibilityRule::Propagation);
            break;
        case ViewNodeType::SurfaceIntersectionEnd:
        case ViewNodeType::CurveEnd:
            // No local rule relates the chains here: each side is seeded by
            // its own ray test.
            break;
        }
    }
    return adjacency;
}

// The seed of a component: a long chain not known to be occluded.
Index pickSeed(const ViewGraph& graph, const std::vector<Index>& component) {
    Index best = component.front();
    auto key = [&](Index c) {
        const ViewChain& chain = graph.chains[c];
        return std::make_pair(chain.qiLowerBound == 0 && !chain.concave, chain.lengthPixels);
    };
    for (Index c : component)
        if (key(c) > key(best))
            best = c;
    return best;
}

} // namespace

Vec3 chainRayOrigin(const ViewChain& chain) {
    const size_t segments = chain.segmentCount();
    if (segments == 0)
        return chain.points.empty() ? Vec3::Zero() : chain.points.front();
    const size_t middle = segments / 2;
    return 0.5 * (chain.points[middle] + chain.points[middle + 1]);
}

VisibilityConflict conflictOf(const ViewChain& chain, Index c, int propagatedQi, int rayQi,
                              std::string reason) {
    VisibilityConflict k;
    k.chain = c;
    k.propagatedQi = propagatedQi;
    k.rayQi = rayQi;
    k.reason = std::move(reason);
    k.fromChain = chain.propagatedFrom;
    k.viaNode = chain.propagatedVia;
    k.rayOrigin = chainRayOrigin(chain);
    return k;
}

int chainRayQi(const ViewChain& chain, const TriangleMesh& mesh, const Camera& camera,
               const RayCaster& rays, bool exact, std::vector<Index>* hits) {
    const size_t segments = chain.segmentCount();
    if (segments == 0)
        return exact ? rays.exactOccluders(chain.points.front(), camera, {})
                     : rays.occluders(chain.points.front(), camera, {}, hits);
    const size_t middle = segments / 2;
    const Vec3 p = chainRayOrigin(chain);
    const std::vector<Index> ignore = segmentFaces(mesh, chain, middle);
    return exact ? rays.exactOccluders(p, camera, ignore) : rays.occluders(p, camera, ignore, hits);
}

namespace {

// The chain's ray (chainRayQi), kept in middleRays when asked for.
int castAndKeep(const ViewGraph& graph, size_t c, const TriangleMesh& mesh, const Camera& camera,
                const RayCaster& rays, std::vector<RayResult>* middleRays) {
    const ViewChain& chain = graph.chains[c];
    if (!middleRays || chain.segmentCount() == 0)
        return chainRayQi(chain, mesh, camera, rays);
    RayResult& kept = (*middleRays)[c];
    kept.count = chainRayQi(chain, mesh, camera, rays, false, &kept.hits);
    return kept.count;
}

} // namespace

void propagateQi(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                 const RayCaster& rays, QiPropagationStats* statsOut,
                 std::vector<RayResult>* middleRays) {
    if (middleRays)
        middleRays->resize(graph.chains.size());
    QiPropagationStats stats;
    const size_t n = graph.chains.size();
    const std::vector<std::vector<Link>> adjacency = links(graph);

    // Connected components of the propagation links.
    std::vector<Index> component(n, kInvalidIndex);
    std::vector<std::vector<Index>> components;
    for (size_t start = 0; start < n; ++start) {
        if (component[start] != kInvalidIndex)
            continue;
        const auto id = static_cast<Index>(components.size());
        components.emplace_back();
        std::deque<Index> queue{static_cast<Index>(start)};
        component[start] = id;
        while (!queue.empty()) {
            const Index c = queue.front();
            queue.pop_front();
            components.back().push_back(c);
            graph.chains[c].component = id;
            for (const Link& l : adjacency[c])
                if (component[l.to] == kInvalidIndex) {
                    component[l.to] = id;
                    queue.push_back(l.to);
                }
        }
    }
    stats.components = static_cast<long long>(components.size());

    // One ray per component (tutorial §4.7 algorithm, step 2).
    std::vector<Index> seeds(components.size());
    std::vector<int> seedQi(components.size());
    for (size_t k = 0; k < components.size(); ++k)
        seeds[k] = pickSeed(graph, components[k]);
    tbb::parallel_for(size_t(0), components.size(), [&](size_t k) {
        seedQi[k] =
            castAndKeep(graph, static_cast<size_t>(seeds[k]), mesh, camera, rays, middleRays);
    });
    stats.seedRays = static_cast<long long>(components.size());

    // Step 3: propagate through each component.
    std::vector<int> raw(n, 0);
    std::vector<std::uint8_t> reached(n, 0);
    for (size_t k = 0; k < components.size(); ++k) {
        const Index seed = seeds[k];
        raw[seed] = seedQi[k];
        reached[seed] = 1;
        graph.chains[seed].decidedBy = VisibilityRule::RayTest;
        graph.chains[seed].rayQi = seedQi[k];
        std::deque<Index> queue{seed};
        while (!queue.empty()) {
            const Index c = queue.front();
            queue.pop_front();
            for (const Link& l : adjacency[c]) {
                const int value = raw[c] + l.delta;
                if (!reached[l.to]) {
                    reached[l.to] = 1;
                    raw[l.to] = value;
                    graph.chains[l.to].decidedBy = l.rule;
                    graph.chains[l.to].propagatedFrom = c;
                    graph.chains[l.to].propagatedVia = l.node;
                    queue.push_back(l.to);
                } else if (raw[l.to] != value) {
                    ++stats.cycleDisagreements;
                    graph.chains[c].cycleDisagreement = true;
                    graph.chains[l.to].cycleDisagreement = true;
                }
            }
        }
    }
    // Each link was seen from both ends.
    stats.cycleDisagreements /= 2;

    for (size_t c = 0; c < n; ++c) {
        ViewChain& chain = graph.chains[c];
        chain.qi = raw[c];
        if (raw[c] < chain.qiLowerBound) {
            // QI cannot be below a known bound (never negative; concave
            // contours ≥ 1): the propagation met an error on its way. The
            // bound is kept and the disagreement reported.
            ++stats.belowLowerBound;
            chain.qi = chain.qiLowerBound;
            chain.conflict = true;
            graph.conflicts.push_back(conflictOf(chain, static_cast<Index>(c), raw[c], chain.rayQi,
                                                 "propagated QI " + std::to_string(raw[c]) +
                                                     " below the lower bound " +
                                                     std::to_string(chain.qiLowerBound)));
        }
    }

    graph.rayTests += stats.seedRays;
    if (statsOut)
        *statsOut = stats;
}

void checkChainsWithRays(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                         const RayCaster& rays, const std::string& decidedBy,
                         QiPropagationStats* stats, std::vector<RayResult>* middleRays) {
    const size_t n = graph.chains.size();
    if (middleRays)
        middleRays->resize(n);
    std::vector<int> check(n, -1);
    tbb::parallel_for(size_t(0), n, [&](size_t c) {
        if (graph.chains[c].decidedBy != VisibilityRule::RayTest)
            check[c] = castAndKeep(graph, c, mesh, camera, rays, middleRays);
    });
    long long tested = 0, recounts = 0;
    for (size_t c = 0; c < n; ++c) {
        if (check[c] < 0)
            continue;
        ++tested;
        ViewChain& chain = graph.chains[c];
        if (check[c] != chain.qi) {
            // A float ray that grazes a fold edge can slip past it: before
            // reporting, recount the same ray exactly.
            ++recounts;
            const int exact = chainRayQi(chain, mesh, camera, rays, true);
            stats->correctedRays += exact != check[c];
            check[c] = exact;
        }
        chain.rayQi = check[c];
        if (check[c] != chain.qi) {
            ++stats->rayConflicts;
            chain.conflict = true;
            graph.conflicts.push_back(
                conflictOf(chain, static_cast<Index>(c), chain.qi, check[c],
                           "ray-check: the chain's own ray test disagrees with " + decidedBy));
        }
    }
    // Roots: the source of the disagreeing step passed its own check.
    for (VisibilityConflict& k : graph.conflicts)
        if (k.reason.rfind("ray-check", 0) == 0 &&
            (k.fromChain == kInvalidIndex || !graph.chains[k.fromChain].conflict)) {
            k.root = true;
            ++stats->rootConflicts;
        }
    stats->checkRays += tested;
    stats->exactRecounts += recounts;
    graph.rayTests += tested + recounts;
}

} // namespace contour
