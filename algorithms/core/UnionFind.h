#pragma once
// Disjoint sets over 0 .. n-1 with path halving; unite() keeps the smaller
// index as the root, so roots are deterministic.
#include "core/Types.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace contour {

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) {
        for (std::size_t i = 0; i < n; ++i)
            parent_[i] = static_cast<Index>(i);
    }
    Index find(Index x) {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];
            x = parent_[x];
        }
        return x;
    }
    // False when a and b were already in one set.
    bool unite(Index a, Index b) {
        a = find(a);
        b = find(b);
        if (a == b)
            return false;
        parent_[std::max(a, b)] = std::min(a, b);
        return true;
    }

private:
    std::vector<Index> parent_;
};

} // namespace contour
