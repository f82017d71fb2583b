#pragma once
// Image-space intersections of curve segments (tutorial §4.3 item 1, §4.6
// step 5; Bénard 2014 §8.2): every pair of 2D segments that meet, decided
// with exact predicates on the input doubles, so that no crossing is missed
// or invented by rounding. The only CGAL user of the visibility core's 2D
// part: its templates compile here once.
#include "core/Types.h"

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
    long long sweptSegments = 0;      // segments kept (that may take part in a wanted crossing)
};

// `ignorePair(i, j)`, when given, names pairs whose meeting the caller does
// not need (segments that share a mesh vertex). A segment that meets no
// other segment except such pairs cannot take part in a wanted crossing, so
// it is left out ("swept" below counts the others): a uniform grid finds
// the pairs of overlapping boxes, and an exact test (orientation predicates
// on the input doubles) keeps the pairs that really meet. Crossings are
// reported among the kept segments only: all those of pairs not ignored,
// and only some of the ignored pairs'. They come in a sweep line's order
// (Bentley–Ottmann) over the kept segments: by meeting point (x, then y,
// compared exactly), then by pair.
//
// The pairs that meet are already known from the exact test, so no sweep is
// run: the meeting points are ordered with interval brackets and exact
// rationals where the brackets overlap. On the ~115k-face consistent meshes
// (about 13k segments, 3-4k kept) CGAL's surface sweep took ~30 ms per view
// (quiet machine), this ~10 ms, with the same crossings on the benchmark's
// views; on segments with many coincidences (test_visibility) the sweep's
// event visitor missed some meetings that this finds.
ImageIntersectionResult
imageIntersections(std::span<const ImageSegment> segments,
                   const std::function<bool(Index, Index)>& ignorePair = {});

} // namespace contour
