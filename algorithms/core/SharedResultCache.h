#pragma once
// A small cache of results built from a shared owner (a surface, a loaded
// mesh) and a key: the last `capacity` results, each dying with its owner.
// Thread-safe; concurrent requests for one (owner, key) build once, and a
// build that throws leaves no entry, so the next request tries again.
#include <algorithm>
#include <future>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace contour {

template <typename Owner, typename Key, typename Value> class SharedResultCache {
public:
    explicit SharedResultCache(std::size_t capacity) : capacity_(capacity) {}

    // The value for (owner, key), built by `build()` (returning
    // shared_ptr<const Value>) when absent; second: it came from the cache.
    template <typename Build>
    std::pair<std::shared_ptr<const Value>, bool> get(const std::shared_ptr<const Owner>& owner,
                                                      const Key& key, Build build) {
        const auto same = [&](const Slot& s) {
            return s.key == key && !s.owner.owner_before(owner) && !owner.owner_before(s.owner);
        };
        std::promise<std::shared_ptr<const Value>> promise;
        std::shared_future<std::shared_ptr<const Value>> existing;
        {
            const std::lock_guard lock(mutex_);
            std::erase_if(slots_, [](const Slot& s) { return s.owner.expired(); });
            for (const Slot& s : slots_)
                if (same(s))
                    existing = s.result;
            if (!existing.valid()) {
                if (slots_.size() >= capacity_)
                    slots_.erase(slots_.begin());
                slots_.push_back({owner, key, promise.get_future().share()});
            }
        }
        if (existing.valid())
            return {existing.get(), true};
        try {
            std::shared_ptr<const Value> value = build();
            promise.set_value(value);
            return {value, false};
        } catch (...) {
            promise.set_exception(std::current_exception());
            const std::lock_guard lock(mutex_);
            std::erase_if(slots_, same);
            throw;
        }
    }

private:
    struct Slot {
        std::weak_ptr<const Owner> owner;
        Key key;
        std::shared_future<std::shared_ptr<const Value>> result;
    };
    std::size_t capacity_;
    std::mutex mutex_;
    std::vector<Slot> slots_;
};

} // namespace contour
