#pragma once
// Crossings of projected polylines that bound a loop smaller than a pixel.
// A polyline that follows a smooth contour zig-zags where the contour turns
// sharply (next to cusps, Bénard 2014 §8.4): two branches a fraction of a
// pixel apart then cross twice (a bigon) where the smooth curves cross once
// or not at all, or a branch crosses itself around a cusp (a monogon) where
// the smooth curve does not. Such crossings are artefacts of the sampling,
// of the method's mesh and of the dense oracle's lattice alike: the view
// graph flags its T-junctions there and the oracle's crossing count leaves
// them out, by this one rule.
#include "core/Types.h"

#include <cstdint>
#include <span>
#include <vector>

namespace contour {

// One crossing: where it lies along each of the two curves, as image arc
// length from the curve's start (the same curve twice for a self-crossing).
struct CurveCrossing {
    Index curveA = kInvalidIndex;
    double arcA = 0.0;
    Index curveB = kInvalidIndex;
    double arcB = 0.0;
};

// A curve's image length and whether it is closed (arc distances wrap).
struct CurveArc {
    double length = 0.0;
    bool closed = false;
};

// The crossings that bound a loop with less than `loopPixels` of arc on each
// curve: pairs of crossings of the same two curves whose arc distances along
// both are below it (bigons), and self-crossings whose two arc positions are
// closer than it along the curve (monogons). Smallest loops first, each
// crossing in one loop at most. Returns a flag per crossing (1: in a small
// loop). loopPixels <= 0 flags none.
std::vector<std::uint8_t> smallLoopCrossings(std::span<const CurveCrossing> crossings,
                                             std::span<const CurveArc> curves, double loopPixels);

} // namespace contour
