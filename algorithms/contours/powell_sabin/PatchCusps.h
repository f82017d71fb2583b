#pragma once
// Cusps of the contour of a quadratic patch (Capouellez et al. 2023 §4.2).
//
// Interior cusps (eq. 5-6): the contour's domain tangent is the isoline
// tangent T = [-f_v, f_u] of f = tau . n, n = p_u x p_v, so its 3D tangent is
//   t(u, v) = -p_u (n_v . tau) + p_v (n_u . tau),
// quadratic in (u, v); a cusp is where t is parallel to tau: t . tau1 = 0 and
// t . tau2 = 0, two conics solved by the pencil method (ConicPencil.h). The
// contour equation f = 0 follows from them where t != 0; it is used as a
// filter, and roots where T vanishes (critical points of f, t = 0) are not
// cusps.
//
// QI (§4.2: "QI increases by 1 along the contour in the direction of t", from
// the near to the far side of the cusp). At a cusp t = (tau . t) tau, so
// moving along the contour in the direction of T (which maps to t) goes away
// from the viewer iff tau . t > 0: QI increases by one in the direction of T
// iff tau . t > 0, and in the direction of -T otherwise. In the image, with
// sigma the contour's parameter along T (ds/dsigma = T) and pi the projection
// onto (tau1, tau2), the image curve near the cusp is
//   x(sigma) = x0 + sigma^2 / 2 a + sigma^3 / 6 b + ...,
//   a = pi(Dt T),  b = pi(D^2t[T, T] + Dt (DT) T)
// (pi t = 0 at the cusp; t and T are quadratic and linear, so Dt, D^2t and DT
// are exact): both branches leave x0 along a, and the branch sigma > 0 lies
// on the side of b's component perpendicular to a. The branch with QI + 1
// (the far one, sigma (tau . t) > 0) is therefore on the side
// farSide = sign(tau . t) * normalize(b - (b . a^) a^).
#include "contours/powell_sabin/ConicPencil.h"
#include "contours/powell_sabin/Ps12Patch.h"

#include <array>
#include <vector>

namespace contour::powell_sabin {

// The image frame of an orthographic view along tau: (tau1, tau2, tau)
// right-handed orthonormal, tau1 = (1, 0, 0) and tau2 = (0, 1, 0) for
// tau = (0, 0, 1) (image x right, y up). Throws std::invalid_argument for a
// zero or non-finite tau.
void viewFrame(const Vec3& tau, Vec3& tau1, Vec3& tau2);

// A quadratic patch in monomial form over s = (w1, w2), the barycentric
// coordinates of corners 1 and 2 of its domain (w0 = 1 - s1 - s2):
//   p(s) = c0 + c1 s1 + c2 s2 + c3 s1^2 + c4 s1 s2 + c5 s2^2.
// The domain is then the reference triangle s1, s2 >= 0, s1 + s2 <= 1, so
// the solvers work on well-scaled conics whatever the face uv.
std::array<Vec3, 6> monomialCoefficients(const QuadraticBezier<Vec3>& patch);

// The part of the line l . (s1, s2, 1) = 0 inside the reference triangle
// grown by `pad`, as the segment [a, b]; false if they do not meet.
bool clipLineToReferenceTriangle(const Eigen::Vector3d& l, double pad, Vec2& a, Vec2& b);

struct PatchCuspOptions {
    // A root is on the contour when |tau . n| <= this times the size of n's
    // coefficients (§4.1: eps = 1e-10 for every zero test).
    double zeroTolerance = 1e-10;
    // A root where |[-f_v, f_u]| <= this times the same size is a critical
    // point of f (t = 0 there), not a cusp.
    double gradientTolerance = 1e-8;
    // Roots with barycentric coordinates >= -this are inside the patch (a
    // cusp on a shared edge may be reported by both patches).
    double domainTolerance = 1e-12;
    ConicPencilOptions pencil;
};

struct PatchCusp {
    Vec3 barycentric; // in the patch's domain
    Vec2 uv;          // in the patch's face uv
    Vec3 position;    // p
    // T = [-f_v, f_u] and t of eq. 5, both in face uv (t is parallel to tau).
    Vec2 domainTangent;
    Vec3 tangent;
    // QI increases by one along the contour in the direction of T (tau . t > 0).
    bool qiIncreasesAlongDomainTangent = false;
    // Unit image direction along which both branches leave the cusp, and the
    // unit perpendicular pointing to the side of the branch with QI + 1 (see
    // above). Zero for a degenerate (higher-order) cusp where a or the
    // perpendicular part of b vanishes.
    Vec2 imageAxis = Vec2::Zero();
    Vec2 farSide = Vec2::Zero();
};

struct PatchCuspResult {
    std::vector<PatchCusp> cusps;
    // Non-generic view: t is parallel to tau along a whole curve in the patch
    // (t . tau1 and t . tau2 share a component where t != 0, or f vanishes on
    // the whole patch). The cusps of that curve are not listed.
    bool degenerate = false;
};

// Throws std::invalid_argument for a non-finite patch or tau, or a
// degenerate domain triangle.
PatchCuspResult patchCusps(const QuadraticBezier<Vec3>& patch, const Vec3& tau,
                           const PatchCuspOptions& options = {});

// Boundary cusp (§4.2): at the common end of two contour segments in adjacent
// patches, with normal n there and the segments' 3D tangents t and t'
// oriented the same way along the contour (e.g. both eq. 5 tangents, which
// are chart independent), a cusp iff tau . (n x t) and tau . (n x t') have
// strictly different signs. Values below options.zeroTolerance relative to
// |n| |t| count as zero (the image tangent vanishes: an interior cusp found
// by patchCusps, not a boundary cusp) and give false.
bool isBoundaryCusp(const Vec3& normal, const Vec3& t, const Vec3& tPrime, const Vec3& tau,
                    const PatchCuspOptions& options = {});

} // namespace contour::powell_sabin
