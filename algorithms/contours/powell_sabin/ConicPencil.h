#pragma once
// Real intersections of two conics in the plane by the pencil method
// (Ogaki & Tokuyoshi 2011, as used by Capouellez et al. 2023 §4.2 for cusps
// and ray tests): a real root lambda of the cubic det(M1 + lambda M2) = 0 gives
// a degenerate member of the pencil, which splits into two lines; every
// common point of the two conics lies on that member, so intersecting each
// line with one of the conics (a quadratic in one variable) yields them all.
// The cubic is solved by the eigenvalues of its companion matrix.
#include "core/Types.h"

#include <Eigen/Core>
#include <vector>

namespace contour::powell_sabin {

// The conic x^T M x = 0 with x = (u, v, 1), M symmetric:
//   a u^2 + b u v + c v^2 + d u + e v + f = 0.
Eigen::Matrix3d conicMatrix(double a, double b, double c, double d, double e, double f);

struct ConicPencilOptions {
    // Relative zero tests (§4.1 tests every "x = 0" as |x| < eps, eps = 1e-10):
    // a determinant of a unit-norm conic, an eigenvalue of a degenerate member
    // relative to its largest, a coefficient of a line's restriction to a conic.
    double zeroTolerance = 1e-10;
    // A candidate is kept when |x^T M x| / |x|^2 of both unit-norm conics is at
    // most this, x = (u, v, 1): it rejects the real vertex of a complex line pair
    // and keeps tangent points, whose residual is quadratically small.
    double residualTolerance = 1e-8;
    // Candidates closer than this times max(1, |p|) are one point (a tangency
    // gives a double root split by round-off).
    double mergeDistance = 1e-7;
    // A homogeneous point (x, y, w) with |w| at most this times its norm lies
    // at infinity and is dropped.
    double infinityTolerance = 1e-14;
    // Newton steps on the original pair that polish each point (each step is
    // kept only when it lowers the residual).
    int newtonSteps = 2;
    // An eigenvalue of the cubic's companion matrix is taken as real when its
    // imaginary part is at most this times 1 + |real part| (a double root may
    // come out as a close complex pair).
    double realRootTolerance = 1e-6;
    // Inputs with |M - M^T| > this times |M| are rejected as not symmetric.
    double symmetryTolerance = 1e-12;
};

struct ConicIntersection {
    // Distinct isolated real common points, at most 4; tangent points appear once.
    std::vector<Vec2> points;
    // Lines (homogeneous l: l . (u, v, 1) = 0, unit norm) contained in both
    // conics, apart from the line at infinity. `points` may then also hold
    // points of these lines.
    std::vector<Eigen::Vector3d> sharedLines;
    // The two conics are the same up to scale, or one of them is identically
    // zero: every real point of the other one is common; `points` is empty.
    bool sharedConic = false;
};

// Throws std::invalid_argument for a non-finite or non-symmetric input.
// Points at infinity (parallel lines, parabolas with a common axis
// direction) are not reported.
ConicIntersection intersectConics(const Eigen::Matrix3d& m1, const Eigen::Matrix3d& m2,
                                  const ConicPencilOptions& options = {});

} // namespace contour::powell_sabin
