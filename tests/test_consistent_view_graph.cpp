// The consistent method's view graph has the smooth surface's topology
// (Bénard 2014 §8 on the consistent mesh of §6): its curtain folds are the
// surface's cusps and its T-junctions the smooth contour's image crossings,
// both counted by reference/DenseGroundTruth (a lattice of the same surface that
// shares no contour code). Shapes made here, on views from a fixed seed: a
// torus-knot tube (long, thin, with many cusps and crossings) and a sphere
// with random bumps; plus spot and bob on a few protocol views (there, a few
// views still differ: floors in tests/baselines). Views where
// the oracle itself is not settled (its counts change between N and N/2,
// e.g. a cusp pair closer than its lattice step) are skipped and counted.
// On views without an inconsistent face, every fold is at a cusp vertex and
// no visibility conflict remains.
#include "ContourTestSupport.h"
#include "pipeline/FieldNames.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QtTest>
#include <cmath>
#include <map>
#include <random>

using namespace contour;
using namespace contour::testing;

namespace {

// A closed quad tube of `sides` around the (p, q) torus knot, `rings` rings
// along it, faces counter-clockwise seen from outside (normals outward).
std::shared_ptr<const PolygonMesh> torusKnotTube(int p, int q, int rings, int sides,
                                                 double radius) {
    const auto centre = [&](double t) {
        const double r = 2.0 + std::cos(q * t);
        return Vec3(r * std::cos(p * t), r * std::sin(p * t), -std::sin(q * t));
    };
    PolygonMesh mesh;
    for (int i = 0; i < rings; ++i) {
        const double t = 2.0 * M_PI * i / rings, h = 1e-4;
        const Vec3 c = centre(t);
        const Vec3 tangent = (centre(t + h) - centre(t - h)).normalized();
        // A frame from the curve's acceleration (the knot has no inflection).
        const Vec3 acceleration = centre(t + h) - 2.0 * c + centre(t - h);
        const Vec3 normal = (acceleration - acceleration.dot(tangent) * tangent).normalized();
        const Vec3 binormal = tangent.cross(normal);
        for (int j = 0; j < sides; ++j) {
            const double a = 2.0 * M_PI * j / sides;
            mesh.positions.push_back(c + radius * (std::cos(a) * normal + std::sin(a) * binormal));
        }
    }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j) {
            const int i1 = (i + 1) % rings, j1 = (j + 1) % sides;
            mesh.addFace({i * sides + j, i1 * sides + j, i1 * sides + j1, i * sides + j1});
        }
    return std::make_shared<const PolygonMesh>(std::move(mesh));
}

// makeSphere's cage with every vertex moved along its radius by up to
// ±amplitude, from a fixed seed.
std::shared_ptr<const PolygonMesh> bumpySphere(int resolution, double amplitude, unsigned seed) {
    PolygonMesh mesh = makeSphere(1.0, resolution);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> bump(-amplitude, amplitude);
    for (Vec3& p : mesh.positions)
        p *= 1.0 + bump(rng);
    return std::make_shared<const PolygonMesh>(std::move(mesh));
}

struct Counts {
    int folds = 0, foldsAtCusps = 0, tJunctions = 0, smallLoopJunctions = 0;
};

// Curtain folds, those at cusp vertices, and T-junctions where a contour
// passes in front of a contour (the oracle counts the contour's crossings
// with itself only), those of sub-pixel loops apart.
Counts countGraph(const Snapshot& s) {
    Counts c;
    const ViewGraph& g = *s.viewGraph;
    const auto contour = [&](Index chain) {
        return chain != kInvalidIndex && g.chains[chain].type == CurveType::Contour;
    };
    for (const ViewNode& n : g.nodes) {
        if (n.type == ViewNodeType::CurtainFold) {
            ++c.folds;
            c.foldsAtCusps += n.smoothCusp || n.singularCusp;
        } else if (n.type == ViewNodeType::ImageIntersection) {
            const bool contours = (contour(n.nearChains[0]) || contour(n.nearChains[1])) &&
                                  (contour(n.farChains[0]) || contour(n.farChains[1]));
            c.tJunctions += contours && !n.smallLoop;
            c.smallLoopJunctions += contours && n.smallLoop;
        }
    }
    return c;
}

std::vector<Camera> randomViews(const BoundingBox& box, int count, unsigned seed) {
    std::vector<Camera> all = protocolViews(box, count, seed);
    return {all.end() - count, all.end()};
}

} // namespace

class TestConsistentViewGraph : public QObject {
    Q_OBJECT

