#include "contours/consistent/numerics/ContourCuspSearch.h"

#include "contours/consistent/numerics/Bisection.h"
#include "surface/SurfaceFields.h"

#include <cmath>
#include <limits>

namespace contour::consistent {

std::optional<ContourPoint> contourPointOnFan(const ConsistentMesh& m, Index o, Index a, Index b,
                                              double s, const ContourCuspOptions& options,
                                              ContourCuspStats& stats) {
    const MeshVertex& vo = m.vertex(o);
    const std::optional<Preimage> q = m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, s);
    if (!q)
        return std::nullopt;
    ++stats.evaluations;
    const double flo = vo.g, fhi = orientation(m.surface().evaluate(*q), m.camera());
    // g must change sign once on O-S(s); otherwise A-B itself crosses g = 0
    // (a sign change the initialization's 10 samples missed).
    if (!(flo * fhi < 0.0))
        return std::nullopt;
    // Regula falsi, Illinois variant, falling back to bisection; the answer
    // is the sample of least |g|.
    struct Probe {
        double t;
        Preimage preimage;
        SurfacePoint point;
        double g;
    };
    BisectionOptions search;
    search.step = BisectionStep::FalsePositionOrMidpoint;
    search.sign = BisectionSign::Positive;
    search.best = BisectionBest::FromInfinity;
    search.maxIterations = options.maxRootIterations;
    search.minWidth = 1e-15;
    search.tolerance = options.gTolerance;
    const BisectionResult<Probe> r = bisect(
        [&](double along) -> std::optional<Probe> {
            const std::optional<Preimage> p = m.interpolate(vo.preimage, *q, along);
            if (!p)
                return std::nullopt;
            const SurfacePoint sp = m.surface().evaluate(*p);
            ++stats.evaluations;
            return Probe{along, *p, sp, orientation(sp, m.camera())};
        },
        [](const Probe& x) { return x.g; }, {0.0, 1.0, flo, fhi}, search);
    if (r.outcome == BisectionOutcome::Failed || !r.best)
        return std::nullopt;
    const bool converged = r.outcome == BisectionOutcome::Converged;
    ContourPoint best;
    best.s = s;
    best.t = r.best->t;
    best.preimage = r.best->preimage;
    const SurfacePoint& bestPoint = r.best->point;
    stats.unconvergedRoots += !converged;
    best.converged = converged;
    best.position = bestPoint.position;
    best.radialCurvature = radialCurvature(bestPoint, m.camera());
    return best;
}

namespace {

// A sample of κr along the contour: `point` is nullopt where the line from O
// has no contour point (the arc is broken there); `defined` is false there
// and where κr is NaN or exactly 0.
struct Sample {
    double s = 0.0;
    std::optional<ContourPoint> point;
    bool defined = false;
    double f = 0.0; // |κr|
};

Sample sampleAt(const ConsistentMesh& m, Index o, Index a, Index b, double s,
                const ContourCuspOptions& options, ContourCuspStats& stats) {
    Sample x;
    x.s = s;
    x.point = contourPointOnFan(m, o, a, b, s, options, stats);
    x.defined =
        x.point && std::isfinite(x.point->radialCurvature) && x.point->radialCurvature != 0.0;
    x.f = x.defined ? std::abs(x.point->radialCurvature) : 0.0;
    stats.undefinedSamples += !x.defined;
    return x;
}

bool positive(const Sample& x) {
    return x.point->radialCurvature > 0.0;
}

} // namespace

