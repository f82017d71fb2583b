#pragma once
// Visibility of consistent contours (Bénard, Hertzmann & Kass 2014 §8.4):
// on a consistent mesh the per-chain ray test is not reliable next to the
// inconsistent faces that remain after the optimisation, so each segment is
// tested on its own, the tests next to inconsistencies or cusps are marked
// ambiguous, the chain takes the majority of the others, and the chains left
// ambiguous are resolved from their neighbours in the view graph.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/ViewGraph.h"

#include <cstdint>
#include <vector>

namespace contour {

class RayCaster;
struct RayResult;

struct ConsistentVisibilityOptions {
    // Footnote 3's reliability threshold of the near-face test: an interior
    // (concave) contour segment whose |v·(w1 − w2)| is below it is not
    // assumed invisible but ray-tested (§8.4 makes the same exception next
    // to cusps, for the same reason).
    double nearFaceEpsilon;
    // §8.4 rule (b): a chain between two T-junctions shorter than this (in
    // pixels) takes the visibility of its visible mates.
    double shortChainPixels;
    // Not in the paper: on a graph whose curtain folds are the surface's
    // cusps, propagation is exact where the mesh is consistent. A chain whose
    // propagation component holds no inconsistent face, no near-face
    // fallback fold and no disagreement (ray check, bound, cycle) keeps its
    // propagated QI; the §8.4 votes decide the other components.
    bool keepCleanPropagation = false;
};

// How resolveConsistentVisibility decided the chains.
struct ConsistentVisibilityStats {
    long long keptFromPropagation = 0; // chains of clean components
    long long voted = 0;               // chains decided by the §8.4 votes
};

// Bénard 2014 §8.4 on a built graph (chains/nodes typed, QI from propagation already set).
// Per-segment ray tests, ambiguity, majority vote, rules (a)-(c), cusp consistency. The
// final chain.qi / decidedBy / ambiguous come from here; where it disagrees with the
// propagated QI, a VisibilityConflict is appended (reason "consistent-vote").
// middleRays (optional, per chain): rays already cast from the midpoint of
// each chain's middle segment ignoring its faces (propagateQi /
// checkChainsWithRays); the vote of that segment reuses the ray instead of
// casting it again. The result is the same; graph.rayTests counts the rays
// cast.
void resolveConsistentVisibility(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                                 const RayCaster& rays,
                                 const std::vector<std::uint8_t>& faceInconsistent,
                                 const std::vector<std::uint8_t>& vertexIsCusp,
                                 const ConsistentVisibilityOptions& options,
                                 const std::vector<RayResult>* middleRays = nullptr,
                                 ConsistentVisibilityStats* stats = nullptr);

} // namespace contour
