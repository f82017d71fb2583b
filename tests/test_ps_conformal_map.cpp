// Discrete conformal map with fixed scale factors at cones and boundary
// (contours/powell_sabin/ConformalMap.h, Capouellez et al. 2023 §5.1): flat
// disks stay flat, spheres with 8 cones and flat tori converge to 2*pi angle
// sums, Gauss-Bonnet holds for the cones, intrinsic flips repair a skinny
// triangle, impossible maps throw, and the shared meshes converge.
#include "contours/powell_sabin/ConformalMap.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <queue>
#include <set>
#include <string>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTolerance = 1e-9;

// Euler characteristic V - E + F over the vertices used by triangles.
long long eulerCharacteristic(const TriangleMesh& mesh) {
    std::set<Index> used;
    for (const Triangle& t : mesh.triangles())
        used.insert(t.begin(), t.end());
    return static_cast<long long>(used.size()) - mesh.edgeCount() + mesh.faceCount();
}

// Angle opposite a by the law of cosines (an independent check of the
// half-angle formula of the implementation).
double lawOfCosines(double a, double b, double c) {
    return std::acos(std::clamp((b * b + c * c - a * a) / (2.0 * b * c), -1.0, 1.0));
}

// The post-conditions of a map: a simplicial, consistently oriented
// connectivity over the input's vertices whose side lengths agree across
// edges and satisfy triangle inequalities, angle sums that match them,
// 2*pi at free vertices, u = 0 at fixed ones, and Gauss-Bonnet.
void verifyMap(const TriangleMesh& mesh, std::span<const Index> cones, const ConformalMap& map) {
    const Index nv = mesh.vertexCount();
    QCOMPARE(static_cast<Index>(map.triangles.size()), mesh.faceCount());
    QCOMPARE(map.sideLengths.size(), map.triangles.size());
    QCOMPARE(static_cast<Index>(map.logScale.size()), nv);
    QCOMPARE(static_cast<Index>(map.fixedScale.size()), nv);
    QCOMPARE(static_cast<Index>(map.angleSum.size()), nv);

    std::map<std::pair<Index, Index>, double> directed;
    std::vector<double> sums(static_cast<size_t>(nv), 0.0);
    for (size_t f = 0; f < map.triangles.size(); ++f) {
        const Triangle& t = map.triangles[f];
        const auto& l = map.sideLengths[f];
        QVERIFY(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
        for (int i = 0; i < 3; ++i) {
            QVERIFY(l[i] > 0.0 && std::isfinite(l[i]));
            // Each directed edge once: orientation is consistent and no
            // edge is doubled.
            QVERIFY(directed.emplace(std::pair{t[i], t[(i + 1) % 3]}, l[i]).second);
        }
        QVERIFY(l[0] < l[1] + l[2] && l[1] < l[2] + l[0] && l[2] < l[0] + l[1]);
        for (int i = 0; i < 3; ++i)
            sums[t[i]] += lawOfCosines(l[(i + 1) % 3], l[(i + 2) % 3], l[i]);
    }
    Index boundaryEdges = 0;
    for (const auto& [e, length] : directed) {
        const auto it = directed.find({e.second, e.first});
        if (it == directed.end()) {
            ++boundaryEdges;
            continue;
        }
        QVERIFY(std::abs(it->second - length) <= 1e-12 * length);
    }
    QCOMPARE(boundaryEdges, mesh.boundaryEdgeCount());

    std::vector<char> cone(static_cast<size_t>(nv), 0);
    for (const Index c : cones)
        cone[c] = 1;
    double defectSum = 0.0;
    double maxError = 0.0;
    for (Index v = 0; v < nv; ++v) {
        QVERIFY(std::abs(sums[v] - map.angleSum[v]) < 1e-7);
        const bool boundary = mesh.isBoundaryVertex(v);
        QCOMPARE(static_cast<bool>(map.fixedScale[v]), boundary || static_cast<bool>(cone[v]));
        if (map.fixedScale[v]) {
            QCOMPARE(map.logScale[v], 0.0);
        } else {
            maxError = std::max(maxError, std::abs(2.0 * kPi - map.angleSum[v]));
        }
        defectSum += (boundary ? kPi : 2.0 * kPi) - map.angleSum[v];
    }
    QVERIFY2(maxError <= kTolerance, qPrintable(QString::number(maxError)));
    QVERIFY(std::abs(maxError - map.maxAngleError) < 1e-12);
    const double chi = static_cast<double>(eulerCharacteristic(mesh));
    QVERIFY(std::abs(defectSum - 2.0 * kPi * chi) < 1e-8);
}

// A regular planar triangulation of the hexagon of side n (unit edges).
TriangleMesh hexagonalDisk(int n, double z = 0.0, std::function<double(Vec2)> height = {}) {
    std::map<std::pair<int, int>, Index> id;
    std::vector<Vec3> positions;
    const Vec2 e0(1.0, 0.0), e1(0.5, std::sqrt(3.0) / 2.0);
    for (int a = -n; a <= n; ++a)
        for (int b = -n; b <= n; ++b) {
            if (std::abs(a + b) > n)
                continue;
            const Vec2 p = a * e0 + b * e1;
            id[{a, b}] = static_cast<Index>(positions.size());
            positions.emplace_back(p.x(), p.y(), height ? height(p) : z);
        }
    std::vector<Triangle> triangles;
    auto at = [&](int a, int b) -> Index {
        const auto it = id.find({a, b});
        return it == id.end() ? kInvalidIndex : it->second;
    };
    for (const auto& [ab, v] : id) {
        const auto [a, b] = ab;
        const Index r = at(a + 1, b), u = at(a, b + 1), l = at(a - 1, b + 1);
        if (r != kInvalidIndex && u != kInvalidIndex)
            triangles.push_back({v, r, u});
        if (u != kInvalidIndex && l != kInvalidIndex)
            triangles.push_back({v, u, l});
    }
    return TriangleMesh(std::move(positions), std::move(triangles));
}

// The vertices nearest the corners of the cube [-1, 1]^3.
std::vector<Index> cubeCornerCones(const TriangleMesh& mesh) {
    std::vector<Index> cones;
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
        Index best = 0;
        for (Index v = 1; v < mesh.vertexCount(); ++v)
            if ((mesh.position(v) - corner).norm() < (mesh.position(best) - corner).norm())
                best = v;
        cones.push_back(best);
    }
    return cones;
}

