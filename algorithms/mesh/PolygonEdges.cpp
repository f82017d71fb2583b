#include "mesh/PolygonEdges.h"

#include <algorithm>
#include <cstdint>

namespace contour {

PolygonEdges polygonEdges(const PolygonMesh& mesh) {
    const Index vertexCount = mesh.vertexCount();
    const auto cornerCount = static_cast<Index>(mesh.indices.size());
    const std::vector<Index>& corner = mesh.indices;
    PolygonEdges edges;
    edges.cornerFace.resize(static_cast<size_t>(cornerCount));
    edges.next.resize(static_cast<size_t>(cornerCount));
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Index first = mesh.offsets[f], last = mesh.offsets[f + 1];
        for (Index c = first; c < last; ++c) {
            edges.cornerFace[c] = f;
            edges.next[c] = c + 1 < last ? c + 1 : first;
        }
    }

    // Bucket the half-edges by their lower vertex (counting sort), then sort
    // each small bucket by the upper one. A bucket entry packs (upper vertex,
    // corner) into one integer, so the sort also orders each edge's corners.
    std::vector<Index> bucket(static_cast<size_t>(vertexCount) + 1, 0);
    for (Index c = 0; c < cornerCount; ++c)
        ++bucket[std::min(corner[c], corner[edges.next[c]]) + 1];
    for (Index v = 0; v < vertexCount; ++v)
        bucket[v + 1] += bucket[v];
    std::vector<std::uint64_t> keys(static_cast<size_t>(cornerCount));
    {
        std::vector<Index> fill(bucket.begin(), bucket.end() - 1);
        for (Index c = 0; c < cornerCount; ++c) {
            const Index a = corner[c], b = corner[edges.next[c]];
            keys[fill[std::min(a, b)]++] =
                static_cast<std::uint64_t>(std::max(a, b)) << 32 | static_cast<std::uint32_t>(c);
        }
    }
    const auto upper = [](std::uint64_t key) {
        return static_cast<Index>(key >> 32);
    };
    edges.corners.reserve(static_cast<size_t>(cornerCount));
    for (Index v = 0; v < vertexCount; ++v) {
        const auto first = keys.begin() + bucket[v];
        const auto last = keys.begin() + bucket[v + 1];
        std::sort(first, last);
        for (auto it = first; it != last; ++it) {
            if (it != first && upper(*it) != upper(it[-1]))
                edges.start.push_back(static_cast<Index>(edges.corners.size()));
            edges.corners.push_back(static_cast<Index>(*it & 0xffffffffu));
        }
        if (first != last)
            edges.start.push_back(static_cast<Index>(edges.corners.size()));
    }
    return edges;
}

} // namespace contour
