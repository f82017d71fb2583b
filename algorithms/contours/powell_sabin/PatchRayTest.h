#pragma once
// Ray tests against quadratic patches (Capouellez et al. 2023 §4.2, after
// Ogaki & Tokuyoshi 2011): the ray along tau through image point (x, y) meets
// patch p where p(u, v) . tau1 = x and p(u, v) . tau2 = y, two conics in the
// patch's parameters solved by the pencil method (ConicPencil.h); each root
// inside the domain is a hit at depth p . tau. (tau1, tau2) is viewFrame(tau),
// so for tau = (0, 0, 1) the image point is (p.x, p.y) and the depth p.z.
// Counting the hits in front of a contour point gives its QI.
#include "contours/powell_sabin/PatchCusps.h"
#include "contours/powell_sabin/PowellSabinSpline.h"

#include <vector>

namespace contour::powell_sabin {

struct PatchRayOptions {
    // Hits with barycentric coordinates >= -this are inside the patch. A hit
    // on an edge shared by two patches is reported by both.
    double domainTolerance = 1e-12;
    // Depth margin of hitsInFront, relative to the diameter of the patch's
    // control points: a hit counts as in front of `depth` when its depth <
    // depth - this * diameter. The ray through a contour point touches the
    // surface there, a double root that round-off may split into two hits
    // about sqrt(machine epsilon) * diameter apart; the margin keeps both out
    // of the count.
    double depthTolerance = 1e-5;
    // The image bounding box of the control points is grown by this times
    // (1 + its diagonal + its largest coordinate) before rejecting a ray, so
    // that rays through the box's edge survive round-off.
    double boundsPad = 1e-12;
    ConicPencilOptions pencil;
};

struct RayHit {
    Vec3 barycentric; // in the patch's domain
    Vec2 uv;          // in the patch's face uv
    double depth = 0.0;
};

struct PatchRayHits {
    std::vector<RayHit> hits; // increasing depth, at most 4
    // Non-generic: the ray lies in the patch along a segment of a curve (an
    // edge-on planar or ruled part), so `hits` is incomplete.
    bool rayInSurface = false;
};

// Throws std::invalid_argument for a non-finite patch, tau or image point,
// or a degenerate domain triangle.
PatchRayHits rayPatchIntersections(const QuadraticBezier<Vec3>& patch, const Vec3& tau,
                                   const Vec2& imagePoint, const PatchRayOptions& options = {});

// The number of points of `patch` on the ray through `imagePoint` that lie
// in front of `depth` (see depthTolerance). A ray whose
// image point is outside the image bounding box of the control points (the
// patch lies in their convex hull) is rejected without solving. Throws
// std::runtime_error when the ray lies in the surface (rayInSurface).
int hitsInFront(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const Vec2& imagePoint,
                double depth, const PatchRayOptions& options = {});
// The same summed over all patches of `spline` (the QI of a point at
// `depth` on the ray, up to hits on shared patch edges, which are counted
// once per patch).
int hitsInFront(const PowellSabinSpline& spline, const Vec3& tau, const Vec2& imagePoint,
                double depth, const PatchRayOptions& options = {});

} // namespace contour::powell_sabin
