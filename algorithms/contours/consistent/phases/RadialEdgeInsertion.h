#pragma once
// The parameters of radial edge insertion (Bénard 2014 §6.3 g) that later
// phases keep to: the radial root search (the radial extension and the
// parameter wiggle move radial ends along the same planes, the patch search
// samples them, and the post-condition of every later phase bounds |h_p(r)|
// by the same tolerance) and whether an edit may add inconsistent faces
// (the radial flips follow the same rule). RadialEdgeInsertionPhase.cpp
// declares the parameters and reads them here.
#include "pipeline/Parameters.h"

namespace contour::consistent {

struct RadialEdgeOptions {
    double rootTolerance = 1e-10; // radial-root-tolerance, times the diagonal
    int rootMaxIterations = 100;  // radial-root-max-iterations
    bool keepConsistency = true;  // radial-keep-consistency
    // The defaults above where the method declares no radial edge insertion.
    static RadialEdgeOptions read(const ParameterSet& p);
};

} // namespace contour::consistent
