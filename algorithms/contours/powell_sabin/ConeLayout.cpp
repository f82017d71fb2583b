#include "contours/powell_sabin/ConeLayout.h"

#include "contours/powell_sabin/ManifoldVertices.h"
#include "core/UnionFind.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace contour::powell_sabin {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

std::string edgeName(const TriangleMesh& mesh, Index e) {
    const Index h = mesh.edgeHalfedge(e);
    return "edge " + std::to_string(e) + " (" + std::to_string(mesh.from(h)) + ", " +
           std::to_string(mesh.to(h)) + ")";
}

double cross(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

double twiceSignedArea(const std::array<Vec2, 3>& t) {
    return cross(t[1] - t[0], t[2] - t[0]);
}

// The corner angle, atan2 of |cross| and dot: accurate for small and for
// nearly flat angles alike.
double cornerAngle(const std::array<Vec2, 3>& t, int corner) {
    const Vec2 a = t[at((corner + 1) % 3)] - t[at(corner)];
    const Vec2 b = t[at((corner + 2) % 3)] - t[at(corner)];
    return std::atan2(std::abs(cross(a, b)), a.dot(b));
}

// uv of the two ends of half-edge h in its own face.
const Vec2& uvFrom(const std::vector<std::array<Vec2, 3>>& uv, Index h) {
    return uv[at(TriangleMesh::face(h))][at(h % 3)];
}
const Vec2& uvTo(const std::vector<std::array<Vec2, 3>>& uv, Index h) {
    return uv[at(TriangleMesh::face(h))][at((h % 3 + 1) % 3)];
}

// Calls fn(neighbour, edge) for every edge at v, boundary edges included.
// Needs manifold vertices: vertexHalfedge() of a boundary vertex is its
// outgoing boundary half-edge, so one counter-clockwise sweep sees the fan.
template <typename Fn> void forEachEdgeAt(const TriangleMesh& mesh, Index v, Fn&& fn) {
    const Index start = mesh.vertexHalfedge(v);
    if (start == kInvalidIndex)
        return;
    Index h = start;
    do {
        fn(mesh.to(h), mesh.edge(h));
        const Index in = TriangleMesh::prev(h);
        const Index o = mesh.opposite(in);
        if (o == kInvalidIndex) {
            fn(mesh.from(in), mesh.edge(in)); // the incoming boundary edge
            return;
        }
        h = o;
    } while (h != start);
}

struct Components {
    std::vector<Index> faceComponent;
    std::vector<Index> vertexComponent; // kInvalidIndex for a vertex without faces
    std::vector<std::vector<Index>> faces;
};

Components labelComponents(const TriangleMesh& mesh) {
    Components c;
    c.faceComponent.assign(at(mesh.faceCount()), kInvalidIndex);
    std::vector<Index> queue;
    for (Index seed = 0; seed < mesh.faceCount(); ++seed) {
        if (c.faceComponent[at(seed)] != kInvalidIndex)
            continue;
        const Index id = static_cast<Index>(c.faces.size());
        c.faces.emplace_back();
        queue.assign(1, seed);
        c.faceComponent[at(seed)] = id;
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const Index f = queue[q];
            c.faces.back().push_back(f);
            for (int i = 0; i < 3; ++i) {
                const Index o = mesh.opposite(TriangleMesh::halfedge(f, i));
                if (o == kInvalidIndex ||
                    c.faceComponent[at(TriangleMesh::face(o))] != kInvalidIndex)
                    continue;
                c.faceComponent[at(TriangleMesh::face(o))] = id;
                queue.push_back(TriangleMesh::face(o));
            }
        }
    }
    c.vertexComponent.assign(at(mesh.vertexCount()), kInvalidIndex);
    for (Index f = 0; f < mesh.faceCount(); ++f)
        for (Index v : mesh.triangle(f))
            c.vertexComponent[at(v)] = c.faceComponent[at(f)];
    return c;
}

