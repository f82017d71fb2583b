// The cut to a disk and the greedy layout of a flat metric
// (contours/powell_sabin/ConeLayout.h, Capouellez et al. 2023 §5.1), on
// inputs whose flat metric is known without the conformal solver: a plane
// grid and a plane annulus (the 3D lengths), a triangulated cube (3D
// lengths: flat but for its 8 corners, cones of angle 3*pi/2), a grid torus
// with the metric of its parameter rectangle; and the layout read back from
// corner uv, with corrupted uv that must throw.
#include "contours/powell_sabin/ConeLayout.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

constexpr double kPi = std::numbers::pi;

struct Surface {
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    std::vector<std::array<double, 3>> lengths; // the flat metric
};

std::vector<std::array<double, 3>> lengths3D(const std::vector<Vec3>& p,
                                             const std::vector<Triangle>& t) {
    std::vector<std::array<double, 3>> l(t.size());
    for (std::size_t f = 0; f < t.size(); ++f)
        for (int i = 0; i < 3; ++i)
            l[f][i] = (p[t[f][(i + 1) % 3]] - p[t[f][i]]).norm();
    return l;
}

ConformalMap flatMap(const Surface& s) {
    ConformalMap m;
    m.triangles = s.triangles;
    m.sideLengths = s.lengths;
    m.logScale.assign(s.positions.size(), 0.0);
    m.fixedScale.assign(s.positions.size(), 0);
    return m;
}

// An n x n vertex grid of [0, 1]^2, rotated and moved in 3D; faces whose
// lower-left cell corner lies in [hole0, hole1)^2 are left out.
Surface planeGrid(int n, int hole0 = 0, int hole1 = 0) {
    Surface s;
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s.positions.push_back(r * Vec3(i / (n - 1.0), j / (n - 1.0), 0.0) + Vec3(3, -1, 2));
    const auto id = [n](int i, int j) {
        return static_cast<Index>(j * n + i);
    };
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            if (i >= hole0 && i < hole1 && j >= hole0 && j < hole1)
                continue;
            s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    // Drop the vertices no face uses (inside the hole).
    std::vector<Index> remap(s.positions.size(), kInvalidIndex);
    std::vector<Vec3> used;
    for (auto& t : s.triangles)
        for (Index& v : t) {
            if (remap[v] == kInvalidIndex) {
                remap[v] = static_cast<Index>(used.size());
                used.push_back(s.positions[v]);
            }
            v = remap[v];
        }
    s.positions = used;
    s.lengths = lengths3D(s.positions, s.triangles);
    return s;
}

