#pragma once
// The "visibility" phase (tutorial ch. 4; Bénard 2014 §8): builds the view
// graph of the snapshot's curves and decides every chain's quantitative
// invisibility. Appended after chaining by the three contour methods.
#include "pipeline/Method.h"

namespace contour {

enum class VisibilityFlavor { Mesh, Consistent, Interpolated };

// Parameter "visibility" (bool, default true; off = the phase passes the
// snapshot through and says so), plus the flavor's parameters.
void addVisibilityPhase(Method& m, VisibilityFlavor flavor);

} // namespace contour