    // Per view: folds = oracle cusps, T-junctions = oracle crossings, every
    // fold at a cusp vertex when no face is inconsistent; `minimumSettled`
    // views must be judged.
    // With a baseline name, the matching views must reach the floors of
    // tests/baselines/test_consistent_view_graph.json instead of every
    // settled view.
    void compareViews(const std::shared_ptr<const PolygonMesh>& cage,
                      const std::vector<Camera>& views, int samples, int minimumSettled,
                      const std::string& floors = {}) {
        const auto surface = cachedSmoothSurface(cage, automaticSurfaceKind(*cage)).surface;
        const DenseGroundTruth truth(surface, {samples, 4});
        const DenseGroundTruth half(surface, {samples / 2, 4});
        int settled = 0, foldsMatch = 0, tMatch = 0;
        // Both sides leave out crossings of sub-pixel loops by the same rule
        // (core/SmallLoopCrossings.h).
        const double minLoop = ParameterSet::defaults(findMethod("consistent")->parameters)
                                   .getDouble("t-junction-min-loop");
        for (size_t v = 0; v < views.size(); ++v) {
            const Snapshot s = runMethod("consistent", cage, views[v], {});
            QVERIFY(s.viewGraph);
            const Counts c = countGraph(s);
            const GroundTruth t = truth.compute(views[v]);
            const GroundTruth h = half.compute(views[v]);
            const int cusps = static_cast<int>(t.cusps.size());
            const int crossings = imageCrossings(t, views[v], minLoop);
            const bool isSettled = cusps == static_cast<int>(h.cusps.size()) &&
                                   crossings == imageCrossings(h, views[v], minLoop);
            // On a consistent mesh every fold is a cusp and propagation
            // agrees with every ray: no visibility conflict (§8.4 puts the
            // ambiguity next to inconsistent faces).
            if (s.counter(counters::kInconsistentFaces) == 0.0) {
                QCOMPARE(c.foldsAtCusps, c.folds);
                QCOMPARE(s.viewGraph->conflicts.size(), size_t(0));
            }
            qInfo("view %zu: folds %d (at cusps %d) / oracle cusps %d, T-junctions %d (and %d in "
                  "sub-pixel loops) / oracle crossings %d%s",
                  v, c.folds, c.foldsAtCusps, cusps, c.tJunctions, c.smallLoopJunctions, crossings,
                  isSettled ? "" : " (oracle not settled: skipped)");
            if (!isSettled)
                continue;
            ++settled;
            foldsMatch += c.folds == cusps;
            tMatch += c.tJunctions == crossings;
        }
        qInfo("%d of %zu views settled; folds = cusps on %d, T-junctions = crossings on %d",
              settled, views.size(), foldsMatch, tMatch);
        QVERIFY(settled >= minimumSettled);
        if (floors.empty()) {
            QCOMPARE(foldsMatch, settled);
            QCOMPARE(tMatch, settled);
        } else {
            const std::string file = "test_consistent_view_graph";
            QVERIFY(foldsMatch >= baseline(file, floors + ": views with folds = cusps"));
            QVERIFY(tMatch >= baseline(file, floors + ": views with T-junctions = crossings"));
        }
    }

private slots:
    void torusKnot() {
        const auto cage = torusKnotTube(2, 3, 48, 6, 0.45);
        compareViews(cage, randomViews(cage->boundingBox(), 6, 7), 48, 4);
    }

    void bumpySphere() {
        const auto cage = ::bumpySphere(8, 0.3, 11);
        compareViews(cage, randomViews(cage->boundingBox(), 6, 13), 48, 4, "bumpy sphere");
    }

    void spotAndBob_data() {
        QTest::addColumn<QString>("name");
        QTest::newRow("spot") << "spot";
        QTest::newRow("bob") << "bob";
    }
    void spotAndBob() {
        QFETCH(QString, name);
        const auto cage = sampleOrShape(name.toStdString(), 0);
        std::vector<Camera> views;
        const std::vector<Camera> all = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        for (size_t v = 0; v < all.size(); v += 5)
            views.push_back(all[v]);
        compareViews(cage, views, 64, 4, name.toStdString());
    }

    // pawn's neck, seen from the protocol's views 1, 4, 7, ...: the contour
    // makes a swallowtail (two cusps, one crossing) whose tip leaves a face
    // through the edge opposite its odd corner and comes back, so that edge
    // crosses g = 0 twice between two of the initialization's samples.
    // Cusp detection splits it (§6.1's sign-crossing split) and finds the
    // cusp beyond it; without the split the cusp was lost and propagation
    // was one off on every chain of the drawing (25 conflicts per view).
    void doubleCrossingOfAnEdge() {
        const auto cage = sharedMesh("pawn");
        if (!cage)
            QSKIP("../shared/meshes/pawn.obj is absent");
        const std::vector<Camera> all = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        const MethodRun detection = run("consistent", cage, all[1], {}, "cusp-detection");
        QVERIFY(detection.last().counter(counters::kCuspDoubleCrossingSplits) > 0.0);
        compareViews(cage, {all[1], all[4], all[7], all[10]}, 64, 4);
    }

