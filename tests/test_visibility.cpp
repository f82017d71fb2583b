// The visibility core: the ray caster, the image-space sweep, the
// view graph and QI propagation (tutorial ch. 4, app. B–C; Bénard 2014 §8)
// on procedural shapes with the mesh and consistent methods: a sphere is one
// visible loop; the far one of two spheres is cut by two T-junctions with a
// QI 2 arc behind the near one; a grazing torus has curtain folds and
// T-junctions; and over the 26-view protocol QI is never negative, concave
// contours are never visible and every chain's own ray test agrees with the
// propagated QI.
#include "ContourTestSupport.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"
#include "visibility/ImageIntersections.h"
#include "visibility/RayCaster.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <QtTest>
#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>
#include <random>

using namespace contour;
using namespace contour::testing;

namespace {

// The specification of imageIntersections (ImageIntersections.h), computed
// the slow way: every pair intersected with exact constructions.
ImageIntersectionResult bruteForceIntersections(const std::vector<ImageSegment>& segments,
                                                const std::function<bool(Index, Index)>& ignore) {
    using K = CGAL::Exact_predicates_exact_constructions_kernel;
    ImageIntersectionResult result;
    const size_t n = segments.size();
    std::vector<K::Segment_2> exact(n);
    std::vector<std::uint8_t> degenerate(n, 0);
    for (size_t i = 0; i < n; ++i) {
        exact[i] = {{segments[i].a.x(), segments[i].a.y()}, {segments[i].b.x(), segments[i].b.y()}};
        degenerate[i] = exact[i].is_degenerate();
        result.degenerateSegments += degenerate[i];
    }
    struct Meet {
        Index i, j;
        bool overlap;
        K::Point_2 point;
    };
    std::vector<Meet> meets;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            if (degenerate[i] || degenerate[j])
                continue;
            const auto x = CGAL::intersection(exact[i], exact[j]);
            if (!x)
                continue;
            if (const K::Point_2* p = boost::get<K::Point_2>(&*x))
                meets.push_back({Index(i), Index(j), false, *p});
            else
                meets.push_back({Index(i), Index(j), true, K::Point_2()});
        }
    std::vector<std::uint8_t> kept(n, ignore ? 0 : 1);
    for (const Meet& m : meets)
        if (ignore && !ignore(m.i, m.j))
            kept[m.i] = kept[m.j] = 1;
    for (size_t i = 0; i < n; ++i)
        result.sweptSegments += kept[i] && !degenerate[i];
    std::vector<Meet> points;
    for (const Meet& m : meets) {
        if (!kept[m.i] || !kept[m.j])
            continue;
        if (m.overlap)
            result.overlaps.emplace_back(m.i, m.j);
        else
            points.push_back(m);
    }
    std::sort(result.overlaps.begin(), result.overlaps.end());
    std::stable_sort(points.begin(), points.end(), [](const Meet& a, const Meet& b) {
        return CGAL::compare_xy(a.point, b.point) == CGAL::SMALLER;
    });
    for (size_t first = 0; first < points.size();) {
        size_t last = first;
        while (last < points.size() && points[last].point == points[first].point)
            ++last;
        std::vector<Index> ids;
        for (size_t k = first; k < last; ++k) {
            ids.push_back(points[k].i);
            ids.push_back(points[k].j);
        }
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        const K::Point_2& p = points[first].point;
        auto endpoint = [&](Index id) -> std::optional<Vec2> {
            if (p == exact[id].source())
                return segments[id].a;
            if (p == exact[id].target())
                return segments[id].b;
            return std::nullopt;
        };
        std::optional<Vec2> at;
        for (Index id : ids)
            if ((at = endpoint(id)))
                break;
        if (!at) {
            // The documented rounding: the first two segments' crossing in double.
            const ImageSegment &s = segments[ids[0]], &o = segments[ids[1]];
            const Vec2 d = s.b - s.a, e = o.b - o.a, w = o.a - s.a;
            const double den = d.x() * e.y() - d.y() * e.x();
            const double t =
                den != 0.0 ? std::clamp((w.x() * e.y() - w.y() * e.x()) / den, 0.0, 1.0) : 0.0;
            at = s.a + t * d;
        }
        std::vector<std::pair<Index, Index>> pairs;
        for (size_t k = first; k < last; ++k)
            pairs.emplace_back(points[k].i, points[k].j);
        std::sort(pairs.begin(), pairs.end());
        for (const auto& [i, j] : pairs) {
            ImageCrossing c;
            c.first = i;
            c.second = j;
            c.point = *at;
            c.interiorFirst = !endpoint(i);
            c.interiorSecond = !endpoint(j);
            result.crossings.push_back(c);
        }
        first = last;
    }
    return result;
}

} // namespace

