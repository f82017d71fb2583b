#include "contours/powell_sabin/ConeSelection.h"

#include "contours/powell_sabin/ManifoldVertices.h"
#include "core/UnionFind.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace contour::powell_sabin {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

// Per-face and per-vertex component labels next to the public summary.
struct Labels {
    std::vector<Index> faceComponent;
    std::vector<Index> vertexComponent; // kInvalidIndex for vertices without faces
    std::vector<ComponentTopology> components;
};

// The boundary half-edge that follows boundary half-edge h on its loop: the
// outgoing boundary half-edge of to(h) in the fan that holds h.
Index nextBoundaryHalfedge(const TriangleMesh& mesh, Index h) {
    Index g = TriangleMesh::next(h);
    while (!mesh.isBoundary(g))
        g = TriangleMesh::next(mesh.opposite(g));
    return g;
}

Labels labelComponents(const TriangleMesh& mesh) {
    requireManifoldVertices(mesh);
    const Index nf = mesh.faceCount();
    UnionFind sets(at(nf));
    for (Index h = 0; h < mesh.halfedgeCount(); ++h)
        if (!mesh.isBoundary(h))
            sets.unite(TriangleMesh::face(h), TriangleMesh::face(mesh.opposite(h)));

    Labels labels;
    labels.faceComponent.assign(at(nf), kInvalidIndex);
    // Roots are the smallest face of their set, so components come out
    // ordered by their first face.
    for (Index f = 0; f < nf; ++f) {
        const Index root = sets.find(f);
        if (root == f) {
            labels.faceComponent[at(f)] = static_cast<Index>(labels.components.size());
            ComponentTopology c;
            c.firstFace = f;
            labels.components.push_back(c);
        } else {
            labels.faceComponent[at(f)] = labels.faceComponent[at(root)];
        }
        ++labels.components[at(labels.faceComponent[at(f)])].faceCount;
    }

    labels.vertexComponent.assign(at(mesh.vertexCount()), kInvalidIndex);
    for (Index f = 0; f < nf; ++f)
        for (Index v : mesh.triangle(f))
            labels.vertexComponent[at(v)] = labels.faceComponent[at(f)];
    for (Index c : labels.vertexComponent)
        if (c != kInvalidIndex)
            ++labels.components[at(c)].vertexCount;

    std::vector<Index> edges(labels.components.size(), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e)
        ++edges[at(labels.faceComponent[at(TriangleMesh::face(mesh.edgeHalfedge(e)))])];

    std::vector<char> onLoop(at(mesh.halfedgeCount()), 0);
    for (Index h = 0; h < mesh.halfedgeCount(); ++h) {
        if (!mesh.isBoundary(h) || onLoop[at(h)])
            continue;
        ++labels.components[at(labels.faceComponent[at(TriangleMesh::face(h))])].boundaryLoops;
        for (Index g = h; !onLoop[at(g)]; g = nextBoundaryHalfedge(mesh, g))
            onLoop[at(g)] = 1;
    }

    for (std::size_t i = 0; i < labels.components.size(); ++i) {
        ComponentTopology& c = labels.components[i];
        const Index chi = c.vertexCount - edges[i] + c.faceCount;
        const Index twiceGenus = 2 - c.boundaryLoops - chi; // chi = 2 - 2g - b
        if (twiceGenus < 0 || twiceGenus % 2 != 0)
            throw std::invalid_argument("component of face " + std::to_string(c.firstFace) +
                                        " has Euler characteristic " + std::to_string(chi) +
                                        " with " + std::to_string(c.boundaryLoops) +
                                        " boundary loops: not an orientable surface");
        c.genus = twiceGenus / 2;
    }
    return labels;
}

// §5.1: 8 cones for genus 0, 4(g - 1) for g > 1; a flat torus needs none.
// Components with a boundary need none either (see the header).
int paperConeCount(const ComponentTopology& c, const ConeOptions& options) {
    if (c.boundaryLoops > 0)
        return 0;
    if (options.conesPerComponent >= 0)
        return options.conesPerComponent;
    if (c.genus == 0)
        return 8;
    return 4 * (c.genus - 1);
}

