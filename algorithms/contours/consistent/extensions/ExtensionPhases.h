#pragma once
// The phases of the consistent method that are not in Bénard, Hertzmann &
// Kass 2014 (the paper's own: phases/ConsistentPhases.h). Each file adds its
// parameters and its phase (or branch rule) to the method; ConsistentContourMethod.cpp
// places them among the paper's phases.
#include "pipeline/Method.h"

namespace contour::consistent {

void addCuspRefinementPhase(Method& m);    // not in the paper: edges near cusps halved
void addVertexRemovalPhase(Method& m);     // extension of §6.4 (§6.3 h vertex deletion)
void addPatchSearchPhase(Method& m);       // extension of §6.4: compound moves
void addContourRefinementPhase(Method& m); // not in the paper: contour edges split near the curve
void addCuspEndPushPhase(Method& m);       // not in the paper: cusps' radial ends pushed again
void addCuspEndRetriangulationPhase(Method& m);           // not in the paper: discs at cusp ends
void addContourRefinementRetriangulationPhase(Method& m); // the discs again after refinement
// Not in the paper: a branch (pipeline/Branch.h) decided after the last
// phase added so far, re-running from cusp-refinement refined around cusps.
void addCuspRetryBranch(Method& m);

} // namespace contour::consistent
