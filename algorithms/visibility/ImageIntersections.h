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
    Vec2 point = Vec2::Zero(); // rounded from the exact intersection
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
// not need (segments that share a mesh vertex). A segment whose bounding box
// overlaps no other box except such pairs' cannot take part in a wanted
// crossing, so it is left out of the sweep (CGAL's box intersection finds
// the overlaps first); crossings are reported among the others only.
ImageIntersectionResult
imageIntersections(std::span<const ImageSegment> segments,
                   const std::function<bool(Index, Index)>& ignorePair = {});

} // namespace contour