std::vector<char> boundaryVertices(const TriangleMesh& mesh) {
    std::vector<char> boundary(at(mesh.vertexCount()), 0);
    for (Index h = 0; h < mesh.halfedgeCount(); ++h)
        if (mesh.isBoundary(h)) {
            boundary[at(mesh.from(h))] = 1;
            boundary[at(mesh.to(h))] = 1;
        }
    return boundary;
}

// Vertex adjacency in compressed rows, with edge lengths for geodesic
// (shortest edge path) distances.
struct Graph {
    std::vector<Index> start;
    std::vector<Index> neighbour;
    std::vector<double> length;

    explicit Graph(const TriangleMesh& mesh) {
        const std::size_t nv = at(mesh.vertexCount());
        start.assign(nv + 1, 0);
        for (Index e = 0; e < mesh.edgeCount(); ++e) {
            const Index h = mesh.edgeHalfedge(e);
            ++start[at(mesh.from(h)) + 1];
            ++start[at(mesh.to(h)) + 1];
        }
        for (std::size_t v = 0; v < nv; ++v)
            start[v + 1] += start[v];
        neighbour.resize(at(start[nv]));
        length.resize(at(start[nv]));
        std::vector<Index> fill(start.begin(), start.end() - 1);
        for (Index e = 0; e < mesh.edgeCount(); ++e) {
            const Index h = mesh.edgeHalfedge(e);
            const Index a = mesh.from(h), b = mesh.to(h);
            const double l = (mesh.position(a) - mesh.position(b)).norm();
            neighbour[at(fill[at(a)])] = b;
            length[at(fill[at(a)]++)] = l;
            neighbour[at(fill[at(b)])] = a;
            length[at(fill[at(b)]++)] = l;
        }
    }
};

using QueueEntry = std::pair<double, Index>;
using Queue = std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>>;

// Dijkstra from the queued sources, relaxing only edges that `allowed`
// accepts and only where the distance strictly drops, so that labels spread
// with their sources and ties keep the label that came first (the queue
// orders by distance, then vertex index: deterministic).
template <class Allowed>
void propagate(const Graph& graph, Queue& queue, std::vector<double>& dist,
               std::vector<Index>& label, Allowed allowed) {
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[at(v)])
            continue;
        for (Index i = graph.start[at(v)]; i < graph.start[at(v) + 1]; ++i) {
            const Index w = graph.neighbour[at(i)];
            const double nd = d + graph.length[at(i)];
            if (nd < dist[at(w)] && allowed(v, w)) {
                dist[at(w)] = nd;
                label[at(w)] = label[at(v)];
                queue.emplace(nd, w);
            }
        }
    }
}

// Geodesic Voronoi regions of `centres` over the component's vertices.
void voronoi(const Graph& graph, std::span<const Index> vertices, std::span<const Index> centres,
             std::vector<double>& dist, std::vector<Index>& region) {
    for (Index v : vertices) {
        dist[at(v)] = kInfinity;
        region[at(v)] = kInvalidIndex;
    }
    Queue queue;
    for (std::size_t j = 0; j < centres.size(); ++j) {
        dist[at(centres[j])] = 0.0;
        region[at(centres[j])] = static_cast<Index>(j);
        queue.emplace(0.0, centres[j]);
    }
    propagate(graph, queue, dist, region, [](Index, Index) { return true; });
}

