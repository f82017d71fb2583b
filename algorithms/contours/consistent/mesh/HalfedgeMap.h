#pragma once
// The face of every directed edge of ConsistentMesh, as an open-addressing
// hash table (linear probing, tombstones). Every phase of the consistent
// method rebuilds it for the whole mesh (reload) and looks edges up in its
// inner loops; std::unordered_map spent most of that time allocating nodes.
// Only lookups, insertions and erasures: no iteration, so the layout never
// affects a result.
#include "mesh/TriangleMesh.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace contour::consistent {

class HalfedgeMap {
public:
    // The face stored for key k, or kInvalidIndex.
    Index find(std::uint64_t k) const {
        if (keys_.empty() || k >= kErased)
            return kInvalidIndex;
        for (size_t i = slot(k);; i = (i + 1) & mask_) {
            if (keys_[i] == k)
                return values_[i];
            if (keys_[i] == kEmpty)
                return kInvalidIndex;
        }
    }

    // Stores k -> f; false (and nothing changes) when k is already present.
    // Keys with kInvalidIndex halves are refused.
    bool insert(std::uint64_t k, Index f) {
        if (k >= kErased)
            return false;
        if (2 * (used_ + 1) > keys_.size())
            rehash(std::max<size_t>(16, 4 * (size_ + 1)));
        size_t erased = keys_.size();
        size_t i = slot(k);
        for (;; i = (i + 1) & mask_) {
            if (keys_[i] == k)
                return false;
            if (keys_[i] == kEmpty)
                break;
            if (keys_[i] == kErased && erased == keys_.size())
                erased = i;
        }
        if (erased != keys_.size())
            i = erased; // reuse a tombstone on the probe path
        else
            ++used_;
        keys_[i] = k;
        values_[i] = f;
        ++size_;
        return true;
    }

    // Removes k when it maps to f.
    void erase(std::uint64_t k, Index f) {
        if (keys_.empty() || k >= kErased)
            return;
        for (size_t i = slot(k);; i = (i + 1) & mask_) {
            if (keys_[i] == k) {
                if (values_[i] == f) {
                    keys_[i] = kErased;
                    values_[i] = kInvalidIndex;
                    --size_;
                }
                return;
            }
            if (keys_[i] == kEmpty)
                return;
        }
    }

    size_t size() const { return size_; }

    void clear() {
        keys_.clear();
        values_.clear();
        size_ = used_ = 0;
        mask_ = 0;
    }

    void reserve(size_t n) {
        if (2 * n > keys_.size())
            rehash(2 * n);
    }

private:
    // Keys are two non-negative 32-bit indices, so the top bit is free.
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
    static constexpr std::uint64_t kErased = ~std::uint64_t(0) - 1;

    std::vector<std::uint64_t> keys_;
    std::vector<Index> values_;
    size_t size_ = 0, used_ = 0; // live keys; live keys + tombstones
    size_t mask_ = 0;

    size_t slot(std::uint64_t k) const {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return static_cast<size_t>(k) & mask_;
    }

    void rehash(size_t wanted) {
        size_t capacity = 16;
        while (capacity < wanted)
            capacity *= 2;
        std::vector<std::uint64_t> keys(capacity, kEmpty);
        std::vector<Index> values(capacity, kInvalidIndex);
        keys.swap(keys_);
        values.swap(values_);
        mask_ = capacity - 1;
        size_ = used_ = 0;
        for (size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty && keys[i] != kErased)
                insert(keys[i], values[i]);
    }
};

} // namespace contour::consistent
