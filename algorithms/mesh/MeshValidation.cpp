#include "mesh/MeshValidation.h"

#include "core/Predicates.h"
#include "core/UnionFind.h"
#include "mesh/MeshError.h"
#include "mesh/PolygonEdges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace contour {

namespace {

// Names elements the way the file does: by line when the reader recorded
// lines, else by 0-based position; vertex numbers shifted by indexBase.
class Namer {
public:
    Namer(const PolygonMesh& mesh, const MeshSourceMap& source)
        : source_(source),
          vertexLines_(source.vertexLine.size() == static_cast<size_t>(mesh.vertexCount())),
          faceLines_(source.faceLine.size() == static_cast<size_t>(mesh.faceCount())) {}

    std::string number(Index v) const {
        return std::to_string(std::int64_t{v} + source_.indexBase);
    }
    std::string vertex(Index v) const { return "vertex " + number(v); }
    std::string edge(Index a, Index b) const {
        return "edge (" + number(std::min(a, b)) + ", " + number(std::max(a, b)) + ")";
    }
    std::string vertexLocation(Index v) const {
        return vertexLines_ ? "line " + std::to_string(source_.vertexLine[v]) : vertex(v);
    }
    // The subject of a sentence about the vertex that the location names.
    std::string vertexSubject(Index v) const { return vertexLines_ ? vertex(v) : "the vertex"; }
    std::string faceLocation(Index f) const {
        return faceLines_ ? "line " + std::to_string(source_.faceLine[f])
                          : "face " + std::to_string(f);
    }
    bool hasFaceLines() const { return faceLines_; }
    // "faces 2, 5 and 8" or "the faces on lines 3, 7 and 9".
    std::string faceList(std::vector<Index> faces) const {
        std::sort(faces.begin(), faces.end());
        std::string text = faceLines_ ? "the faces on lines " : "faces ";
        const size_t shown = std::min<size_t>(faces.size(), 6);
        for (size_t i = 0; i < shown; ++i) {
            if (i > 0)
                text += i + 1 == shown && shown == faces.size() ? " and " : ", ";
            text +=
                faceLines_ ? std::to_string(source_.faceLine[faces[i]]) : std::to_string(faces[i]);
        }
        if (shown < faces.size())
            text += ", ...";
        return text;
    }

private:
    const MeshSourceMap& source_;
    bool vertexLines_;
    bool faceLines_;
};

void checkCoordinates(const PolygonMesh& mesh, const std::string& file, const Namer& name) {
    for (Index v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3& p = mesh.positions[v];
        for (int axis = 0; axis < 3; ++axis) {
            if (std::isfinite(p[axis]))
                continue;
            throw MeshError(file, name.vertexLocation(v),
                            name.vertexSubject(v) + " has " +
                                (std::isnan(p[axis]) ? "a NaN " : "an infinite ") + "xyz"[axis] +
                                " coordinate");
        }
    }
}

void checkFaces(const PolygonMesh& mesh, const std::string& file, const Namer& name) {
    const Index vertexCount = mesh.vertexCount();
    std::vector<Index> sorted;
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto face = mesh.face(f);
        const auto fail = [&](const std::string& problem) {
            throw MeshError(file, name.faceLocation(f), problem);
        };
        if (face.size() < 3)
            fail("the face has " +
                 (face.empty() ? std::string("no corners")
                               : "only " + std::to_string(face.size()) +
                                     (face.size() == 1 ? " corner" : " corners")) +
                 " (a face needs at least 3)");
        for (const Index v : face) {
            if (v < 0)
                fail("the face uses the negative vertex index " + std::to_string(v));
            if (v >= vertexCount)
                fail("face index " + name.number(v) + " is out of range (the mesh has " +
                     std::to_string(vertexCount) + " vertices)");
        }
        // Repeated corner.
        if (face.size() <= 8) {
            for (size_t i = 0; i < face.size(); ++i)
                for (size_t j = i + 1; j < face.size(); ++j)
                    if (face[i] == face[j])
                        fail("the face is degenerate: it uses " + name.vertex(face[i]) + " twice");
        } else {
            sorted.assign(face.begin(), face.end());
            std::sort(sorted.begin(), sorted.end());
            const auto repeated = std::adjacent_find(sorted.begin(), sorted.end());
            if (repeated != sorted.end())
                fail("the face is degenerate: it uses " + name.vertex(*repeated) + " twice");
        }
        // Zero area: every corner on one line (exact predicate).
        const Vec3& a = mesh.positions[face[0]];
        size_t second = 1;
        while (second < face.size() && mesh.positions[face[second]] == a)
            ++second;
        if (second == face.size())
            fail("the face is degenerate: all its corners are at the same point");
        const Vec3& b = mesh.positions[face[second]];
        bool flat = true;
        for (size_t i = second + 1; i < face.size() && flat; ++i)
            flat = collinear(a, b, mesh.positions[face[i]]);
        if (flat) {
            // Explain the usual cause: two corners at one point.
            for (size_t i = 0; i < face.size() && face.size() <= 64; ++i)
                for (size_t j = i + 1; j < face.size(); ++j)
                    if (mesh.positions[face[i]] == mesh.positions[face[j]])
                        fail("the face is degenerate: its corners lie on one line (zero area); "
                             "vertices " +
                             name.number(face[i]) + " and " + name.number(face[j]) +
                             " are at the same point");
            fail("the face is degenerate: its corners lie on one line (zero area)");
        }
    }
}

