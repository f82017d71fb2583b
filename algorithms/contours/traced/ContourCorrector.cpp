#include "contours/traced/ContourCorrector.h"

#include "surface/SurfaceFields.h"

#include <cmath>

namespace contour::traced {

ContourSample sampleContourField(const SmoothSurface& surface, const Camera& camera,
                                 const Preimage& p) {
    ContourSample s;
    s.point = surface.evaluate(p);
    s.g = orientation(s.point, camera);
    s.gradient = orientationGradient(s.point, camera);
    return s;
}

CorrectedPoint correctOntoContour(const SmoothSurface& surface, const Camera& camera, Index face,
                                  const Vec2& start, const CorrectorOptions& options) {
    CorrectedPoint c;
    c.uv = start;
    for (int i = 0;; ++i) {
        c.sample = sampleContourField(surface, camera, {face, c.uv.x(), c.uv.y()});
        c.iterations = i;
        if (!std::isfinite(c.sample.g))
            return c;
        if (std::abs(c.sample.g) <= options.gTolerance) {
            c.converged = true;
            return c;
        }
        const double n2 = c.sample.gradient.squaredNorm();
        if (i >= options.maxIterations || !(n2 > 0.0))
            return c;
        c.uv -= (c.sample.g / n2) * c.sample.gradient;
    }
}

} // namespace contour::traced