// Boundary loops: per vertex its loop (kInvalidIndex inside), and per loop
// its vertices in order.
struct BoundaryLoops {
    std::vector<Index> loopOf;
    std::vector<std::vector<Index>> vertices;
};

BoundaryLoops boundaryLoops(const TriangleMesh& mesh) {
    BoundaryLoops loops;
    loops.loopOf.assign(at(mesh.vertexCount()), kInvalidIndex);
    for (Index h = 0; h < mesh.halfedgeCount(); ++h) {
        if (!mesh.isBoundary(h) || loops.loopOf[at(mesh.from(h))] != kInvalidIndex)
            continue;
        const Index id = static_cast<Index>(loops.vertices.size());
        loops.vertices.emplace_back();
        // On a manifold vertex the outgoing boundary half-edge is unique and
        // is vertexHalfedge(): that is the next one on the loop.
        for (Index g = h; loops.loopOf[at(mesh.from(g))] == kInvalidIndex;
             g = mesh.vertexHalfedge(mesh.to(g))) {
            loops.loopOf[at(mesh.from(g))] = id;
            loops.vertices.back().push_back(mesh.from(g));
        }
    }
    return loops;
}

// The cut graph (Erickson & Whittlesey 2005 tree-cotree, with the terminals
// contracted first):
//  1. S: a Steiner tree joining the cones and the boundary loops of each
//     component, grown greedily by shortest paths in the flat metric from the
//     tree built so far (Takahashi & Matsuyama 1980). A boundary loop joins
//     the tree whole, since the surface is already open along it.
//  2. T: the shortest-path forest from S and the boundary (the same Dijkstra
//     run to completion); with S contracted to a point it is a spanning tree.
//  3. C: a maximum spanning tree of the dual graph over the interior edges in
//     neither S nor T, each weighted by the length of its loop through T, so
//     that the 2g edges left over close the shortest loops of the greedy
//     system.
//  4. The cut is every interior edge not in C (the faces glued along C form
//     a disk), pruned of its dangling branches that end at an interior
//     vertex that is not a cone. What remains is S and the 2g handle loops.
std::vector<char> buildCutGraph(const TriangleMesh& mesh, const Components& comps,
                                const BoundaryLoops& loops, const std::vector<char>& isCone,
                                const std::vector<double>& edgeLength) {
    const Index nv = mesh.vertexCount();
    const Index ne = mesh.edgeCount();
    std::vector<double> dist(at(nv), kInfinity);
    std::vector<Index> parentVertex(at(nv), kInvalidIndex);
    std::vector<Index> parentEdge(at(nv), kInvalidIndex);
    std::vector<char> source(at(nv), 0);
    std::vector<char> inS(at(ne), 0);
    std::vector<char> loopJoined(loops.vertices.size(), 0);

    std::vector<std::vector<Index>> componentCones(comps.faces.size());
    for (Index v = 0; v < nv; ++v)
        if (isCone[at(v)])
            componentCones[at(comps.vertexComponent[at(v)])].push_back(v);
    std::vector<std::vector<Index>> componentLoops(comps.faces.size());
    for (std::size_t l = 0; l < loops.vertices.size(); ++l)
        componentLoops[at(comps.vertexComponent[at(loops.vertices[l].front())])].push_back(
            static_cast<Index>(l));

    using Entry = std::pair<double, Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;

    for (std::size_t c = 0; c < comps.faces.size(); ++c) {
        std::size_t remaining = componentCones[c].size() + componentLoops[c].size();
        // A vertex becomes a Dijkstra source at distance 0; a loop vertex
        // brings its whole loop along.
        std::vector<Index> pending;
        const auto addSource = [&](Index v0) {
            pending.assign(1, v0);
            while (!pending.empty()) {
                const Index v = pending.back();
                pending.pop_back();
                if (source[at(v)])
                    continue;
                source[at(v)] = 1;
                dist[at(v)] = 0.0;
                parentVertex[at(v)] = kInvalidIndex;
                parentEdge[at(v)] = kInvalidIndex;
                heap.push({0.0, v});
                if (isCone[at(v)])
                    --remaining;
                const Index l = loops.loopOf[at(v)];
                if (l != kInvalidIndex && !loopJoined[at(l)]) {
                    loopJoined[at(l)] = 1;
                    --remaining;
                    pending.insert(pending.end(), loops.vertices[at(l)].begin(),
                                   loops.vertices[at(l)].end());
                }
            }
        };
        if (!componentCones[c].empty())
            addSource(componentCones[c].front());
        else if (!componentLoops[c].empty())
            addSource(loops.vertices[at(componentLoops[c].front())].front());
        else
            addSource(mesh.triangle(comps.faces[c].front())[0]);

        // Labels only decrease when sources are added, and every vertex
        // whose label dropped is queued again, so the lazy heap stays exact.
        while (!heap.empty()) {
            const auto [d, v] = heap.top();
            heap.pop();
            if (d > dist[at(v)])
                continue;
            const bool terminal =
                !source[at(v)] && (isCone[at(v)] || (loops.loopOf[at(v)] != kInvalidIndex &&
                                                     !loopJoined[at(loops.loopOf[at(v)])]));
            if (remaining > 0 && terminal) {
                for (Index w = v; !source[at(w)];) {
                    const Index up = parentVertex[at(w)];
                    inS[at(parentEdge[at(w)])] = 1;
                    addSource(w);
                    w = up;
                }
                continue;
            }
            forEachEdgeAt(mesh, v, [&](Index w, Index e) {
                const double nd = d + edgeLength[at(e)];
                if (nd < dist[at(w)]) {
                    dist[at(w)] = nd;
                    parentVertex[at(w)] = v;
                    parentEdge[at(w)] = e;
                    heap.push({nd, w});
                }
            });
        }
        if (remaining != 0)
            throw std::invalid_argument("component of face " + std::to_string(comps.faces[c][0]) +
                                        ": a cone or boundary loop cannot be reached along edges");
    }

    std::vector<char> inT(at(ne), 0);
    for (Index v = 0; v < nv; ++v)
        if (!source[at(v)] && parentEdge[at(v)] != kInvalidIndex)
            inT[at(parentEdge[at(v)])] = 1;

    // The cotree, Kruskal on decreasing loop length.
    std::vector<std::pair<double, Index>> candidates;
    for (Index e = 0; e < ne; ++e) {
        if (mesh.isBoundaryEdge(e) || inS[at(e)] || inT[at(e)])
            continue;
        const Index h = mesh.edgeHalfedge(e);
        candidates.push_back(
            {dist[at(mesh.from(h))] + dist[at(mesh.to(h))] + edgeLength[at(e)], e});
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    UnionFind faces(at(mesh.faceCount()));
    std::vector<char> cut(at(ne), 0);
    for (Index e = 0; e < ne; ++e)
        cut[at(e)] = !mesh.isBoundaryEdge(e);
    for (const auto& [weight, e] : candidates) {
        const Index h = mesh.edgeHalfedge(e);
        if (faces.unite(TriangleMesh::face(h), TriangleMesh::face(mesh.opposite(h))))
            cut[at(e)] = 0;
    }

    // Pruning. Boundary edges count in the degree, so a branch that ends on
    // the boundary stays (boundary vertices have degree >= 2).
    std::vector<Index> degree(at(nv), 0);
    for (Index e = 0; e < ne; ++e) {
        if (!cut[at(e)] && !mesh.isBoundaryEdge(e))
            continue;
        const Index h = mesh.edgeHalfedge(e);
        ++degree[at(mesh.from(h))];
        ++degree[at(mesh.to(h))];
    }
    std::vector<Index> leaves;
    for (Index v = 0; v < nv; ++v)
        if (degree[at(v)] == 1 && !isCone[at(v)])
            leaves.push_back(v);
    while (!leaves.empty()) {
        const Index v = leaves.back();
        leaves.pop_back();
        if (degree[at(v)] != 1)
            continue;
        forEachEdgeAt(mesh, v, [&](Index w, Index e) {
            if (!cut[at(e)] || degree[at(v)] != 1)
                return;
            cut[at(e)] = 0;
            degree[at(v)] = 0;
            if (--degree[at(w)] == 1 && !isCone[at(w)])
                leaves.push_back(w);
        });
    }
    return cut;
}

// Breadth-first search over the faces of one component across uncut edges:
// the faces in visiting order, with their parents.
std::vector<Index> faceSweep(const TriangleMesh& mesh, const std::vector<char>& cut, Index root,
                             std::vector<Index>& parent) {
    std::vector<Index> order{root};
    parent[at(root)] = root;
    for (std::size_t q = 0; q < order.size(); ++q) {
        const Index f = order[q];
        for (int i = 0; i < 3; ++i) {
            const Index h = TriangleMesh::halfedge(f, i);
            const Index o = mesh.opposite(h);
            if (o == kInvalidIndex || cut[at(mesh.edge(h))])
                continue;
            const Index g = TriangleMesh::face(o);
            if (parent[at(g)] != kInvalidIndex)
                continue;
            parent[at(g)] = f;
            order.push_back(g);
        }
    }
    return order;
}

// Height of the apex over side c (from P to Q) of a triangle with sides
// c = |PQ|, a = |QR|, b = |RP|, and its foot's distance from P. The area is
// Kahan's stable form of Heron's formula, so needle triangles keep their
// digits.
std::pair<double, double> apexOffset(double c, double a, double b) {
    std::array<double, 3> s{a, b, c};
    std::sort(s.begin(), s.end(), std::greater<>());
    const double x = s[0], y = s[1], z = s[2];
    const double product = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
    const double area = 0.25 * std::sqrt(std::max(0.0, product));
    return {(b * b - a * a + c * c) / (2.0 * c), 2.0 * area / c};
}

void fillChecks(ConeLayout& layout, const std::vector<std::array<double, 3>>* flatLengths) {
    const TriangleMesh& mesh = layout.mesh;
    std::vector<double> angleSum(at(mesh.vertexCount()), 0.0);
    std::vector<char> hasCorner(at(mesh.vertexCount()), 0);
    layout.flippedTriangles = 0;
    layout.maxSideLengthError = 0.0;
    layout.logAreaRatio.assign(at(mesh.faceCount()), 0.0);
    layout.minLogAreaRatio = kInfinity;
    layout.maxLogAreaRatio = -kInfinity;
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto& t = layout.cornerUv[at(f)];
        for (int i = 0; i < 3; ++i) {
            const Index v = mesh.triangle(f)[at(i)];
            angleSum[at(v)] += cornerAngle(t, i);
            hasCorner[at(v)] = 1;
            if (flatLengths) {
                const double l = (*flatLengths)[at(f)][at(i)];
                const double uvLength = (t[at((i + 1) % 3)] - t[at(i)]).norm();
                layout.maxSideLengthError =
                    std::max(layout.maxSideLengthError, std::abs(uvLength - l) / l);
            }
        }
        const double uvArea = 0.5 * twiceSignedArea(t);
        if (!(uvArea > 0.0))
            ++layout.flippedTriangles;
        const double area = 0.5 * mesh.faceAreaNormal(f).norm();
        const double ratio = uvArea > 0.0 ? std::log(uvArea / area) : -kInfinity;
        layout.logAreaRatio[at(f)] = ratio;
        layout.minLogAreaRatio = std::min(layout.minLogAreaRatio, ratio);
        layout.maxLogAreaRatio = std::max(layout.maxLogAreaRatio, ratio);
    }
    if (mesh.faceCount() == 0)
        layout.minLogAreaRatio = layout.maxLogAreaRatio = 0.0;

    layout.maxAngleSumError = 0.0;
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (hasCorner[at(v)] && !layout.isCone[at(v)] && !mesh.isBoundaryVertex(v))
            layout.maxAngleSumError =
                std::max(layout.maxAngleSumError, std::abs(kTwoPi - angleSum[at(v)]));

    layout.maxCutLengthMismatch = 0.0;
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (mesh.isBoundaryEdge(e))
            continue;
        const Index h = mesh.edgeHalfedge(e);
        const Index o = mesh.opposite(h);
        const double a = (uvTo(layout.cornerUv, h) - uvFrom(layout.cornerUv, h)).norm();
        const double b = (uvTo(layout.cornerUv, o) - uvFrom(layout.cornerUv, o)).norm();
        const double mismatch = std::abs(a - b) / std::max(a, b);
        if (layout.cutEdge[at(e)])
            layout.maxCutLengthMismatch = std::max(layout.maxCutLengthMismatch, mismatch);
        else if (!flatLengths)
            layout.maxSideLengthError = std::max(layout.maxSideLengthError, mismatch);
    }
}

} // namespace

