#pragma once
// The sub-phases of Bénard, Hertzmann & Kass 2014 §6, in the paper's order.
// Each file adds its parameters (the paper's values as defaults) and its
// phase (run + post-conditions) to the method; ConsistentContourMethod.cpp
// calls them in order.
#include "pipeline/Method.h"

namespace contour::consistent {

void addInitializationPhase(Method& m);   // §6.1, Fig. 15a-c
void addContourInsertionPhase(Method& m); // §6.2 e-f, Fig. 15d-f
void addChainingPhase(Method& m);         // §8: the contour generator as polylines

} // namespace contour::consistent
