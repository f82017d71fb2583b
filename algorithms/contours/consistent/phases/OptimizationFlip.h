#pragma once
// The parameter of the optimization flips (Bénard 2014 §6.4) that every
// later §6.4 move keeps to: whether moves may change a cusp's valence
// before radial edges reach it (optimization-cusp-edits; lockedCusp).
// OptimizationFlipPhase.cpp declares the parameter and reads it here.
#include "pipeline/Parameters.h"

namespace contour::consistent {

struct CuspEditOptions {
    bool cuspEdits = false; // optimization-cusp-edits
    static CuspEditOptions read(const ParameterSet& p);
};

} // namespace contour::consistent
