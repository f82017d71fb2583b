#include "contours/traced/BernsteinRoots.h"

#include <cmath>

namespace contour::traced {

namespace {

int signVariations(const std::vector<double>& b, double zero) {
    int variations = 0, last = 0;
    for (double x : b) {
        const int s = x > zero ? 1 : x < -zero ? -1 : 0;
        if (s != 0 && last != 0 && s != last)
            ++variations;
        if (s != 0)
            last = s;
    }
    return variations;
}

// de Casteljau at 1/2: the coefficients of the two halves.
void split(const std::vector<double>& b, std::vector<double>& left, std::vector<double>& right) {
    const size_t n = b.size();
    std::vector<double> work = b;
    left.resize(n);
    right.resize(n);
    for (size_t k = 0; k < n; ++k) {
        left[k] = work[0];
        right[n - 1 - k] = work[n - 1 - k];
        for (size_t i = 0; i + 1 < n - k; ++i)
            work[i] = 0.5 * (work[i] + work[i + 1]);
    }
}

// The single root of a piece with one sign variation, by bisection on the
// polynomial mapped to [a, b].
double bisectPiece(const std::vector<double>& piece, double a, double b) {
    double lo = 0.0, hi = 1.0;
    const double gLo = bernsteinValue(piece, 0.0);
    for (int i = 0; i < 60 && (hi - lo) * (b - a) > 1e-16; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double gm = bernsteinValue(piece, mid);
        if (gm == 0.0)
            return a + mid * (b - a);
        if ((gm > 0.0) == (gLo > 0.0))
            lo = mid;
        else
            hi = mid;
    }
    return a + 0.5 * (lo + hi) * (b - a);
}

void isolate(const std::vector<double>& b, double lo, double hi, int depth,
             const BernsteinRootOptions& options, BernsteinRoots& out) {
    const int v = signVariations(b, options.zeroTolerance);
    if (v == 0)
        return;
    // One variation with both end values of opposite signs: exactly one root.
    const double z = options.zeroTolerance;
    if (v == 1 && std::abs(b.front()) > z && std::abs(b.back()) > z) {
        out.roots.push_back(bisectPiece(b, lo, hi));
        return;
    }
    if (depth >= options.maxDepth) {
        out.roots.push_back(0.5 * (lo + hi));
        ++out.unresolved;
        return;
    }
    std::vector<double> left, right;
    split(b, left, right);
    const double mid = 0.5 * (lo + hi);
    isolate(left, lo, mid, depth + 1, options, out);
    isolate(right, mid, hi, depth + 1, options, out);
}

} // namespace

double bernsteinValue(std::span<const double> coefficients, double t) {
    std::vector<double> work(coefficients.begin(), coefficients.end());
    for (size_t k = work.size(); k > 1; --k)
        for (size_t i = 0; i + 1 < k; ++i)
            work[i] = (1.0 - t) * work[i] + t * work[i + 1];
    return work.empty() ? 0.0 : work[0];
}

BernsteinRoots isolateRoots(std::span<const double> coefficients,
                            const BernsteinRootOptions& options) {
    BernsteinRoots out;
    const std::vector<double> b(coefficients.begin(), coefficients.end());
    bool allZero = true;
    for (double x : b)
        allZero = allZero && std::abs(x) <= options.zeroTolerance;
    if (allZero) {
        out.vanishes = !b.empty();
        return out;
    }
    isolate(b, 0.0, 1.0, 0, options, out);
    return out;
}

} // namespace contour::traced
