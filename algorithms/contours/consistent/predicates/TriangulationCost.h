#pragma once
// The cost of a candidate triangulation in the §6.4 extensions that
// re-triangulate a polygon (vertex removal, patch search): fewest
// inconsistent faces, then the largest minimum Bank-Smith quality; a
// triangle that is not allowed makes the triangulation invalid.
#include <limits>

namespace contour::consistent {

struct TriangulationCost {
    int inconsistent = std::numeric_limits<int>::max();
    double minQuality = -1.0;
    bool valid() const { return inconsistent != std::numeric_limits<int>::max(); }
};

// a is strictly better than b (an invalid cost is worse than any valid one).
inline bool better(const TriangulationCost& a, const TriangulationCost& b) {
    if (!b.valid())
        return a.valid();
    if (!a.valid())
        return false;
    return a.inconsistent < b.inconsistent ||
           (a.inconsistent == b.inconsistent && a.minQuality > b.minQuality);
}

} // namespace contour::consistent
