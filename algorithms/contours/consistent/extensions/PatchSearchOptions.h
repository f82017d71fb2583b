#pragma once
// The parameters of the patch-search phase (not in the paper; the search
// itself: edits/PatchSearch.h), read once per run, and the search's settings
// they give on a mesh. PatchSearchPhase.cpp declares the parameters and
// reads them here.
#include "contours/consistent/edits/PatchSearch.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/OptimizationFlip.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "pipeline/Parameters.h"

namespace contour::consistent {

struct PatchSearchOptions {
    bool enabled = false; // patch-search
    int maxSweeps = 0;    // patch-max-sweeps
    int rows = 0, maxCorners = 0;
    bool relocate = false, grow = false, radialEnds = false, contourSlide = false,
         newRadialEnds = false, newRadialCusps = false, cuspTies = false;
    CuspEditOptions cusps;
    RadialEdgeOptions radial;
    ContourRootOptions root;
    static PatchSearchOptions read(const ParameterSet& p);
    // The search's settings on mesh m: the root tolerances made distances
    // by the scene's scale, |g| of a slid C vertex within half the bound
    // the post-condition checks (as contour insertion).
    PatchSearchSettings settings(const ConsistentMesh& m) const;
};

} // namespace contour::consistent
