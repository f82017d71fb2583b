#pragma once
// Cusps along the contour's crossing of one face (Bénard 2014 §6.2 d, a
// variant of the paper's test). The paper bisects a face while g and the
// radial curvature κr both change sign over its corners; but κr at the
// corners is κr off the contour, so a κr = 0 curve that crosses the
// contour twice inside the face (a cusp pair), or once near a face edge,
// can leave all three corners with one sign of κr: the cusps are missed.
// Here κr is sampled ON the contour instead: a face with corner O whose
// label differs from A's and B's is crossed by g = 0 between O and edge
// A-B, and every line from O to a point S(s) of A-B (s in [0, 1], appendix
// B interpolation) meets it at one contour point c(s) (the root of g on
// O-S(s)). A cusp is a sign change of κr(c(s)); it is refined by bisection
// on s, and its s is exactly the split point of A-B that puts it on the new
// edge O-S (Fig. 16b), the cusp edge placeCusp makes. The neighbouring face
// across O-A (O-B) meets the same contour point on that edge, so a sign
// change is seen from one face, or from two at the same point.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <optional>
#include <vector>

namespace contour::consistent {

struct ContourCuspOptions {
    // κr at c(i / 4), i = 0..4, then adaptively down to a spacing of
    // 1 / samples next to each local minimum of |κr|.
    int samples = 32;
    double gTolerance = 0.0;    // |g| at which a root of g on O-S(s) is accepted
    int maxRootIterations = 60; // per root (regula falsi, Illinois variant)
    double sTolerance = 1e-11;  // bisection on s stops below this interval
    // A sign change whose final bracket keeps |κr| above jumpRatio times the
    // larger |κr| of the two samples around it is a jump, not a root.
    double jumpRatio = 1e-3;
    // Used by cusp detection: a cusp whose root of g on its cusp edge does
    // not converge (g jumps over 0 there, on a sub-patch boundary) is moved
    // along A-B by the first of jumpOffset * 10^k (k = 0..3, either side)
    // where it converges.
    double jumpOffset = 1e-6;
};

struct ContourCuspStats {
    long long evaluations = 0;      // surface evaluations
    long long undefinedSamples = 0; // no chart, g of one sign on O-S(s), or κr NaN / 0
    long long unconvergedRoots = 0; // roots of g left above gTolerance
    long long jumps = 0;            // sign changes where κr jumps over 0 (kept)
    // Per sign change across a gap in the contour arc (a broken arc), the s where the bisection found no contour point: S(s)
    // on O's side of g = 0 means A-B crosses g = 0 twice around it (the
    // contour leaves the face through A-B and comes back), and κr changes
    // sign on the piece outside the face.
    std::vector<double> brokenArcGaps;
};

struct ContourPoint {
    double s = 0.0; // S(s) = A + s (B - A)
    double t = 0.0; // the root of g at O + t (S(s) - O)
    Preimage preimage;
    Vec3 position = Vec3::Zero();
    double radialCurvature = 0.0; // NaN when undefined
    bool converged = false;       // |g| <= gTolerance reached
};

// The contour point on the line from o to S(s) on a-b; nullopt when a
// preimage has no common chart (appendix B) or g(S(s)) has o's sign (then
// A-B itself crosses g = 0 and the contour leaves the face through it).
std::optional<ContourPoint> contourPointOnFan(const ConsistentMesh& m, Index o, Index a, Index b,
                                              double s, const ContourCuspOptions& options,
                                              ContourCuspStats& stats);

// The cusps of face (o, a, b): o's label differs from a's and b's (both F or
// both B). Sorted by s.
std::vector<ContourPoint> contourCuspsInFace(const ConsistentMesh& m, Index o, Index a, Index b,
                                             const ContourCuspOptions& options,
                                             ContourCuspStats& stats);

} // namespace contour::consistent
