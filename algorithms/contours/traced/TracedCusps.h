#pragma once
// Cusps of the traced contour: the points where the radial curvature kr
// changes sign along the curve (Koenderink; Bénard 2014 §6.2 d; Summers
// 2016 computes none). kr is sampled at every point of the curve and at
// points between them pulled onto g = 0, so that a cusp pair closer than a
// tracing step is still seen; each sign change is then bisected on the
// curve (midpoints corrected onto g = 0). Samples where kr is NaN (the view
// along the normal) or exactly 0 are skipped, as the dense ground truth
// skips them.
#include "camera/Camera.h"
#include "contours/traced/CurveTracer.h"

#include <vector>

namespace contour::traced {

struct TracedCusp {
    Preimage preimage;
    Vec3 position = Vec3::Zero();
    int curve = -1;
    // kr jumps over 0 here instead of passing through it: the evaluator's
    // patches meet with different second derivatives (the Gregory end caps
    // next to extraordinary vertices, SubdivisionSurface.h). Still a sign
    // change, so still counted.
    bool jump = false;
    // Where along the curve: segment `segment` at `fraction` of its chord,
    // and the radial curvature at the samples before and after the cusp.
    size_t segment = 0;
    double fraction = 0.0;
    double krBefore = 0.0, krAfter = 0.0;
};

struct CuspOptions {
    int samplesPerSegment = 16; // kr samples per segment (its start and samplesPerSegment - 1
                                // points between)
    int bisections = 30;
    double gTolerance = 0.0;
    // |kr| above this on both sides of the final bracket marks a jump.
    double jumpCurvature = 0.0;
};

std::vector<TracedCusp> findTracedCusps(const SmoothSurface& surface, const Camera& camera,
                                        const std::vector<TracedCurve>& curves,
                                        const CuspOptions& options, long long* samples = nullptr);

} // namespace contour::traced