// The surface of the cube [0, 1]^3, each side a k x k grid of triangle pairs.
Surface cube(int k, std::vector<Index>* corners) {
    Surface s;
    std::map<std::array<int, 3>, Index> index;
    const auto vertex = [&](const std::array<int, 3>& p) {
        auto [it, added] = index.try_emplace(p, static_cast<Index>(s.positions.size()));
        if (added)
            s.positions.push_back(Vec3(p[0], p[1], p[2]) / k);
        return it->second;
    };
    // Origin and axes of each side, a x b along the outward normal.
    const std::array<std::array<std::array<int, 3>, 3>, 6> sides = {{
        {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}},
        {{{0, 0, k}, {1, 0, 0}, {0, 1, 0}}},
        {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}},
        {{{0, k, 0}, {0, 0, 1}, {1, 0, 0}}},
        {{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}},
        {{{k, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
    }};
    for (const auto& side : sides) {
        const auto at = [&](int i, int j) {
            std::array<int, 3> p;
            for (int c = 0; c < 3; ++c)
                p[c] = side[0][c] + i * side[1][c] + j * side[2][c];
            return vertex(p);
        };
        for (int j = 0; j < k; ++j)
            for (int i = 0; i < k; ++i) {
                s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
    }
    if (corners) {
        corners->clear();
        for (const auto& [p, v] : index)
            if ((p[0] == 0 || p[0] == k) && (p[1] == 0 || p[1] == k) && (p[2] == 0 || p[2] == k))
                corners->push_back(v);
    }
    s.lengths = lengths3D(s.positions, s.triangles);
    return s;
}

// An m x n grid torus embedded around the z axis, with the flat metric of
// the parameter rectangle [0, a] x [0, b] (cell du = a/m by dv = b/n).
struct Torus {
    Surface s;
    std::vector<std::array<Vec2, 3>> parameter; // per corner, unwrapped
};
Torus flatTorus(int m, int n, double a, double b) {
    Torus t;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j) {
            const double u = 2 * kPi * i / m, v = 2 * kPi * j / n;
            t.s.positions.push_back(Vec3((2.0 + std::cos(v)) * std::cos(u),
                                         (2.0 + std::cos(v)) * std::sin(u), std::sin(v)));
        }
    const auto id = [&](int i, int j) {
        return static_cast<Index>((i % m) * n + (j % n));
    };
    const auto add = [&](std::array<std::array<int, 2>, 3> c) {
        t.s.triangles.push_back({id(c[0][0], c[0][1]), id(c[1][0], c[1][1]), id(c[2][0], c[2][1])});
        std::array<Vec2, 3> p;
        for (int k = 0; k < 3; ++k)
            p[k] = Vec2(c[k][0] * a / m, c[k][1] * b / n);
        t.parameter.push_back(p);
        std::array<double, 3> l;
        for (int k = 0; k < 3; ++k)
            l[k] = (p[(k + 1) % 3] - p[k]).norm();
        t.s.lengths.push_back(l);
    };
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j) {
            add({{{i, j}, {i + 1, j}, {i + 1, j + 1}}});
            add({{{i, j}, {i + 1, j + 1}, {i, j + 1}}});
        }
    return t;
}

// The cut as a graph: its edges, vertices and components, per-vertex degree.
struct CutGraph {
    Index edges = 0, vertices = 0, components = 0, leaves = 0, leavesNotCones = 0;
    std::vector<Index> degree;
};
CutGraph cutGraph(const ConeLayout& l) {
    const TriangleMesh& mesh = l.mesh;
    CutGraph g;
    g.degree.assign(mesh.vertexCount(), 0);
    std::vector<Index> parent(mesh.vertexCount());
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        parent[v] = v;
    const auto find = [&](Index v) {
        while (parent[v] != v)
            v = parent[v] = parent[parent[v]];
        return v;
    };
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (!l.cutEdge[e])
            continue;
        ++g.edges;
        const Index h = mesh.edgeHalfedge(e);
        ++g.degree[mesh.from(h)];
        ++g.degree[mesh.to(h)];
        parent[find(mesh.from(h))] = find(mesh.to(h));
    }
    std::set<Index> roots;
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (g.degree[v] > 0) {
            ++g.vertices;
            roots.insert(find(v));
            if (g.degree[v] == 1) {
                ++g.leaves;
                if (!l.isCone[v])
                    ++g.leavesNotCones;
            }
        }
    g.components = static_cast<Index>(roots.size());
    return g;
}

double uvAngleSum(const ConeLayout& l, Index v) {
    double sum = 0.0;
    for (Index f = 0; f < l.mesh.faceCount(); ++f)
        for (int i = 0; i < 3; ++i)
            if (l.mesh.triangle(f)[i] == v) {
                const Vec2 a = l.cornerUv[f][(i + 1) % 3] - l.cornerUv[f][i];
                const Vec2 b = l.cornerUv[f][(i + 2) % 3] - l.cornerUv[f][i];
                sum += std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
            }
    return sum;
}

