// Cones of the flat metric (Capouellez et al. 2023 §5.1,
// contours/powell_sabin/ConeSelection.h): topology and cone counts per
// component, angle defects (discrete Gauss-Bonnet), clusters of close size
// with the cone at the cluster's smallest defect, and the conforming Loop
// refinement of the cones' one-rings.
#include "contours/powell_sabin/ConeSelection.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

constexpr double kPi = std::numbers::pi;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

Index eulerCharacteristic(const TriangleMesh& m) {
    std::vector<char> used(at(m.vertexCount()), 0);
    for (const Triangle& t : m.triangles())
        for (Index v : t)
            used[at(v)] = 1;
    const Index v = static_cast<Index>(std::count(used.begin(), used.end(), char(1)));
    return v - m.edgeCount() + m.faceCount();
}

// A slab of thickness 0.5 over a 2D region of unit squares (cells x cells
// per square), with the listed unit squares cut out as holes: a closed
// surface of genus = number of holes. Quads are split along one diagonal.
TriangleMesh makeHoledSlab(int unitsX, int unitsY, const std::vector<std::pair<int, int>>& holes,
                           int cells) {
    const int nx = unitsX * cells, ny = unitsY * cells;
    auto present = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= nx || j >= ny)
            return false;
        return std::find(holes.begin(), holes.end(), std::pair(i / cells, j / cells)) ==
               holes.end();
    };
    std::vector<Vec3> positions;
    std::map<std::pair<int, int>, Index> top, bottom;
    const double h = 1.0 / cells;
    auto vertex = [&](std::map<std::pair<int, int>, Index>& layer, int i, int j, double z) {
        auto [it, inserted] = layer.try_emplace({i, j}, static_cast<Index>(positions.size()));
        if (inserted)
            positions.emplace_back(i * h, j * h, z);
        return it->second;
    };
    std::vector<Triangle> triangles;
    auto quad = [&](Index a, Index b, Index c, Index d) {
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
    };
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            if (!present(i, j))
                continue;
            const int ci[4] = {i, i + 1, i + 1, i};
            const int cj[4] = {j, j, j + 1, j + 1};
            Index t[4], b[4];
            for (int k = 0; k < 4; ++k) {
                t[k] = vertex(top, ci[k], cj[k], 0.5);
                b[k] = vertex(bottom, ci[k], cj[k], 0.0);
            }
            quad(t[0], t[1], t[2], t[3]); // up
            quad(b[3], b[2], b[1], b[0]); // down
            // Sides k -> k+1 run counter-clockwise with the cell on their
            // left; a wall where the neighbour across is missing.
            const int di[4] = {0, 1, 0, -1}, dj[4] = {-1, 0, 1, 0};
            for (int k = 0; k < 4; ++k)
                if (!present(i + di[k], j + dj[k]))
                    quad(b[k], b[(k + 1) % 4], t[(k + 1) % 4], t[k]);
        }
    return TriangleMesh(std::move(positions), std::move(triangles));
}