// Edges: at most two faces each, traversed in opposite directions; then each
// vertex's faces must form one fan (one edge-connected component).
void checkTopology(const PolygonMesh& mesh, const std::string& file, const Namer& name) {
    const Index vertexCount = mesh.vertexCount();
    const auto cornerCount = static_cast<Index>(mesh.indices.size());
    const std::vector<Index>& corner = mesh.indices;
    const PolygonEdges edges = polygonEdges(mesh);
    const std::vector<Index>& cornerFace = edges.cornerFace;
    const std::vector<Index>& next = edges.next;

    UnionFind fans(static_cast<size_t>(cornerCount));
    std::vector<Index> fanCount(static_cast<size_t>(vertexCount), 0);
    for (const Index v : corner)
        ++fanCount[v];
    std::vector<Index> group;
    for (Index e = 0; e < edges.edgeCount(); ++e) {
        const std::span<const Index> halfedges = edges.halfedges(e);
        const Index a = std::min(corner[halfedges[0]], corner[next[halfedges[0]]]);
        const Index b = std::max(corner[halfedges[0]], corner[next[halfedges[0]]]);
        if (halfedges.size() > 2) {
            group.clear();
            for (const Index c : halfedges)
                group.push_back(cornerFace[c]);
            const Index lastFace = *std::max_element(group.begin(), group.end());
            throw MeshError(
                file, name.hasFaceLines() ? name.faceLocation(lastFace) : name.edge(a, b),
                (name.hasFaceLines() ? name.edge(a, b) : std::string("the edge")) +
                    " is non-manifold: it is shared by " + std::to_string(halfedges.size()) +
                    " faces (" + name.faceList(group) + "); an edge may border at most 2 faces");
        }
        if (halfedges.size() == 2) {
            const Index c0 = halfedges[0], c1 = halfedges[1];
            if (corner[c0] == corner[c1]) {
                const Index f0 = cornerFace[c0], f1 = cornerFace[c1];
                throw MeshError(
                    file,
                    name.hasFaceLines() ? name.faceLocation(std::max(f0, f1)) : name.edge(a, b),
                    name.faceList({f0, f1}) + " both run along " + name.edge(a, b) + " from " +
                        name.vertex(corner[c0]) + " to " + name.vertex(corner[next[c0]]) +
                        ", so they are inconsistently oriented (one of them is "
                        "flipped, or the surface is not orientable)");
            }
            // c0 runs one way and c1 the other: the corners of the two
            // faces at each end of the edge are joined.
            if (fans.unite(c0, next[c1]))
                --fanCount[corner[c0]];
            if (fans.unite(next[c0], c1))
                --fanCount[corner[c1]];
        }
    }

    for (Index v = 0; v < vertexCount; ++v) {
        if (fanCount[v] <= 1)
            continue;
        // One face from each fan, for the message.
        std::vector<Index> roots, examples;
        for (Index c = 0; c < cornerCount; ++c) {
            if (corner[c] != v)
                continue;
            const Index root = fans.find(c);
            if (std::find(roots.begin(), roots.end(), root) == roots.end()) {
                roots.push_back(root);
                examples.push_back(cornerFace[c]);
            }
        }
        throw MeshError(file, name.vertexLocation(v),
                        name.vertexSubject(v) + " is non-manifold: the faces around it form " +
                            std::to_string(fanCount[v]) +
                            " separate fans that meet only at this vertex (e.g. " +
                            name.faceList(examples) + ")");
    }
}

} // namespace

void validatePolygonMesh(const PolygonMesh& mesh, const std::string& file) {
    validatePolygonMesh(mesh, file, MeshSourceMap{});
}

void validatePolygonMesh(const PolygonMesh& mesh, const std::string& file,
                         const MeshSourceMap& source) {
    // The compressed face layout itself (a mesh built in code could break it).
    bool layoutOk = !mesh.offsets.empty() && mesh.offsets.front() == 0 &&
                    static_cast<size_t>(mesh.offsets.back()) == mesh.indices.size();
    for (size_t i = 1; i < mesh.offsets.size() && layoutOk; ++i)
        layoutOk = mesh.offsets[i] >= mesh.offsets[i - 1];
    if (!layoutOk)
        throw MeshError(file, "", "the mesh's face offsets are inconsistent with its index list");
    if (mesh.positions.empty())
        throw MeshError(file, "", "the mesh has no vertices");
    if (mesh.faceCount() == 0)
        throw MeshError(file, "",
                        "the mesh has no faces (" + std::to_string(mesh.vertexCount()) +
                            (mesh.vertexCount() == 1 ? " vertex" : " vertices") +
                            " but nothing connects them)");
    const Namer name(mesh, source);
    checkCoordinates(mesh, file, name);
    checkFaces(mesh, file, name);
    checkTopology(mesh, file, name);
}

} // namespace contour