ConeLayout layoutConformalMap(std::span<const Vec3> positions, const ConformalMap& map,
                              std::span<const Index> cones, const ConeLayoutOptions& options) {
    if (map.sideLengths.size() != map.triangles.size())
        throw std::invalid_argument(
            "layoutConformalMap: the flat metric has " + std::to_string(map.sideLengths.size()) +
            " side-length triples for " + std::to_string(map.triangles.size()) + " triangles");
    ConeLayout layout;
    layout.mesh =
        TriangleMesh(std::vector<Vec3>(positions.begin(), positions.end()), map.triangles);
    const TriangleMesh& mesh = layout.mesh;
    requireManifoldVertices(mesh);
    const Index nv = mesh.vertexCount();
    const Index nf = mesh.faceCount();
    const std::vector<std::array<double, 3>>& lengths = map.sideLengths;

    for (Index f = 0; f < nf; ++f) {
        const auto& l = lengths[at(f)];
        for (int i = 0; i < 3; ++i)
            if (!(l[at(i)] > 0.0) || !std::isfinite(l[at(i)]))
                throw std::invalid_argument("layoutConformalMap: face " + std::to_string(f) +
                                            " has a non-positive or non-finite side length");
        for (int i = 0; i < 3; ++i)
            if (l[at(i)] > l[at((i + 1) % 3)] + l[at((i + 2) % 3)])
                throw std::invalid_argument("layoutConformalMap: the side lengths of face " +
                                            std::to_string(f) + " violate the triangle inequality");
    }
    std::vector<double> edgeLength(at(mesh.edgeCount()));
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        const Index h = mesh.edgeHalfedge(e);
        const double a = lengths[at(TriangleMesh::face(h))][at(h % 3)];
        edgeLength[at(e)] = a;
        const Index o = mesh.opposite(h);
        if (o == kInvalidIndex)
            continue;
        const double b = lengths[at(TriangleMesh::face(o))][at(o % 3)];
        if (std::abs(a - b) > options.edgeLengthTolerance * std::max(a, b))
            throw std::invalid_argument("layoutConformalMap: the flat metric gives " +
                                        edgeName(mesh, e) + " the lengths " + std::to_string(a) +
                                        " and " + std::to_string(b) + " in its two faces");
    }

    const Components comps = labelComponents(mesh);
    layout.isCone.assign(at(nv), 0);
    for (Index v : cones) {
        if (v < 0 || v >= nv)
            throw std::invalid_argument("layoutConformalMap: cone index " + std::to_string(v) +
                                        " is out of range");
        if (comps.vertexComponent[at(v)] == kInvalidIndex)
            throw std::invalid_argument("layoutConformalMap: cone " + std::to_string(v) +
                                        " has no incident triangle");
        layout.isCone[at(v)] = 1;
    }
    const BoundaryLoops loops = boundaryLoops(mesh);
    layout.cutEdge = buildCutGraph(mesh, comps, loops, layout.isCone, edgeLength);
    const std::vector<char>& cut = layout.cutEdge;

    // Per component: connected across uncut edges, Euler characteristic 1
    // after cutting (a vertex splits into one copy per wedge between cut or
    // boundary edges), then the layout from a central face, found by a double
    // sweep, so that round-off accumulates over the fewest steps.
    std::vector<Index> cutDegree(at(nv), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (!cut[at(e)])
            continue;
        const Index h = mesh.edgeHalfedge(e);
        ++cutDegree[at(mesh.from(h))];
        ++cutDegree[at(mesh.to(h))];
    }
    std::vector<long long> wedges(comps.faces.size(), 0), edgeCopies(comps.faces.size(), 0);
    for (Index v = 0; v < nv; ++v) {
        const Index c = comps.vertexComponent[at(v)];
        if (c == kInvalidIndex)
            continue;
        wedges[at(c)] +=
            mesh.isBoundaryVertex(v) ? 1 + cutDegree[at(v)] : std::max<Index>(1, cutDegree[at(v)]);
    }
    for (Index e = 0; e < mesh.edgeCount(); ++e)
        edgeCopies[at(comps.faceComponent[at(TriangleMesh::face(mesh.edgeHalfedge(e)))])] +=
            cut[at(e)] ? 2 : 1;

    layout.cornerUv.assign(at(nf), {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()});
    std::vector<Index> parent(at(nf), kInvalidIndex);
    const auto resetParents = [&](const std::vector<Index>& faces) {
        for (Index f : faces)
            parent[at(f)] = kInvalidIndex;
    };
    for (std::size_t c = 0; c < comps.faces.size(); ++c) {
        const std::vector<Index>& faces = comps.faces[c];
        std::vector<Index> order = faceSweep(mesh, cut, faces.front(), parent);
        if (order.size() != faces.size()) {
            Index missing = kInvalidIndex;
            for (Index f : faces)
                if (parent[at(f)] == kInvalidIndex && missing == kInvalidIndex)
                    missing = f;
            throw std::invalid_argument("layoutConformalMap: face " + std::to_string(missing) +
                                        " cannot be reached from face " +
                                        std::to_string(faces.front()) + " across uncut edges");
        }
        const long long chi = wedges[c] - edgeCopies[c] + static_cast<long long>(faces.size());
        if (chi != 1)
            throw std::invalid_argument(
                "layoutConformalMap: the component of face " + std::to_string(faces.front()) +
                " is not a disk after cutting (Euler characteristic " + std::to_string(chi) + ")" +
                (chi == 2 ? ": a closed genus-0 component needs at least two cones" : ""));

        const Index far = order.back();
        resetParents(faces);
        order = faceSweep(mesh, cut, far, parent);
        Index root = order.back();
        std::vector<Index> path{root};
        while (path.back() != far)
            path.push_back(parent[at(path.back())]);
        root = path[path.size() / 2];
        resetParents(faces);
        order = faceSweep(mesh, cut, root, parent);

        // The root from its own side lengths, counter-clockwise.
        {
            const auto& l = lengths[at(root)];
            const auto [x, y] = apexOffset(l[0], l[1], l[2]);
            layout.cornerUv[at(root)] = {Vec2(0.0, 0.0), Vec2(l[0], 0.0), Vec2(x, y)};
        }
        // Every other face from the two ends of the side it shares with its
        // parent and its own other two sides, apex to the left of that side.
        for (std::size_t q = 1; q < order.size(); ++q) {
            const Index g = order[q];
            const Index f = parent[at(g)];
            Index shared = kInvalidIndex;
            for (int i = 0; i < 3 && shared == kInvalidIndex; ++i) {
                const Index o = mesh.opposite(TriangleMesh::halfedge(g, i));
                if (o != kInvalidIndex && TriangleMesh::face(o) == f && !cut[at(mesh.edge(o))])
                    shared = i;
            }
            const Index h = mesh.opposite(TriangleMesh::halfedge(g, static_cast<int>(shared)));
            const Vec2 p = uvTo(layout.cornerUv, h);
            const Vec2 qv = uvFrom(layout.cornerUv, h);
            const auto& l = lengths[at(g)];
            const int i = static_cast<int>(shared);
            const auto [x, y] = apexOffset(l[at(i)], l[at((i + 1) % 3)], l[at((i + 2) % 3)]);
            const Vec2 along = (qv - p).normalized();
            const Vec2 left(-along.y(), along.x());
            auto& t = layout.cornerUv[at(g)];
            t[at(i)] = p;
            t[at((i + 1) % 3)] = qv;
            t[at((i + 2) % 3)] = p + x * along + y * left;
        }
    }

    fillChecks(layout, &lengths);
    return layout;
}

