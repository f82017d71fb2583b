#pragma once
// g = (c - f(u)) · n(u) and its parameter gradient at a preimage (the
// definitions of surface/SurfaceFields.h, so the traced curve is the zero set
// the dense ground truth samples), and the corrector of Summers 2016
// §3.4.2.1: a point pulled back onto g = 0. Summers minimises g^2 by a line
// search; the Gauss-Newton step x <- x - g ∇g / |∇g|^2 used here is the
// minimum-norm Newton step of the same problem and converges quadratically
// next to a regular point of the zero set.
#include "camera/Camera.h"
#include "surface/SmoothSurface.h"

namespace contour::traced {

struct ContourSample {
    double g = 0.0;
    Vec2 gradient = Vec2::Zero(); // dg/du, dg/dv in the face's chart
    SurfacePoint point;
};

ContourSample sampleContourField(const SmoothSurface& surface, const Camera& camera,
                                 const Preimage& p);

struct CorrectorOptions {
    double gTolerance = 0.0; // |g| accepted on the curve (length units)
    int maxIterations = 8;
};

struct CorrectedPoint {
    bool converged = false;
    Vec2 uv = Vec2::Zero();
    ContourSample sample;
    int iterations = 0;
};

// Newton steps from `start` in face `face`'s chart. The point may leave the
// face slightly (the chart extends affinely, SmoothSurface.h): the caller
// decides what an exit means.
CorrectedPoint correctOntoContour(const SmoothSurface& surface, const Camera& camera, Index face,
                                  const Vec2& start, const CorrectorOptions& options);

// The unit tangent of g = 0 with the front side (g > 0) on its right:
// (-g_v, g_u) / |∇g|. One orientation for every chart, since the domain's
// charts are all counter-clockwise, so a curve keeps its direction across
// faces.
inline Vec2 contourTangent(const Vec2& gradient) {
    const double n = gradient.norm();
    return n > 0.0 ? Vec2(-gradient.y() / n, gradient.x() / n) : Vec2::Zero();
}

} // namespace contour::traced