// Balanced region growing from `centres`: the cluster of smallest size so
// far (ties: lower index) claims the unclaimed vertex nearest to its centre
// along paths inside the cluster, so that sizes stay within about one vertex
// of each other until a cluster is enclosed by the others. `weight` is a
// vertex's contribution to its cluster's size.
void growBalanced(const Graph& graph, std::span<const Index> vertices,
                  std::span<const Index> centres, std::span<const double> weight,
                  std::vector<Index>& region) {
    for (Index v : vertices)
        region[at(v)] = kInvalidIndex;
    const std::size_t k = centres.size();
    std::vector<Queue> fronts(k);
    std::vector<double> size(k, 0.0);
    for (std::size_t j = 0; j < k; ++j) {
        region[at(centres[j])] = static_cast<Index>(j);
        size[j] = weight[at(centres[j])];
    }
    auto pushNeighbours = [&](std::size_t j, Index v, double d) {
        for (Index i = graph.start[at(v)]; i < graph.start[at(v) + 1]; ++i)
            if (region[at(graph.neighbour[at(i)])] == kInvalidIndex)
                fronts[j].emplace(d + graph.length[at(i)], graph.neighbour[at(i)]);
    };
    // Growing clusters ordered by (size, index).
    std::set<std::pair<double, std::size_t>> growing;
    for (std::size_t j = 0; j < k; ++j) {
        pushNeighbours(j, centres[j], 0.0);
        if (!fronts[j].empty())
            growing.emplace(size[j], j);
    }
    while (!growing.empty()) {
        const std::size_t j = growing.begin()->second;
        growing.erase(growing.begin());
        Queue& front = fronts[j];
        while (!front.empty() && region[at(front.top().second)] != kInvalidIndex)
            front.pop();
        if (front.empty())
            continue; // enclosed by the other clusters
        const auto [d, v] = front.top();
        front.pop();
        region[at(v)] = static_cast<Index>(j);
        size[j] += weight[at(v)];
        pushNeighbours(j, v, d);
        growing.emplace(size[j], j);
    }
}

// Clusters of close size on one closed component (§5.1): farthest-point
// seeds by geodesic (shortest edge path) distance, balanced region growing
// from them, then Lloyd-like re-centering: each centre moves to the vertex
// of its cluster farthest from the cluster's border (its geodesic inner
// centre) and the clusters are grown again, until the centres stop moving
// or after `iterations` passes. Returns the centres; `region` holds each
// vertex's cluster in 0 .. k-1.
// Per-vertex scratch arrays of a whole mesh, reused by every component so
// that a mesh of many small components costs no more than one.
struct Scratch {
    std::vector<double> dist;
    std::vector<Index> label;
    std::vector<char> mark;
    explicit Scratch(Index n)
        : dist(at(n), kInfinity), label(at(n), kInvalidIndex), mark(at(n), 0) {}
};

std::vector<Index> clusterComponent(const Graph& graph, std::span<const Index> vertices, int k,
                                    int iterations, std::span<const double> weight,
                                    Scratch& scratch, std::vector<Index>& region) {
    std::vector<double>& dist = scratch.dist;
    std::vector<Index> centres;
    centres.reserve(at(k));
    auto farthestNonCentre = [&] {
        // Every non-centre vertex is farther than 0 unless edges have zero
        // length; centres are excluded explicitly for that case.
        Index best = kInvalidIndex;
        for (Index v : vertices)
            if ((best == kInvalidIndex || dist[at(v)] > dist[at(best)]) && !scratch.mark[at(v)])
                best = v;
        scratch.mark[at(best)] = 1;
        return best;
    };

    // The first seed is the vertex farthest from the component's first
    // vertex: an extreme point of the shape rather than an arbitrary one.
    voronoi(graph, vertices, std::span<const Index>(&vertices.front(), 1), dist, region);
    centres.push_back(farthestNonCentre());
    voronoi(graph, vertices, centres, dist, region);
    while (static_cast<int>(centres.size()) < k) {
        const Index best = farthestNonCentre();
        const Index j = static_cast<Index>(centres.size());
        centres.push_back(best);
        // Incremental update: only vertices that get closer change region.
        dist[at(best)] = 0.0;
        region[at(best)] = j;
        Queue queue;
        queue.emplace(0.0, best);
        propagate(graph, queue, dist, region, [](Index, Index) { return true; });
    }
    for (Index c : centres)
        scratch.mark[at(c)] = 0;
    growBalanced(graph, vertices, centres, weight, region);
    if (k < 2)
        return centres;

    std::vector<Index>& depthLabel = scratch.label;
    for (int pass = 0; pass < iterations; ++pass) {
        // dist becomes the distance to the cluster's border, inside it.
        Queue queue;
        for (Index v : vertices) {
            dist[at(v)] = kInfinity;
            depthLabel[at(v)] = region[at(v)];
            for (Index i = graph.start[at(v)]; i < graph.start[at(v) + 1]; ++i)
                if (region[at(graph.neighbour[at(i)])] != region[at(v)]) {
                    dist[at(v)] = 0.0;
                    queue.emplace(0.0, v);
                    break;
                }
        }
        propagate(graph, queue, dist, depthLabel,
                  [&](Index a, Index b) { return region[at(a)] == region[at(b)]; });
        std::vector<Index> moved = centres;
        for (Index v : vertices) {
            Index& c = moved[at(region[at(v)])];
            if (dist[at(v)] > dist[at(c)])
                c = v;
        }
        if (moved == centres)
            break;
        centres = std::move(moved);
        growBalanced(graph, vertices, centres, weight, region);
    }
    return centres;
}

