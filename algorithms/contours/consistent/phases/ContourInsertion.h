#pragma once
// The root search of contour insertion (Bénard 2014 §6.2 e) that other
// phases keep to: cusp detection predicts whether it converges on a cusp
// edge, the patch search samples the same roots, and the post-condition of
// every later phase bounds |g| at C vertices by the same tolerance.
// ContourInsertionPhase.cpp declares the parameters and reads them here.
#include "pipeline/Parameters.h"

namespace contour::consistent {

struct ContourRootOptions {
    double tolerance = 0.0; // root-tolerance, times the bounding-box diagonal
    int maxIterations = 0;  // root-max-iterations
    static ContourRootOptions read(const ParameterSet& p);
};

} // namespace contour::consistent
