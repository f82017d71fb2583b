#pragma once
// Joint roots of two scalar functions over a parameter-space triangle, by
// recursive bisection (Bénard 2014 §6.2 d, cusp detection: g = 0 and
// κr = 0; §6.3 g, the two-C radial vertex: h_p1 = 0 and h_p2 = 0). The
// triangle is bisected along its longest edge while both functions change
// sign over its corners; a triangle whose area falls below a threshold and
// still shows both sign changes yields its centroid. Coordinates are long
// double (the paper ran this search in quad precision); the functions are
// whatever the caller evaluates, typically in double.
#include <array>
#include <functional>
#include <vector>

namespace contour::consistent {

using Point2L = std::array<long double, 2>;
using Barycentric = std::array<long double, 3>; // weights of the triangle's corners

struct JointRootOptions {
    // Stop bisecting below this area (paper: 1e-20).
    long double minArea = 1e-20L;
    // Also stop when the longest edge is shorter than this: a precision floor
    // for callers that evaluate in double (0: none).
    long double minEdge = 0.0L;
    // Roots closer than this are one root (a root on a bisection edge shows
    // in both halves); < 0: 1e4 times the edge of a right triangle of area
    // minArea.
    long double mergeDistance = -1.0L;
    // Evaluation budget; when exhausted the search stops (budgetExhausted).
    long long maxEvaluations = 200000;
};

struct JointRoot {
    Point2L point{};
    Barycentric barycentric{};
};

struct JointRootResult {
    std::vector<JointRoot> roots;
    long long evaluations = 0;
    // Smallest triangles with both sign changes rejected because a value
    // was not finite (NaN is never a root).
    long long rejectedUndefined = 0;
    bool budgetExhausted = false;
};

// Both functions at a point of the triangle (its coordinates and its
// barycentric coordinates with respect to the corners).
using JointFunctions = std::function<std::array<double, 2>(const Point2L&, const Barycentric&)>;

// Whether a function may have a root over a triangle with these corner
// values: some value <= 0 and some >= 0 (not all exactly zero), or a value
// is not finite (unknown, so the search keeps looking but never returns a
// root there).
bool mayChangeSign(double a, double b, double c);
// The same, with all three values finite.
bool changesSign(double a, double b, double c);

// Every joint root found in the triangle `corners`, given the functions'
// values at the corners (cornerValues[i] = f(corners[i])).
JointRootResult findJointRoots(const std::array<Point2L, 3>& corners,
                               const std::array<std::array<double, 2>, 3>& cornerValues,
                               const JointFunctions& functions, const JointRootOptions& options);

} // namespace contour::consistent