double cornerAngle(const Vec3& at0, const Vec3& a, const Vec3& b) {
    const Vec3 u = a - at0, w = b - at0;
    return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Loop's edge rule on the input mesh: 3/8 of the edge's ends and 1/8 of the
// two opposite corners; the midpoint on a boundary edge.
Vec3 loopEdgePoint(const TriangleMesh& mesh, Index e) {
    const Index h = mesh.edgeHalfedge(e);
    const Vec3& a = mesh.position(mesh.from(h));
    const Vec3& b = mesh.position(mesh.to(h));
    if (mesh.isBoundary(h))
        return 0.5 * (a + b);
    const Vec3& c = mesh.position(mesh.to(TriangleMesh::next(h)));
    const Vec3& d = mesh.position(mesh.to(TriangleMesh::next(mesh.opposite(h))));
    return 0.375 * (a + b) + 0.125 * (c + d);
}

} // namespace

std::vector<ComponentTopology> meshComponents(const TriangleMesh& mesh) {
    std::vector<ComponentTopology> components = labelComponents(mesh).components;
    for (ComponentTopology& c : components)
        c.coneCount = paperConeCount(c, ConeOptions{});
    return components;
}

std::vector<double> angleDefects(const TriangleMesh& mesh) {
    std::vector<double> sum(at(mesh.vertexCount()), 0.0);
    std::vector<char> hasFace(at(mesh.vertexCount()), 0);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Triangle& t = mesh.triangle(f);
        for (int i = 0; i < 3; ++i) {
            const Index v = t[at(i)];
            sum[at(v)] += cornerAngle(mesh.position(v), mesh.position(t[at((i + 1) % 3)]),
                                      mesh.position(t[at((i + 2) % 3)]));
            hasFace[at(v)] = 1;
        }
    }
    const std::vector<char> boundary = boundaryVertices(mesh);
    std::vector<double> defect(sum.size(), 0.0);
    for (std::size_t v = 0; v < sum.size(); ++v)
        if (hasFace[v])
            defect[v] = (boundary[v] ? std::numbers::pi : 2.0 * std::numbers::pi) - sum[v];
    return defect;
}