namespace {

#ifdef __OPTIMIZE__
constexpr size_t kViewStride = 1;
#else
constexpr size_t kViewStride = 5;
#endif

// The method's defaults; the consistent method on the Catmull-Clark surface.
Overrides defaultsOf(const std::string& method) {
    return method == "consistent" ? Overrides{{"surface", "catmull-clark"}} : Overrides{};
}

Camera lookAt(const Vec3& eye, const Vec3& target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.up = Vec3(0, 1, 0);
    if (std::abs((eye - target).normalized().dot(c.up)) > 0.9)
        c.up = Vec3(0, 0, 1);
    c.viewport = Viewport{800, 600};
    return c;
}

long long nodesOf(const ViewGraph& g, ViewNodeType type) {
    return std::count_if(g.nodes.begin(), g.nodes.end(),
                         [&](const ViewNode& n) { return n.type == type; });
}

void verifyInvariants(const Snapshot& s) {
    for (const InvariantCheck& c : s.invariants)
        QVERIFY2(c.violations == 0,
                 qPrintable(QString::fromStdString(s.phaseName + ": " + c.name + " violated " +
                                                   std::to_string(c.violations) + "x, first " +
                                                   c.firstExample)));
}

// The facts every graph must satisfy whatever the method.
void verifyGraph(const ViewGraph& g, bool concaveHidden) {
    for (size_t i = 0; i < g.chains.size(); ++i) {
        const ViewChain& c = g.chains[i];
        QVERIFY2(c.qi >= 0, qPrintable(QString("chain %1 has QI %2").arg(i).arg(c.qi)));
        QVERIFY(c.decidedBy != VisibilityRule::Unknown);
        if (concaveHidden && c.type == CurveType::Contour && c.concave)
            QVERIFY2(!c.visible(), qPrintable(QString("concave chain %1 is visible").arg(i)));
        QCOMPARE(c.image.size(), c.points.size());
        QCOMPARE(c.segmentElement.size(), c.segmentCount());
    }
}

} // namespace

class TestVisibility : public QObject {
    Q_OBJECT

private slots:
    // Ray casting counts every face on the open segment to the camera, once.
    void rayCaster_data() {
        QTest::addColumn<bool>("orthographic");
        QTest::newRow("perspective") << false;
        QTest::newRow("orthographic") << true;
    }
    void rayCaster() {
        QFETCH(bool, orthographic);
        const Snapshot input = makeInputSnapshot(shape("sphere", 16));
        const RayCaster rays(*input.mesh);
        Camera camera = lookAt(Vec3(0.1, 0.2, 5), Vec3::Zero());
        if (orthographic)
            camera.projection = Projection::Orthographic;
        QCOMPARE(rays.occluders(Vec3(0, 0, 0), camera, {}), 1);
        QCOMPARE(rays.occluders(Vec3(0.05, -0.02, -3), camera, {}), 2);
        QCOMPARE(rays.occluders(Vec3(0.05, 0.03, 3), camera, {}), 0);
        // Ignored faces are not counted, and the faces hit are returned.
        std::vector<Index> hits;
        QCOMPARE(rays.occluders(Vec3(0.05, -0.02, -3), camera, {}, &hits), 2);
        QCOMPARE(rays.occluders(Vec3(0.05, -0.02, -3), camera, std::span<const Index>(hits)), 0);
        QCOMPARE(
            rays.occluders(Vec3(0.05, -0.02, -3), camera, std::span<const Index>(hits.data(), 1)),
            1);
    }

    // The CGAL sweep: a crossing, a touch at an endpoint, shared endpoints,
    // a collinear overlap and a degenerate segment.
    void imageSweep() {
        const std::vector<ImageSegment> segments = {
            {Vec2(0, 0), Vec2(10, 10)},   // 0
            {Vec2(0, 10), Vec2(10, 0)},   // 1: crosses 0 at (5, 5)
            {Vec2(10, 10), Vec2(20, 10)}, // 2: shares 0's endpoint
            {Vec2(15, 0), Vec2(15, 10)},  // 3: touches 2 inside it with its endpoint
            {Vec2(30, 0), Vec2(40, 0)},   // 4
            {Vec2(35, 0), Vec2(45, 0)},   // 5: overlaps 4
            {Vec2(50, 50), Vec2(50, 50)}, // 6: degenerate
        };
        const ImageIntersectionResult r = imageIntersections(segments);
        QCOMPARE(r.degenerateSegments, 1LL);
        QCOMPARE(r.overlaps.size(), size_t(1));
        QCOMPARE(r.overlaps[0], std::make_pair(Index(4), Index(5)));
        int interior = 0, touches = 0, shared = 0;
        for (const ImageCrossing& c : r.crossings) {
            if (c.interiorFirst && c.interiorSecond) {
                ++interior;
                QCOMPARE(c.first, Index(0));
                QCOMPARE(c.second, Index(1));
                QVERIFY((c.point - Vec2(5, 5)).norm() < 1e-12);
            } else if (c.interiorFirst != c.interiorSecond) {
                ++touches;
                QCOMPARE(c.first, Index(2));
                QCOMPARE(c.second, Index(3));
            } else {
                ++shared;
            }
        }
        QCOMPARE(interior, 1);
        QCOMPARE(touches, 1);
        QCOMPARE(shared, 1); // 0 and 2 at (10, 10)
    }

