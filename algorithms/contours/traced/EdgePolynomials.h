#pragma once
// The view-independent part of g restricted to each domain edge (Summers
// 2016 §3.4.2.2). On an edge inside one polynomial patch, with the
// unnormalised normal N = f_u x f_v (the same sign as g),
//   g(t) = (c - p(t)) · N(t) = c · N(t) - (p · N)(t)   (perspective),
//   g(t) = d · N(t)                                     (orthographic),
// so g's Bernstein coefficients for any camera are dot products of two
// stored sets: N's (a vector polynomial) and p · N's. Degrees: a bicubic
// Catmull-Clark patch has p cubic and N of degree 5 along an edge, so
// p · N has degree 8; a quartic Loop box-spline patch gives 4 + 6 = 10.
// The coefficients are fitted to samples of the surface at Chebyshev
// nodes and accepted only when the fit reproduces the surface at other
// points of the edge: an edge in several patches (near an extraordinary
// vertex, adaptive isolation) or in a rational Gregory end cap fails the
// check and is sampled densely instead.
#include "surface/SmoothSurface.h"

#include <memory>
#include <vector>

namespace contour::traced {

// A domain edge: the face with the lower index that holds it, its local
// edge, and the face across (kInvalidIndex on a boundary).
struct DomainEdge {
    Index face = kInvalidIndex;
    int edge = -1;
    Index otherFace = kInvalidIndex;
    int otherEdge = -1;
};

struct EdgePolynomial {
    bool polynomial = false;
    // Bernstein coefficients (degree D) of N(t) and of p(t) · N(t), t along
    // `edge` of `face` from its corner `edge`.
    std::vector<Vec3> normal;
    std::vector<double> positionDotNormal;
    // When not polynomial: p and N at `samples` + 1 evenly spaced t.
    std::vector<Vec3> samplePositions, sampleNormals;
};

struct EdgePolynomials {
    int degree = 0;
    int fallbackSamples = 0;
    std::vector<DomainEdge> edges;
    std::vector<EdgePolynomial> polynomials; // per edge
    long long polynomialEdges = 0;
    double seconds = 0.0;
};

struct EdgePolynomialOptions {
    // Largest error of the fit at the check points, relative to the largest
    // coefficient of the same function.
    double fitTolerance = 1e-9;
    int fallbackSamples = 16; // intervals per edge that is not one polynomial
};

// Built once per (surface, options) and shared by every view (cached; the
// entries die with the surface).
std::shared_ptr<const EdgePolynomials>
sharedEdgePolynomials(const std::shared_ptr<const SmoothSurface>& surface,
                      const EdgePolynomialOptions& options);

// The degree of g along an edge of a polynomial patch of this surface kind.
int edgeDegree(SurfaceKind kind);

} // namespace contour::traced