Cones selectCones(const TriangleMesh& mesh, const ConeOptions& options) {
    if (options.conesPerComponent < -1)
        throw std::invalid_argument("ConeOptions::conesPerComponent must be >= -1, got " +
                                    std::to_string(options.conesPerComponent));
    if (options.lloydIterations < 0)
        throw std::invalid_argument("ConeOptions::lloydIterations must be >= 0, got " +
                                    std::to_string(options.lloydIterations));
    Labels labels = labelComponents(mesh);
    Cones cones;
    cones.cluster.assign(at(mesh.vertexCount()), kInvalidIndex);
    for (ComponentTopology& c : labels.components)
        c.coneCount = paperConeCount(c, options);

    std::vector<std::vector<Index>> componentVertices(labels.components.size());
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (labels.vertexComponent[at(v)] != kInvalidIndex)
            componentVertices[at(labels.vertexComponent[at(v)])].push_back(v);

    const Graph graph(mesh);
    std::vector<double> weight(at(mesh.vertexCount()), options.balanceByArea ? 0.0 : 1.0);
    if (options.balanceByArea)
        for (Index f = 0; f < mesh.faceCount(); ++f)
            for (Index v : mesh.triangle(f))
                weight[at(v)] += mesh.faceAreaNormal(f).norm() / 6.0;
    const std::vector<double> defect = angleDefects(mesh);
    const std::vector<char> boundary = boundaryVertices(mesh);
    Scratch scratch(mesh.vertexCount());
    std::vector<Index> region(at(mesh.vertexCount()), kInvalidIndex);
    std::vector<char> blocked(at(mesh.vertexCount()), 0); // a cone or next to one

    for (std::size_t ci = 0; ci < labels.components.size(); ++ci) {
        const ComponentTopology& c = labels.components[ci];
        const int k = c.coneCount;
        if (k == 0)
            continue;
        const std::vector<Index>& vertices = componentVertices[ci];
        if (static_cast<Index>(vertices.size()) < k)
            throw std::invalid_argument("the component of face " + std::to_string(c.firstFace) +
                                        " has " + std::to_string(vertices.size()) +
                                        " vertices, fewer than its " + std::to_string(k) +
                                        " cones (genus " + std::to_string(c.genus) + ")");
        clusterComponent(graph, vertices, k, options.lloydIterations, weight, scratch, region);

        // §5.1: the vertex of smallest discrete curvature per cluster, read
        // as the smallest signed angle defect. Clusters whose minimum is
        // smaller choose first, so that the adjacency rule displaces the
        // cones that matter least.
        std::vector<Index> clusterMin(at(k), kInvalidIndex);
        for (Index v : vertices) {
            Index& m = clusterMin[at(region[at(v)])];
            if (m == kInvalidIndex || defect[at(v)] < defect[at(m)])
                m = v;
        }
        std::vector<Index> order(at(k));
        for (Index j = 0; j < k; ++j)
            order[at(j)] = j;
        std::sort(order.begin(), order.end(), [&](Index a, Index b) {
            const double da = defect[at(clusterMin[at(a)])], db = defect[at(clusterMin[at(b)])];
            return da != db ? da < db : a < b;
        });
        std::vector<Index> chosen(at(k), kInvalidIndex);
        for (Index j : order) {
            auto smallest = [&](bool skipBlocked) {
                Index best = kInvalidIndex;
                for (Index v : vertices)
                    if (region[at(v)] == j && !boundary[at(v)] &&
                        !(skipBlocked && blocked[at(v)]) &&
                        (best == kInvalidIndex || defect[at(v)] < defect[at(best)]))
                        best = v;
                return best;
            };
            Index best = smallest(true);
            if (best == kInvalidIndex && options.requireNonAdjacent)
                throw std::invalid_argument(
                    "cluster " + std::to_string(j) + " of the component of face " +
                    std::to_string(c.firstFace) +
                    " has no vertex that is not a cone or adjacent to one: the mesh is too "
                    "coarse for " +
                    std::to_string(k) +
                    " cones (subdivide it, or clear "
                    "ConeOptions::requireNonAdjacent)");
            if (best == kInvalidIndex)
                best = smallest(false);
            if (best == kInvalidIndex)
                throw std::invalid_argument("cluster " + std::to_string(j) +
                                            " has only boundary vertices");
            chosen[at(j)] = best;
            blocked[at(best)] = 1;
            for (Index i = graph.start[at(best)]; i < graph.start[at(best) + 1]; ++i)
                blocked[at(graph.neighbour[at(i)])] = 1;
        }
        const Index base = static_cast<Index>(cones.vertices.size());
        cones.vertices.insert(cones.vertices.end(), chosen.begin(), chosen.end());
        for (Index v : vertices)
            cones.cluster[at(v)] = base + region[at(v)];
    }
    cones.components = std::move(labels.components);
    return cones;
}

