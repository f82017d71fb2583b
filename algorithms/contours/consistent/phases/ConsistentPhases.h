#pragma once
// The sub-phases of Bénard, Hertzmann & Kass 2014 §6, in the paper's order
// (the phases not in the paper: extensions/ExtensionPhases.h). Each file
// adds its parameters (the paper's values as defaults) and its phase (run +
// post-conditions) to the method; ConsistentContourMethod.cpp calls them in
// order.
#include "pipeline/Method.h"

namespace contour::consistent {

void addInitializationPhase(Method& m);      // §6.1, Fig. 15a-c
void addCuspDetectionPhase(Method& m);       // §6.2 d, Fig. 15d, 16b, 18b
void addContourInsertionPhase(Method& m);    // §6.2 e-f, Fig. 15d-f
void addRadialEdgeInsertionPhase(Method& m); // §6.3 g, Fig. 15g, 16d, 17, 18e
void addRadialFlipPhase(Method& m);          // §6.3 h, Fig. 15h, 16e
void addRadialExtensionPhase(Method& m);     // §6.4 (i), Fig. 15i, 16f
void addOptimizationFlipPhase(Method& m);    // §6.4 edge flipping
void addParameterWigglePhase(Method& m);     // §6.4 vertex wiggling in parameter space
void addEdgeSplitPhase(Method& m);           // §6.4 edge splitting
void addNormalWigglePhase(Method& m);        // §6.4 vertex wiggling along the normal
void addChainingPhase(Method& m);            // §8: the contour generator as polylines

} // namespace contour::consistent
