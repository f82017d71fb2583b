#pragma once
// Real roots of a polynomial on [0, 1] given by its Bernstein coefficients:
// Descartes' rule of signs on the coefficients bounds the number of roots
// in the interval (the sign variations, with the same parity), and de
// Casteljau subdivision at the midpoint refines it until every piece has
// zero or one variation (Vincent's theorem; the "Sturm or Vincent counting"
// of Summers 2016 §3.4.2.2). A piece with one variation holds exactly one
// root, found by bisection on the polynomial.
#include <span>
#include <vector>

namespace contour::traced {

// de Casteljau evaluation at t.
double bernsteinValue(std::span<const double> coefficients, double t);

struct BernsteinRootOptions {
    // Coefficients with |b| <= zeroTolerance count as zero (no sign).
    double zeroTolerance = 0.0;
    // Subdivision depth at which a piece still holding two or more
    // variations is given up: a cluster of roots closer than 2^-maxDepth,
    // or a double root (a contour tangent to the edge).
    int maxDepth = 40;
};

struct BernsteinRoots {
    std::vector<double> roots; // increasing, in (0, 1)
    int unresolved = 0;        // pieces given up at maxDepth (their midpoints are in roots)
    bool vanishes = false;     // every coefficient is zero: no isolated roots
};

BernsteinRoots isolateRoots(std::span<const double> coefficients,
                            const BernsteinRootOptions& options);

} // namespace contour::traced
