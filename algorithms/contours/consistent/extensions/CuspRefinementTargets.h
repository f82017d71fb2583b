#pragma once
// What the cusp-refinement phase offers a branch (pipeline/Branch.h; the
// cusp retry): the data that makes a re-run refine around chosen cusps only,
// and the variants of its own settings a branch may try.
#include "camera/Camera.h"
#include "pipeline/Branch.h"

#include <memory>
#include <vector>

namespace contour::consistent {

// Branch data: a cusp is refined around when its image lies within
// `pixels` of one of `at` (image positions of the first run's cusps).
struct CuspRefinementTargets : BranchData {
    std::vector<Vec2> at;
    double pixels = 0.0;

    bool selects(const Camera& camera, const Vec3& cusp) const;
};

// The cusp-refinement-rings and -levels set first, then with `every` every
// other rings <= cusp-refinement-rings and levels <= cusp-refinement-levels,
// fewest levels, then rings, first; each variant overrides those two
// parameters and carries `targets`.
std::vector<BranchVariant>
cuspRefinementVariants(const ParameterSet& p, bool every,
                       std::shared_ptr<const CuspRefinementTargets> targets);

} // namespace contour::consistent
