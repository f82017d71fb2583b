#pragma once
// Radial edge extension (Bénard 2014 §6.4 i) used outside its own phase: the
// push of the cusps' radial ends along their radial curves
// (extension-cusp-push-depth), run again after the normal wiggle
// (CuspEndPushPhase.cpp).
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "pipeline/Method.h"

namespace contour::consistent {

struct CuspPushCounts {
    long long tried = 0, moved = 0, flips = 0;
    long long everyEndMoved = 0; // of `moved`: non-cusp ends (extension-push-every-end-final)
};

// Sweeps of RadialExtensionPhase's push over the radial edges p-q of cusps
// whose far end q touches an inconsistent face, until a sweep moves none
// (at most extension-max-sweeps), then, with `everyEnd`
// (extension-push-every-end-final), the same over every radial edge; moved
// ends are marked with `phase`.
CuspPushCounts pushCuspRadialEnds(const PhaseContext& ctx, ConsistentMesh& m, int phase,
                                  bool everyEnd);

} // namespace contour::consistent
