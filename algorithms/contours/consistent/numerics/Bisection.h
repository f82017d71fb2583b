#pragma once
// The one bracketed root search of the consistent method: the roots of g on
// an FB edge (Bénard 2014 §6.2 e), of h_p on a segment (§6.3 g, §6.4) and of
// κr along the contour (§6.2 d). The caller evaluates its own function along
// its own appendix B path (no library root finder can drive those charts);
// the search chooses the points, keeps the bracket and applies the stopping
// rule. Every difference between the callers (midpoint or Illinois regula
// falsi, |f| tolerance, bracket width, iteration cap, which sample is the
// answer) is an option, so each caller's sequence of evaluations is its own.
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace contour::consistent {

// How the next point of the bracket [lo, hi] is chosen.
enum class BisectionStep {
    Midpoint, // 0.5 (lo + hi)
    // Regula falsi, Illinois variant: the end kept twice in a row has its
    // value halved, so the bracket shrinks from both sides.
    FalsePosition,
    // The same, falling back to the midpoint when the false position is not
    // strictly inside the bracket.
    FalsePositionOrMidpoint,
};

// Which sign decides the side: a point replaces lo when test(f) equals
// test(f(lo)), hi otherwise. The two differ only where f or f(lo) is 0 or
// NaN.
enum class BisectionSign {
    Positive, // f > 0
    Negative, // f < 0
};

// The sample `best` reports: the one of least |f| seen, the earliest of
// equals.
enum class BisectionBest {
    None,         // not tracked
    FromInfinity, // a NaN or infinite |f| is never the best
    FromFirst,    // the first sample is the best until a smaller |f|
};

struct BisectionOptions {
    BisectionStep step = BisectionStep::Midpoint;
    BisectionSign sign = BisectionSign::Positive;
    BisectionBest best = BisectionBest::None;
    int maxIterations = std::numeric_limits<int>::max();
    // When set, the search goes on only while hi - lo > minWidth.
    std::optional<double> minWidth;
    // The search stops at the first sample with |f| <= tolerance (negative:
    // never).
    double tolerance = -1.0;
};

// The bracket [lo, hi] and the function's values there (Midpoint reads only
// the sign of flo).
struct BisectionBracket {
    double lo = 0.0, hi = 1.0;
    double flo = 0.0, fhi = 0.0;
};

enum class BisectionOutcome {
    Converged, // a sample with |f| <= tolerance: `last`
    Exhausted, // the iteration cap or the bracket width ended the search
    Failed,    // the evaluation returned nothing (e.g. no common chart)
};

template <class Sample> struct BisectionResult {
    BisectionOutcome outcome = BisectionOutcome::Exhausted;
    std::optional<Sample> last; // the last sample evaluated
    std::optional<Sample> best; // per BisectionOptions::best
    BisectionBracket bracket;   // the final bracket
};

// `evaluate(t)` returns std::optional<Sample> (nothing: the search fails);
// `value(sample)` is f there. Each iteration: choose t, evaluate, update
// best, stop when |f| <= tolerance, else replace one end. When loEnd / hiEnd
// are given, the sample replacing lo / hi is stored there.
template <class Evaluate, class Value,
          class Sample = typename std::invoke_result_t<Evaluate, double>::value_type>
BisectionResult<Sample> bisect(const Evaluate& evaluate, const Value& value,
                               BisectionBracket bracket, const BisectionOptions& options,
                               Sample* loEnd = nullptr, Sample* hiEnd = nullptr) {
    BisectionResult<Sample> result;
    BisectionBracket& r = bracket;
    const auto signOf = [&](double f) {
        return options.sign == BisectionSign::Positive ? f > 0.0 : f < 0.0;
    };
    double bestF = std::numeric_limits<double>::infinity();
    int side = 0; // -1: lo was replaced last, +1: hi
    for (int it = 0;
         it < options.maxIterations && (!options.minWidth || r.hi - r.lo > *options.minWidth);
         ++it) {
        double t = 0.5 * (r.lo + r.hi);
        if (options.step != BisectionStep::Midpoint) {
            t = (r.lo * r.fhi - r.hi * r.flo) / (r.fhi - r.flo);
            if (options.step == BisectionStep::FalsePositionOrMidpoint && !(t > r.lo && t < r.hi))
                t = 0.5 * (r.lo + r.hi);
        }
        std::optional<Sample> sample = evaluate(t);
        if (!sample) {
            result.outcome = BisectionOutcome::Failed;
            result.bracket = r;
            return result;
        }
        const double f = value(*sample);
        if (options.best == BisectionBest::FromFirst
                ? !result.best || std::abs(f) < bestF
                : options.best == BisectionBest::FromInfinity && std::abs(f) < bestF) {
            bestF = std::abs(f);
            result.best = *sample;
        }
        if (std::abs(f) <= options.tolerance) {
            result.outcome = BisectionOutcome::Converged;
            result.last = std::move(sample);
            result.bracket = r;
            return result;
        }
        const bool illinois = options.step != BisectionStep::Midpoint;
        if (signOf(f) == signOf(r.flo)) {
            r.lo = t;
            r.flo = f;
            if (illinois && side == -1)
                r.fhi *= 0.5;
            side = -1;
            if (loEnd)
                *loEnd = *sample;
        } else {
            r.hi = t;
            r.fhi = f;
            if (illinois && side == 1)
                r.flo *= 0.5;
            side = 1;
            if (hiEnd)
                *hiEnd = *sample;
        }
        result.last = std::move(sample);
    }
    result.outcome = BisectionOutcome::Exhausted;
    result.bracket = r;
    return result;
}

} // namespace contour::consistent