// `count` vertices spread by farthest-point sampling in the edge-length
// graph distance (Dijkstra), starting from the vertex farthest from 0.
std::vector<Index> farthestPointCones(const TriangleMesh& mesh, int count) {
    const Index nv = mesh.vertexCount();
    std::vector<std::vector<std::pair<Index, double>>> adjacent(static_cast<size_t>(nv));
    for (Index h = 0; h < mesh.halfedgeCount(); ++h) {
        const double l = (mesh.position(mesh.to(h)) - mesh.position(mesh.from(h))).norm();
        adjacent[mesh.from(h)].emplace_back(mesh.to(h), l);
        adjacent[mesh.to(h)].emplace_back(mesh.from(h), l);
    }
    std::vector<double> distance(static_cast<size_t>(nv), std::numeric_limits<double>::infinity());
    auto grow = [&](Index source) {
        using Item = std::pair<double, Index>;
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        distance[source] = 0.0;
        queue.emplace(0.0, source);
        while (!queue.empty()) {
            const auto [d, v] = queue.top();
            queue.pop();
            if (d > distance[v])
                continue;
            for (const auto& [w, l] : adjacent[v])
                if (d + l < distance[w]) {
                    distance[w] = d + l;
                    queue.emplace(d + l, w);
                }
        }
    };
    auto farthest = [&] {
        Index best = 0;
        for (Index v = 0; v < nv; ++v)
            if (distance[v] > distance[best] && std::isfinite(distance[v]))
                best = v;
        return best;
    };
    if (count == 0)
        return {};
    grow(0);
    std::vector<Index> cones = {farthest()};
    std::fill(distance.begin(), distance.end(), std::numeric_limits<double>::infinity());
    grow(cones[0]);
    while (static_cast<int>(cones.size()) < count) {
        cones.push_back(farthest());
        grow(cones.back());
    }
    return cones;
}

