// The local operators of the consistent method's editable mesh (Bénard,
// Hertzmann & Kass 2014 §6, Fig. 16): edge split, face split, flip, vertex
// shift, valence-3 vertex removal, compaction, and building by faces or all
// at once. Each runs on a tiny hand-built mesh (a quad of two triangles, a
// fan around a vertex, a tetrahedron, an octahedron) and is followed by
// connectivityErrors() (MeshChecks.h) and the counts the edit must leave:
// faces, vertices, edges, boundary, Euler characteristic, and the records
// of the vertices it creates or moves. Refusals are reported as the header
// says (false and nothing changed, or std::logic_error from addFace()).
//
// Vertices carry preimages in one quad face of a Catmull-Clark sphere (the
// operators never look at the surface; the fold tests of FoldTest.h do, in
// parameter space and in 3D).
#include "ContourTestSupport.h"
#include "MeshChecks.h"
#include "contours/consistent/predicates/FoldTest.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

using namespace contour;
using namespace contour::consistent;
using namespace contour::testing;

namespace {

constexpr Index kDomainFace = 0;
constexpr int kBuildPhase = 0, kEditPhase = 7;

std::shared_ptr<const SmoothSurface> sphereSurface() {
    static const auto surface = makeSmoothSurface(*shape("sphere", 8), SurfaceKind::CatmullClark);
    return surface;
}

ConsistentMesh emptyMesh() {
    const auto surface = sphereSurface();
    const Camera camera = Camera::views26(surface->domain().boundingBox(), Viewport{800, 600})[0];
    return ConsistentMesh(surface, camera, 1e-9);
}

Index addAt(ConsistentMesh& m, double u, double v) {
    return m.addVertex(m.evaluate({kDomainFace, u, v}));
}

// A quad of two triangles in the domain face, diagonal a-b:
//   c ---- b        faces a-b-c and b-a-d (counter-clockwise in (u, v))
//   |    / |
//   |  /   |        d at `dPosition` (the convex square by default)
//   a ---- d
struct Quad {
    ConsistentMesh m = emptyMesh();
    Index a, b, c, d;
    explicit Quad(Vec2 dPosition = Vec2(0.7, 0.3)) {
        a = addAt(m, 0.3, 0.3);
        b = addAt(m, 0.7, 0.7);
        c = addAt(m, 0.3, 0.7);
        d = addAt(m, dPosition.x(), dPosition.y());
        m.addFace({a, b, c}, kBuildPhase);
        m.addFace({b, a, d}, kBuildPhase);
    }
};

// `n` triangles around a centre vertex 0 on a circle of ring vertices 1..;
// closed: the fan goes all the way round (an interior centre).
ConsistentMesh fan(int n, bool closed) {
    ConsistentMesh m = emptyMesh();
    addAt(m, 0.5, 0.5);
    const int ring = closed ? n : n + 1;
    const double step = (closed ? 2.0 : 1.5) * std::numbers::pi / n;
    for (int k = 0; k < ring; ++k)
        addAt(m, 0.5 + 0.3 * std::cos(k * step), 0.5 + 0.3 * std::sin(k * step));
    for (int k = 0; k < n; ++k)
        m.addFace({0, 1 + k, 1 + (k + 1) % ring}, kBuildPhase);
    return m;
}

// Closed meshes, faces counter-clockwise seen from outside. The preimages
// are distinct points of the domain face (the operators need only records).
ConsistentMesh closedMesh(int vertices, const std::vector<Triangle>& faces) {
    ConsistentMesh m = emptyMesh();
    for (int k = 0; k < vertices; ++k)
        addAt(m, 0.2 + 0.1 * k, 0.3 + 0.05 * k);
    for (const Triangle& t : faces)
        m.addFace(t, kBuildPhase);
    return m;
}

ConsistentMesh tetrahedron() {
    return closedMesh(4, {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}});
}