ConeRefinement refineAroundCones(const TriangleMesh& mesh, std::span<const Index> cones) {
    const Index nv = mesh.vertexCount();
    std::vector<char> isCone(at(nv), 0);
    for (Index v : cones) {
        if (v < 0 || v >= nv)
            throw std::invalid_argument("cone index " + std::to_string(v) +
                                        " is out of range (the mesh has " + std::to_string(nv) +
                                        " vertices)");
        if (isCone[at(v)])
            throw std::invalid_argument("cone " + std::to_string(v) + " is listed twice");
        isCone[at(v)] = 1;
    }
    std::vector<char> coneHasFace(at(nv), 0);
    std::vector<char> split(at(mesh.faceCount()), 0);
    for (Index f = 0; f < mesh.faceCount(); ++f)
        for (Index v : mesh.triangle(f))
            if (isCone[at(v)]) {
                split[at(f)] = 1;
                coneHasFace[at(v)] = 1;
            }
    for (Index v : cones)
        if (!coneHasFace[at(v)])
            throw std::invalid_argument("cone " + std::to_string(v) + " has no incident triangle");

    // One new vertex per edge of a split triangle, numbered after the input
    // vertices in edge order.
    std::vector<Index> edgeVertex(at(mesh.edgeCount()), kInvalidIndex);
    for (Index h = 0; h < mesh.halfedgeCount(); ++h)
        if (split[at(TriangleMesh::face(h))])
            edgeVertex[at(mesh.edge(h))] = 0;
    std::vector<Vec3> positions(mesh.positions().begin(), mesh.positions().end());
    for (Index e = 0; e < mesh.edgeCount(); ++e)
        if (edgeVertex[at(e)] != kInvalidIndex) {
            edgeVertex[at(e)] = static_cast<Index>(positions.size());
            positions.push_back(loopEdgePoint(mesh, e));
        }

    ConeRefinement result;
    std::vector<Triangle> triangles;
    std::vector<Index> source;
    auto emit = [&](Index f, Index a, Index b, Index c) {
        triangles.push_back({a, b, c});
        result.parentFace.push_back(f);
        source.push_back(mesh.sourcePolygon(f));
    };
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Triangle& t = mesh.triangle(f);
        // m[i]: the new vertex on the side from corner i to corner i + 1.
        std::array<Index, 3> m{};
        int splitSides = 0;
        for (int i = 0; i < 3; ++i) {
            m[at(i)] = edgeVertex[at(mesh.edge(TriangleMesh::halfedge(f, i)))];
            splitSides += m[at(i)] != kInvalidIndex;
        }
        if (splitSides == 0) {
            emit(f, t[0], t[1], t[2]);
            continue;
        }
        if (split[at(f)])
            ++result.splitTriangles;
        else
            ++result.bisectedTriangles;
        if (splitSides == 3) {
            emit(f, t[0], m[0], m[2]);
            emit(f, m[0], t[1], m[1]);
            emit(f, m[2], m[1], t[2]);
            emit(f, m[0], m[1], m[2]);
        } else if (splitSides == 1) {
            const int i = m[0] != kInvalidIndex ? 0 : m[1] != kInvalidIndex ? 1 : 2;
            const Index a = t[at(i)], b = t[at((i + 1) % 3)], c = t[at((i + 2) % 3)];
            emit(f, a, m[at(i)], c);
            emit(f, m[at(i)], b, c);
        } else {
            // Sides i -> i+1 and i+1 -> i+2 split, side i+2 -> i not: the
            // corner triangle at i+1 and the quad (a, mab, mbc, c) cut along
            // its shorter diagonal.
            const int i = m[0] == kInvalidIndex ? 1 : m[1] == kInvalidIndex ? 2 : 0;
            const Index a = t[at(i)], b = t[at((i + 1) % 3)], c = t[at((i + 2) % 3)];
            const Index mab = m[at(i)], mbc = m[at((i + 1) % 3)];
            emit(f, mab, b, mbc);
            if ((positions[at(a)] - positions[at(mbc)]).squaredNorm() <=
                (positions[at(mab)] - positions[at(c)]).squaredNorm()) {
                emit(f, a, mab, mbc);
                emit(f, a, mbc, c);
            } else {
                emit(f, a, mab, c);
                emit(f, mab, mbc, c);
            }
        }
    }
    result.mesh = TriangleMesh(std::move(positions), std::move(triangles), std::move(source));
    result.cones.assign(cones.begin(), cones.end());
    return result;
}

} // namespace contour::powell_sabin
