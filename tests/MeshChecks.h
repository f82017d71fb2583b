#pragma once
// Connectivity and orientation of the consistent method's editable mesh
// (Bénard 2014 §6: every local edit must leave an oriented 2-manifold),
// checked from its faces alone and compared with what the mesh keeps about
// them (the half-edge table, the faces around each vertex, edges(),
// isBoundaryVertex(), toTriangleMesh()). Everything here is observable
// through ConsistentMesh's public interface, so the check lives with the
// tests rather than in the class.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace contour::testing {

// What connectivityErrors() counted (vertices: those with a face; isolated
// ones, e.g. after removeValence3Vertex() and before compact(), apart).
struct MeshCounts {
    Index vertices = 0, isolated = 0, edges = 0, faces = 0;
    Index boundaryEdges = 0, boundaryLoops = 0;
    int euler() const { return vertices - edges + faces; }
};

// "" when the mesh is an oriented manifold whose bookkeeping agrees with its
// faces, else the first problem found. Fills `counts` either way.
inline std::string connectivityErrors(const consistent::ConsistentMesh& m,
                                      MeshCounts* counts = nullptr) {
    using consistent::ConsistentMesh;
    MeshCounts c;
    c.faces = m.faceCount();
    const auto at = [](Index a, Index b) {
        std::string s(1, '(');
        s += std::to_string(a);
        s += ", ";
        s += std::to_string(b);
        s += ')';
        return s;
    };
    std::string error;
    const auto fail = [&](const std::string& what) {
        if (error.empty())
            error = what;
    };
    // Directed edges from the faces themselves: each at most once (two faces
    // holding a -> b are oppositely oriented, or the edge is non-manifold).
    std::map<std::pair<Index, Index>, Index> directed;
    std::vector<std::vector<Index>> around(static_cast<size_t>(m.vertexCount()));
    for (Index f = 0; f < m.faceCount(); ++f) {
        const Triangle& t = m.face(f);
        for (int i = 0; i < 3; ++i) {
            if (t[i] < 0 || t[i] >= m.vertexCount()) {
                fail("face " + std::to_string(f) + " has corner " + std::to_string(t[i]));
                continue;
            }
            if (t[i] == t[(i + 1) % 3])
                fail("face " + std::to_string(f) + " repeats vertex " + std::to_string(t[i]));
            around[static_cast<size_t>(t[i])].push_back(f);
            const auto e = std::pair{t[i], t[(i + 1) % 3]};
            if (!directed.emplace(e, f).second)
                fail("half-edge " + at(e.first, e.second) + " in faces " +
                     std::to_string(directed[e]) + " and " + std::to_string(f) +
                     " (inconsistent orientation or non-manifold edge)");
        }
    }
    if (!error.empty()) {
        if (counts)
            *counts = c;
        return error;
    }
    // The half-edge table holds exactly these half-edges.
    if (m.halfedges().size() != directed.size())
        fail("half-edge table holds " + std::to_string(m.halfedges().size()) + " entries, faces " +
             std::to_string(directed.size()));
    std::map<Index, Index> boundaryNext; // boundary half-edge a -> b, keyed by a
    for (const auto& [e, f] : directed) {
        const auto [a, b] = e;
        if (m.faceOfHalfedge(a, b) != f)
            fail("faceOfHalfedge" + at(a, b) + " = " + std::to_string(m.faceOfHalfedge(a, b)) +
                 ", the faces say " + std::to_string(f));
        const auto twin = directed.find({b, a});
        if (twin == directed.end()) {
            ++c.boundaryEdges;
            if (m.faceOfHalfedge(b, a) != kInvalidIndex)
                fail("boundary half-edge " + at(b, a) + " has a face in the table");
            if (!boundaryNext.emplace(a, b).second)
                fail("vertex " + std::to_string(a) + " starts two boundary half-edges");
        }
        if (twin == directed.end() || a < b)
            ++c.edges;
    }
    // Boundary loops: follow a -> boundaryNext[a].
    std::set<Index> seen;
    for (const auto& [start, next] : boundaryNext) {
        if (seen.count(start))
            continue;
        ++c.boundaryLoops;
        for (Index v = start; seen.insert(v).second;) {
            const auto it = boundaryNext.find(v);
            if (it == boundaryNext.end()) {
                fail("boundary loop through " + std::to_string(start) + " is open at " +
                     std::to_string(v));
                break;
            }
            v = it->second;
        }
    }
    for (Index v = 0; v < m.vertexCount(); ++v) {
        std::vector<Index> expected = around[static_cast<size_t>(v)];
        std::vector<Index> kept = m.vertexFaces(v);
        std::sort(expected.begin(), expected.end());
        std::sort(kept.begin(), kept.end());
        if (kept != expected)
            fail("vertexFaces(" + std::to_string(v) + ") disagrees with the faces");
        if (expected.empty()) {
            ++c.isolated;
            continue;
        }
        ++c.vertices;
        if (m.isBoundaryVertex(v) != (boundaryNext.count(v) > 0))
            fail("isBoundaryVertex(" + std::to_string(v) + ") disagrees with the boundary");
        // The faces around v form one fan (faces sharing an edge at v are
        // joined): v is a manifold vertex.
        std::vector<size_t> parent(expected.size());
        std::iota(parent.begin(), parent.end(), size_t{0});
        const auto root = [&](size_t i) {
            while (parent[i] != i)
                i = parent[i] = parent[parent[i]];
            return i;
        };
        for (size_t i = 0; i < expected.size(); ++i) {
            const Triangle t = consistent::rotatedTo(m.face(expected[i]), v);
            // The face across v -> t[1] holds t[1] -> v.
            const auto nb = directed.find({t[1], v});
            if (nb == directed.end())
                continue;
            const auto j = static_cast<size_t>(
                std::find(expected.begin(), expected.end(), nb->second) - expected.begin());
            parent[root(i)] = root(j);
        }
        for (size_t i = 1; i < expected.size(); ++i)
            if (root(i) != root(0)) {
                fail("the faces around vertex " + std::to_string(v) + " form several fans");
                break;
            }
    }
    // edges() lists every edge once, oriented as a half-edge of a face.
    std::set<std::pair<Index, Index>> listed;
    for (const auto& [a, b] : m.edges()) {
        if (!directed.count({a, b}))
            fail("edges() lists " + at(a, b) + ", no face holds it");
        if (!listed.insert({std::min(a, b), std::max(a, b)}).second)
            fail("edges() lists " + at(a, b) + " twice");
    }
    if (static_cast<Index>(listed.size()) != c.edges)
        fail("edges() lists " + std::to_string(listed.size()) + " edges, the faces have " +
             std::to_string(c.edges));
    // The published mesh builds the same opposite links (an independent
    // half-edge structure); it has no isolated vertices' faces to lose.
    if (error.empty()) {
        const auto published = m.toTriangleMesh();
        if (published->faceCount() != c.faces || published->edgeCount() != c.edges)
            fail("toTriangleMesh() has " + std::to_string(published->faceCount()) + " faces and " +
                 std::to_string(published->edgeCount()) + " edges");
    }
    if (counts)
        *counts = c;
    return error;
}

} // namespace contour::testing