// Largest distance between two uv images of one vertex.
double maxVertexSpread(const ConeLayout& l) {
    std::vector<Vec2> first(l.mesh.vertexCount(), Vec2::Constant(std::nan("")));
    double spread = 0.0;
    for (Index f = 0; f < l.mesh.faceCount(); ++f)
        for (int i = 0; i < 3; ++i) {
            Vec2& p = first[l.mesh.triangle(f)[i]];
            if (std::isnan(p.x()))
                p = l.cornerUv[f][i];
            spread = std::max(spread, (p - l.cornerUv[f][i]).norm());
        }
    return spread;
}

// The uv of corner pairs against their 3D positions: 0 for a rigid copy of
// a planar mesh.
double maxCornerDistanceError(const ConeLayout& l) {
    double error = 0.0;
    const Index nf = l.mesh.faceCount();
    for (Index f = 0; f < nf; ++f)
        for (Index g = f; g < nf; g += 7)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) {
                    const double uv = (l.cornerUv[f][i] - l.cornerUv[g][j]).norm();
                    const double xyz = (l.mesh.position(l.mesh.triangle(f)[i]) -
                                        l.mesh.position(l.mesh.triangle(g)[j]))
                                           .norm();
                    error = std::max(error, std::abs(uv - xyz));
                }
    return error;
}

void verifyChecks(const ConeLayout& l, double tolerance) {
    QCOMPARE(l.flippedTriangles, Index(0));
    QVERIFY2(l.maxAngleSumError < tolerance, qPrintable(QString::number(l.maxAngleSumError)));
    QVERIFY2(l.maxCutLengthMismatch < tolerance,
             qPrintable(QString::number(l.maxCutLengthMismatch)));
    QVERIFY2(l.maxSideLengthError < tolerance, qPrintable(QString::number(l.maxSideLengthError)));
    QCOMPARE(l.logAreaRatio.size(), std::size_t(l.mesh.faceCount()));
}

} // namespace

