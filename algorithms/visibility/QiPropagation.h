#pragma once
// Quantitative invisibility by propagation (tutorial §4.6–4.7, after Appel
// 1967 and Markosian 1997): one ray test per connected piece of the view
// graph, then QI carried through its nodes: equal across a node without a
// singularity, + the node's step behind a T-junction or a curtain fold, the
// local one-ring counts at Y junctions and bifurcations. checkChainsWithRays
// then ray-tests every chain and keeps each disagreement as a conflict.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/ViewGraph.h"

#include <string>

namespace contour {

class RayCaster;
struct RayResult;

struct QiPropagationStats {
    long long components = 0;
    long long seedRays = 0;
    long long checkRays = 0;
    long long cycleDisagreements = 0; // a chain reached twice with different QI
    long long belowLowerBound = 0;    // propagated QI below the chain's known bound
    long long rayConflicts = 0;       // check rays that disagree with propagation
    long long rootConflicts = 0;      // ... whose source agrees with its own ray
    long long exactRecounts = 0;      // disagreeing check rays recounted exactly
    long long correctedRays = 0;      // ... whose exact count differed from Embree's
};

// Where chainRayQi's ray starts: the midpoint of the chain's middle segment.
Vec3 chainRayOrigin(const ViewChain& chain);
// A conflict on chain c with its propagation step (the chain's propagatedFrom
// and propagatedVia) and the origin of its ray.
VisibilityConflict conflictOf(const ViewChain& chain, Index c, int propagatedQi, int rayQi,
                              std::string reason);

// The QI of a chain from one ray: the midpoint of its middle segment,
// ignoring the faces adjacent to that segment's element (tutorial app. C.1).
// exact: count with RayCaster::exactOccluders (every face, exact predicates).
// hits (not with exact): the faces hit, as RayCaster::occluders returns them.
int chainRayQi(const ViewChain& chain, const TriangleMesh& mesh, const Camera& camera,
               const RayCaster& rays, bool exact = false, std::vector<Index>* hits = nullptr);

// middleRays, when given, receives per chain (resized to the chain count;
// untouched where no ray was cast) the Embree ray of chainRayQi from the
// midpoint of the chain's middle segment: Bénard 2014 §8.4's per-segment
// votes cast that same ray (resolveConsistentVisibility takes them, so each
// is cast once). Chains without a segment are left out.

// Ray-tests every chain not decided by a ray and records each disagreement
// with its QI as a conflict (reason names `decidedBy`); the chain keeps its
// QI and gets rayQi and the conflict flag.
void checkChainsWithRays(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                         const RayCaster& rays, const std::string& decidedBy,
                         QiPropagationStats* stats, std::vector<RayResult>* middleRays = nullptr);

void propagateQi(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                 const RayCaster& rays, QiPropagationStats* stats = nullptr,
                 std::vector<RayResult>* middleRays = nullptr);

} // namespace contour