// 8 cones for genus 0, 4(g - 1) for g > 1, none for a torus (§5.1).
int paperConeCount(const TriangleMesh& mesh) {
    const long long genus = (2 - eulerCharacteristic(mesh)) / 2;
    return genus == 0 ? 8 : genus == 1 ? 0 : static_cast<int>(4 * (genus - 1));
}

std::optional<TriangleMesh> meshFile(const std::string& path) {
    if (!std::filesystem::exists(path))
        return std::nullopt;
    return readMesh(path).triangulate();
}

} // namespace

class TestPsConformalMap : public QObject {
    Q_OBJECT
private slots:
    // A planar disk is already flat: nothing moves, nothing flips.
    void flatDiskStaysFlat() {
        const TriangleMesh disk = hexagonalDisk(5);
        const ConformalMap map = computeConformalMap(disk, {});
        verifyMap(disk, {}, map);
        QCOMPARE(map.newtonIterations, 0);
        QCOMPARE(map.flips, 0);
        for (Index v = 0; v < disk.vertexCount(); ++v) {
            QVERIFY(std::abs(map.logScale[v]) < 1e-12);
            if (!disk.isBoundaryVertex(v))
                QVERIFY(std::abs(map.angleSum[v] - 2.0 * kPi) < 1e-12);
        }
        // The unflipped faces keep the input's order and 3D lengths.
        for (Index f = 0; f < disk.faceCount(); ++f) {
            QCOMPARE(map.triangles[f], disk.triangle(f));
            QVERIFY(std::abs(map.sideLengths[f][0] - 1.0) < 1e-12);
        }
    }

    // A curved disk: u changes at interior vertices only and flattens them.
    void curvedDiskFlattens() {
        const TriangleMesh cap = hexagonalDisk(
            6, 0.0, [](const Vec2& p) { return 2.0 * std::exp(-p.squaredNorm() / 8.0); });
        const ConformalMap map = computeConformalMap(cap, {});
        verifyMap(cap, {}, map);
        QVERIFY(map.newtonIterations > 0);
        double maxU = 0.0;
        for (double u : map.logScale)
            maxU = std::max(maxU, std::abs(u));
        QVERIFY(maxU > 0.01);
    }

    // The sphere with 8 cones near the cube's corners: the cones absorb
    // the whole 4*pi of curvature, and they share it alike.
    void sphereWithEightCones() {
        const TriangleMesh sphere = makeSphere(1.0, 12).triangulate();
        const std::vector<Index> cones = cubeCornerCones(sphere);
        QCOMPARE(std::set<Index>(cones.begin(), cones.end()).size(), size_t(8));
        const ConformalMap map = computeConformalMap(sphere, cones);
        verifyMap(sphere, cones, map);
        QVERIFY(map.maxAngleError < 1e-9);
        double freeDefects = 0.0;
        for (Index v = 0; v < sphere.vertexCount(); ++v)
            if (!map.fixedScale[v])
                freeDefects += 2.0 * kPi - map.angleSum[v];
        double coneDefects = 0.0;
        for (const Index c : cones) {
            const double defect = 2.0 * kPi - map.angleSum[c];
            QVERIFY(defect > 0.0 && defect < 2.0 * kPi);
            coneDefects += defect;
        }
        QVERIFY(std::abs(coneDefects - (2.0 * kPi * 2 - freeDefects)) < 1e-8);
        qInfo("sphere(12): %d iterations, %d flips, max angle error %.3g", map.newtonIterations,
              map.flips, map.maxAngleError);
    }

    // A torus needs no cone: the flat metric exists (chi = 0), up to scale.
    void torusBecomesFlat() {
        const TriangleMesh torus = makeTorus(1.0, 0.4, 16).triangulate();
        QCOMPARE(eulerCharacteristic(torus), 0LL);
        const ConformalMap map = computeConformalMap(torus, {});
        verifyMap(torus, {}, map);
        for (Index v = 0; v < torus.vertexCount(); ++v)
            QVERIFY(std::abs(map.angleSum[v] - 2.0 * kPi) <= kTolerance);
        QVERIFY(map.newtonIterations > 0);
    }

