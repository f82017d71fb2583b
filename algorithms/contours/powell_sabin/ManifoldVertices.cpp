#include "contours/powell_sabin/ManifoldVertices.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace contour::powell_sabin {

void requireManifoldVertices(const TriangleMesh& mesh) {
    std::vector<Index> corners(static_cast<std::size_t>(mesh.vertexCount()), 0);
    for (Index h = 0; h < mesh.halfedgeCount(); ++h)
        ++corners[static_cast<std::size_t>(mesh.from(h))];
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
        const Index count = corners[static_cast<std::size_t>(v)];
        if (count == 0)
            continue;
        const Index start = mesh.vertexHalfedge(v);
        Index visited = 0;
        Index h = start;
        do {
            ++visited;
            h = mesh.rotate(h);
        } while (h != kInvalidIndex && h != start && visited <= count);
        if (visited != count)
            throw std::invalid_argument("vertex " + std::to_string(v) +
                                        " is non-manifold: its faces form more than one fan");
    }
}

} // namespace contour::powell_sabin
