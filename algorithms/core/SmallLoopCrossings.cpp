#include "core/SmallLoopCrossings.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace contour {

namespace {

double arcDistance(const CurveArc& curve, double a, double b) {
    const double d = std::abs(a - b);
    return curve.closed ? std::min(d, std::max(0.0, curve.length - d)) : d;
}

// A bigon (two crossings) or a monogon (first == second).
struct Loop {
    double size = 0.0; // the longer of its arcs
    size_t first = 0, second = 0;
};

} // namespace

std::vector<std::uint8_t> smallLoopCrossings(std::span<const CurveCrossing> crossings,
                                             std::span<const CurveArc> curves, double loopPixels) {
    std::vector<std::uint8_t> small(crossings.size(), 0);
    if (!(loopPixels > 0.0))
        return small;
    const auto arc = [&](Index curve, double a, double b) {
        return arcDistance(curves[static_cast<size_t>(curve)], a, b);
    };
    std::vector<Loop> loops;
    // Crossings grouped by their (unordered) pair of curves: only those of
    // one group can form a bigon.
    std::map<std::pair<Index, Index>, std::vector<size_t>> byPair;
    for (size_t i = 0; i < crossings.size(); ++i) {
        const CurveCrossing& x = crossings[i];
        byPair[std::minmax(x.curveA, x.curveB)].push_back(i);
        if (x.curveA == x.curveB) {
            const double d = arc(x.curveA, x.arcA, x.arcB);
            if (d < loopPixels)
                loops.push_back({d, i, i});
        }
    }
    for (const auto& [pair, members] : byPair)
        for (size_t u = 0; u < members.size(); ++u)
            for (size_t w = u + 1; w < members.size(); ++w) {
                const CurveCrossing& x = crossings[members[u]];
                const CurveCrossing& y = crossings[members[w]];
                // Match y's ends to x's: by curve, and for a self-crossing
                // pair by the closer assignment.
                double alongA = 0.0, alongB = 0.0;
                if (x.curveA != x.curveB) {
                    const bool same = y.curveA == x.curveA;
                    alongA = arc(x.curveA, x.arcA, same ? y.arcA : y.arcB);
                    alongB = arc(x.curveB, x.arcB, same ? y.arcB : y.arcA);
                } else {
                    const double straight =
                        std::max(arc(x.curveA, x.arcA, y.arcA), arc(x.curveA, x.arcB, y.arcB));
                    const double swapped =
                        std::max(arc(x.curveA, x.arcA, y.arcB), arc(x.curveA, x.arcB, y.arcA));
                    alongA = alongB = std::min(straight, swapped);
                }
                const double size = std::max(alongA, alongB);
                if (size < loopPixels)
                    loops.push_back({size, members[u], members[w]});
            }
    std::stable_sort(loops.begin(), loops.end(),
                     [](const Loop& a, const Loop& b) { return a.size < b.size; });
    for (const Loop& l : loops) {
        if (small[l.first] || small[l.second])
            continue;
        small[l.first] = 1;
        small[l.second] = 1;
    }
    return small;
}

} // namespace contour
