#pragma once
// The sign-crossing search of initialization (Bénard 2014 §6.1), read through
// this phase's own options by the phases that repeat it on new edges.
#include "pipeline/Parameters.h"

namespace contour::consistent {

struct CrossingSearchOptions {
    int samples = 0; // crossing-samples
    int rounds = 0;  // crossing-search-rounds
    static CrossingSearchOptions read(const ParameterSet& p);
};

} // namespace contour::consistent
