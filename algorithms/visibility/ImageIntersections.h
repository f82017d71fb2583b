#pragma once
// Image-space intersections of curve segments (tutorial §4.3 item 1, §4.6
// step 5; Bénard 2014 §8.2): every pair of 2D segments that meet, found with
// CGAL's sweep line (Bentley–Ottmann) on exact predicates and exact
// constructions, so that no crossing is missed or invented by rounding. The
// only CGAL user of the visibility core: its templates compile here once.
#include "mesh/Types.h"

#include <functional>
#include <span>
#include <vector>

namespace contour {

struct ImageSegment {
    Vec2 a;
    Vec2 b;
};

// Two segments meeting at one point. `interiorFirst` / `interiorSecond` say
// (exactly) whether the point lies strictly inside that segment rather than
// at one of its endpoints.
struct ImageCrossing {
    Index first = kInvalidIndex; // first < second
    Index second = kInvalidIndex;
    // At a segment's endpoint: that endpoint. Inside both: the two segments'
    // crossing computed in double (within a few ulps of the exact point,
    // which is not evaluated: GMP cost more than the sweep).
    Vec2 point = Vec2::Zero();
    bool interiorFirst = false;
    bool interiorSecond = false;
};

struct ImageIntersectionResult {
    std::vector<ImageCrossing> crossings;
    // Pairs of collinear segments that overlap along a piece (degenerate: no
    // single crossing point); reported, not split.
    std::vector<std::pair<Index, Index>> overlaps;
    long long degenerateSegments = 0; // zero length in the image: left out
    long long sweptSegments = 0;      // segments that went into the sweep
};

// `ignorePair(i, j)`, when given, names pairs whose meeting the caller does
// not need (segments that share a mesh vertex). A segment that meets no
// other segment except such pairs cannot take part in a wanted crossing, so
// it is left out of the sweep: CGAL's box intersection finds the pairs of
// overlapping boxes, and an exact test (orientation predicates on the input
// doubles) keeps the pairs that really meet. Crossings are reported among
// the swept segments only: all those of pairs not ignored, and only some of
// the ignored pairs'.
ImageIntersectionResult
imageIntersections(std::span<const ImageSegment> segments,
                   const std::function<bool(Index, Index)>& ignorePair = {});

} // namespace contour
