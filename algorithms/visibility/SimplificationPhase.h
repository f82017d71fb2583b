#pragma once
// The "simplification" phase (Bénard 2014 §9), after "visibility" in every
// method: parameters "simplify" (off by default) and "simplify-threshold".
#include "pipeline/Method.h"

namespace contour {

void addSimplificationPhase(Method& m);

} // namespace contour
