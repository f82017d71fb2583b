#include "surface/SmoothSurfaceFactory.h"

#include "surface/SubdivisionSurface.h"
#include "surface/VertexNormalPatches.h"

#include <chrono>
#include <future>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace contour {

SurfaceKind automaticSurfaceKind(const PolygonMesh& cage) {
    return cage.isTriangleMesh() ? SurfaceKind::Loop : SurfaceKind::CatmullClark;
}

std::optional<SurfaceKind> surfaceKindFromName(const std::string& name) {
    for (SurfaceKind kind :
         {SurfaceKind::CatmullClark, SurfaceKind::Loop, SurfaceKind::VertexNormalPatches})
        if (name == toString(kind))
            return kind;
    return std::nullopt;
}

std::shared_ptr<const SmoothSurface> makeSmoothSurface(const PolygonMesh& cage, SurfaceKind kind) {
    switch (kind) {
    case SurfaceKind::CatmullClark:
    case SurfaceKind::Loop:
        return SubdivisionSurface::create(cage, kind);
    case SurfaceKind::VertexNormalPatches:
        return VertexNormalPatches::create(cage);
    }
    throw std::invalid_argument("unknown smooth surface kind");
}

namespace {

struct Entry {
    std::weak_ptr<const PolygonMesh> cage;
    SurfaceKind kind;
    std::shared_future<CachedSmoothSurface> result;
};

// A few cages times a few kinds: a session switching surfaces keeps them all.
constexpr size_t kCapacity = 6;

} // namespace

CachedSmoothSurface cachedSmoothSurface(const std::shared_ptr<const PolygonMesh>& cage,
                                        SurfaceKind kind) {
    if (!cage)
        throw std::invalid_argument("no control cage to build a smooth surface from");
    static std::mutex mutex;
    static std::vector<Entry> entries;
    const auto sameCage = [&](const Entry& e) {
        return !e.cage.owner_before(cage) && !cage.owner_before(e.cage);
    };
    std::promise<CachedSmoothSurface> promise;
    std::shared_future<CachedSmoothSurface> existing;
    {
        const std::lock_guard lock(mutex);
        std::erase_if(entries, [](const Entry& e) { return e.cage.expired(); });
        for (const Entry& e : entries)
            if (e.kind == kind && sameCage(e))
                existing = e.result;
        if (!existing.valid()) {
            if (entries.size() >= kCapacity)
                entries.erase(entries.begin());
            entries.push_back({cage, kind, promise.get_future().share()});
        }
    }
    if (existing.valid()) {
        CachedSmoothSurface hit = existing.get(); // waits while another thread builds it
        hit.fromCache = true;
        return hit;
    }
    // Built outside the lock; other callers for this key wait on the future.
    try {
        const auto start = std::chrono::steady_clock::now();
        CachedSmoothSurface built;
        built.surface = makeSmoothSurface(*cage, kind);
        built.buildSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        promise.set_value(built);
        return built;
    } catch (...) {
        promise.set_exception(std::current_exception());
        const std::lock_guard lock(mutex);
        std::erase_if(entries, [&](const Entry& e) { return e.kind == kind && sameCage(e); });
        throw;
    }
}

} // namespace contour