TriangleMesh makeTetrahedron() {
    return TriangleMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                        {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

TriangleMesh makeCube() {
    std::vector<Vec3> p;
    for (int k = 0; k < 8; ++k)
        p.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    // Outward, counter-clockwise quads split into triangles.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<Triangle> t;
    for (const auto& q : quads) {
        t.push_back({q[0], q[1], q[2]});
        t.push_back({q[0], q[2], q[3]});
    }
    return TriangleMesh(std::move(p), std::move(t));
}

TriangleMesh withoutFaces(const TriangleMesh& m, const std::set<Index>& drop) {
    std::vector<Triangle> t;
    for (Index f = 0; f < m.faceCount(); ++f)
        if (!drop.count(f))
            t.push_back(m.triangle(f));
    return TriangleMesh(std::vector<Vec3>(m.positions().begin(), m.positions().end()),
                        std::move(t));
}

std::vector<std::set<Index>> neighbours(const TriangleMesh& m) {
    std::vector<std::set<Index>> n(at(m.vertexCount()));
    for (const Triangle& t : m.triangles())
        for (int i = 0; i < 3; ++i) {
            n[at(t[at(i)])].insert(t[at((i + 1) % 3)]);
            n[at(t[at((i + 1) % 3)])].insert(t[at(i)]);
        }
    return n;
}

double sum(const std::vector<double>& x) {
    double s = 0.0;
    for (double v : x)
        s += v;
    return s;
}

std::vector<Index> clusterSizes(const Cones& cones) {
    std::vector<Index> size(cones.vertices.size(), 0);
    for (Index c : cones.cluster)
        if (c != kInvalidIndex)
            ++size[at(c)];
    return size;
}

// What every selection promises: one cone per cluster, in its own cluster,
// no two cones adjacent, no cone on the boundary, and each cone of smallest
// angle defect among its cluster's vertices that are not next to another
// cone (those are eligible whatever order the clusters chose in). Returns
// the first broken promise, empty when none; `plainMinimum` counts the
// cones that are their cluster's plain minimum.
QString selectionProblem(const TriangleMesh& m, const Cones& cones, int* plainMinimum = nullptr) {
    const auto n = neighbours(m);
    const std::vector<double> defect = angleDefects(m);
    std::set<Index> coneSet(cones.vertices.begin(), cones.vertices.end());
    if (coneSet.size() != cones.vertices.size())
        return QStringLiteral("a cone is listed twice");
    int plain = 0;
    for (std::size_t j = 0; j < cones.vertices.size(); ++j) {
        const Index c = cones.vertices[j];
        if (cones.cluster[at(c)] != static_cast<Index>(j))
            return QStringLiteral("cone %1 is not in its own cluster").arg(c);
        if (m.isBoundaryVertex(c))
            return QStringLiteral("cone %1 is on the boundary").arg(c);
        for (Index w : n[at(c)])
            if (coneSet.count(w))
                return QStringLiteral("cones %1 and %2 are adjacent").arg(c).arg(w);
        double eligibleMin = std::numeric_limits<double>::infinity();
        double clusterMin = eligibleMin;
        for (Index v = 0; v < m.vertexCount(); ++v) {
            if (cones.cluster[at(v)] != static_cast<Index>(j))
                continue;
            clusterMin = std::min(clusterMin, defect[at(v)]);
            bool nextToCone = false;
            for (Index w : n[at(v)])
                nextToCone |= coneSet.count(w) > 0;
            if (!nextToCone)
                eligibleMin = std::min(eligibleMin, defect[at(v)]);
        }
        if (defect[at(c)] > eligibleMin)
            return QStringLiteral("cone %1: defect %2 above its cluster's eligible minimum %3")
                .arg(c)
                .arg(defect[at(c)])
                .arg(eligibleMin);
        plain += defect[at(c)] == clusterMin;
    }
    if (plainMinimum)
        *plainMinimum = plain;
    return {};
}

// Everything refineAroundCones promises, checked against the input.
void checkRefinement(const TriangleMesh& m, const std::vector<Index>& cones) {
    const ConeRefinement r = refineAroundCones(m, cones);
    const TriangleMesh& out = r.mesh; // built: manifold and oriented
    std::set<Index> coneSet(cones.begin(), cones.end());
    std::vector<char> split(at(m.faceCount()), 0);
    for (Index f = 0; f < m.faceCount(); ++f)
        for (Index v : m.triangle(f))
            split[at(f)] |= coneSet.count(v) > 0;
    std::vector<char> edgeSplit(at(m.edgeCount()), 0);
    for (Index h = 0; h < m.halfedgeCount(); ++h)
        if (split[at(TriangleMesh::face(h))])
            edgeSplit[at(m.edge(h))] = 1;
    Index splitCount = 0, bisected = 0, bisectionSides = 0;
    std::vector<Index> children(at(m.faceCount()), 1);
    for (Index f = 0; f < m.faceCount(); ++f) {
        int sides = 0;
        for (int i = 0; i < 3; ++i)
            sides += edgeSplit[at(m.edge(TriangleMesh::halfedge(f, i)))];
        if (split[at(f)]) {
            ++splitCount;
            children[at(f)] = 4;
        } else if (sides > 0) {
            ++bisected;
            bisectionSides += sides;
            children[at(f)] = sides + 1;
        }
    }
    QCOMPARE(r.splitTriangles, splitCount);
    QCOMPARE(r.bisectedTriangles, bisected);
    QCOMPARE(out.faceCount(), m.faceCount() + 3 * splitCount + bisectionSides);
    const Index newVertices = static_cast<Index>(std::count(edgeSplit.begin(), edgeSplit.end(), 1));
    QCOMPARE(out.vertexCount(), m.vertexCount() + newVertices);
    QCOMPARE(eulerCharacteristic(out), eulerCharacteristic(m));
    const auto before = meshComponents(m), after = meshComponents(out);
    QCOMPARE(after.size(), before.size());
    for (std::size_t i = 0; i < before.size(); ++i) {
        QCOMPARE(after[i].genus, before[i].genus);
        QCOMPARE(after[i].boundaryLoops, before[i].boundaryLoops);
    }
    QCOMPARE(r.cones, cones);

    // Old vertices unmoved; new ones by Loop's edge rule, in edge order.
    for (Index v = 0; v < m.vertexCount(); ++v)
        QVERIFY(out.position(v) == m.position(v));
    Index next = m.vertexCount();
    std::vector<Index> edgeVertex(at(m.edgeCount()), kInvalidIndex);
    for (Index e = 0; e < m.edgeCount(); ++e) {
        if (!edgeSplit[at(e)])
            continue;
        edgeVertex[at(e)] = next;
        const Index h = m.edgeHalfedge(e);
        const Vec3 a = m.position(m.from(h)), b = m.position(m.to(h));
        Vec3 expected = 0.5 * (a + b);
        if (!m.isBoundary(h))
            expected =
                0.375 * (a + b) + 0.125 * (m.position(m.to(TriangleMesh::next(h))) +
                                           m.position(m.to(TriangleMesh::next(m.opposite(h)))));
        QVERIFY((out.position(next) - expected).norm() < 1e-12);
        ++next;
    }

    // Children: counts per parent, and corners among the parent's corners
    // and the new vertices of its sides.
    QCOMPARE(static_cast<Index>(r.parentFace.size()), out.faceCount());
    std::vector<Index> seen(at(m.faceCount()), 0);
    for (Index g = 0; g < out.faceCount(); ++g) {
        const Index f = r.parentFace[at(g)];
        QVERIFY(f >= 0 && f < m.faceCount());
        ++seen[at(f)];
        std::set<Index> allowed(m.triangle(f).begin(), m.triangle(f).end());
        for (int i = 0; i < 3; ++i)
            if (const Index w = edgeVertex[at(m.edge(TriangleMesh::halfedge(f, i)))];
                w != kInvalidIndex)
                allowed.insert(w);
        for (Index v : out.triangle(g))
            QVERIFY(allowed.count(v));
        QCOMPARE(out.sourcePolygon(g), m.sourcePolygon(f));
    }
    QCOMPARE(seen, children);

    // Each cone's one-ring lies inside split triangles, and its neighbours
    // are all new edge vertices: the ring has shrunk towards the cone.
    for (Index g = 0; g < out.faceCount(); ++g)
        for (Index v : out.triangle(g))
            if (coneSet.count(v))
                QVERIFY(split[at(r.parentFace[at(g)])]);
    const auto n = neighbours(out);
    for (Index c : cones)
        for (Index w : n[at(c)])
            QVERIFY(w >= m.vertexCount());
}

QString sharedMesh(const char* name) {
    return QStringLiteral(CONTOUR_SHARED_DIR "/meshes/") + QString::fromLatin1(name);
}

} // namespace

class TestPsCones : public QObject {
    Q_OBJECT
private slots:
    void sphereHasEightCones() {
        const TriangleMesh m = makeSphere(1.0, 16).triangulate();
        const auto comps = meshComponents(m);
        QCOMPARE(comps.size(), std::size_t(1));
        QCOMPARE(comps[0].genus, 0);
        QCOMPARE(comps[0].boundaryLoops, 0);
        QCOMPARE(comps[0].faceCount, m.faceCount());
        QCOMPARE(comps[0].vertexCount, m.vertexCount());
        QCOMPARE(comps[0].firstFace, 0);
        QCOMPARE(comps[0].coneCount, 8);
        const Cones cones = selectCones(m);
        QCOMPARE(cones.vertices.size(), std::size_t(8));
        QCOMPARE(cones.components.size(), std::size_t(1));
        QCOMPARE(cones.components[0].coneCount, 8);
        QCOMPARE(selectionProblem(m, cones), QString());
        for (Index s : clusterSizes(cones))
            QVERIFY(s > 0);
        for (Index c : cones.cluster)
            QVERIFY(c != kInvalidIndex);
    }

    void torusHasNone() {
        const TriangleMesh m = makeTorus(2.0, 0.7, 24).triangulate();
        const auto comps = meshComponents(m);
        QCOMPARE(comps.size(), std::size_t(1));
        QCOMPARE(comps[0].genus, 1);
        QCOMPARE(comps[0].boundaryLoops, 0);
        QCOMPARE(comps[0].coneCount, 0);
        const Cones cones = selectCones(m);
        QVERIFY(cones.vertices.empty());
        for (Index c : cones.cluster)
            QCOMPARE(c, kInvalidIndex);
        // The override applies to closed components, a torus included.
        ConeOptions two;
        two.conesPerComponent = 2;
        const Cones forced = selectCones(m, two);
        QCOMPARE(forced.vertices.size(), std::size_t(2));
        QCOMPARE(selectionProblem(m, forced), QString());
    }

    void higherGenus() {
        // A slab with two holes is a genus-2 surface: 4(g - 1) = 4 cones;
        // with three holes, 8.
        const TriangleMesh two = makeHoledSlab(5, 3, {{1, 1}, {3, 1}}, 3);
        auto comps = meshComponents(two);
        QCOMPARE(comps.size(), std::size_t(1));
        QCOMPARE(comps[0].genus, 2);
        QCOMPARE(comps[0].boundaryLoops, 0);
        QCOMPARE(comps[0].coneCount, 4);
        const Cones cones = selectCones(two);
        QCOMPARE(cones.vertices.size(), std::size_t(4));
        QCOMPARE(selectionProblem(two, cones), QString());

        const TriangleMesh three = makeHoledSlab(7, 3, {{1, 1}, {3, 1}, {5, 1}}, 3);
        comps = meshComponents(three);
        QCOMPARE(comps[0].genus, 3);
        QCOMPARE(comps[0].coneCount, 8);
        QCOMPARE(selectionProblem(three, selectCones(three)), QString());
    }

    void openMeshesHaveNone() {
        const TriangleMesh saddle = makeSaddlePatch(12).triangulate();
        auto comps = meshComponents(saddle);
        QCOMPARE(comps.size(), std::size_t(1));
        QCOMPARE(comps[0].genus, 0);
        QCOMPARE(comps[0].boundaryLoops, 1);
        QCOMPARE(comps[0].coneCount, 0);
        // No override for components with a boundary.
        ConeOptions three;
        three.conesPerComponent = 3;
        QVERIFY(selectCones(saddle, three).vertices.empty());

        // A sphere with one face removed is a disk; with two far apart, an
        // annulus.
        const TriangleMesh sphere = makeSphere(1.0, 12).triangulate();
        const TriangleMesh disk = withoutFaces(sphere, {0});
        comps = meshComponents(disk);
        QCOMPARE(comps[0].genus, 0);
        QCOMPARE(comps[0].boundaryLoops, 1);
        QCOMPARE(comps[0].coneCount, 0);
        QVERIFY(selectCones(disk).vertices.empty());
        const TriangleMesh annulus = withoutFaces(sphere, {0, sphere.faceCount() - 1});
        comps = meshComponents(annulus);
        QCOMPARE(comps[0].genus, 0);
        QCOMPARE(comps[0].boundaryLoops, 2);
        // A torus with a hole: genus 1, one loop.
        const TriangleMesh torus = makeTorus(2.0, 0.7, 16).triangulate();
        comps = meshComponents(withoutFaces(torus, {5}));
        QCOMPARE(comps[0].genus, 1);
        QCOMPARE(comps[0].boundaryLoops, 1);
        QCOMPARE(comps[0].coneCount, 0);
    }

    void twoComponents() {
        const TriangleMesh m = makeTwoSpheres(16).triangulate();
        const auto comps = meshComponents(m);
        QCOMPARE(comps.size(), std::size_t(2));
        QCOMPARE(comps[0].firstFace, 0);
        QVERIFY(comps[1].firstFace > 0);
        QCOMPARE(comps[0].faceCount + comps[1].faceCount, m.faceCount());
        QCOMPARE(comps[0].vertexCount + comps[1].vertexCount, m.vertexCount());
        const Cones cones = selectCones(m);
        QCOMPARE(cones.vertices.size(), std::size_t(16));
        QCOMPARE(selectionProblem(m, cones), QString());
        // The first 8 cones on the first sphere (z = 0), the rest on the
        // second (z = -3), each with clusters inside its own component.
        for (std::size_t j = 0; j < 16; ++j) {
            const double z = m.position(cones.vertices[j]).z();
            QVERIFY(j < 8 ? z > -1.5 : z < -1.5);
        }
        for (Index v = 0; v < m.vertexCount(); ++v)
            QCOMPARE(cones.cluster[at(v)]<8, m.position(v).z()> - 1.5);
    }

    void coneCountOverride() {
        const TriangleMesh m = makeSphere(1.0, 16).triangulate();
        ConeOptions o;
        o.conesPerComponent = 3;
        const Cones three = selectCones(m, o);
        QCOMPARE(three.vertices.size(), std::size_t(3));
        QCOMPARE(three.components[0].coneCount, 3);
        QCOMPARE(selectionProblem(m, three), QString());
        o.conesPerComponent = 1;
        const Cones one = selectCones(m, o);
        QCOMPARE(one.vertices.size(), std::size_t(1));
        for (Index c : one.cluster)
            QCOMPARE(c, 0);
        // The single cone is the sphere's vertex of smallest defect.
        const auto defect = angleDefects(m);
        QCOMPARE(defect[at(one.vertices[0])], *std::min_element(defect.begin(), defect.end()));
        o.conesPerComponent = 0;
        QVERIFY(selectCones(m, o).vertices.empty());
        // meshComponents reports the paper's count, whatever the options.
        QCOMPARE(meshComponents(m)[0].coneCount, 8);
    }

    void badInputThrows() {
        // Fewer vertices than cones.
        try {
            selectCones(makeTetrahedron());
            QFAIL("a tetrahedron cannot carry 8 cones");
        } catch (const std::invalid_argument& e) {
            QVERIFY(std::string(e.what()).find("fewer") != std::string::npos);
        }
        // A cube has 8 vertices but they cannot be 8 non-adjacent cones.
        const TriangleMesh cube = makeCube();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, selectCones(cube));
        ConeOptions loose;
        loose.requireNonAdjacent = false;
        const Cones all = selectCones(cube, loose);
        QCOMPARE(std::set<Index>(all.vertices.begin(), all.vertices.end()).size(), std::size_t(8));
        ConeOptions negative;
        negative.lloydIterations = -1;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, selectCones(cube, negative));
        // Two tetrahedra sharing one vertex: two fans at that vertex.
        const TriangleMesh pinched({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                                    Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)},
                                   {{0, 2, 1},
                                    {0, 1, 3},
                                    {0, 3, 2},
                                    {1, 2, 3},
                                    {0, 5, 4},
                                    {0, 4, 6},
                                    {0, 6, 5},
                                    {4, 5, 6}});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, meshComponents(pinched));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, selectCones(pinched));
    }

    void angleDefectsObeyGaussBonnet() {
        // Sum of defects = 2 pi chi, boundary vertices counted with pi - sum.
        const TriangleMesh sphere = makeSphere(1.0, 16).triangulate();
        QVERIFY(std::abs(sum(angleDefects(sphere)) - 4.0 * kPi) < 1e-9);
        const TriangleMesh torus = makeTorus(2.0, 0.7, 16).triangulate();
        QVERIFY(std::abs(sum(angleDefects(torus))) < 1e-9);
        const TriangleMesh saddle = makeSaddlePatch(10).triangulate();
        QVERIFY(std::abs(sum(angleDefects(saddle)) - 2.0 * kPi) < 1e-9);
        const TriangleMesh two = makeHoledSlab(5, 3, {{1, 1}, {3, 1}}, 2);
        QVERIFY(std::abs(sum(angleDefects(two)) + 4.0 * kPi) < 1e-9);
        // A cube's corners carry pi/2 each; a flat interior vertex none, a
        // straight boundary vertex none.
        for (double d : angleDefects(makeCube()))
            QVERIFY(std::abs(d - kPi / 2.0) < 1e-12);
        const TriangleMesh fan({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0),
                                Vec3(0, -1, 0), Vec3(5, 5, 5)},
                               {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}});
        const auto d = angleDefects(fan);
        QVERIFY(std::abs(d[0]) < 1e-12);
        QVERIFY(std::abs(d[1] - kPi / 2.0) < 1e-12); // boundary corner of 90 degrees
        QCOMPARE(d[5], 0.0);                         // no faces
    }

    void spotClusters() {
        const QString path = sharedMesh("spot_control_mesh.obj");
        if (!QFileInfo::exists(path))
            QSKIP(qPrintable(path + " is absent (../shared is not part of a clone)"));
        const TriangleMesh m = readMesh(path.toStdString()).triangulate();
        const Cones cones = selectCones(m);
        QCOMPARE(cones.components[0].genus, 0);
        QCOMPARE(cones.vertices.size(), std::size_t(8));
        int plain = 0;
        QCOMPARE(selectionProblem(m, cones, &plain), QString());
        qInfo("spot: %d of 8 cones are their cluster's plain minimum defect", plain);
        QVERIFY(plain >= 6);
        const auto size = clusterSizes(cones);
        const Index smallest = *std::min_element(size.begin(), size.end());
        const Index largest = *std::max_element(size.begin(), size.end());
        qInfo("spot: cluster sizes %d .. %d vertices", smallest, largest);
        QVERIFY(smallest > 0);
        QVERIFY2(largest <= 3 * smallest,
                 qPrintable(QStringLiteral("cluster sizes %1 .. %2").arg(smallest).arg(largest)));
        // Deterministic.
        const Cones again = selectCones(m);
        QCOMPARE(again.vertices, cones.vertices);
        QCOMPARE(again.cluster, cones.cluster);

        // Balanced by area: cluster areas within the same factor.
        ConeOptions byArea;
        byArea.balanceByArea = true;
        const Cones area = selectCones(m, byArea);
        QCOMPARE(selectionProblem(m, area), QString());
        std::vector<double> clusterArea(8, 0.0);
        for (Index f = 0; f < m.faceCount(); ++f)
            for (Index v : m.triangle(f))
                clusterArea[at(area.cluster[at(v)])] += m.faceAreaNormal(f).norm() / 6.0;
        const double amin = *std::min_element(clusterArea.begin(), clusterArea.end());
        const double amax = *std::max_element(clusterArea.begin(), clusterArea.end());
        QVERIFY2(amax <= 3.0 * amin,
                 qPrintable(QStringLiteral("cluster areas %1 .. %2").arg(amin).arg(amax)));
    }

    void sharedMeshGenus() {
        // Genus from the Euler characteristic of real models: fertility has
        // four handles, killeroo none, bob is a torus.
        const QString fertility = sharedMesh("fertility.obj");
        if (!QFileInfo::exists(fertility))
            QSKIP(qPrintable(fertility + " is absent (../shared is not part of a clone)"));
        const TriangleMesh f = readMesh(fertility.toStdString()).triangulate();
        const auto comps = meshComponents(f);
        QCOMPARE(comps.size(), std::size_t(1));
        QCOMPARE(comps[0].genus, 4);
        QCOMPARE(comps[0].coneCount, 12);
        const Cones cones = selectCones(f);
        QCOMPARE(cones.vertices.size(), std::size_t(12));
        QCOMPARE(selectionProblem(f, cones), QString());
        const auto size = clusterSizes(cones);
        QVERIFY(*std::max_element(size.begin(), size.end()) <=
                3 * *std::min_element(size.begin(), size.end()));
        const TriangleMesh k =
            readMesh(sharedMesh("killeroo_small.obj").toStdString()).triangulate();
        QCOMPARE(meshComponents(k)[0].genus, 0);
        const TriangleMesh bob =
            readMesh(sharedMesh("bob_controlmesh.obj").toStdString()).triangulate();
        QCOMPARE(meshComponents(bob)[0].genus, 1);
        QCOMPARE(meshComponents(bob)[0].coneCount, 0);
    }

    void refinementOfSelectedCones() {
        const TriangleMesh sphere = makeSphere(1.0, 16).triangulate();
        checkRefinement(sphere, selectCones(sphere).vertices);
        const TriangleMesh two = makeHoledSlab(5, 3, {{1, 1}, {3, 1}}, 3);
        checkRefinement(two, selectCones(two).vertices);
        checkRefinement(sphere, {});
    }

    void refinementOfNeighbouringCones() {
        const TriangleMesh m = makeSphere(1.0, 16).triangulate();
        const auto n = neighbours(m);
        // Two adjacent cones (they share two triangles) and a third two
        // edges away from the first.
        const Index a = 40;
        const Index b = *n[at(a)].begin();
        Index c = kInvalidIndex;
        for (Index w : n[at(b)])
            if (w != a && !n[at(a)].count(w))
                c = w;
        QVERIFY(c != kInvalidIndex);
        checkRefinement(m, {a, b, c});

        // A face whose three neighbours across its sides hold the three
        // cones: it is not incident to a cone but has all sides split.
        bool found = false;
        for (Index f = 0; f < m.faceCount() && !found; ++f) {
            std::vector<Index> across;
            for (int i = 0; i < 3; ++i) {
                const Index h = TriangleMesh::halfedge(f, i);
                across.push_back(m.to(TriangleMesh::next(m.opposite(h))));
            }
            std::set<Index> distinct(across.begin(), across.end());
            bool clear = distinct.size() == 3;
            for (Index v : m.triangle(f))
                clear &= !distinct.count(v);
            if (!clear)
                continue;
            const ConeRefinement r = refineAroundCones(m, across);
            QCOMPARE(static_cast<int>(std::count(r.parentFace.begin(), r.parentFace.end(), f)), 4);
            checkRefinement(m, across);
            found = true;
        }
        QVERIFY(found);
    }

    void refinementAtTheBoundary() {
        // Cones on and next to the boundary: boundary edges get midpoints.
        const TriangleMesh saddle = makeSaddlePatch(8).triangulate();
        std::vector<Index> cones;
        for (Index v = 0; v < saddle.vertexCount() && cones.size() < 2; ++v)
            if (saddle.isBoundaryVertex(v))
                cones.push_back(v);
        cones.push_back(saddle.vertexCount() / 2);
        checkRefinement(saddle, cones);
    }

    void refinementRejectsBadCones() {
        const TriangleMesh m = makeSphere(1.0, 8).triangulate();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 refineAroundCones(m, std::vector<Index>{m.vertexCount()}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 refineAroundCones(m, std::vector<Index>{-1}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 refineAroundCones(m, std::vector<Index>{3, 3}));
        const TriangleMesh isolated({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 2, 2)},
                                    {{0, 1, 2}});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 refineAroundCones(isolated, std::vector<Index>{3}));
    }
};

QTEST_GUILESS_MAIN(TestPsCones)
#include "test_ps_cones.moc"
