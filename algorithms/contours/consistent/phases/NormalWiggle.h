#pragma once
// Vertex wiggling along the normal (Bénard 2014 §6.4, final step) used
// outside its own phase: the one-vertex sweeps run again after the cusps'
// final push (CuspEndPushPhase.cpp), the normal offsets' statistics and the
// post-conditions of the phases that finish §6.4's final step.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "pipeline/Method.h"

#include <vector>

namespace contour::consistent {

// The normal-wiggle-* parameters, read once.
struct NormalWiggleOptions {
    int samples = 100, fine = 48;
    double fraction = 1.0; // normal-wiggle-max-offset
    int maxSweeps = 100;
    int pairSamples = 48;
    bool ringPairs = true;
    double ringShift = 0.0; // pixels; infinity for no bound
};
NormalWiggleOptions normalWiggleOptions(const ParameterSet& p);

struct NormalWiggleStats {
    long long rejectedFold = 0, pairsTried = 0, pairsAccepted = 0, ringPairsAccepted = 0;
};

// Sweeps over the vertices of the inconsistent faces, each moved along its
// normal to the offset leaving the fewest inconsistent faces around it
// (strictly fewer; ties to the smallest |α|; no face turned over in 3D),
// until a sweep moves none or after maxSweeps.
void wiggleVertices(const PhaseContext& ctx, ConsistentMesh& m, const NormalWiggleOptions& o,
                    int phase, OptimizationTally& tally, NormalWiggleStats& st);

// Vertices off the surface, the largest |α| over the mean one-ring
// distance, the largest image shift of a C vertex off the surface (px).
struct NormalOffsetStats {
    long long offVertices = 0;
    double largest = 0.0, contourShift = 0.0;
};
NormalOffsetStats normalOffsetStats(const ConsistentMesh& m);
void publishNormalOffsetStats(Snapshot& s, const NormalOffsetStats& n);

// optimizationChecks (radial edges off the surface) and docs/dev/invariants.md item 2
// for the normal offsets: |α| <= normal-wiggle-max-offset times the mean
// one-ring distance.
std::vector<InvariantCheck> normalWiggleChecks(const PhaseContext& ctx, const Snapshot& s);

} // namespace contour::consistent
