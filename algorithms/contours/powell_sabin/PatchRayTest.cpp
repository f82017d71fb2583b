// Ray-patch intersection by the pencil method (Capouellez et al. 2023 §4.2,
// Ogaki & Tokuyoshi 2011), in the patch's reference triangle.
#include "contours/powell_sabin/PatchRayTest.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace contour::powell_sabin {
namespace {

void requireFinite(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const Vec2& imagePoint) {
    bool ok = tau.allFinite() && imagePoint.allFinite();
    for (const Vec3& c : patch.control)
        ok = ok && c.allFinite();
    for (const Vec2& d : patch.domain)
        ok = ok && d.allFinite();
    if (!ok)
        throw std::invalid_argument("rayPatchIntersections: the patch, tau or the image point "
                                    "is not finite");
}

// Image bounding box and depth range of the control points, which bound the
// patch (convex hull property).
struct Bounds {
    Vec2 lo, hi;
    double minDepth, maxDepth;
    double diameter() const {
        return std::sqrt((hi - lo).squaredNorm() + (maxDepth - minDepth) * (maxDepth - minDepth));
    }
};

Bounds boundsOf(const QuadraticBezier<Vec3>& patch, const Vec3& tau1, const Vec3& tau2,
                const Vec3& view) {
    Bounds b{Vec2::Constant(std::numeric_limits<double>::infinity()),
             Vec2::Constant(-std::numeric_limits<double>::infinity()),
             std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Vec3& c : patch.control) {
        const Vec2 x(tau1.dot(c), tau2.dot(c));
        b.lo = b.lo.cwiseMin(x);
        b.hi = b.hi.cwiseMax(x);
        b.minDepth = std::min(b.minDepth, view.dot(c));
        b.maxDepth = std::max(b.maxDepth, view.dot(c));
    }
    return b;
}

bool outside(const Bounds& b, const Vec2& x, double padding) {
    const double pad = padding * (1.0 + (b.hi - b.lo).norm() + b.hi.cwiseAbs().maxCoeff());
    return (x.array() < b.lo.array() - pad).any() || (x.array() > b.hi.array() + pad).any();
}

PatchRayHits solve(const QuadraticBezier<Vec3>& patch, const Vec3& tau1, const Vec3& tau2,
                   const Vec3& view, const Vec2& x, const PatchRayOptions& options) {
    const std::array<Vec3, 6> p = monomialCoefficients(patch);
    auto conic = [&](const Vec3& axis, double value) {
        return conicMatrix(axis.dot(p[3]), axis.dot(p[4]), axis.dot(p[5]), axis.dot(p[1]),
                           axis.dot(p[2]), axis.dot(p[0]) - value);
    };
    const ConicIntersection roots =
        intersectConics(conic(tau1, x.x()), conic(tau2, x.y()), options.pencil);
    PatchRayHits result;
    result.rayInSurface = roots.sharedConic;
    for (const Eigen::Vector3d& l : roots.sharedLines) {
        Vec2 a, b;
        if (clipLineToReferenceTriangle(l, options.domainTolerance, a, b))
            result.rayInSurface = true;
    }
    Eigen::Matrix2d jac;
    jac.col(0) = patch.domain[1] - patch.domain[0];
    jac.col(1) = patch.domain[2] - patch.domain[0];
    if (!(std::abs(jac.determinant()) > 0.0))
        throw std::invalid_argument(
            "rayPatchIntersections: the patch's domain triangle is degenerate");
    for (const Vec2& s : roots.points) {
        const Vec3 w(1.0 - s.x() - s.y(), s.x(), s.y());
        if (w.minCoeff() < -options.domainTolerance)
            continue;
        const Vec3 q = p[0] + p[1] * s.x() + p[2] * s.y() + p[3] * s.x() * s.x() +
                       p[4] * s.x() * s.y() + p[5] * s.y() * s.y();
        result.hits.push_back({w, patch.domain[0] + jac * s, view.dot(q)});
    }
    std::sort(result.hits.begin(), result.hits.end(),
              [](const RayHit& a, const RayHit& b) { return a.depth < b.depth; });
    return result;
}

int countInFront(const PatchRayHits& h, double depth, double margin) {
    if (h.rayInSurface)
        throw std::runtime_error("hitsInFront: the ray lies in the surface along a curve "
                                 "(non-generic view); its hits cannot be counted");
    return static_cast<int>(std::count_if(
        h.hits.begin(), h.hits.end(), [&](const RayHit& r) { return r.depth < depth - margin; }));
}

} // namespace

PatchRayHits rayPatchIntersections(const QuadraticBezier<Vec3>& patch, const Vec3& tau,
                                   const Vec2& imagePoint, const PatchRayOptions& options) {
    requireFinite(patch, tau, imagePoint);
    Vec3 tau1, tau2;
    viewFrame(tau, tau1, tau2);
    const Vec3 view = tau.normalized();
    if (outside(boundsOf(patch, tau1, tau2, view), imagePoint, options.boundsPad))
        return {};
    return solve(patch, tau1, tau2, view, imagePoint, options);
}

int hitsInFront(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const Vec2& imagePoint,
                double depth, const PatchRayOptions& options) {
    requireFinite(patch, tau, imagePoint);
    if (!std::isfinite(depth))
        throw std::invalid_argument("hitsInFront: the depth is not finite");
    Vec3 tau1, tau2;
    viewFrame(tau, tau1, tau2);
    const Vec3 view = tau.normalized();
    const Bounds b = boundsOf(patch, tau1, tau2, view);
    const double margin = options.depthTolerance * b.diameter();
    if (outside(b, imagePoint, options.boundsPad) || b.minDepth >= depth - margin)
        return 0;
    return countInFront(solve(patch, tau1, tau2, view, imagePoint, options), depth, margin);
}

int hitsInFront(const PowellSabinSpline& spline, const Vec3& tau, const Vec2& imagePoint,
                double depth, const PatchRayOptions& options) {
    int count = 0;
    for (const QuadraticBezier<Vec3>& patch : spline.patches)
        count += hitsInFront(patch, tau, imagePoint, depth, options);
    return count;
}

} // namespace contour::powell_sabin