    // imageIntersections against a brute-force reference with CGAL's exact
    // constructions (every pair intersected, meeting points compared
    // exactly), on segments on a small integer grid (shared endpoints,
    // endpoints inside other segments, collinear overlaps, several segments
    // through one point, degenerate ones) and general ones, with and without
    // ignored pairs: same crossings, same order, same points and overlaps.
    void imageIntersectionsMatchBruteForce() {
        std::mt19937 random(5);
        for (int trial = 0; trial < 24; ++trial) {
            const bool grid = trial % 2 == 0;
            std::uniform_int_distribution<int> cell(0, 12);
            std::uniform_real_distribution<double> real(0.0, 12.0);
            std::vector<ImageSegment> segments;
            for (int k = 0; k < 150; ++k) {
                auto coordinate = [&] {
                    return grid ? double(cell(random)) : real(random);
                };
                const Vec2 a(coordinate(), coordinate());
                // Short segments (as along a curve), a few long ones.
                const double reach = k % 10 == 0 ? 12.0 : 3.0;
                Vec2 d(reach * (real(random) / 6.0 - 1.0), reach * (real(random) / 6.0 - 1.0));
                if (grid)
                    d = Vec2(std::round(d.x()), std::round(d.y()));
                segments.push_back({a, a + d});
            }
            // Three segments through one point inside all of them.
            segments.push_back({Vec2(0.5, 0.5), Vec2(2.5, 2.5)});
            segments.push_back({Vec2(0.5, 2.5), Vec2(2.5, 0.5)});
            segments.push_back({Vec2(1.5, 0.25), Vec2(1.5, 2.75)});
            for (const bool ignoring : {false, true}) {
                std::function<bool(Index, Index)> ignore;
                if (ignoring)
                    ignore = [](Index i, Index j) {
                        return (i + j) % 3 == 0;
                    };
                const ImageIntersectionResult fast = imageIntersections(segments, ignore);
                const ImageIntersectionResult slow = bruteForceIntersections(segments, ignore);
                QCOMPARE(fast.degenerateSegments, slow.degenerateSegments);
                QCOMPARE(fast.sweptSegments, slow.sweptSegments);
                QCOMPARE(fast.overlaps, slow.overlaps);
                QCOMPARE(fast.crossings.size(), slow.crossings.size());
                for (size_t i = 0; i < fast.crossings.size(); ++i) {
                    const ImageCrossing &x = fast.crossings[i], &y = slow.crossings[i];
                    QCOMPARE(x.first, y.first);
                    QCOMPARE(x.second, y.second);
                    QCOMPARE(x.interiorFirst, y.interiorFirst);
                    QCOMPARE(x.interiorSecond, y.interiorSecond);
                    QVERIFY(x.point == y.point);
                }
                if (grid && !ignoring)
                    QVERIFY(!slow.overlaps.empty());
                QVERIFY(slow.crossings.size() > 50);
            }
        }
    }

    // A sphere: one closed visible contour loop, no curtain fold, QI 0.
    void sphere_data() {
        QTest::addColumn<QString>("method");
        QTest::newRow("mesh") << "mesh";
        QTest::newRow("consistent") << "consistent";
    }
    void sphere() {
        QFETCH(QString, method);
        const auto cage = shape("sphere", 16);
        const MethodRun r =
            run(method.toStdString(), cage, lookAt(Vec3(0.3, 0.8, 4.5), Vec3::Zero()),
                defaultsOf(method.toStdString()));
        const Snapshot& s = r.phase("visibility");
        verifyInvariants(s);
        QVERIFY(s.viewGraph);
        const ViewGraph& g = *s.viewGraph;
        verifyGraph(g, method == "mesh");
        QCOMPARE(nodesOf(g, ViewNodeType::CurtainFold), 0LL);
        QCOMPARE(nodesOf(g, ViewNodeType::ImageIntersection), 0LL);
        QCOMPARE(g.chains.size(), size_t(1));
        QVERIFY(g.chains[0].closed);
        QCOMPARE(g.chains[0].qi, 0);
        QVERIFY(g.chains[0].visible());
        QCOMPARE(g.conflicts.size(), size_t(0));
        QVERIFY(g.hiddenLengthPixels() == 0.0);
        QVERIFY(g.visibleLengthPixels() > 100.0);
    }

