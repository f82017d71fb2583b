#pragma once
// The sub-phases of Bénard, Hertzmann & Kass 2014 §6, in the paper's order.
// Each file adds its parameters (the paper's values as defaults) and its
// phase (run + post-conditions) or branch rule to the method;
// ConsistentContourMethod.cpp calls them in order.
#include "pipeline/Method.h"

namespace contour::consistent {

void addInitializationPhase(Method& m);         // §6.1, Fig. 15a-c
void addCuspDetectionPhase(Method& m);          // §6.2 d, Fig. 15d, 16b, 18b
void addCuspRefinementPhase(Method& m);         // not in the paper: edges near cusps halved
void addContourInsertionPhase(Method& m);       // §6.2 e-f, Fig. 15d-f
void addRadialEdgeInsertionPhase(Method& m);    // §6.3 g, Fig. 15g, 16d, 17, 18e
void addRadialFlipPhase(Method& m);             // §6.3 h, Fig. 15h, 16e
void addRadialExtensionPhase(Method& m);        // §6.4 (i), Fig. 15i, 16f
void addOptimizationFlipPhase(Method& m);       // §6.4 edge flipping
void addParameterWigglePhase(Method& m);        // §6.4 vertex wiggling in parameter space
void addEdgeSplitPhase(Method& m);              // §6.4 edge splitting
void addVertexRemovalPhase(Method& m);          // extension of §6.4 (§6.3 h vertex deletion)
void addPatchSearchPhase(Method& m);            // extension of §6.4: compound moves
void addNormalWigglePhase(Method& m);           // §6.4 vertex wiggling along the normal
void addCuspEndPushPhase(Method& m);            // not in the paper: cusps' radial ends pushed again
void addCuspEndRetriangulationPhase(Method& m); // not in the paper: discs at cusps' radial ends
void addContourRefinementPhase(Method& m); // not in the paper: contour edges split near the curve
void addContourRefinementRetriangulationPhase(Method& m); // the discs again after it
// Not in the paper: a branch (pipeline/Branch.h) decided after the last
// phase added so far, re-running from cusp-refinement refined around cusps.
void addCuspRetryBranch(Method& m);
void addChainingPhase(Method& m); // §8: the contour generator as polylines

} // namespace contour::consistent