ConeLayout layoutFromCornerUv(const TriangleMesh& mesh,
                              std::span<const std::array<Vec2, 3>> cornerUv,
                              double coneAngleTolerance, const ConeLayoutOptions& options) {
    if (static_cast<Index>(cornerUv.size()) != mesh.faceCount())
        throw std::invalid_argument("layoutFromCornerUv: " + std::to_string(cornerUv.size()) +
                                    " uv triples for " + std::to_string(mesh.faceCount()) +
                                    " faces");
    ConeLayout layout;
    layout.mesh = mesh;
    layout.cornerUv.assign(cornerUv.begin(), cornerUv.end());
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto& t = layout.cornerUv[at(f)];
        for (const Vec2& p : t)
            if (!p.allFinite())
                throw std::invalid_argument("layoutFromCornerUv: face " + std::to_string(f) +
                                            " has a missing or non-finite uv");
        double longest = 0.0;
        for (int i = 0; i < 3; ++i)
            longest = std::max(longest, (t[at((i + 1) % 3)] - t[at(i)]).norm());
        if (!(std::abs(twiceSignedArea(t)) > options.degenerateUvTolerance * longest * longest))
            throw std::invalid_argument("layoutFromCornerUv: the uv triangle of face " +
                                        std::to_string(f) + " is degenerate");
    }

    // A cut edge: its two faces place one of its ends differently.
    layout.cutEdge.assign(at(mesh.edgeCount()), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (mesh.isBoundaryEdge(e))
            continue;
        const Index h = mesh.edgeHalfedge(e);
        const Index o = mesh.opposite(h);
        const Vec2 a0 = uvFrom(layout.cornerUv, h), b0 = uvTo(layout.cornerUv, h);
        const Vec2 a1 = uvTo(layout.cornerUv, o), b1 = uvFrom(layout.cornerUv, o);
        const double la = (b0 - a0).norm(), lb = (b1 - a1).norm();
        const double scale = options.uvMatchTolerance * std::max(la, lb);
        if ((a0 - a1).norm() <= scale && (b0 - b1).norm() <= scale)
            continue;
        layout.cutEdge[at(e)] = 1;
        if (std::abs(la - lb) > options.edgeLengthTolerance * std::max(la, lb))
            throw std::invalid_argument("layoutFromCornerUv: the two uv images of cut " +
                                        edgeName(mesh, e) + " have lengths " + std::to_string(la) +
                                        " and " + std::to_string(lb));
    }

    std::vector<double> angleSum(at(mesh.vertexCount()), 0.0);
    for (Index f = 0; f < mesh.faceCount(); ++f)
        for (int i = 0; i < 3; ++i)
            angleSum[at(mesh.triangle(f)[at(i)])] += cornerAngle(layout.cornerUv[at(f)], i);
    layout.isCone.assign(at(mesh.vertexCount()), 0);
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.vertexHalfedge(v) != kInvalidIndex && !mesh.isBoundaryVertex(v) &&
            std::abs(kTwoPi - angleSum[at(v)]) > coneAngleTolerance)
            layout.isCone[at(v)] = 1;

    fillChecks(layout, nullptr);
    return layout;
}

} // namespace contour::powell_sabin