    // Two unit spheres, the far one partly behind the near one: its contour
    // is cut by two T-junctions, and the arc behind the near sphere has QI 2
    // (tutorial §4.7: +2 behind a contour). Nothing of the near one hides.
    void twoSpheres_data() {
        QTest::addColumn<QString>("method");
        QTest::newRow("mesh") << "mesh";
        QTest::newRow("consistent") << "consistent";
    }
    void twoSpheres() {
        QFETCH(QString, method);
        const auto cage = shape("two-spheres", 16);
        const MethodRun r =
            run(method.toStdString(), cage, lookAt(Vec3(2, 0.2, 8), Vec3(0, 0, -1.5)),
                defaultsOf(method.toStdString()));
        const Snapshot& s = r.phase("visibility");
        verifyInvariants(s);
        const ViewGraph& g = *s.viewGraph;
        verifyGraph(g, method == "mesh");
        QCOMPARE(nodesOf(g, ViewNodeType::ImageIntersection), 2LL);
        int hidden = 0, visibleFar = 0, visibleNear = 0;
        for (const ViewChain& c : g.chains) {
            const bool far = c.points.front().z() < -1.5;
            for (const Vec3& p : c.points)
                QCOMPARE(p.z() < -1.5, far); // a chain stays on one sphere
            if (!c.visible()) {
                ++hidden;
                QVERIFY2(far, "a hidden chain on the near sphere");
                QCOMPARE(c.qi, 2);
            } else {
                (far ? visibleFar : visibleNear)++;
            }
        }
        QCOMPARE(hidden, 1);
        QVERIFY(visibleFar >= 1);
        QCOMPARE(visibleNear, 2); // the near loop is cut at both T-junctions too
        for (const ViewNode& n : g.nodes) {
            if (n.type != ViewNodeType::ImageIntersection)
                continue;
            QCOMPARE(n.qiStep, 2);
            QVERIFY(n.position.z() < -1.5 && n.nearPoint.z() > -1.5);
            QCOMPARE(g.chains[n.farChains[1]].qi, 2);
            QCOMPARE(g.chains[n.farChains[0]].qi, 0);
        }
        QCOMPARE(s.counter(counters::kRayCheckConflicts), 0.0);
    }

    // A torus seen from a grazing angle: the inner contour folds (curtain
    // folds, tutorial §4.3 item 3) and crosses the outer one (T-junctions).
    void grazingTorus_data() {
        QTest::addColumn<QString>("method");
        QTest::newRow("mesh") << "mesh";
        QTest::newRow("consistent") << "consistent";
    }
    void grazingTorus() {
        QFETCH(QString, method);
        const auto cage = shape("torus", 24);
        const MethodRun r = run(method.toStdString(), cage, lookAt(Vec3(6, 1, 1.4), Vec3::Zero()),
                                defaultsOf(method.toStdString()));
        const Snapshot& s = r.phase("visibility");
        verifyInvariants(s);
        const ViewGraph& g = *s.viewGraph;
        verifyGraph(g, method == "mesh");
        qInfo("%s grazing torus: %lld curtain folds, %lld T-junctions, %zu chains, %g conflicts",
              qPrintable(method), nodesOf(g, ViewNodeType::CurtainFold),
              nodesOf(g, ViewNodeType::ImageIntersection), g.chains.size(),
              s.counter(counters::kRayCheckConflicts));
        if (method == "mesh") {
            // The polygonal torus's own contour crosses itself.
            QVERIFY(nodesOf(g, ViewNodeType::ImageIntersection) >= 2);
        } else {
            // The smooth surface's contour from here does not cross itself
            // in the image (the dense ground truth at N = 64 and 128: 2
            // loops, 4 cusps, 0 crossings); the consistent mesh's view graph
            // must have as many T-junctions. With the paper's single §6.4
            // flips (optimization-flip-pairs off) it had 4, in two pairs
            // near the hole's cusps.
            const DenseGroundTruth dense(
                cachedSmoothSurface(cage, SurfaceKind::CatmullClark).surface, {64, 4});
            const Camera camera = lookAt(Vec3(6, 1, 1.4), Vec3::Zero());
            QCOMPARE(nodesOf(g, ViewNodeType::ImageIntersection),
                     static_cast<long long>(imageCrossings(dense.compute(camera), camera)));
        }
        QCOMPARE(s.counter(counters::kRayCheckConflicts), 0.0);
        // Curtain folds where the one-ring occludes one side (tutorial
        // §4.7). The consistent mesh's near-face test (Bénard 2014 fn. 3)
        // also flags vertices where neither side is occluded: those carry
        // QI unchanged (step 0) and are counted, not required.
        int stepping = 0;
        for (const ViewNode& n : g.nodes) {
            if (n.type != ViewNodeType::CurtainFold)
                continue;
            if (method == "mesh")
                QVERIFY(n.qiStep >= 1);
            if (n.qiStep >= 1) {
                ++stepping;
                if (method == "mesh")
                    QCOMPARE(g.chains[n.farChains[1]].qi, g.chains[n.nearChains[0]].qi + n.qiStep);
            }
        }
        QVERIFY(stepping >= 2);
    }

