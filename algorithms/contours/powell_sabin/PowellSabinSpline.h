#pragma once
// The fitted G1 piecewise-quadratic surface (Capouellez et al. 2023 §5): 12
// quadratic Bezier patches per triangle of the layout, patch 12 f + l the
// l-th sub-triangle of face f (Ps12Patch.h). Positions after the view's
// projective transform when the fit was given transformed targets.
#include "contours/powell_sabin/Ps12Patch.h"

#include <vector>

namespace contour::powell_sabin {

struct PowellSabinSpline {
    std::vector<QuadraticBezier<Vec3>> patches; // 12 per face
    std::vector<char> conePatch;                // per patch: touches a cone vertex

    Index faceCount() const { return static_cast<Index>(patches.size() / kPs12Patches); }
    // Point and uv derivatives at barycentric coordinates of a patch.
    Vec3 position(Index patch, const Vec3& barycentric) const;
    void derivatives(Index patch, const Vec3& barycentric, Vec3& du, Vec3& dv) const;
    // Unnormalized normal p_u x p_v (zero at cones).
    Vec3 normal(Index patch, const Vec3& barycentric) const;
};

} // namespace contour::powell_sabin
