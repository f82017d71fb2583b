#pragma once
// What the traced method's phases hand on (Snapshot::methodState): the
// surface, the seeds, the traced curves with their preimages and the cusps.
// Each piece can be rebuilt from the parameters and the surface, so a
// reader without it recomputes it (TracedContourMethod.cpp).
#include "contours/traced/CurveTracer.h"
#include "contours/traced/EdgePolynomials.h"
#include "contours/traced/EdgeSeeds.h"
#include "contours/traced/InteriorSeeds.h"
#include "contours/traced/TracedCusps.h"
#include "pipeline/Snapshot.h"

#include <memory>
#include <vector>

namespace contour::traced {

struct TracedState final : MethodState {
    std::shared_ptr<const SmoothSurface> surface;
    std::shared_ptr<const EdgePolynomials> polynomials;
    std::shared_ptr<const EdgeSeeds> edgeSeeds;
    std::shared_ptr<const InteriorSeeds> interiorSeeds;
    std::shared_ptr<const std::vector<TracedCurve>> curves;
    std::shared_ptr<const std::vector<TracedCusp>> cusps;
};

} // namespace contour::traced