    // Over the 26-view protocol: QI never negative, concave contours never
    // visible (mesh contours), and zero conflicts between propagation and
    // every chain's own ray test.
    void protocol_data() {
        QTest::addColumn<QString>("method");
        QTest::addColumn<QString>("shapeName");
        QTest::addColumn<int>("resolution");
        for (const char* method : {"mesh", "consistent"}) {
            const bool mesh = std::string(method) == "mesh";
            QTest::newRow((std::string(method) + " sphere").c_str())
                << method << "sphere" << (mesh ? 24 : 8);
            QTest::newRow((std::string(method) + " ellipsoid").c_str())
                << method << "ellipsoid" << (mesh ? 24 : 8);
            QTest::newRow((std::string(method) + " torus").c_str())
                << method << "torus" << (mesh ? 32 : 12);
            QTest::newRow((std::string(method) + " bumpy-torus").c_str())
                << method << "bumpy-torus" << (mesh ? 48 : 16);
        }
    }
    void protocol() {
        QFETCH(QString, method);
        QFETCH(QString, shapeName);
        QFETCH(int, resolution);
        const auto cage = shape(shapeName.toStdString(), resolution);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        double conflicts = 0, seconds = 0, rays = 0, tJunctions = 0, folds = 0, below = 0;
        int runs = 0;
        for (size_t v = 0; v < views.size(); v += kViewStride) {
            const MethodRun r =
                run(method.toStdString(), cage, views[v], defaultsOf(method.toStdString()));
            const Snapshot& s = r.phase("visibility");
            verifyInvariants(s);
            verifyGraph(*s.viewGraph, method == "mesh");
            if (s.counter(counters::kRayCheckConflicts) != 0.0) {
                for (const VisibilityConflict& c : s.viewGraph->conflicts)
                    qWarning("view %zu: chain %d propagated %d ray %d (%s)", v, c.chain,
                             c.propagatedQi, c.rayQi, c.reason.c_str());
            }
            conflicts += s.counter(counters::kRayCheckConflicts);
            below += s.counter(counters::kChainsPropagatedBelowTheirBound);
            seconds += s.counter(counters::kVisibilitySeconds);
            rays += s.counter(counters::kRayTests);
            tJunctions += s.counter(counters::kTJunctions);
            folds += s.counter(counters::kCurtainFolds);
            ++runs;
        }
        qInfo("%s %s: %d views, %g ray-check conflicts, %g below bound, %.1f ms and %.0f rays "
              "per view, %.1f T-junctions and %.1f curtain folds per view",
              qPrintable(method), qPrintable(shapeName), runs, conflicts, below,
              1000.0 * seconds / runs, rays / runs, tJunctions / runs, folds / runs);
        QCOMPARE(conflicts, 0.0);
        QCOMPARE(below, 0.0);
    }

    // The parameter turns the phase into a pass-through that says so.
    void visibilityOff() {
        const MethodRun r = run("mesh", shape("sphere", 12), lookAt(Vec3(0, 1, 5), Vec3::Zero()),
                                {{"visibility", false}});
        const Snapshot& s = r.phase("visibility");
        QVERIFY(!s.viewGraph);
        QVERIFY(!s.notes.empty());
        QCOMPARE(s.curves->size(), r.phase("chaining").curves->size());
    }
};

QTEST_GUILESS_MAIN(TestVisibility)
#include "test_visibility.moc"