    // pig's tail: its cage pinches the limit surface (f_u and f_v nearly
    // parallel, principal curvature radii near 1e-12 of the scene), and
    // κr flips sign there in every view, so §6.2 d puts a cusp vertex there.
    // The surface has no smooth fold there: rays on both branches see the
    // same QI. The fold is stepped by the one-ring test (no step), not by
    // one sheet; one sheet gave 2 conflicts on each of these views.
    void singularPointsOfTheSurface() {
        const auto cage = sharedMesh("pig_quad_controlmesh");
        if (!cage)
            QSKIP("../shared/meshes/pig_quad_controlmesh.obj is absent");
        const std::vector<Camera> all = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        for (const int v : {0, 14, 25}) {
            const Snapshot s = runMethod("consistent", cage, all[static_cast<size_t>(v)], {});
            QVERIFY(s.viewGraph);
            QCOMPARE(s.counter(counters::kInconsistentFaces), 0.0);
            const auto& singular = *s.field(fields::kSingularCusp)->labels();
            const auto& cusp = *s.field(fields::kCusp)->labels();
            int singularNodes = 0;
            for (const ViewNode& n : s.viewGraph->nodes) {
                if (!n.singularCusp)
                    continue;
                ++singularNodes;
                QVERIFY(!n.smoothCusp);
                QCOMPARE(n.type, ViewNodeType::CurtainFold);
                QVERIFY(cusp[static_cast<size_t>(n.meshVertex)] != 0);
                QVERIFY(singular[static_cast<size_t>(n.meshVertex)] != 0);
                QCOMPARE(n.localOccluders.size(), size_t(2));
                QCOMPARE(n.qiStep, std::abs(n.localOccluders[1] - n.localOccluders[0]));
            }
            qInfo("pig view %d: %d curtain folds at singular points, %zu conflicts", v,
                  singularNodes, s.viewGraph->conflicts.size());
            QVERIFY(singularNodes > 0);
            QCOMPARE(s.counter(counters::kCurtainFoldsAtSingularPoints),
                     static_cast<double>(singularNodes));
            QCOMPARE(s.viewGraph->conflicts.size(), size_t(0));
        }
    }

    // A wrong propagation step repeats itself on every chain downstream; the
    // root conflicts are those whose source chain passed its own ray check.
    // pig view 4 keeps 20 conflicts (no face is inconsistent there): each
    // non-root ray check comes from a chain that is itself in conflict, and
    // following the sources from any of them reaches a root.
    void conflictRoots() {
        const auto cage = sharedMesh("pig_quad_controlmesh");
        if (!cage)
            QSKIP("../shared/meshes/pig_quad_controlmesh.obj is absent");
        const Camera camera = Camera::views26(cage->boundingBox(), Viewport{800, 600})[4];
        const Snapshot s = runMethod("consistent", cage, camera, {});
        QVERIFY(s.viewGraph);
        const ViewGraph& g = *s.viewGraph;
        std::map<Index, const VisibilityConflict*> rayCheck;
        int roots = 0;
        for (const VisibilityConflict& k : g.conflicts)
            if (k.reason.rfind("ray-check", 0) == 0) {
                rayCheck[k.chain] = &k;
                roots += k.root;
            } else {
                QVERIFY(!k.root);
            }
        qInfo("pig view 4: %zu conflicts, %zu ray checks, %d roots", g.conflicts.size(),
              rayCheck.size(), roots);
        QVERIFY(roots > 0);
        QCOMPARE(s.counter(counters::kRootRayCheckConflicts), static_cast<double>(roots));
        for (const auto& [chain, k] : rayCheck) {
            QCOMPARE(k->root, k->fromChain == kInvalidIndex || !g.chains[k->fromChain].conflict);
            const VisibilityConflict* at = k;
            for (size_t steps = 0; !at->root; ++steps) {
                QVERIFY(steps < g.chains.size());
                const auto up = rayCheck.find(at->fromChain);
                if (up == rayCheck.end())
                    break; // the source's conflict is a bound, not a ray check
                at = up->second;
            }
        }
    }

    // The near-face test of §8.1 at every contour vertex (the switch off)
    // makes curtain folds at zig-zags of the polyline: more folds than cusps.
    void nearFaceEverywhereOverCounts() {
        const auto cage = sampleOrShape("spot", 0);
        const Camera camera = Camera::views26(cage->boundingBox(), Viewport{800, 600})[0];
        const Snapshot on = runMethod("consistent", cage, camera, {});
        const Snapshot off =
            runMethod("consistent", cage, camera, {{"curtain-folds-from-cusps", false}});
        const Counts a = countGraph(on), b = countGraph(off);
        qInfo("spot view 0: %d folds from cusps, %d by the near-face test everywhere", a.folds,
              b.folds);
        QCOMPARE(a.folds, static_cast<int>(on.counter(counters::kCusps)));
        QVERIFY(b.folds > a.folds);
        QCOMPARE(b.foldsAtCusps, 0);
    }
};

QTEST_GUILESS_MAIN(TestConsistentViewGraph)
#include "test_consistent_view_graph.moc"
