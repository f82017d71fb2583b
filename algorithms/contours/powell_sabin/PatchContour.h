#pragma once
// The contour generator of one quadratic patch under an orthographic view
// along tau (Capouellez et al. 2023 §4.1): n = p_u x p_v is quadratic in the
// patch's uv, so tau . n = 1/2 r^T A r + b^T r + c (eq. 2) and its zero set
// is a conic, parameterized rationally by the cases of Table 1 (with the
// errata of the reading notes) and trimmed to the patch's domain triangle.
#include "contours/powell_sabin/Ps12Patch.h"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace contour::powell_sabin {

// f(r) = 1/2 r^T A r + b^T r + c over the patch's uv (r in face uv).
struct QuadraticForm2 {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero(); // symmetric
    Vec2 b = Vec2::Zero();
    double c = 0.0;
    double operator()(const Vec2& r) const { return 0.5 * r.dot(A * r) + b.dot(r) + c; }
    Vec2 gradient(const Vec2& r) const { return A * r + b; }
};

// tau . (p_u x p_v) of `patch` as a quadratic form in face uv.
QuadraticForm2 contourFunction(const QuadraticBezier<Vec3>& patch, const Vec3& tau);

// Table 1's cases; Empty covers the cases that give no stable contour.
enum class ConicKind { Empty, Ellipse, Hyperbola, IntersectingLines, Parabola, ParallelLines };
const char* toString(ConicKind kind);

// A rational quadratic curve in face uv: r(t) = (X(t), Y(t)) / W(t), each a
// quadratic in t with coefficients [t^0, t^1, t^2]; W = 1 for polynomial
// curves (lines, parabolas).
struct RationalQuadratic {
    Eigen::Matrix3d coefficients = Eigen::Matrix3d::Zero(); // rows X, Y, W
    Vec2 at(double t) const;
    Vec2 derivative(double t) const;
};

// One trimmed piece of the contour generator inside one patch.
struct ContourSegment {
    Index patch = kInvalidIndex;
    ConicKind kind = ConicKind::Empty;
    RationalQuadratic curve;
    double t0 = 0.0, t1 = 0.0; // t0 < t1; r(t) lies in the patch's domain on [t0, t1]
    // The domain triangle's side (0: corner 0 -> 1, 1: 1 -> 2, 2: 2 -> 0)
    // each end lies on, or -1 for an end inside the triangle: an ellipse
    // entirely inside the domain comes as two segments (two halves, each a
    // finite t interval) whose ends meet, all four ends -1.
    int startSide = -1, endSide = -1;
};

struct PatchContourOptions {
    double zeroTolerance = 1e-10; // §4.1: |x| < eps for every test "x = 0"
};

// The contour segments of `patch` (at most three per conic branch).
// Throws std::invalid_argument for a non-finite or zero tau, non-finite
// control points, a clockwise, degenerate or non-finite domain, or a
// negative or non-finite zeroTolerance (the same for the functions below).
std::vector<ContourSegment> patchContours(const QuadraticBezier<Vec3>& patch, Index patchId,
                                          const Vec3& tau, const PatchContourOptions& options = {});

// The same for a given form over a domain triangle (counter-clockwise, in
// the form's uv): patchContours is conicContours of the patch's
// contourFunction, computed without the round trip through face uv.
//
// Conventions (all tests "x = 0" are |x| < zeroTolerance, §4.1):
// - Units. The form is rewritten in s = (r - centroid) / h, h the domain's
//   longest side, and divided by its scale |A|_F + |b| + |c| in those
//   coordinates; every tolerance applies there, so the classification does
//   not depend on the domain's position, size or the form's magnitude. A
//   form whose scale is 0 (tau . n = 0 on the whole patch) is Empty.
// - Near-singular A (cylinder-like patches, §4.1): A counts as singular when
//   its smaller eigenvalue |sigma_2| < eps (dropping 1/2 sigma_2 z_2^2 moves f
//   by less than eps over the domain), then Parabola if |b^_2| >= eps,
//   otherwise ParallelLines if b^_1^2 - 2 sigma_1 c > eps, otherwise Empty
//   (a double line or none). When both eigenvalues are below eps, f is
//   linear: its line comes as the Parabola of Table 1 with sigma_1 = 0.
// - Nonsingular A: |c^| < eps with sigma_1 sigma_2 < 0 gives IntersectingLines
//   (stable at cones, §5), and a definite A gives Empty (an isolated zero);
//   c^ > 0 after the sign normalization gives Ellipse (sigma_1, sigma_2 < 0),
//   Hyperbola (mixed signs) or Empty (sigma_1, sigma_2 > 0).
// - Parameterizations: lines and parabolas have W = 1 and t over R (a line's
//   t is arc length in s; intersecting lines are built from their linear
//   factors, not through the center). A hyperbola branch is Table 1's
//   formula on t in (-1, 1) (the other branch is the same with k_1 negated,
//   i.e. t -> -1/t), written about the branch's vertex. An ellipse that
//   leaves the domain has its point at t = infinity outside the domain: the
//   major-axis vertex farther from the domain when that one is outside,
//   otherwise the point farthest outside a side (a rotation of Table 1's
//   angle, i.e. a Moebius map of t), so every trimmed piece has a finite t
//   range; an ellipse inside the domain comes as two halves on [-1, 1].
//   Vertices are the roots of f on the axis, so the curves stay accurate
//   when A is nearly singular and the center is far (|s0| ~ |b| / sigma_2).
//   Limit: both degeneracies at once (sigma_2 below ~1e-6 and c^ near 0, a
//   cone on a cylinder-like patch) leave c^ itself uncertain beyond eps, and
//   a hyperbola close to its asymptotes with a far center loses about
//   1e-16 |s0| / |1 - t^2| in position.
// - Degenerate trimming (the paper assumes general position): pieces whose
//   end points are closer than eps (in s) are dropped, so a curve through a
//   corner gives no zero-length segment, and its end at the corner records
//   one of the two sides meeting there (match such ends by position). A
//   piece lying along a side (its midpoint within eps of the side line) is
//   kept only by the patch into which grad f points, so the neighbour across
//   that side does not report it twice. A conic tangent to a side within
//   round-off may lose or keep the touching point.
std::vector<ContourSegment> conicContours(const QuadraticForm2& form,
                                          const std::array<Vec2, 3>& domain, Index patchId,
                                          const PatchContourOptions& options = {});

// The Table-1 case of `form` over `domain` (the domain sets the units only),
// regardless of whether the curve meets the domain.
ConicKind classifyConic(const QuadraticForm2& form, const std::array<Vec2, 3>& domain,
                        const PatchContourOptions& options = {});

} // namespace contour::powell_sabin