    void spotWithEightCones() {
        const auto spot = meshFile(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj");
        if (!spot)
            QSKIP("samples/spot_control_mesh.obj is absent");
        QCOMPARE(eulerCharacteristic(*spot), 2LL);
        const std::vector<Index> cones = farthestPointCones(*spot, 8);
        const ConformalMap map = computeConformalMap(*spot, cones);
        verifyMap(*spot, cones, map);
    }

    // A vertex pushed next to a link edge makes a cap triangle of ~179
    // degrees, whose edge the initial Delaunay pass flips; the curved disk
    // then converges on the flipped connectivity.
    void skinnyTriangleNeedsFlips() {
        const TriangleMesh base = hexagonalDisk(
            4, 0.0, [](const Vec2& p) { return 1.5 * std::exp(-p.squaredNorm() / 4.0); });
        std::vector<Vec3> positions(base.positions().begin(), base.positions().end());
        // The centre vertex and a face around it, rotated to start there.
        Index centre = 0;
        for (Index v = 0; v < base.vertexCount(); ++v)
            if (positions[v].head<2>().norm() < positions[centre].head<2>().norm())
                centre = v;
        Triangle t{};
        for (const Triangle& f : base.triangles())
            for (int i = 0; i < 3; ++i)
                if (f[i] == centre)
                    t = {f[i], f[(i + 1) % 3], f[(i + 2) % 3]};
        QCOMPARE(t[0], centre);
        const Vec3 mid = 0.5 * (positions[t[1]] + positions[t[2]]);
        positions[centre] = mid + 0.002 * (positions[centre] - mid);
        const TriangleMesh skinny(positions, {base.triangles().begin(), base.triangles().end()});
        const Vec3 a = skinny.position(t[1]) - skinny.position(t[0]);
        const Vec3 b = skinny.position(t[2]) - skinny.position(t[0]);
        QVERIFY(std::acos(a.normalized().dot(b.normalized())) > 179.0 * kPi / 180.0);

        const ConformalMap map = computeConformalMap(skinny, {});
        verifyMap(skinny, {}, map);
        QVERIFY(map.flips > 0);
        QCOMPARE(map.refusedFlips, 0);
        QVERIFY(map.triangles !=
                std::vector<Triangle>(skinny.triangles().begin(), skinny.triangles().end()));

        // Without flips the obtuse triangle stays, with a negative cotangent
        // weight; the map still converges or reports why it cannot.
        ConformalMapOptions noFlips;
        noFlips.intrinsicFlips = false;
        try {
            const ConformalMap plain = computeConformalMap(skinny, {}, noFlips);
            QCOMPARE(plain.flips, 0);
            qInfo("without flips: %d iterations, %d regularized Hessians, max angle error %.3g",
                  plain.newtonIterations, plain.regularizedSteps, plain.maxAngleError);
            QCOMPARE(plain.triangles,
                     std::vector<Triangle>(skinny.triangles().begin(), skinny.triangles().end()));
        } catch (const ConformalMapError& e) {
            qInfo("without flips: %s", e.what());
            QVERIFY(std::string(e.what()).find("conformal map") != std::string::npos);
        }
    }

    // Gauss-Bonnet forbids a flat closed sphere: the angle defects must sum
    // to 4*pi, and with no cone there is nowhere to put them.
    void impossibleMapsThrow() {
        const TriangleMesh sphere = makeSphere(1.0, 8).triangulate();
        try {
            computeConformalMap(sphere, {});
            QFAIL("a sphere without cones was accepted");
        } catch (const ConformalMapError& e) {
            const std::string what = e.what();
            QVERIFY2(what.find("Gauss-Bonnet") != std::string::npos, e.what());
            QVERIFY2(what.find("Euler characteristic 2") != std::string::npos, e.what());
        }
        const std::vector<Index> outOfRange = {sphere.vertexCount()};
        QVERIFY_THROWS_EXCEPTION(ConformalMapError, computeConformalMap(sphere, outOfRange));
        // Too few iterations: the error names the residual reached.
        ConformalMapOptions once;
        once.maxNewtonIterations = 1;
        const std::vector<Index> cones = cubeCornerCones(sphere);
        try {
            computeConformalMap(sphere, cones, once);
            QFAIL("one Newton step was reported as converged");
        } catch (const ConformalMapError& e) {
            QVERIFY2(std::string(e.what()).find("did not converge") != std::string::npos, e.what());
        }
    }

    // One or two cones on a sphere must absorb 4*pi of curvature, which
    // needs angle sums of at most 0 there: Newton's method cannot reach it
    // and the error says how far it got.
    void tooFewConesThrow() {
        const TriangleMesh sphere = makeSphere(1.0, 12).triangulate();
        for (const int n : {1, 2}) {
            const std::vector<Index> cones = cubeCornerCones(sphere);
            try {
                computeConformalMap(sphere, std::span(cones).first(n));
                QFAIL("a sphere with too few cones was accepted");
            } catch (const ConformalMapError& e) {
                QVERIFY2(std::string(e.what()).find("2*pi - angle sum") != std::string::npos,
                         e.what());
            }
        }
    }

    // A flat tetrahedron: the edge under the apex is not Delaunay, but its
    // flip would double the edge from the apex to the opposite base corner,
    // so it is refused and counted; all four vertices are cones.
    void doublingFlipsAreRefused() {
        const std::vector<Vec3> positions = {Vec3(0, 0, 0), Vec3(1, 0, 0),
                                             Vec3(0.5, std::sqrt(3.0) / 2.0, 0),
                                             Vec3(0.5, 0.02, 0.01)};
        const TriangleMesh tetrahedron(positions, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
        const std::vector<Index> cones = {0, 1, 2, 3};
        const ConformalMap map = computeConformalMap(tetrahedron, cones);
        verifyMap(tetrahedron, cones, map);
        QCOMPARE(map.flips, 0);
        QVERIFY(map.refusedFlips >= 1);
        QCOMPARE(map.newtonIterations, 0);
    }

    void cancellationIsChecked() {
        const TriangleMesh sphere = makeSphere(1.0, 8).triangulate();
        const std::vector<Index> cones = cubeCornerCones(sphere);
        int calls = 0;
        ConformalMapOptions options;
        options.checkCancelled = [&] {
            if (++calls == 2)
                throw std::runtime_error("cancelled");
        };
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, computeConformalMap(sphere, cones, options));
        QCOMPARE(calls, 2);
    }

    // The meshes of the paper's tables, with the paper's cone count spread
    // by farthest-point sampling; figures are printed for the record.
    void sharedMeshes_data() {
        QTest::addColumn<QString>("path");
        QTest::newRow("spot") << QStringLiteral(CONTOUR_SOURCE_DIR
                                                "/samples/spot_control_mesh.obj");
        QTest::newRow("bob") << QStringLiteral(CONTOUR_SOURCE_DIR "/samples/bob_controlmesh.obj");
        QTest::newRow("fertility") << QStringLiteral(CONTOUR_SHARED_DIR "/meshes/fertility.obj");
        QTest::newRow("killeroo") << QStringLiteral(CONTOUR_SHARED_DIR
                                                    "/meshes/killeroo_small.obj");
    }
    void sharedMeshes() {
        QFETCH(QString, path);
        const auto mesh = meshFile(path.toStdString());
        if (!mesh)
            QSKIP(qPrintable(path + " is absent"));
        const std::vector<Index> cones = farthestPointCones(*mesh, paperConeCount(*mesh));
        QElapsedTimer timer;
        timer.start();
        const ConformalMap map = computeConformalMap(*mesh, cones);
        const qint64 ms = timer.elapsed();
        verifyMap(*mesh, cones, map);
        qInfo("%s: %d vertices, %d faces, %zu cones: %d iterations, %d flips, max angle error "
              "%.3g, %lld ms",
              qPrintable(QFileInfo(path).baseName()), mesh->vertexCount(), mesh->faceCount(),
              cones.size(), map.newtonIterations, map.flips, map.maxAngleError,
              static_cast<long long>(ms));
    }
};

QTEST_GUILESS_MAIN(TestPsConformalMap)
#include "test_ps_conformal_map.moc"