std::vector<ContourPoint> contourCuspsInFace(const ConsistentMesh& m, Index o, Index a, Index b,
                                             const ContourCuspOptions& options,
                                             ContourCuspStats& stats) {
    const int finest = std::max(1, options.samples);
    const int first = std::min(finest, 4);
    std::vector<Sample> samples;
    for (int i = 0; i <= first; ++i)
        samples.push_back(sampleAt(m, o, a, b, static_cast<double>(i) / first, options, stats));
    // Adaptive refinement: a cusp pair between two samples makes |κr| dip to
    // 0 between them, so the samples around it show a local minimum of |κr|
    // (an end of the face's arc counts when |κr| decreases towards it: the
    // dip may straddle the face's edge). The intervals next to each such
    // minimum are halved down to 1 / samples; elsewhere the coarse samples
    // stand.
    const double minWidth = (1.0 + 1e-9) / finest;
    for (bool refined = true; refined;) {
        refined = false;
        std::vector<Sample> next;
        for (size_t i = 0; i < samples.size(); ++i) {
            next.push_back(samples[i]);
            if (i + 1 == samples.size())
                break;
            const Sample &l = samples[i], &r = samples[i + 1];
            if (r.s - l.s <= minWidth)
                continue;
            // The end of an arc (the contour leaves through A-B): a sign
            // change may lie just before the gap.
            if (l.defined != r.defined && (!l.point || !r.point)) {
                next.push_back(sampleAt(m, o, a, b, 0.5 * (l.s + r.s), options, stats));
                refined = true;
                continue;
            }
            if (!l.defined || !r.defined || positive(l) != positive(r))
                continue;
            // Whether l (r) is a local minimum of |κr| on its arc: its other
            // neighbour is absent, undefined, of the other sign, or larger.
            const auto isMinimum = [&](size_t j, size_t other) {
                if (other >= samples.size())
                    return true;
                const Sample& x = samples[other];
                return !x.defined || positive(x) != positive(samples[j]) || x.f >= samples[j].f;
            };
            const bool lMin = l.f <= r.f && (i == 0 || isMinimum(i, i - 1));
            const bool rMin = r.f <= l.f && isMinimum(i + 1, i + 2);
            if (!lMin && !rMin)
                continue;
            next.push_back(sampleAt(m, o, a, b, 0.5 * (l.s + r.s), options, stats));
            refined = true;
        }
        samples = std::move(next);
    }
    std::vector<ContourPoint> out;
    // The last sample with a defined κr on the current arc: a sample without
    // a contour point (the contour leaves through A-B, or no chart) ends the
    // arc, since the samples on both sides of it need not lie on one contour
    // curve; a κr that is NaN or 0 is only skipped.
    const Sample* previous = nullptr;
    for (const Sample& x : samples) {
        if (!x.point) {
            previous = nullptr;
            continue;
        }
        if (!x.defined)
            continue;
        if (previous && positive(*previous) != positive(x)) {
            // One sign change of κr along the contour between the two
            // samples: bisection on s (the sign at the midpoint decides).
            ContourPoint lo = *previous->point, hi = *x.point;
            BisectionOptions search;
            search.step = BisectionStep::Midpoint;
            search.sign = BisectionSign::Positive;
            search.minWidth = options.sTolerance;
            // A κr that is 0 or not finite ends the search (tolerance 0).
            search.tolerance = 0.0;
            const BisectionResult<ContourPoint> r =
                bisect([&](double sm) { return contourPointOnFan(m, o, a, b, sm, options, stats); },
                       [](const ContourPoint& c) {
                           return std::isfinite(c.radialCurvature) ? c.radialCurvature : 0.0;
                       },
                       {lo.s, hi.s, lo.radialCurvature, hi.radialCurvature}, search, &lo, &hi);
            const bool broken = r.outcome == BisectionOutcome::Failed; // a gap: not one curve
            // κr that jumps across 0 instead of passing through it: both
            // ends of the final bracket keep a large |κr|. Near extraordinary
            // vertices the surface's second derivatives (and, slightly, its
            // normals) are not continuous across the evaluator's sub-patch
            // boundaries. The sign change is kept (the contour's κr does
            // change sign there, and the cusps of a closed loop pair up).
            const double scale = std::max(previous->f, x.f);
            stats.jumps += std::min(std::abs(lo.radialCurvature), std::abs(hi.radialCurvature)) >
                           options.jumpRatio * scale;
            if (broken) // midpoint steps: the failed sample was the final bracket's middle
                stats.brokenArcGaps.push_back(0.5 * (r.bracket.lo + r.bracket.hi));
            else
                out.push_back(std::abs(lo.radialCurvature) <= std::abs(hi.radialCurvature) ? lo
                                                                                           : hi);
        }
        previous = &x;
    }
    return out;
}

} // namespace contour::consistent