class TestPsLayout : public QObject {
    Q_OBJECT
private slots:
    void planeGridNeedsNoCut() {
        const Surface s = planeGrid(13);
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), {});
        QCOMPARE(l.mesh.faceCount(), Index(s.triangles.size()));
        QCOMPARE(cutGraph(l).edges, Index(0));
        QCOMPARE(std::count(l.isCone.begin(), l.isCone.end(), 1), 0);
        verifyChecks(l, 1e-12);
        // One uv per vertex, a rigid copy of the plane: the 3D lengths are
        // the plane's, and no triangle is mirrored.
        QVERIFY(maxVertexSpread(l) < 1e-12);
        QVERIFY(maxCornerDistanceError(l) < 1e-12);
        QVERIFY(std::abs(l.minLogAreaRatio) < 1e-12 && std::abs(l.maxLogAreaRatio) < 1e-12);
    }

    void planeAnnulusIsCutOnceBetweenItsLoops() {
        const Surface s = planeGrid(13, 4, 8);
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), {});
        const CutGraph g = cutGraph(l);
        // One path from the hole to the outer boundary: a tree with two
        // leaves, both on the boundary (vertices of the boundary loops).
        QVERIFY(g.edges > 0);
        QCOMPARE(g.components, Index(1));
        QCOMPARE(g.vertices, g.edges + 1);
        QCOMPARE(g.leaves, Index(2));
        for (Index v = 0; v < l.mesh.vertexCount(); ++v)
            if (g.degree[v] == 1)
                QVERIFY(l.mesh.isBoundaryVertex(v));
        // The shortest join: the hole is 4 cells from the outer boundary.
        QCOMPARE(g.edges, Index(4));
        verifyChecks(l, 1e-12);
        // A flat annulus has no holonomy: the two images of the cut coincide.
        QVERIFY(maxVertexSpread(l) < 1e-12);
        QVERIFY(maxCornerDistanceError(l) < 1e-12);
    }

    void cubeIsCutThroughItsCorners() {
        const int k = 6;
        std::vector<Index> corners;
        const Surface s = cube(k, &corners);
        QCOMPARE(corners.size(), std::size_t(8));
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), corners);
        for (Index c : corners) {
            QVERIFY(l.isCone[c]);
            QVERIFY(std::abs(uvAngleSum(l, c) - 1.5 * kPi) < 1e-12);
        }
        QCOMPARE(std::count(l.isCone.begin(), l.isCone.end(), 1), 8);
        const CutGraph g = cutGraph(l);
        // Genus 0: the cut is one tree whose leaves are cones, through all 8.
        QCOMPARE(g.components, Index(1));
        QCOMPARE(g.vertices, g.edges + 1);
        QCOMPARE(g.leavesNotCones, Index(0));
        for (Index c : corners)
            QVERIFY(g.degree[c] >= 1);
        // Short: no longer than 7 of the cube's edges, each k mesh edges.
        QVERIFY2(g.edges <= 7 * k, qPrintable(QString::number(g.edges)));
        verifyChecks(l, 1e-12);
        QVERIFY(std::abs(l.minLogAreaRatio) < 1e-12 && std::abs(l.maxLogAreaRatio) < 1e-12);
    }

    void componentsAreCutApart() {
        // Two cubes and a plane grid in one mesh: one tree per cube, none in
        // the grid.
        std::vector<Index> corners;
        const Surface c = cube(3, &corners);
        const Surface grid = planeGrid(6);
        Surface s;
        std::vector<Index> cones;
        const auto append = [&](const Surface& part, const Vec3& offset) {
            const Index base = Index(s.positions.size());
            for (const Vec3& p : part.positions)
                s.positions.push_back(p + offset);
            for (const Triangle& t : part.triangles)
                s.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
            s.lengths.insert(s.lengths.end(), part.lengths.begin(), part.lengths.end());
            return base;
        };
        for (int k = 0; k < 2; ++k) {
            const Index base = append(c, Vec3(3.0 * k, 0.0, 0.0));
            for (Index v : corners)
                cones.push_back(v + base);
        }
        const Index gridBase = append(grid, Vec3(0.0, 5.0, 0.0));
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), cones);
        const CutGraph g = cutGraph(l);
        QCOMPARE(g.components, Index(2));
        QCOMPARE(g.vertices, g.edges + 2);
        QCOMPARE(g.leavesNotCones, Index(0));
        for (Index v = gridBase; v < Index(s.positions.size()); ++v)
            QCOMPARE(g.degree[v], Index(0));
        verifyChecks(l, 1e-12);
    }

    void flatTorusIsCutAlongTwoLoops() {
        const double a = 4.0, b = 1.5;
        const int m = 24, n = 10;
        const Torus t = flatTorus(m, n, a, b);
        const ConeLayout l = layoutConformalMap(t.s.positions, flatMap(t.s), {});
        const CutGraph g = cutGraph(l);
        // Two loops through one point (or joined by a path): a connected
        // graph of cycle rank 2 without dangling branches.
        QCOMPARE(g.components, Index(1));
        QCOMPARE(g.edges - g.vertices + 1, Index(2));
        QCOMPARE(g.leaves, Index(0));
        // The shortest such loops go once around each way: n + m edges.
        QCOMPARE(g.edges, Index(m + n));
        verifyChecks(l, 1e-11);

        // The disk tiles the rectangle: the area is a * b, the parameter's
        // axes keep one direction everywhere (no rotation holonomy), and the
        // two images of a cut edge differ by a vector of the lattice
        // a Z x b Z.
        double area = 0.0;
        for (const auto& uv : l.cornerUv)
            area += 0.5 * ((uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() -
                           (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x());
        QVERIFY(std::abs(area - a * b) < 1e-10);
        const Vec2 eu = (l.cornerUv[0][1] - l.cornerUv[0][0]).normalized(); // face 0: (0,0)->(1,0)
        const Vec2 ev(-eu.y(), eu.x());
        double axisError = 0.0;
        for (Index f = 0; f < l.mesh.faceCount(); ++f)
            for (int i = 0; i < 3; ++i) {
                const Vec2 dp = t.parameter[f][(i + 1) % 3] - t.parameter[f][i];
                const Vec2 duv = l.cornerUv[f][(i + 1) % 3] - l.cornerUv[f][i];
                axisError = std::max(axisError, (duv - (dp.x() * eu + dp.y() * ev)).norm());
            }
        QVERIFY2(axisError < 1e-11, qPrintable(QString::number(axisError)));
        std::set<std::pair<long, long>> shifts;
        for (Index e = 0; e < l.mesh.edgeCount(); ++e) {
            if (!l.cutEdge[e])
                continue;
            const Index h = l.mesh.edgeHalfedge(e), o = l.mesh.opposite(h);
            const Vec2 shift = l.cornerUv[o / 3][(o % 3 + 1) % 3] - l.cornerUv[h / 3][h % 3];
            const Vec2 other = l.cornerUv[o / 3][o % 3] - l.cornerUv[h / 3][(h % 3 + 1) % 3];
            QVERIFY((shift - other).norm() < 1e-11);
            const double su = shift.dot(eu) / a, sv = shift.dot(ev) / b;
            QVERIFY(std::abs(su - std::round(su)) < 1e-9 && std::abs(sv - std::round(sv)) < 1e-9);
            QVERIFY(std::round(su) != 0.0 || std::round(sv) != 0.0);
            shifts.insert({std::lround(std::abs(su)), std::lround(std::abs(sv))});
        }
        // Both generators of the lattice appear.
        QVERIFY(shifts.count({1, 0}) == 1 && shifts.count({0, 1}) == 1);

        // Read back from its uv: no cone, the same cut.
        const ConeLayout back = layoutFromCornerUv(l.mesh, l.cornerUv);
        QCOMPARE(std::count(back.isCone.begin(), back.isCone.end(), 1), 0);
        QVERIFY(back.cutEdge == l.cutEdge);
    }

    void cornerUvRoundTrip() {
        std::vector<Index> corners;
        const Surface s = cube(5, &corners);
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), corners);
        const ConeLayout back = layoutFromCornerUv(l.mesh, l.cornerUv);
        QVERIFY(back.isCone == l.isCone);
        QVERIFY(back.cutEdge == l.cutEdge);
        verifyChecks(back, 1e-12);
        QCOMPARE(back.logAreaRatio, l.logAreaRatio);

        // A rigid motion of all uv changes nothing.
        std::vector<std::array<Vec2, 3>> moved = l.cornerUv;
        const Eigen::Rotation2Dd r(2.1);
        for (auto& t : moved)
            for (Vec2& p : t)
                p = r * p + Vec2(-7.0, 3.5);
        const ConeLayout rigid = layoutFromCornerUv(l.mesh, moved);
        QVERIFY(rigid.isCone == l.isCone);
        QVERIFY(rigid.cutEdge == l.cutEdge);

        // One missing uv.
        std::vector<std::array<Vec2, 3>> bad = l.cornerUv;
        bad[17][1].x() = std::nan("");
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, layoutFromCornerUv(l.mesh, bad));
        // A degenerate uv triangle.
        bad = l.cornerUv;
        bad[3] = {bad[3][0], bad[3][0], bad[3][0]};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, layoutFromCornerUv(l.mesh, bad));
        // Too few uv triples.
        bad = l.cornerUv;
        bad.pop_back();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, layoutFromCornerUv(l.mesh, bad));

        // A stretched cut edge: move the end b of a cut edge (a, b) along it
        // in every face of the wedge at b on one side of the cut, so that
        // uncut edges still agree and only cut edges at b change length.
        Index cutHalfedge = kInvalidIndex;
        for (Index e = 0; e < l.mesh.edgeCount() && cutHalfedge == kInvalidIndex; ++e)
            if (l.cutEdge[e] && !l.isCone[l.mesh.to(l.mesh.edgeHalfedge(e))])
                cutHalfedge = l.mesh.edgeHalfedge(e);
        QVERIFY(cutHalfedge != kInvalidIndex);
        const Vec2 along = 1e-3 * (l.cornerUv[cutHalfedge / 3][(cutHalfedge % 3 + 1) % 3] -
                                   l.cornerUv[cutHalfedge / 3][cutHalfedge % 3]);
        bad = l.cornerUv;
        // Walk the wedge clockwise from the cut edge's face: outgoing
        // half-edge of b in face f is next(h); cross uncut edges only.
        Index h = TriangleMesh::next(cutHalfedge);
        for (int guard = 0; guard < 100; ++guard) {
            bad[h / 3][h % 3] += along;
            const Index o = l.mesh.opposite(h);
            if (o == kInvalidIndex || l.cutEdge[l.mesh.edge(h)])
                break;
            h = TriangleMesh::next(o);
        }
        bool threw = false;
        try {
            layoutFromCornerUv(l.mesh, bad);
        } catch (const std::invalid_argument& e) {
            threw = true;
            QVERIFY2(QString(e.what()).contains("cut edge"), e.what());
        }
        QVERIFY(threw);
    }

    void sphereThroughTheConformalMap() {
        // The cube's grid pushed onto the unit sphere, its 8 corners as the
        // cones; the real solver flattens the metric everywhere else.
        std::vector<Index> corners;
        Surface s = cube(8, &corners);
        for (Vec3& p : s.positions)
            p = (p - Vec3::Constant(0.5)).normalized();
        const TriangleMesh mesh(s.positions, s.triangles);
        const ConformalMap map = computeConformalMap(mesh, corners);
        const ConeLayout l = layoutConformalMap(s.positions, map, corners);
        QCOMPARE(l.mesh.faceCount(), mesh.faceCount());
        const CutGraph g = cutGraph(l);
        QCOMPARE(g.components, Index(1));
        QCOMPARE(g.vertices, g.edges + 1);
        QCOMPARE(g.leavesNotCones, Index(0));
        QCOMPARE(l.flippedTriangles, Index(0));
        // The solver's angle tolerance, and round-off for the lengths.
        QVERIFY2(l.maxAngleSumError < 1e-8, qPrintable(QString::number(l.maxAngleSumError)));
        QVERIFY2(l.maxCutLengthMismatch < 1e-10,
                 qPrintable(QString::number(l.maxCutLengthMismatch)));
        QVERIFY2(l.maxSideLengthError < 1e-10, qPrintable(QString::number(l.maxSideLengthError)));
        // Gauss-Bonnet: the cones carry all of the sphere's curvature,
        // sum (2 pi - theta) = 4 pi, each near the cube's 3 pi / 2 (the
        // triangulation's diagonals break the cube's symmetry).
        double defect = 0.0;
        for (Index c : corners) {
            const double theta = uvAngleSum(l, c);
            QVERIFY2(std::abs(theta - 1.5 * kPi) < 0.25, qPrintable(QString::number(theta)));
            defect += 2 * kPi - theta;
        }
        QVERIFY2(std::abs(defect - 4 * kPi) < 1e-7, qPrintable(QString::number(defect - 4 * kPi)));
        // Read back as an OBJ's uv would be: the same cones and cut.
        const ConeLayout back = layoutFromCornerUv(l.mesh, l.cornerUv, 1e-6);
        QVERIFY(back.isCone == l.isCone);
        QVERIFY(back.cutEdge == l.cutEdge);
        qInfo("sphere: %d faces, %d Newton iterations, %d flips, %d cut edges, log area ratio "
              "[%.3f, %.3f]",
              int(l.mesh.faceCount()), map.newtonIterations, map.flips, int(g.edges),
              l.minLogAreaRatio, l.maxLogAreaRatio);
    }

    void genusTwoGetsFourLoops() {
        // Two grid tori, one quad cut out of each, joined by a tube of 4
        // quads: a closed genus-2 surface. Its 3D lengths are not flat; only
        // the cut's topology and the layout's own checks are tested.
        const Torus a = flatTorus(12, 8, 1.0, 1.0);
        Surface s;
        s.positions = a.s.positions;
        for (const Vec3& p : a.s.positions)
            s.positions.push_back(p + Vec3(8.0, 0.0, 0.0));
        const Index shift = Index(a.s.positions.size());
        const auto id = [](int i, int j) {
            return Index(i * 8 + j);
        };
        const std::array<Index, 4> hole{id(3, 2), id(4, 2), id(4, 3), id(3, 3)}; // ccw
        for (const Triangle& t : a.s.triangles) {
            const bool inHole = std::all_of(t.begin(), t.end(), [&](Index v) {
                return std::find(hole.begin(), hole.end(), v) != hole.end();
            });
            if (inHole)
                continue;
            s.triangles.push_back(t);
            s.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
        }
        // The removed quad's half-edges p_k -> p_k+1 are free on both tori;
        // tube quad k holds p_k -> p_k+1 of the first and q_-k-1 -> q_-k of
        // the second (the second torus is the same, so its hole runs the
        // same way and the tube reverses it).
        for (int k = 0; k < 4; ++k) {
            const Index p0 = hole[k], p1 = hole[(k + 1) % 4];
            const Index q0 = hole[(4 - k) % 4] + shift, q1 = hole[(3 - k) % 4] + shift;
            s.triangles.push_back({p0, p1, q1});
            s.triangles.push_back({p0, q1, q0});
        }
        s.lengths = lengths3D(s.positions, s.triangles);
        const std::vector<Index> cones{id(0, 0), id(6, 4), id(0, 0) + shift, id(6, 4) + shift};
        const ConeLayout l = layoutConformalMap(s.positions, flatMap(s), cones);
        const CutGraph g = cutGraph(l);
        QCOMPARE(g.components, Index(1));
        QCOMPARE(g.edges - g.vertices + 1, Index(4));
        QCOMPARE(g.leavesNotCones, Index(0));
        for (Index c : cones)
            QVERIFY(g.degree[c] >= 1);
        QCOMPARE(l.flippedTriangles, Index(0));
        QVERIFY(l.maxCutLengthMismatch < 1e-12);
        QVERIFY(l.maxSideLengthError < 1e-12);
    }

    void badInputThrows() {
        std::vector<Index> corners;
        const Surface s = cube(3, &corners);
        const ConformalMap m = flatMap(s);
        // A closed genus-0 component with fewer than two cones stays a sphere.
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, layoutConformalMap(s.positions, m, {}));
        const std::vector<Index> one{corners[0]};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, layoutConformalMap(s.positions, m, one));
        // Two cones are enough to open it (a sphere-like cut, not flat).
        const std::vector<Index> two{corners[0], corners[7]};
        const ConeLayout opened = layoutConformalMap(s.positions, m, two);
        QCOMPARE(cutGraph(opened).leaves, Index(2));
        QCOMPARE(opened.flippedTriangles, Index(0));
        QVERIFY(opened.maxAngleSumError > 0.1); // the other 6 corners are not flat
        // A cone out of range.
        const std::vector<Index> outOfRange{Index(s.positions.size())};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 layoutConformalMap(s.positions, m, outOfRange));
        // Metric sizes, the triangle inequality, and one edge with two lengths.
        ConformalMap wrong = m;
        wrong.sideLengths.pop_back();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 layoutConformalMap(s.positions, wrong, corners));
        wrong = m;
        wrong.sideLengths[4][0] = 10.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 layoutConformalMap(s.positions, wrong, corners));
        wrong = m;
        wrong.sideLengths[4][0] *= 1.01;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 layoutConformalMap(s.positions, wrong, corners));
        wrong = m;
        wrong.sideLengths[2][1] = std::nan("");
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 layoutConformalMap(s.positions, wrong, corners));
    }
};

QTEST_GUILESS_MAIN(TestPsLayout)
#include "test_ps_layout.moc"