// Vertices +x, -x, +y, -y, +z, -z.
ConsistentMesh octahedron() {
    return closedMesh(
        6,
        {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

// What a mesh must look like after an edit.
struct Expected {
    Index vertices, edges, faces, boundaryEdges;
    int euler;
    Index isolated = 0;
};

// connectivityErrors() is empty and the counts are `e`; else a message.
QString check(const ConsistentMesh& m, const Expected& e) {
    MeshCounts c;
    const std::string error = connectivityErrors(m, &c);
    if (!error.empty())
        return QString::fromStdString(error);
    if (c.vertices != e.vertices || c.edges != e.edges || c.faces != e.faces ||
        c.boundaryEdges != e.boundaryEdges || c.euler() != e.euler || c.isolated != e.isolated)
        return QString("V %1 E %2 F %3 boundary %4 Euler %5 isolated %6, expected V %7 E %8 F %9 "
                       "boundary %10 Euler %11 isolated %12")
            .arg(c.vertices)
            .arg(c.edges)
            .arg(c.faces)
            .arg(c.boundaryEdges)
            .arg(c.euler())
            .arg(c.isolated)
            .arg(e.vertices)
            .arg(e.edges)
            .arg(e.faces)
            .arg(e.boundaryEdges)
            .arg(e.euler)
            .arg(e.isolated);
    return {};
}

#define VERIFY_MESH(m, ...)                                                                        \
    do {                                                                                           \
        const QString why = check(m, Expected{__VA_ARGS__});                                       \
        QVERIFY2(why.isEmpty(), qPrintable(why));                                                  \
    } while (false)

bool samePreimage(const Preimage& p, const Preimage& q) {
    return p.face == q.face && p.u == q.u && p.v == q.v;
}

// The face of the mesh with corners t in this cyclic order, or kInvalidIndex.
Index findFace(const ConsistentMesh& m, const Triangle& t) {
    for (Index f = 0; f < m.faceCount(); ++f) {
        const Triangle& g = m.face(f);
        if (std::find(g.begin(), g.end(), t[0]) != g.end() && rotatedTo(g, t[0]) == t)
            return f;
    }
    return kInvalidIndex;
}

// A vertex record to insert on a-b: the preimage at t along the segment
// (appendix B), marked as an insertion the way the phases mark it.
MeshVertex inserted(const ConsistentMesh& m, Index a, Index b, double t) {
    const std::optional<Preimage> p = m.interpolate(m.vertex(a).preimage, m.vertex(b).preimage, t);
    if (!p)
        throw std::runtime_error("no common chart");
    MeshVertex v = m.evaluate(*p);
    v.provenance = Provenance::Inserted;
    return v;
}

} // namespace

class TestMeshOperators : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QVERIFY(sphereSurface()->isQuad(kDomainFace)); }

    // The check itself must see what it is for.
    void checkDetectsBrokenMeshes() {
        Quad q;
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        // A face turned over against its neighbour: refused by the table.
        QVERIFY_THROWS_EXCEPTION(std::logic_error, q.m.addFace({q.a, q.b, q.d}, kBuildPhase));
        // A third face on edge a-b repeats one of its half-edges too.
        Quad r;
        const Index e = addAt(r.m, 0.5, 0.1);
        QVERIFY_THROWS_EXCEPTION(std::logic_error, r.m.addFace({r.b, r.a, e}, kBuildPhase));
        // Two tetrahedra sharing one vertex: every edge is fine, the vertex
        // is not.
        const ConsistentMesh bow = closedMesh(7, {{0, 1, 2},
                                                  {0, 3, 1},
                                                  {1, 3, 2},
                                                  {0, 2, 3},
                                                  {0, 4, 5},
                                                  {0, 6, 4},
                                                  {4, 6, 5},
                                                  {0, 5, 6}});
        QVERIFY(connectivityErrors(bow).find("several fans") != std::string::npos);
        // The counts: Euler characteristic of a disc, and of a sphere.
        VERIFY_MESH(fan(5, true), 6, 10, 5, 5, 1);
        VERIFY_MESH(fan(4, false), 6, 9, 4, 6, 1);
        VERIFY_MESH(tetrahedron(), 4, 6, 4, 0, 2);
        VERIFY_MESH(octahedron(), 6, 12, 8, 0, 2);
    }

    // §6, Fig. 16a/c: both faces on a-b split in two around the new vertex.
    void splitInteriorEdge() {
        Quad q;
        q.m.setEdgeTag(q.a, q.b, kCuspEdge);
        q.m.setEdgeTag(q.a, q.c, kRadialEdge);
        const MeshVertex v = inserted(q.m, q.a, q.b, 0.5);
        const Index n = q.m.splitEdge(q.a, q.b, v, kEditPhase);
        QCOMPARE(n, Index{4});
        VERIFY_MESH(q.m, 5, 8, 4, 4, 1);
        // The record as given, with the phase that made it.
        QVERIFY(samePreimage(q.m.vertex(n).preimage, v.preimage));
        QCOMPARE(q.m.vertex(n).label, v.label);
        QCOMPARE(q.m.vertex(n).g, v.g);
        QCOMPARE(q.m.vertex(n).provenance, Provenance::Inserted);
        QCOMPARE(q.m.vertex(n).phase, kEditPhase);
        // The midpoint of a segment inside one face is the mean preimage.
        QCOMPARE(q.m.vertex(n).preimage.face, kDomainFace);
        QVERIFY(std::abs(q.m.vertex(n).preimage.u - 0.5) < 1e-15);
        QVERIFY(std::abs(q.m.vertex(n).preimage.v - 0.5) < 1e-15);
        // a-n-c and n-b-c replace a-b-c; b-n-d and n-a-d replace b-a-d.
        for (const Triangle& t : {Triangle{q.a, n, q.c}, Triangle{n, q.b, q.c},
                                  Triangle{q.b, n, q.d}, Triangle{n, q.a, q.d}}) {
            const Index f = findFace(q.m, t);
            QVERIFY(f != kInvalidIndex);
            QCOMPARE(q.m.facePhase(f), kEditPhase);
        }
        QCOMPARE(q.m.faceOfHalfedge(q.a, q.b), kInvalidIndex);
        // The split edge's tag goes, the others stay.
        QCOMPARE(q.m.edgeTag(q.a, q.b), int{kNoTag});
        QCOMPARE(q.m.edgeTag(q.c, q.a), int{kRadialEdge});
        QCOMPARE(q.m.neighbours(n).size(), size_t{4});
        QVERIFY(!q.m.isBoundaryVertex(n));
    }

    void splitBoundaryEdge() {
        for (const bool reversed : {false, true}) {
            Quad q;
            // a -> d is the boundary half-edge; either order names the edge.
            const Index x = reversed ? q.d : q.a, y = reversed ? q.a : q.d;
            const Index n = q.m.splitEdge(x, y, inserted(q.m, x, y, 0.25), kEditPhase);
            VERIFY_MESH(q.m, 5, 7, 3, 5, 1);
            QVERIFY(q.m.isBoundaryVertex(n));
            QVERIFY(findFace(q.m, {q.b, q.a, n}) != kInvalidIndex);
            QVERIFY(findFace(q.m, {n, q.d, q.b}) != kInvalidIndex);
            const double u = q.m.vertex(n).preimage.u;
            QVERIFY(std::abs(u - (reversed ? 0.6 : 0.4)) < 1e-15);
        }
    }

    void splitEdgeOfClosedMesh() {
        ConsistentMesh m = octahedron();
        const Index n = m.splitEdge(0, 2, inserted(m, 0, 2, 0.5), kEditPhase);
        VERIFY_MESH(m, 7, 15, 10, 0, 2);
        QCOMPARE(m.vertexFaces(n).size(), size_t{4});
        QCOMPARE(m.vertexFaces(4).size(), size_t{5});
        QCOMPARE(m.vertexFaces(5).size(), size_t{5});
    }

    // §6.3, Fig. 16d: face a-b-c becomes a-b-v (same slot), b-c-v, c-a-v.
    void splitFace() {
        Quad q;
        const Index f = findFace(q.m, {q.a, q.b, q.c});
        MeshVertex v = q.m.evaluate({kDomainFace, 0.45, 0.6});
        v.provenance = Provenance::Inserted;
        const Index n = q.m.splitFace(f, v, kEditPhase);
        VERIFY_MESH(q.m, 5, 8, 4, 4, 1);
        QCOMPARE(rotatedTo(q.m.face(f), q.a), (Triangle{q.a, q.b, n}));
        for (const Triangle& t :
             {Triangle{q.a, q.b, n}, Triangle{q.b, q.c, n}, Triangle{q.c, q.a, n}})
            QCOMPARE(q.m.facePhase(findFace(q.m, t)), kEditPhase);
        // The other face is untouched.
        QCOMPARE(q.m.facePhase(findFace(q.m, {q.b, q.a, q.d})), kBuildPhase);
        QVERIFY(samePreimage(q.m.vertex(n).preimage, v.preimage));
        QCOMPARE(q.m.vertex(n).phase, kEditPhase);
        QCOMPARE(q.m.vertex(n).provenance, Provenance::Inserted);
        // Inside the face in parameter space: no fold (Fig. 17).
        for (Index g = 0; g < q.m.faceCount(); ++g)
            QCOMPARE(q.m.parameterOrientation(g), std::optional<int>(1));

        ConsistentMesh t = tetrahedron();
        t.splitFace(0, t.evaluate({kDomainFace, 0.5, 0.5}), kEditPhase);
        VERIFY_MESH(t, 5, 9, 6, 0, 2);
    }

    // §6, Fig. 16e: a-b-c and b-a-d become a-d-c and b-c-d.
    void flipInteriorEdge() {
        Quad q;
        q.m.setEdgeTag(q.a, q.b, kRadialEdge);
        QCOMPARE(q.m.oppositeVertices(q.a, q.b), (std::array<Index, 2>{q.c, q.d}));
        QVERIFY(!flipFolds(q.m, q.a, q.b).folds());
        QVERIFY(q.m.flipEdge(q.a, q.b, kEditPhase));
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        QVERIFY(findFace(q.m, {q.a, q.d, q.c}) != kInvalidIndex);
        QVERIFY(findFace(q.m, {q.b, q.c, q.d}) != kInvalidIndex);
        QCOMPARE(q.m.faceOfHalfedge(q.a, q.b), kInvalidIndex);
        QCOMPARE(q.m.faceOfHalfedge(q.b, q.a), kInvalidIndex);
        QCOMPARE(q.m.edgeTag(q.a, q.b), int{kNoTag});
        for (Index f = 0; f < q.m.faceCount(); ++f) {
            QCOMPARE(q.m.facePhase(f), kEditPhase);
            QCOMPARE(q.m.parameterOrientation(f), std::optional<int>(1));
        }
        // Flipping back restores the first diagonal.
        QVERIFY(q.m.flipEdge(q.c, q.d, kEditPhase));
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        QVERIFY(findFace(q.m, {q.a, q.b, q.c}) != kInvalidIndex);
        QVERIFY(findFace(q.m, {q.b, q.a, q.d}) != kInvalidIndex);
    }

    void flipOnClosedMesh() {
        ConsistentMesh m = octahedron();
        QVERIFY(m.flipEdge(0, 2, kEditPhase));
        VERIFY_MESH(m, 6, 12, 8, 0, 2);
        QCOMPARE(m.vertexFaces(0).size(), size_t{3});
        QCOMPARE(m.vertexFaces(2).size(), size_t{3});
        QCOMPARE(m.vertexFaces(4).size(), size_t{5});
        QVERIFY(m.faceOfHalfedge(4, 5) != kInvalidIndex);
    }

    // Refusals: false and nothing changed.
    void flipRefusals() {
        Quad q;
        const std::vector<Triangle> before{q.m.face(0), q.m.face(1)};
        // A boundary edge, in either direction.
        QVERIFY(!q.m.flipEdge(q.a, q.d, kEditPhase));
        QVERIFY(!q.m.flipEdge(q.d, q.a, kEditPhase));
        QVERIFY(flipFolds(q.m, q.a, q.d).impossible);
        // Not an edge at all.
        QVERIFY(!q.m.flipEdge(q.c, q.d, kEditPhase));
        QCOMPARE((std::vector<Triangle>{q.m.face(0), q.m.face(1)}), before);
        QCOMPARE(q.m.facePhase(0), kBuildPhase);
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        // On a tetrahedron the new edge c-d always exists already.
        ConsistentMesh t = tetrahedron();
        for (const auto& [a, b] : t.edges()) {
            QVERIFY(!t.flipEdge(a, b, kEditPhase));
            QVERIFY(flipFolds(t, a, b).impossible);
        }
        VERIFY_MESH(t, 4, 6, 4, 0, 2);
        for (Index f = 0; f < t.faceCount(); ++f)
            QCOMPARE(t.facePhase(f), kBuildPhase);
    }

    // A flip across a reflex corner folds (the new diagonal leaves the quad):
    // flipEdge() leaves that test to its caller (FoldTest.h), which reports
    // it in parameter space and in 3D.
    void flipThatWouldFold() {
        Quad q(Vec2(0.9, 0.8)); // b is a reflex corner of a-d-b-c
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        const FlipFold fold = flipFolds(q.m, q.a, q.b);
        QVERIFY(fold.parameterSpace);
        QVERIFY(fold.space3d);
        QVERIFY(!fold.impossible);
        QVERIFY(q.m.flipEdge(q.a, q.b, kEditPhase));
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1);
        QCOMPARE(q.m.parameterOrientation(findFace(q.m, {q.b, q.c, q.d})), std::optional<int>(-1));
    }

    // Fig. 16e right: the three faces around a valence-3 vertex become one.
    void removeValence3Vertex() {
        Quad q;
        q.m.setEdgeTag(q.a, q.c, kRadialEdge);
        const Index f = findFace(q.m, {q.a, q.b, q.c});
        const Index n = q.m.splitFace(f, q.m.evaluate({kDomainFace, 0.45, 0.6}), kEditPhase);
        q.m.setEdgeTag(n, q.b, kRadialEdge);
        VERIFY_MESH(q.m, 5, 8, 4, 4, 1);
        QVERIFY(q.m.removeValence3Vertex(n, kEditPhase + 1));
        // The vertex stays, isolated, until compact().
        VERIFY_MESH(q.m, 4, 5, 2, 4, 1, 1);
        QCOMPARE(q.m.vertexCount(), Index{5});
        QVERIFY(q.m.vertexFaces(n).empty());
        const Index merged = findFace(q.m, {q.a, q.b, q.c});
        QVERIFY(merged != kInvalidIndex);
        QCOMPARE(q.m.facePhase(merged), kEditPhase + 1);
        QCOMPARE(q.m.facePhase(findFace(q.m, {q.b, q.a, q.d})), kBuildPhase);
        // Tags at the removed vertex go, the others stay.
        QCOMPARE(q.m.edgeTag(n, q.b), int{kNoTag});
        QCOMPARE(q.m.edgeTag(q.a, q.c), int{kRadialEdge});
        QCOMPARE(q.m.edgeTags().size(), size_t{1});
    }

    void removeValence3VertexOfClosedMesh() {
        // A flip leaves vertex 0 of the octahedron with three faces.
        ConsistentMesh m = octahedron();
        QVERIFY(m.flipEdge(0, 2, kEditPhase));
        QVERIFY(m.removeValence3Vertex(0, kEditPhase));
        VERIFY_MESH(m, 5, 9, 6, 0, 2, 1);
        QVERIFY(findFace(m, {3, 5, 4}) != kInvalidIndex);
        // The face slots stay dense.
        QCOMPARE(m.faceCount(), Index{6});
    }

    void removalRefusals() {
        // Interior vertices of valence 4 and 5.
        ConsistentMesh o = octahedron();
        QVERIFY(!o.removeValence3Vertex(0, kEditPhase));
        ConsistentMesh f5 = fan(5, true);
        QVERIFY(!f5.removeValence3Vertex(0, kEditPhase));
        VERIFY_MESH(f5, 6, 10, 5, 5, 1);
        // A boundary vertex with three faces (an open fan).
        ConsistentMesh f3 = fan(3, false);
        QCOMPARE(f3.vertexFaces(0).size(), size_t{3});
        QVERIFY(f3.isBoundaryVertex(0));
        QVERIFY(!f3.removeValence3Vertex(0, kEditPhase));
        VERIFY_MESH(f3, 5, 7, 3, 5, 1);
        for (Index f = 0; f < f3.faceCount(); ++f)
            QCOMPARE(f3.facePhase(f), kBuildPhase);
        // An interior valence-3 vertex after all: the closed fan of 3.
        ConsistentMesh f3c = fan(3, true);
        QVERIFY(f3c.removeValence3Vertex(0, kEditPhase));
        VERIFY_MESH(f3c, 3, 3, 1, 3, 1, 1);
    }

    // compact() drops isolated vertices, keeps the others' records in order
    // and renumbers faces and tags.
    void compactRenumbers() {
        ConsistentMesh m = octahedron();
        QVERIFY(m.flipEdge(0, 2, kEditPhase));
        m.setEdgeTag(4, 5, kRadialEdge);
        m.setEdgeTag(1, 3, kCuspEdge);
        QVERIFY(m.removeValence3Vertex(0, kEditPhase));
        std::vector<MeshVertex> kept(m.vertices().begin() + 1, m.vertices().end());
        std::vector<Triangle> faces;
        for (Index f = 0; f < m.faceCount(); ++f) {
            Triangle t = m.face(f);
            for (Index& w : t)
                --w;
            faces.push_back(t);
        }
        m.compact();
        VERIFY_MESH(m, 5, 9, 6, 0, 2);
        QCOMPARE(m.vertexCount(), Index{5});
        for (Index v = 0; v < m.vertexCount(); ++v)
            QVERIFY(samePreimage(m.vertex(v).preimage, kept[static_cast<size_t>(v)].preimage));
        for (Index f = 0; f < m.faceCount(); ++f)
            QCOMPARE(m.face(f), faces[static_cast<size_t>(f)]);
        QCOMPARE(m.edgeTag(3, 4), int{kRadialEdge});
        QCOMPARE(m.edgeTag(0, 2), int{kCuspEdge});
        QCOMPARE(m.edgeTags().size(), size_t{2});
        // Nothing isolated: nothing changes.
        m.compact();
        VERIFY_MESH(m, 5, 9, 6, 0, 2);
        QCOMPARE(m.face(0), faces[0]);
    }

    // §6: a vertex shift re-evaluates f, n, g at the new preimage.
    void shiftAndSetVertex() {
        ConsistentMesh m = fan(5, true);
        const Preimage p{kDomainFace, 0.52, 0.47};
        m.shiftVertex(0, p, VertexLabel::Contour, kEditPhase);
        VERIFY_MESH(m, 6, 10, 5, 5, 1);
        const MeshVertex expected = m.evaluate(p);
        QVERIFY(samePreimage(m.vertex(0).preimage, p));
        QVERIFY(m.vertex(0).position == expected.position);
        QCOMPARE(m.vertex(0).g, expected.g);
        QCOMPARE(m.vertex(0).label, VertexLabel::Contour);
        QCOMPARE(m.vertex(0).provenance, Provenance::Shifted);
        QCOMPARE(m.vertex(0).phase, kEditPhase);
        for (Index f = 0; f < m.faceCount(); ++f)
            QCOMPARE(m.facePhase(f), kEditPhase);
        // setVertex with a phase marks the faces around; an undo (phase < 0)
        // does not.
        ConsistentMesh n = fan(4, false);
        MeshVertex x = n.evaluate({kDomainFace, 0.3, 0.2});
        n.setVertex(1, x, -1);
        QVERIFY(samePreimage(n.vertex(1).preimage, x.preimage));
        for (Index f = 0; f < n.faceCount(); ++f)
            QCOMPARE(n.facePhase(f), kBuildPhase);
        n.setVertex(1, x, kEditPhase);
        QCOMPARE(n.facePhase(0), kEditPhase);
        QCOMPARE(n.facePhase(1), kBuildPhase);
        VERIFY_MESH(n, 6, 9, 4, 6, 1);
    }

    // assign() builds what addVertex() and addFace() build; a shared table
    // is copied on the first edit, never changed under its other readers.
    void assignAndShareTable() {
        ConsistentMesh built = octahedron();
        ConsistentMesh assigned = emptyMesh();
        std::vector<Triangle> faces;
        for (Index f = 0; f < built.faceCount(); ++f)
            faces.push_back(built.face(f));
        assigned.assign(built.vertices(), faces, std::vector<int>(faces.size(), kBuildPhase),
                        nullptr);
        VERIFY_MESH(assigned, 6, 12, 8, 0, 2);
        for (Index v = 0; v < built.vertexCount(); ++v)
            QCOMPARE(assigned.vertexFaces(v), built.vertexFaces(v));

        const std::shared_ptr<const HalfedgeMap> table = built.shareHalfedges();
        ConsistentMesh reloaded = emptyMesh();
        reloaded.assignShared(built.vertices(), faces, std::vector<int>(faces.size(), kBuildPhase),
                              table);
        VERIFY_MESH(reloaded, 6, 12, 8, 0, 2);
        QVERIFY(reloaded.flipEdge(0, 2, kEditPhase));
        VERIFY_MESH(reloaded, 6, 12, 8, 0, 2);
        // The shared table still describes the octahedron.
        QCOMPARE(table->size(), size_t{24});
        QCOMPARE(built.faceOfHalfedge(0, 2), Index{0});
        QCOMPARE(built.faceOfHalfedge(4, 5), kInvalidIndex);
        VERIFY_MESH(built, 6, 12, 8, 0, 2);
        QVERIFY(built.splitEdge(1, 3, inserted(built, 1, 3, 0.5), kEditPhase) == 6);
        VERIFY_MESH(built, 7, 15, 10, 0, 2);
        QCOMPARE(table->size(), size_t{24});
    }

    // A sequence of every edit on one fan, checked after each.
    void editSequence() {
        ConsistentMesh m = fan(6, true);
        VERIFY_MESH(m, 7, 12, 6, 6, 1);
        const Index s = m.splitEdge(0, 1, inserted(m, 0, 1, 0.5), kEditPhase);
        VERIFY_MESH(m, 8, 15, 8, 6, 1);
        QVERIFY(m.flipEdge(0, 2, kEditPhase));
        VERIFY_MESH(m, 8, 15, 8, 6, 1);
        const Index f = m.vertexFaces(0).front();
        const Index c = m.splitFace(f, m.evaluate({kDomainFace, 0.5, 0.55}), kEditPhase);
        VERIFY_MESH(m, 9, 18, 10, 6, 1);
        QVERIFY(m.removeValence3Vertex(c, kEditPhase));
        VERIFY_MESH(m, 8, 15, 8, 6, 1, 1);
        m.compact();
        VERIFY_MESH(m, 8, 15, 8, 6, 1);
        QCOMPARE(m.vertexCount(), Index{8});
        QVERIFY(s < m.vertexCount());
    }
};

QTEST_APPLESS_MAIN(TestMeshOperators)
#include "test_mesh_operators.moc"
