// Evaluation of the fitted Powell-Sabin spline (Capouellez et al. 2023 §5):
// each patch is a quadratic Bezier triangle of Ps12Patch.h.
#include "contours/powell_sabin/PowellSabinSpline.h"

#include <stdexcept>
#include <string>

namespace contour::powell_sabin {
namespace {

const QuadraticBezier<Vec3>& patchAt(const PowellSabinSpline& spline, Index patch) {
    if (patch < 0 || static_cast<std::size_t>(patch) >= spline.patches.size())
        throw std::out_of_range("PowellSabinSpline: patch " + std::to_string(patch) +
                                " is out of range [0, " + std::to_string(spline.patches.size()) +
                                ")");
    return spline.patches[static_cast<std::size_t>(patch)];
}

} // namespace

Vec3 PowellSabinSpline::position(Index patch, const Vec3& barycentric) const {
    return evaluate(patchAt(*this, patch), barycentric);
}

void PowellSabinSpline::derivatives(Index patch, const Vec3& barycentric, Vec3& du,
                                    Vec3& dv) const {
    uvDerivatives(patchAt(*this, patch), barycentric, du, dv);
}

Vec3 PowellSabinSpline::normal(Index patch, const Vec3& barycentric) const {
    Vec3 du;
    Vec3 dv;
    uvDerivatives(patchAt(*this, patch), barycentric, du, dv);
    // Zero gradient DOFs at a cone make both derivatives vanish there, so the
    // normal is zero at the cone point itself (§5.2).
    return du.cross(dv);
}

} // namespace contour::powell_sabin
