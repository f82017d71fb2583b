#pragma once
// The Powell-Sabin 12-split of one domain triangle (Powell & Sabin 1977;
// Capouellez et al. 2023 §5.2): 12 quadratic Bezier patches forming a C1
// macro-patch, whose 72 Bezier ordinates are linear in 12 local degrees of
// freedom. The paper's matrices B_l are in its supplement, which we do not
// have; they are derived here in closed form from the interpolation and C1
// conditions (docs/methods/powell-sabin-ps12.md).
//
// Local DOFs of triangle (V0, V1, V2), counter-clockwise in uv, per scalar
// coordinate, in this order:
//   [p0, gu0, gv0, p1, gu1, gv1, p2, gu2, gv2, m0, m1, m2]
// p_i the value at V_i, (gu_i, gv_i) the gradient there in the triangle's
// uv, m_s the derivative at the midpoint of side s (V_s -> V_{s+1}) along
// that side's unit normal pointing into the triangle.
#include "core/Types.h"

#include <Eigen/Core>
#include <array>

namespace contour::powell_sabin {

inline constexpr int kPs12Patches = 12;
inline constexpr int kPs12LocalDofs = 12;

// One quadratic Bezier triangle over a uv triangle. Control points in the
// order [b0, b1, b2, b01, b12, b20]: b_i at corner i, b_ij the middle point
// of side i -> j.
template <typename T> struct QuadraticBezier {
    std::array<Vec2, 3> domain;
    std::array<T, 6> control;
};

// The split's points (docs/methods/powell-sabin-ps12.md): the corners V_i
// (0..2), the side midpoints M_s (3..5), the medians' midpoints Q_i (6..8)
// and the centroid C (9); sub-triangle l has the corners
// ps12SubTriangleCorners[l]: 2i (V_i, M_i, Q_i), 2i+1 (V_i, Q_i, M_{i-1}),
// 6+2i (M_i, Q_{i+1}, C), 7+2i (Q_{i+1}, M_{i+1}, C).
inline constexpr int kPs12SplitPoints = 10;
constexpr int ps12CornerPoint(int i) {
    return i;
}
constexpr int ps12MidpointPoint(int s) {
    return 3 + s;
}
constexpr int ps12MedianPoint(int i) {
    return 6 + i;
}
inline constexpr int kPs12CentroidPoint = 9;
inline constexpr std::array<std::array<int, 3>, kPs12Patches> ps12SubTriangleCorners = [] {
    std::array<std::array<int, 3>, kPs12Patches> t{};
    for (int i = 0; i < 3; ++i) {
        const int n = (i + 1) % 3, p = (i + 2) % 3;
        t[2 * i] = {ps12CornerPoint(i), ps12MidpointPoint(i), ps12MedianPoint(i)};
        t[2 * i + 1] = {ps12CornerPoint(i), ps12MedianPoint(i), ps12MidpointPoint(p)};
        t[6 + 2 * i] = {ps12MidpointPoint(i), ps12MedianPoint(n), kPs12CentroidPoint};
        t[7 + 2 * i] = {ps12MedianPoint(n), ps12MidpointPoint(n), kPs12CentroidPoint};
    }
    return t;
}();

// The split: 12 sub-triangles of `uv`, each counter-clockwise. Sub-triangle
// numbering is documented in Ps12Patch.cpp and stable. Both functions throw
// std::invalid_argument for a clockwise, degenerate or non-finite `uv`.
std::array<std::array<Vec2, 3>, kPs12Patches> ps12SubTriangles(const std::array<Vec2, 3>& uv);

// Row 6*l + c: control point c of sub-triangle l as a combination of the
// 12 local DOFs.
using Ps12Matrix = Eigen::Matrix<double, 6 * kPs12Patches, kPs12LocalDofs>;
Ps12Matrix ps12BezierMatrix(const std::array<Vec2, 3>& uv);

// Evaluation of a quadratic Bezier triangle at barycentric coordinates of
// its domain, and its uv derivatives (first and the constant second).
template <typename T> T evaluate(const QuadraticBezier<T>& patch, const Vec3& barycentric);
template <typename T>
void uvDerivatives(const QuadraticBezier<T>& patch, const Vec3& barycentric, T& du, T& dv);
template <typename T>
void uvSecondDerivatives(const QuadraticBezier<T>& patch, T& duu, T& duv, T& dvv);
// Barycentric coordinates of `uv` in `domain`.
Vec3 barycentricOf(const std::array<Vec2, 3>& domain, const Vec2& uv);

} // namespace contour::powell_sabin
