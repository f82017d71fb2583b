#pragma once
// Differential fields on any SmoothSurface, from one SurfacePoint (position,
// first and second parameter derivatives): the orientation function g and its
// parameter gradient, the fundamental forms, principal, Gaussian and mean
// curvature, normal curvature in a direction, and radial curvature.
//
// Sign conventions (stated once, tested in tests/test_surface_fields.cpp):
//   - n is the unit normal f_u x f_v / |f_u x f_v|, outward for a cage whose
//     faces are counter-clockwise seen from outside (SmoothSurface.h).
//   - g(u) = (c - f(u)) · n(u) (Bénard 2014 eq. 1), through facingFunction()
//     of camera/Facing.h, the single definition: g > 0 front-facing. For an
//     orthographic camera c - f is the constant direction towards the camera.
//   - Second fundamental form II_ij = f_ij · n with the OUTWARD unit normal.
//     Normal curvature in a tangent direction t is II(t, t) / I(t, t). So a
//     sphere of radius R has normal curvature -1/R in every direction,
//     principal curvatures -1/R, Gaussian curvature +1/R^2 and mean curvature
//     -1/R; a convex surface curves away from its outward normal and has
//     negative normal curvatures.
//   - Radial curvature kr is the normal curvature along w = v - (v·n) n, the
//     view vector v = c - p (orthographic: the direction to the camera)
//     projected onto the tangent plane (DeCarlo et al. 2003; Bénard 2014
//     §1.6 of the notes). With the convention above kr < 0 at an ordinary
//     exterior contour (the surface bends away from the viewer, behind the
//     tangent plane), which is what Bénard 2014 calls "radial curvature is
//     negative". The tutorial (§7.4) uses the opposite sign and says "visible
//     only where kr > 0"; in this code base a contour can be visible only
//     where kr < 0. Cusps are the zeros of kr on the contour; only the sign
//     changes matter, so both conventions find the same cusps.
//     Where w vanishes (the view is along the normal) the direction is
//     undefined and radialCurvature() returns NaN.
//   - Where f_u x f_v vanishes (a degenerate parameterization) the normal is
//     zero: g is then 0, and every curvature is NaN.
#include "camera/Camera.h"
#include "surface/SmoothSurface.h"

#include <cmath>
#include <span>
#include <vector>

namespace contour {

// First fundamental form I = [[E, F], [F, G]] (E = f_u·f_u, F = f_u·f_v,
// G = f_v·f_v) and second II = [[L, M], [M, N]] (L = f_uu·n, M = f_uv·n,
// N = f_vv·n), in the preimage face's (u, v).
struct FundamentalForms {
    double E = 0, F = 0, G = 0;
    double L = 0, M = 0, N = 0;

    double firstDeterminant() const { return E * G - F * F; } // |f_u x f_v|^2
    double secondDeterminant() const { return L * N - M * M; }
    // I(a, a) and II(a, a) for a parameter-space direction a = (du, dv).
    double first(const Vec2& a) const {
        return E * a.x() * a.x() + 2.0 * F * a.x() * a.y() + G * a.y() * a.y();
    }
    double second(const Vec2& a) const {
        return L * a.x() * a.x() + 2.0 * M * a.x() * a.y() + N * a.y() * a.y();
    }
};

FundamentalForms fundamentalForms(const SurfacePoint& p);

// The second fundamental form as a symmetric 2x2 matrix S in the orthonormal
// tangent frame (e1, e2 = n x e1), e1 = f_u / |f_u|: everything curvature
// needs, independent of the chart, in 9 numbers. S_ab = II(e_a, e_b); its
// eigenvalues are the principal curvatures, and the normal curvature along a
// unit tangent t = a e1 + b e2 is S11 a^2 + 2 S12 a b + S22 b^2. Every
// curvature function below goes through it. NaN entries where degenerate.
struct ShapeOperator {
    Vec3 e1 = Vec3::Zero();
    Vec3 n = Vec3::Zero();
    double s11 = 0, s12 = 0, s22 = 0;

    Vec3 e2() const { return n.cross(e1); }
    double gaussian() const { return s11 * s22 - s12 * s12; } // det S
    double mean() const { return 0.5 * (s11 + s22); }         // trace S / 2
    bool valid() const { return std::isfinite(s11) && std::isfinite(s12) && std::isfinite(s22); }
};

ShapeOperator shapeOperator(const SurfacePoint& p);

// Principal curvatures (kMin <= kMax) with unit 3D principal directions in
// the tangent plane; (dirMax, dirMin, n) is right-handed. At an umbilic the
// directions are an arbitrary orthonormal pair. All NaN where degenerate.
struct Curvatures {
    double kMin = 0, kMax = 0;
    Vec3 dirMin = Vec3::Zero(), dirMax = Vec3::Zero();
    double gaussian = 0; // kMin kMax = det II / det I
    double mean = 0;     // (kMin + kMax) / 2
};

Curvatures curvatures(const SurfacePoint& p);
Curvatures curvatures(const ShapeOperator& s);
double gaussianCurvature(const SurfacePoint& p);
double meanCurvature(const SurfacePoint& p);

// Normal curvature II(t, t) / I(t, t) along a 3D direction, projected onto the
// tangent plane first. NaN when the projection is shorter than
// minSine |direction| (the direction is along the normal) or the point is
// degenerate.
double normalCurvature(const SurfacePoint& p, const Vec3& direction, double minSine = 1e-12);
double normalCurvature(const ShapeOperator& s, const Vec3& direction, double minSine = 1e-12);
// The same for a direction given in the preimage face's parameters (du, dv).
double normalCurvature(const SurfacePoint& p, const Vec2& parameterDirection);

// g(u) = (c - f(u)) · n(u) (Facing.h).
double orientation(const SurfacePoint& p, const Camera& camera);

// dg/du and dg/dv in the preimage face's parameters. Since f_u · n = 0,
// dg/du_i = (c - f) · dn/du_i in both projections, with the derivative of
// the unit normal dn/du_i = (N_i - (N_i · n) n) / |N|, N = f_u x f_v,
// N_u = f_uu x f_v + f_u x f_uv, N_v = f_uv x f_v + f_u x f_vv.
// Zero where the normal is degenerate.
Vec2 orientationGradient(const SurfacePoint& p, const Camera& camera);

// Derivatives of the unit normal, dn/du and dn/dv (as above).
void unitNormalDerivatives(const SurfacePoint& p, Vec3& dnu, Vec3& dnv);

// Radial curvature: the normal curvature along the view vector projected
// onto the tangent plane (see the sign convention above). NaN where that
// projection is shorter than minSine |v| (view along the normal) or the
// point is degenerate.
double radialCurvature(const SurfacePoint& p, const Camera& camera, double minSine = 1e-12);
// The same from a stored shape operator and the point's position.
double radialCurvature(const ShapeOperator& s, const Vec3& position, const Camera& camera,
                       double minSine = 1e-12);

// Batch versions over many points, in parallel.
std::vector<double> orientations(std::span<const SurfacePoint> points, const Camera& camera);
std::vector<double> radialCurvatures(std::span<const SurfacePoint> points, const Camera& camera);
std::vector<double> gaussianCurvatures(std::span<const SurfacePoint> points);
std::vector<double> meanCurvatures(std::span<const SurfacePoint> points);
std::vector<ShapeOperator> shapeOperators(std::span<const SurfacePoint> points);

} // namespace contour
