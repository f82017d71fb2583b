#include "contours/traced/TracedCusps.h"

#include "contours/traced/ContourCorrector.h"
#include "surface/SurfaceFields.h"

#include <cmath>
#include <tbb/parallel_for.h>

namespace contour::traced {

namespace {

struct CurveSample {
    size_t segment = 0;
    double fraction = 0.0; // along the segment's chord
    double kr = 0.0;
};

// The point of segment `s` at `fraction` of its chord, pulled onto g = 0.
struct OnCurve {
    Preimage preimage;
    SurfacePoint point;
};
OnCurve pointOnSegment(const SmoothSurface& surface, const Camera& camera, const TracedSegment& s,
                       double fraction, const CorrectorOptions& corrector) {
    const Vec2 chord = s.a + fraction * (s.b - s.a);
    Vec2 uv = chord;
    if (fraction > 0.0 && fraction < 1.0) {
        const CorrectedPoint c = correctOntoContour(surface, camera, s.face, chord, corrector);
        if (c.converged)
            uv = c.uv;
    }
    const Preimage p{s.face, uv.x(), uv.y()};
    return {p, surface.evaluate(p)};
}

} // namespace

std::vector<TracedCusp> findTracedCusps(const SmoothSurface& surface, const Camera& camera,
                                        const std::vector<TracedCurve>& curves,
                                        const CuspOptions& options, long long* samplesOut) {
    CorrectorOptions corrector;
    corrector.gTolerance = options.gTolerance;
    const int perSegment = std::max(1, options.samplesPerSegment);
    std::vector<std::vector<TracedCusp>> found(curves.size());
    std::vector<long long> sampleCounts(curves.size(), 0);
    tbb::parallel_for(size_t(0), curves.size(), [&](size_t ci) {
        const TracedCurve& curve = curves[ci];
        std::vector<CurveSample> samples;
        for (size_t s = 0; s < curve.segments.size(); ++s) {
            const int last = (!curve.closed && s + 1 == curve.segments.size()) ? perSegment : 0;
            for (int k = 0; k < perSegment + (last ? 1 : 0); ++k) {
                const double f = static_cast<double>(k) / perSegment;
                const OnCurve p = pointOnSegment(surface, camera, curve.segments[s], f, corrector);
                const double kr = radialCurvature(p.point, camera);
                if (std::isfinite(kr) && kr != 0.0)
                    samples.push_back({s, f, kr});
            }
        }
        sampleCounts[ci] = static_cast<long long>(samples.size());
        const size_t m = samples.size();
        const size_t pairs = curve.closed ? (m >= 2 ? m : 0) : (m >= 1 ? m - 1 : 0);
        for (size_t q = 0; q < pairs; ++q) {
            const CurveSample& a = samples[q];
            const CurveSample& b = samples[(q + 1) % m];
            if ((a.kr > 0.0) == (b.kr > 0.0))
                continue;
            // Bisect inside a's segment: up to b, or to the segment's end
            // when b lies in a later segment (the end is the next start).
            const TracedSegment& segment = curve.segments[a.segment];
            double lo = a.fraction;
            double hi = b.segment == a.segment && b.fraction > a.fraction ? b.fraction : 1.0;
            const bool loPositive = a.kr > 0.0;
            OnCurve at = pointOnSegment(surface, camera, segment, 0.5 * (lo + hi), corrector);
            double krLo = a.kr, krHi = b.kr;
            for (int i = 0; i < options.bisections; ++i) {
                const double mid = 0.5 * (lo + hi);
                at = pointOnSegment(surface, camera, segment, mid, corrector);
                const double kr = radialCurvature(at.point, camera);
                if (!std::isfinite(kr))
                    break;
                if ((kr > 0.0) == loPositive) {
                    lo = mid;
                    krLo = kr;
                } else {
                    hi = mid;
                    krHi = kr;
                }
            }
            const bool jump = std::min(std::abs(krLo), std::abs(krHi)) > options.jumpCurvature;
            found[ci].push_back({at.preimage, at.point.position, static_cast<int>(ci), jump,
                                 a.segment, 0.5 * (lo + hi), a.kr, b.kr});
        }
    });
    std::vector<TracedCusp> cusps;
    long long total = 0;
    for (size_t ci = 0; ci < curves.size(); ++ci) {
        cusps.insert(cusps.end(), found[ci].begin(), found[ci].end());
        total += sampleCounts[ci];
    }
    if (samplesOut)
        *samplesOut = total;
    return cusps;
}

} // namespace contour::traced
