#include "contours/common/VertexNormalCache.h"

#include <algorithm>
#include <mutex>
#include <vector>

namespace contour {

namespace {
struct Entry {
    std::weak_ptr<const TriangleMesh> mesh;
    NormalWeighting weighting;
    std::shared_ptr<const Field> normals;
};

constexpr size_t kCapacity = 4;

const char* weightingName(NormalWeighting w) {
    switch (w) {
    case NormalWeighting::Area:
        return "area";
    case NormalWeighting::Angle:
        return "angle";
    case NormalWeighting::Max:
        return "max";
    }
    return "?";
}
} // namespace

std::shared_ptr<const Field> cachedVertexNormals(const std::shared_ptr<const TriangleMesh>& mesh,
                                                 NormalWeighting weighting) {
    static std::mutex mutex;
    static std::vector<Entry> entries;
    const auto sameMesh = [&](const Entry& e) {
        return !e.mesh.owner_before(mesh) && !mesh.owner_before(e.mesh);
    };
    {
        const std::lock_guard lock(mutex);
        std::erase_if(entries, [](const Entry& e) { return e.mesh.expired(); });
        for (const Entry& e : entries)
            if (e.weighting == weighting && sameMesh(e))
                return e.normals;
    }
    // Computed outside the lock: it is the expensive part, and two threads
    // racing on the same mesh just compute the same answer twice.
    auto field = std::make_shared<const Field>(
        Field{FieldLocation::Vertex, vertexNormals(*mesh, weighting),
              std::string("unit vertex normal (") + weightingName(weighting) +
                  "-weighted average of face normals)"});
    const std::lock_guard lock(mutex);
    if (entries.size() >= kCapacity)
        entries.erase(entries.begin());
    entries.push_back({mesh, weighting, field});
    return field;
}

} // namespace contour
