#include "surface/SurfaceTessellation.h"

#include <mutex>
#include <stdexcept>
#include <string>

namespace contour {

namespace {

// The grid point (i, j) of a face at level L, as (u, v) = (i, j) / L.
Preimage gridPreimage(Index face, int i, int j, int level) {
    return {face, static_cast<double>(i) / level, static_cast<double>(j) / level};
}

// Which local edge of a face a boundary grid point (i, j) lies on, and its
// position k (0 < k < L) along that edge from corner `edge` to corner
// `edge + 1`; returns false for corners and interior points.
bool onEdge(bool quad, int i, int j, int level, int& edge, int& k) {
    const int L = level;
    if (quad) {
        if (j == 0 && i > 0 && i < L) {
            edge = 0, k = i;
        } else if (i == L && j > 0 && j < L) {
            edge = 1, k = j;
        } else if (j == L && i > 0 && i < L) {
            edge = 2, k = L - i;
        } else if (i == 0 && j > 0 && j < L) {
            edge = 3, k = L - j;
        } else {
            return false;
        }
        return true;
    }
    if (j == 0 && i > 0 && i < L) {
        edge = 0, k = i;
    } else if (i + j == L && j > 0 && j < L) {
        edge = 1, k = j;
    } else if (i == 0 && j > 0 && j < L) {
        edge = 2, k = L - j;
    } else {
        return false;
    }
    return true;
}

// Corner index of a grid point, or -1.
int cornerOf(bool quad, int i, int j, int level) {
    if (i == 0 && j == 0)
        return 0;
    if (i == level && j == 0)
        return 1;
    if (quad && i == level && j == level)
        return 2;
    if (quad && i == 0 && j == level)
        return 3;
    if (!quad && i == 0 && j == level)
        return 2;
    return -1;
}

} // namespace

SurfaceTessellation tessellate(const SmoothSurface& surface, int level) {
    if (level < 1)
        throw std::invalid_argument("tessellation level must be at least 1, not " +
                                    std::to_string(level));
    const PolygonMesh& domain = surface.domain();
    const Index faceCount = domain.faceCount();
    if (faceCount == 0)
        throw std::invalid_argument("cannot tessellate a surface with an empty domain");
    const int L = level;

    SurfaceTessellation t;
    t.level = level;
    std::vector<Index> cornerVertex(domain.vertexCount(), kInvalidIndex);
    // Per (face, local edge): the id of the first of the L - 1 vertices inside
    // the domain edge, counted along the owner's direction, and whether this
    // face runs the other way. The owner of an edge is the smaller of its two
    // (face, edge) pairs, so it is always visited first.
    std::vector<Index> edgeBase(static_cast<size_t>(faceCount) * 4, kInvalidIndex);
    std::vector<char> edgeReversed(static_cast<size_t>(faceCount) * 4, 0);
    std::vector<std::vector<Index>> grids(faceCount);

    size_t triangleCount = 0, interiorCount = 0;
    for (Index f = 0; f < faceCount; ++f) {
        const bool quad = domain.face(f).size() == 4;
        triangleCount += quad ? 2 * static_cast<size_t>(L) * L : static_cast<size_t>(L) * L;
        interiorCount +=
            quad ? static_cast<size_t>(L - 1) * (L - 1) : static_cast<size_t>(L - 1) * (L - 1) / 2;
    }
    // Corners and edge points: at most 1 + 4 (L - 1) new ones per face.
    t.preimages.reserve(interiorCount + static_cast<size_t>(faceCount) * (4 * L - 3));
    const auto addVertex = [&](const Preimage& p) {
        t.preimages.push_back(p);
        return static_cast<Index>(t.preimages.size() - 1);
    };

    for (Index f = 0; f < faceCount; ++f) {
        const auto corners = domain.face(f);
        const bool quad = corners.size() == 4;
        const int edges = static_cast<int>(corners.size());
        // Domain corners.
        for (int c = 0; c < edges; ++c)
            if (cornerVertex[corners[c]] == kInvalidIndex) {
                const Vec2 uv = SmoothSurface::cornerCoordinates(quad, c);
                cornerVertex[corners[c]] = addVertex({f, uv.x(), uv.y()});
            }
        // Domain edges.
        for (int e = 0; e < edges; ++e) {
            const size_t slot = static_cast<size_t>(f) * 4 + e;
            const SmoothSurface::EdgeNeighbor nb = surface.neighbor(f, e);
            const bool owner =
                nb.face == kInvalidIndex || f < nb.face || (f == nb.face && e < nb.edge);
            if (!owner) {
                const size_t other = static_cast<size_t>(nb.face) * 4 + nb.edge;
                const SmoothSurface::EdgeNeighbor back = surface.neighbor(nb.face, nb.edge);
                if (back.face != f || back.edge != e || edgeBase[other] == kInvalidIndex)
                    throw std::logic_error(
                        "tessellate: domain adjacency is not symmetric at face " +
                        std::to_string(f) + " edge " + std::to_string(e));
                edgeBase[slot] = edgeBase[other];
                edgeReversed[slot] = 1;
                continue;
            }
            edgeBase[slot] = static_cast<Index>(t.preimages.size());
            const Vec2 a = SmoothSurface::cornerCoordinates(quad, e);
            const Vec2 b = SmoothSurface::cornerCoordinates(quad, (e + 1) % edges);
            for (int k = 1; k < L; ++k) {
                const Vec2 uv = a + (b - a) * (static_cast<double>(k) / L);
                addVertex({f, uv.x(), uv.y()});
            }
        }
        // The face's grid, (i, j) at index j (L + 1) + i.
        std::vector<Index>& grid = grids[f];
        grid.assign(static_cast<size_t>(L + 1) * (L + 1), kInvalidIndex);
        for (int j = 0; j <= L; ++j)
            for (int i = 0; i <= (quad ? L : L - j); ++i) {
                Index& id = grid[static_cast<size_t>(j) * (L + 1) + i];
                int edge = -1, k = 0;
                if (const int c = cornerOf(quad, i, j, L); c >= 0) {
                    id = cornerVertex[corners[c]];
                } else if (onEdge(quad, i, j, L, edge, k)) {
                    const size_t slot = static_cast<size_t>(f) * 4 + edge;
                    id = edgeBase[slot] + (edgeReversed[slot] ? L - k : k) - 1;
                } else {
                    id = addVertex(gridPreimage(f, i, j, L));
                }
            }
    }

    const Index vertexCount = static_cast<Index>(t.preimages.size());
    t.points.resize(vertexCount);
    surface.evaluate(t.preimages, t.points);
    std::vector<Vec3> positions(vertexCount);
    t.normals.resize(vertexCount);
    for (Index v = 0; v < vertexCount; ++v) {
        positions[v] = t.points[v].position;
        t.normals[v] = t.points[v].normal();
    }

    std::vector<Triangle> triangles;
    triangles.reserve(triangleCount);
    t.cornerUv.reserve(triangleCount);
    t.sourceFace.reserve(triangleCount);
    for (Index f = 0; f < faceCount; ++f) {
        const bool quad = surface.isQuad(f);
        const std::vector<Index>& grid = grids[f];
        const auto at = [&](int i, int j) {
            return grid[static_cast<size_t>(j) * (L + 1) + i];
        };
        const auto uv = [&](int i, int j) {
            return Vec2(static_cast<double>(i) / L, static_cast<double>(j) / L);
        };
        for (int j = 0; j < L; ++j)
            for (int i = 0; i < (quad ? L : L - j); ++i) {
                const Index a = at(i, j), b = at(i + 1, j), d = at(i, j + 1);
                const Vec2 ua = uv(i, j), ub = uv(i + 1, j), uc = uv(i + 1, j + 1),
                           ud = uv(i, j + 1);
                if (!quad) {
                    triangles.push_back({a, b, d});
                    t.cornerUv.push_back({ua, ub, ud});
                    t.sourceFace.push_back(f);
                    if (i + j <= L - 2) {
                        triangles.push_back({b, at(i + 1, j + 1), d});
                        t.cornerUv.push_back({ub, uc, ud});
                        t.sourceFace.push_back(f);
                    }
                    continue;
                }
                const Index c = at(i + 1, j + 1);
                // Split along the shorter diagonal: the one that bends least.
                if ((positions[a] - positions[c]).squaredNorm() <=
                    (positions[b] - positions[d]).squaredNorm()) {
                    triangles.push_back({a, b, c});
                    triangles.push_back({a, c, d});
                    t.cornerUv.push_back({ua, ub, uc});
                    t.cornerUv.push_back({ua, uc, ud});
                } else {
                    triangles.push_back({a, b, d});
                    triangles.push_back({b, c, d});
                    t.cornerUv.push_back({ua, ub, ud});
                    t.cornerUv.push_back({ub, uc, ud});
                }
                t.sourceFace.insert(t.sourceFace.end(), 2, f);
            }
    }
    t.mesh = std::make_shared<const TriangleMesh>(std::move(positions), std::move(triangles),
                                                  t.sourceFace);
    return t;
}

std::shared_ptr<const SurfaceTessellation>
sharedTessellation(const std::shared_ptr<const SmoothSurface>& surface, int level) {
    if (!surface)
        throw std::invalid_argument("sharedTessellation: no surface");
    struct Entry {
        std::weak_ptr<const SmoothSurface> surface;
        int level = 0;
        std::shared_ptr<const SurfaceTessellation> tessellation;
    };
    // A few surfaces (SmoothSurfaceFactory's cache holds six).
    constexpr size_t kCapacity = 6;
    static std::mutex mutex;
    static std::vector<Entry> entries;
    const auto same = [&](const Entry& e) {
        return e.level == level && !e.surface.owner_before(surface) &&
               !surface.owner_before(e.surface);
    };
    {
        const std::lock_guard lock(mutex);
        std::erase_if(entries, [](const Entry& e) { return e.surface.expired(); });
        for (const Entry& e : entries)
            if (same(e))
                return e.tessellation;
    }
    // Built outside the lock (two threads may both build it; either result
    // is the same tessellation).
    auto built = std::make_shared<const SurfaceTessellation>(tessellate(*surface, level));
    const std::lock_guard lock(mutex);
    for (const Entry& e : entries)
        if (same(e))
            return e.tessellation;
    if (entries.size() >= kCapacity)
        entries.erase(entries.begin());
    entries.push_back({surface, level, built});
    return built;
}

} // namespace contour
