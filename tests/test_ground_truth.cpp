// The dense ground truth of the smooth contour's topology (DenseGroundTruth.h,
// an answer independent of the methods): first its own sanity on shapes
// whose answer is known analytically, then the interpolated and consistent
// methods on Catmull-Clark surfaces compared with it, view by view. The
// floors and ceilings asserted are in tests/baselines/test_ground_truth.json.
#include "ContourTestSupport.h"
#include "camera/Facing.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QtTest>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

using namespace contour;
using namespace contour::testing;

namespace {

std::shared_ptr<const SmoothSurface> catmullClark(const std::shared_ptr<const PolygonMesh>& cage) {
    // Through the cache, so that the method's surface phase sees the very same
    // surface (and domain face numbering) as the ground truth.
    return cachedSmoothSurface(cage, SurfaceKind::CatmullClark).surface;
}

Camera lookingFrom(const BoundingBox& box, const Vec3& direction) {
    return Camera::framing(box, direction, Viewport{800, 600});
}

std::shared_ptr<const PolygonMesh> sampleCage(const std::string& name) {
    const std::string path = std::string(CONTOUR_SOURCE_DIR) + "/samples/" + name;
    return std::make_shared<const PolygonMesh>(readMesh(path));
}

std::shared_ptr<const PolygonMesh> spotCage() {
    return sampleCage("spot_control_mesh.obj");
}

// The cage of a comparison row: a sample by name (spot, bob), else a
// procedural shape at `resolution`.
std::shared_ptr<const PolygonMesh> comparisonCage(const QString& name, int resolution) {
    return name == "spot"  ? spotCage()
           : name == "bob" ? sampleCage("bob_controlmesh.obj")
                           : shape(name.toStdString(), resolution);
}

// Pairs of the method's cusps closer to each other than the ground truth's
// lattice step next to them (the longest of the three lattice segments of
// its contour around the one nearest to the pair), with no ground-truth cusp
// within that step: DenseGroundTruth.h says a cusp pair closer than one
// lattice step "can cancel out". Spot views 3 and 20: a pair 3.9e-5 of the
// diagonal apart (0.03 px) beside an extraordinary vertex, one a root of κr
// inside domain face 216 (a lattice 400 times finer over that corner of the
// face follows κr along the contour from +1.05 through 0 to -0.57 at the
// face's edge), the other a jump of κr over 0 (-0.57 | +0.13) across that
// edge, where the evaluator's patches meet. Both are sign changes of κr
// along the contour, as DenseGroundTruth defines cusps, but inside one of
// its lattice segments. Counted apart; the raw cusp counts stay as measured.
int subLatticeCuspPairs(const GroundTruth& truth, const Snapshot& snapshot) {
    const Field* field = snapshot.field(fields::kCusp);
    if (!field || !field->labels())
        return 0;
    std::vector<Vec3> cusps;
    for (Index v = 0; v < snapshot.mesh->vertexCount(); ++v)
        if ((*field->labels())[static_cast<size_t>(v)])
            cusps.push_back(snapshot.mesh->position(v));
    // The lattice step of the ground truth's contour next to p.
    const auto step = [&](const Vec3& p) {
        double best = std::numeric_limits<double>::infinity(), length = 0.0;
        for (const GroundTruthLoop& loop : truth.loops) {
            const size_t n = loop.points.size();
            if (n < 2)
                continue;
            for (size_t k = 0; k + (loop.closed ? 0 : 1) < n; ++k) {
                const Vec3 a = loop.points[k], ab = loop.points[(k + 1) % n] - a;
                const double t = ab.squaredNorm() > 0.0
                                     ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                                     : 0.0;
                const double d = (a + t * ab - p).norm();
                if (d >= best)
                    continue;
                best = d;
                length = 0.0;
                for (const size_t j : {(k + n - 1) % n, k, (k + 1) % n})
                    length = std::max(length, (loop.points[(j + 1) % n] - loop.points[j]).norm());
            }
        }
        return length;
    };
    // No step is longer than the longest lattice segment: farther pairs are
    // skipped without the search above (it is slow in unoptimized builds).
    double longest = 0.0;
    for (const GroundTruthLoop& loop : truth.loops) {
        const size_t n = loop.points.size();
        for (size_t k = 0; k + (loop.closed ? 0 : 1) < n; ++k)
            longest = std::max(longest, (loop.points[(k + 1) % n] - loop.points[k]).norm());
    }
    std::vector<char> used(cusps.size(), 0);
    int pairs = 0;
    for (size_t i = 0; i < cusps.size(); ++i)
        for (size_t j = i + 1; j < cusps.size() && !used[i]; ++j) {
            if (used[j] || (cusps[i] - cusps[j]).norm() >= longest)
                continue;
            const Vec3 mid = 0.5 * (cusps[i] + cusps[j]);
            const double h = step(mid);
            if ((cusps[i] - cusps[j]).norm() >= h)
                continue;
            bool seen = false;
            for (const GroundTruthCusp& c : truth.cusps)
                seen = seen || (c.position - mid).norm() < h;
            if (seen)
                continue;
            used[i] = used[j] = 1;
            ++pairs;
        }
    return pairs;
}

} // namespace

class TestGroundTruth : public QObject {
    Q_OBJECT

private slots:
    void sphereHasOneLoopAndNoCusp();
    void ellipsoidHasOneLoop();
    void torusFromAboveHasTwoLoopsAndNoCusp();
    void torusFromTheSideHasTwoLoopsAndCusps();
    void sharedEdgesCloseLoops();
    void interpolatedAgainstGroundTruth_data();
    void interpolatedAgainstGroundTruth();
    void consistentAgainstGroundTruth_data();
    void consistentAgainstGroundTruth();
    void contourRefinementFollowsTheCurve();
    void crossingsAgainstGroundTruth_data();
    void crossingsAgainstGroundTruth();
    void timingOnSpot();
};

void TestGroundTruth::sphereHasOneLoopAndNoCusp() {
    const auto cage = shape("sphere", 16);
    const DenseGroundTruth dense(catmullClark(cage));
    for (const Camera& camera : Camera::views26(cage->boundingBox(), Viewport{800, 600})) {
        const GroundTruth truth = dense.compute(camera);
        QCOMPARE(int(truth.loops.size()), 1);
        QCOMPARE(truth.closedLoops(), 1);
        QCOMPARE(int(truth.cusps.size()), 0);
    }
    // Random views: still one loop, but the Catmull-Clark limit surface of
    // this cage is not convex everywhere. Around the valence-16 extraordinary
    // vertices at the poles it has a ring of negative Gaussian curvature
    // (Catmull-Clark does not preserve convexity at high valence; checked
    // against finite differences of the limit positions), so a contour that
    // passes through that ring has real cusps. Every cusp must lie there.
    const std::vector<Camera> views = protocolViews(cage->boundingBox(), 10);
    int cusps = 0;
    for (size_t v = 26; v < views.size(); ++v) {
        const GroundTruth truth = dense.compute(views[v]);
        QCOMPARE(int(truth.loops.size()), 1);
        QCOMPARE(truth.closedLoops(), 1);
        for (const GroundTruthCusp& cusp : truth.cusps)
            QVERIFY2(std::abs(cusp.position.z()) > 0.9, "a cusp away from the poles");
        cusps += int(truth.cusps.size());
    }
    qInfo("sphere, 10 random views: %d cusps, all in the hyperbolic ring around a pole", cusps);
}

void TestGroundTruth::ellipsoidHasOneLoop() {
    const auto cage = shape("ellipsoid", 16);
    const DenseGroundTruth dense(catmullClark(cage));
    for (const Camera& camera : protocolViews(cage->boundingBox(), 10)) {
        const GroundTruth truth = dense.compute(camera);
        QCOMPARE(int(truth.loops.size()), 1);
        QCOMPARE(truth.closedLoops(), 1);
        QCOMPARE(int(truth.cusps.size()), 0);
    }
}

void TestGroundTruth::torusFromAboveHasTwoLoopsAndNoCusp() {
    // The torus turns around the z axis: seen along it, the outer and the
    // inner silhouette circles, with constant radial curvature on each.
    const auto cage = shape("torus", 16);
    const DenseGroundTruth dense(catmullClark(cage));
    for (const Vec3& axis : {Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
        const GroundTruth truth = dense.compute(lookingFrom(cage->boundingBox(), axis));
        QCOMPARE(int(truth.loops.size()), 2);
        QCOMPARE(truth.closedLoops(), 2);
        QCOMPARE(int(truth.cusps.size()), 0);
    }
}

void TestGroundTruth::torusFromTheSideHasTwoLoopsAndCusps() {
    const auto cage = shape("torus", 16);
    const DenseGroundTruth dense(catmullClark(cage));
    for (const Vec3& direction : {Vec3(1, 0.3, 0.5), Vec3(-0.4, 1, 0.35), Vec3(1, 1, -0.6)}) {
        const GroundTruth truth = dense.compute(lookingFrom(cage->boundingBox(), direction));
        qInfo("torus from (%g, %g, %g): %d loops, %d cusps", direction.x(), direction.y(),
              direction.z(), int(truth.loops.size()), int(truth.cusps.size()));
        QCOMPARE(int(truth.loops.size()), 2);
        QCOMPARE(truth.closedLoops(), 2);
        QVERIFY(!truth.cusps.empty());
        QCOMPARE(int(truth.cusps.size()) % 2, 0);
        // Cusps pair up on a loop (the radial curvature changes sign and back).
        for (const GroundTruthLoop& loop : truth.loops)
            QCOMPARE(loop.cusps % 2, 0);
    }
}

void TestGroundTruth::sharedEdgesCloseLoops() {
    // Every loop of a closed surface closes, at coarse and fine lattices, and
    // the loop count does not depend on the lattice once it resolves the
    // contour. Also: the refined crossings lie on g = 0.
    const auto cage = shape("bumpy-torus", 24);
    const Camera camera = lookingFrom(cage->boundingBox(), Vec3(0.7, -0.4, 0.6));
    std::vector<int> counts;
    for (int samples : {8, 16, 32}) {
        const DenseGroundTruth dense(catmullClark(cage), {samples, 4});
        const GroundTruth truth = dense.compute(camera);
        QCOMPARE(truth.openLoops(), 0);
        counts.push_back(int(truth.loops.size()));
        double worst = 0.0;
        for (const GroundTruthLoop& loop : truth.loops)
            for (const Preimage& p : loop.preimages) {
                const SurfacePoint sp = dense.surface().evaluate(p);
                const double scale = camera.toCamera(sp.position).norm();
                worst = std::max(worst, std::abs(facingFunction(camera, sp.position, sp.normal())) /
                                            scale);
            }
        qInfo("bumpy torus, N = %d: %d loops, %d cusps, worst |g|/|c - p| at crossings %.2e",
              samples, counts.back(), int(truth.cusps.size()), worst);
        QVERIFY(worst < 1e-3);
    }
    QCOMPARE(counts[1], counts[2]);
}

void TestGroundTruth::interpolatedAgainstGroundTruth_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<int>("resolution");
    QTest::addColumn<bool>("assertLoops");
    QTest::newRow("sphere") << QString("sphere") << 16 << true;
    QTest::newRow("ellipsoid") << QString("ellipsoid") << 16 << true;
    QTest::newRow("torus") << QString("torus") << 16 << true;
    QTest::newRow("bumpy-torus") << QString("bumpy-torus") << 24 << false;
    QTest::newRow("spot") << QString("spot") << 0 << false;
}

// The full comparison (N = 64, 26 + 10 views) takes about 40 s optimized
// and over 5 minutes in Debug or ASan builds; those run a coarser lattice on
// the 26 protocol views only, with the same assertions.
#ifdef __OPTIMIZE__
constexpr int kComparisonSamples = 64;
constexpr int kComparisonRandomViews = 10;
#else
constexpr int kComparisonSamples = 32;
constexpr int kComparisonRandomViews = 0;
#endif

// A face crossed by one side only counts as a resolution difference, not a
// topology difference, when it lies within this many image pixels of the
// other side's curve (a chord of the consistent mesh cutting a domain face's
// corner that the true contour grazes).
constexpr double kFaceTolerancePixels = 1.0;

// A floor or ceiling of tests/baselines/test_ground_truth.json, "<shape>: <what>".
static int measured(const char* shape, const char* what) {
    return static_cast<int>(baseline("test_ground_truth", std::string(shape) + ": " + what));
}

void TestGroundTruth::interpolatedAgainstGroundTruth() {
    QFETCH(QString, name);
    QFETCH(int, resolution);
    QFETCH(bool, assertLoops);
    const auto cage = name == "spot" ? spotCage() : shape(name.toStdString(), resolution);
    GroundTruthOptions options;
    options.samples = kComparisonSamples;
    const DenseGroundTruth dense(catmullClark(cage), options);
    Overrides parameters;
    parameters.set("surface", std::string("catmull-clark"));
    parameters.set("tessellation-level", 8);
    const std::vector<Camera> views = protocolViews(cage->boundingBox(), kComparisonRandomViews);
    int sameLoops = 0, sameFaces = 0, truthCusps = 0;
    double jaccard = 0.0;
    for (size_t v = 0; v < views.size(); ++v) {
        const GroundTruth truth = dense.compute(views[v]);
        const Snapshot snapshot = runMethod("interpolated", cage, views[v], parameters);
        const TopologyComparison c = compareTopology(truth, snapshot);
        sameLoops += c.loopCountsMatch();
        sameFaces += c.faceSetsMatch();
        truthCusps += c.truthCusps;
        jaccard += c.meanJaccard;
        if (!c.loopCountsMatch() || !c.faceSetsMatch())
            qInfo("%s view %d: ground truth %d loops (%d open, %d cusps), interpolated %d loops "
                  "(%d open); %d matched, %d with the same faces, mean Jaccard %.3f",
                  qPrintable(name), int(v), c.truthLoops, c.truthOpenLoops, c.truthCusps,
                  c.methodLoops, c.methodOpenLoops, c.matchedLoops, c.sameFaceLoops, c.meanJaccard);
        if (assertLoops)
            QCOMPARE(c.methodLoops, c.truthLoops);
    }
    const int n = int(views.size());
    qInfo("%s (%d domain faces, N = %d, interpolated at level 8): loop counts match in %d/%d "
          "views (%.0f%%), crossed-face sets match in %d/%d (%.0f%%), mean Jaccard %.3f, "
          "ground-truth cusps %d in all",
          qPrintable(name), int(dense.surface().domain().faceCount()), dense.options().samples,
          sameLoops, n, 100.0 * sameLoops / n, sameFaces, n, 100.0 * sameFaces / n, jaccard / n,
          truthCusps);
}

void TestGroundTruth::consistentAgainstGroundTruth_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<int>("resolution");
    // Views (in %) where loop counts, crossed-face sets and cusp counts must
    // match: floors measured on this implementation, so that a regression
    // fails; the figures themselves are printed.
    QTest::addColumn<int>("minLoopsPercent");
    QTest::addColumn<int>("minCuspsPercent");
    QTest::addColumn<int>("minFacesPercent"); // face sets within kFaceTolerancePixels
    // Cusp counts leaving out the method's pairs closer than one lattice
    // step of the ground truth, where it has no cusp (subLatticeCuspPairs).
    QTest::addColumn<int>("minResolvedCuspsPercent");
    for (const auto& [shape, resolution] : {std::pair{"sphere", 16},
                                            {"ellipsoid", 16},
                                            {"torus", 16},
                                            {"bumpy-torus", 24},
                                            {"spot", 0},
                                            {"bob", 0}})
        QTest::newRow(shape) << QString(shape) << resolution
                             << measured(shape, "views with matching loop counts (%)")
                             << measured(shape, "views with matching cusp counts (%)")
                             << measured(shape, "views with crossed-face sets within 1 px (%)")
                             << measured(shape, "views with matching resolved cusp counts (%)");
}

// The consistent method's contour generator (after every phase) against the dense ground
// truth, per view: the number of loops, the domain faces each crosses, and
// the number of cusps.
void TestGroundTruth::consistentAgainstGroundTruth() {
    QFETCH(QString, name);
    QFETCH(int, resolution);
    QFETCH(int, minLoopsPercent);
    QFETCH(int, minCuspsPercent);
    QFETCH(int, minFacesPercent);
    QFETCH(int, minResolvedCuspsPercent);
    const auto cage = comparisonCage(name, resolution);
    const DenseGroundTruth dense(catmullClark(cage), {kComparisonSamples, 4});
    Overrides parameters;
    parameters.set("surface", std::string("catmull-clark"));
    const std::vector<Camera> views = protocolViews(cage->boundingBox(), kComparisonRandomViews);
    int sameLoops = 0, sameFaces = 0, sameFacesWithin = 0, sameCusps = 0, truthCusps = 0,
        methodCusps = 0, mismatchesBeyond = 0, sameResolvedCusps = 0, subLatticePairs = 0;
    long long onlyTruth = 0, onlyMethod = 0, both = 0;
    double jaccard = 0.0, seconds = 0.0, worstMismatch = 0.0;
    for (size_t v = 0; v < views.size(); ++v) {
        const GroundTruth truth = dense.compute(views[v]);
        const auto start = std::chrono::steady_clock::now();
        const Snapshot snapshot = runMethod("consistent", cage, views[v], parameters);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const TopologyComparison c =
            compareTopology(truth, snapshot, dense.surfacePtr(), &views[v], kFaceTolerancePixels);
        sameLoops += c.loopCountsMatch();
        sameFaces += c.faceSetsMatch();
        sameFacesWithin += c.faceSetsMatchWithinTolerance();
        worstMismatch = std::max(worstMismatch, c.worstMismatchPixels);
        mismatchesBeyond += c.mismatchesBeyond;
        sameCusps += c.cuspCountsMatch();
        const int pairs = subLatticeCuspPairs(truth, snapshot);
        subLatticePairs += pairs;
        sameResolvedCusps += c.methodCusps - 2 * pairs == c.truthCusps;
        truthCusps += c.truthCusps;
        methodCusps += std::max(0, c.methodCusps);
        onlyTruth += c.facesOnlyInTruth;
        onlyMethod += c.facesOnlyInMethod;
        both += c.facesInBoth;
        jaccard += c.meanJaccard;
        if (!c.loopCountsMatch() || !c.cuspCountsMatch())
            qInfo("%s view %d: ground truth %d loops (%d open, %d cusps), consistent %d loops "
                  "(%d open, %d cusps); %d matched, %d with the same faces, mean Jaccard %.3f",
                  qPrintable(name), int(v), c.truthLoops, c.truthOpenLoops, c.truthCusps,
                  c.methodLoops, c.methodOpenLoops, c.methodCusps, c.matchedLoops, c.sameFaceLoops,
                  c.meanJaccard);
    }
    const int n = int(views.size());
    qInfo("%s (%d domain faces, N = %d), consistent: loop counts match in %d/%d views (%.0f%%), "
          "crossed-face sets in %d/%d (%.0f%%), cusp counts in %d/%d (%.0f%%; %d ground-truth "
          "cusps, %d found), mean Jaccard %.3f (crossed faces in both %lld, only in the ground "
          "truth %lld, only in the method %lld), %.2f s per view",
          qPrintable(name), int(dense.surface().domain().faceCount()), dense.options().samples,
          sameLoops, n, 100.0 * sameLoops / n, sameFaces, n, 100.0 * sameFaces / n, sameCusps, n,
          100.0 * sameCusps / n, truthCusps, methodCusps, jaccard / n, both, onlyTruth, onlyMethod,
          seconds / n);
    qInfo("%s, consistent: crossed-face sets match within %.1f px in %d/%d views (%.0f%%); faces "
          "crossed by one side only lie at most %.2f px from the other side's curve; %d such "
          "faces farther than %.1f px",
          qPrintable(name), kFaceTolerancePixels, sameFacesWithin, n, 100.0 * sameFacesWithin / n,
          worstMismatch, mismatchesBeyond, kFaceTolerancePixels);
    qInfo("%s, consistent: cusp counts match in %d/%d views (%.0f%%) when the method's %d cusp "
          "pairs closer than a ground-truth lattice step, where it has none, are left out",
          qPrintable(name), sameResolvedCusps, n, 100.0 * sameResolvedCusps / n, subLatticePairs);
    // The floors were measured on the full comparison; the coarser lattice of
    // unoptimized builds only checks the shapes whose answer is exact.
    if (kComparisonSamples == 64 || name == "sphere" || name == "ellipsoid") {
        QVERIFY2(100 * sameLoops >= minLoopsPercent * n, "fewer views with matching loop counts");
        QVERIFY2(100 * sameCusps >= minCuspsPercent * n, "fewer views with matching cusp counts");
        QVERIFY2(100 * sameResolvedCusps >= minResolvedCuspsPercent * n,
                 "fewer views with matching cusp counts up to sub-lattice pairs");
    }
    // The coarser lattice's own chords are longer than the tolerance.
    if (kComparisonSamples == 64)
        QVERIFY2(100 * sameFacesWithin >= minFacesPercent * n,
                 "fewer views with crossed-face sets matching within the tolerance");
}

// contour-refinement (not in the paper): contour edges straying more than
// contour-refinement-pixels from the smooth contour are split at a root of g
// beside their middle. On spot, the coarsest sample, the crossed-face sets
// then match the ground truth within 1 px in more views and fewer faces lie
// farther than 1 px, with the same loops and never more inconsistent faces.
void TestGroundTruth::contourRefinementFollowsTheCurve() {
    const auto cage = comparisonCage("spot", 0);
    const DenseGroundTruth dense(catmullClark(cage), {kComparisonSamples, 4});
    const std::vector<Camera> views = protocolViews(cage->boundingBox(), kComparisonRandomViews);
    int sameLoops[2] = {0, 0}, sameFacesWithin[2] = {0, 0}, beyond[2] = {0, 0};
    long long splits = 0;
    for (size_t v = 0; v < views.size(); ++v) {
        const GroundTruth truth = dense.compute(views[v]);
        double inconsistent[2] = {0.0, 0.0};
        for (int on = 0; on < 2; ++on) {
            Overrides parameters;
            parameters.set("surface", std::string("catmull-clark"));
            if (!on)
                parameters.set("contour-refinement-pixels", 0.0);
            const Snapshot snapshot = runMethod("consistent", cage, views[v], parameters);
            const TopologyComparison c = compareTopology(truth, snapshot, dense.surfacePtr(),
                                                         &views[v], kFaceTolerancePixels);
            sameLoops[on] += c.loopCountsMatch();
            sameFacesWithin[on] += c.faceSetsMatchWithinTolerance();
            beyond[on] += c.mismatchesBeyond;
            inconsistent[on] = snapshot.counter(counters::kInconsistentFaces, -1.0);
            if (on)
                splits += static_cast<long long>(snapshot.counter("contour edges split", 0.0));
            else
                QCOMPARE(snapshot.counter("contour edges split", -1.0), 0.0);
        }
        QVERIFY(inconsistent[0] >= 0.0);
        QVERIFY2(inconsistent[1] <= inconsistent[0],
                 qPrintable(QString("view %1: %2 -> %3 inconsistent faces")
                                .arg(v)
                                .arg(inconsistent[0])
                                .arg(inconsistent[1])));
    }
    const int n = int(views.size());
    qInfo("spot, %d views: crossed-face sets within %.1f px in %d (refinement off) -> %d (on), "
          "faces farther than that %d -> %d, loop counts matching %d -> %d; %lld contour edges "
          "split",
          n, kFaceTolerancePixels, sameFacesWithin[0], sameFacesWithin[1], beyond[0], beyond[1],
          sameLoops[0], sameLoops[1], splits);
    QCOMPARE(sameLoops[1], sameLoops[0]);
    QVERIFY(splits > 0);
    if (kComparisonSamples == 64) {
        QVERIFY(sameFacesWithin[1] > sameFacesWithin[0]);
        QVERIFY(beyond[1] < beyond[0]);
    }
}

void TestGroundTruth::crossingsAgainstGroundTruth_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<int>("resolution");
    // Views with as many T-junctions as crossings (a floor), and the
    // difference of their totals (a ceiling).
    QTest::addColumn<int>("minSameViews");
    QTest::addColumn<int>("maxApart");
    for (const auto& [shape, resolution] :
         {std::pair{"torus", 16}, {"bumpy-torus", 24}, {"spot", 0}, {"bob", 0}})
        QTest::newRow(shape) << QString(shape) << resolution
                             << measured(shape, "views with as many T-junctions as crossings")
                             << measured(shape, "T-junctions and crossings apart in all");
}

// The consistent method's
// T-junctions (a drawn curve in front of another in 2D) per view, against
// the crossings of the dense ground truth's projected contour
// (imageCrossings). A view graph with extra crossings draws T-junctions
// the smooth surface does not have; one with fewer misses occlusions.
// Crossings behind a mesh fold that lies on no drawn curve (next to
// inconsistent faces) are counted apart: the smooth contour has no such
// fold. The method's own contour curves are also crossed by brute force, so
// that the graph's exactness on its input is told apart from the input's
// fidelity to the smooth contour.
void TestGroundTruth::crossingsAgainstGroundTruth() {
    QFETCH(QString, name);
    QFETCH(int, resolution);
    QFETCH(int, minSameViews);
    QFETCH(int, maxApart);
    const auto cage = comparisonCage(name, resolution);
    const DenseGroundTruth dense(catmullClark(cage), {kComparisonSamples, 4});
    Overrides parameters;
    parameters.set("surface", std::string("catmull-clark"));
    std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
    if (kComparisonSamples != 64)
        views.resize(6); // unoptimized builds: print only
    int same = 0, truthTotal = 0, junctionTotal = 0, apart = 0;
    int hiddenFoldTotal = 0, curveTotal = 0, sameAsCurves = 0;
    for (const Camera& camera : views) {
        const int truth = imageCrossings(dense.compute(camera), camera);
        const Snapshot s = runMethod("consistent", cage, camera, parameters);
        QVERIFY(s.viewGraph);
        QVERIFY(s.curves);
        int junctions = 0, hiddenFold = 0;
        for (const ViewNode& node : s.viewGraph->nodes) {
            junctions += node.type == ViewNodeType::ImageIntersection;
            hiddenFold += node.type == ViewNodeType::HiddenFoldCrossing;
        }
        const int curves = imageCrossings(*s.curves, camera);
        // Every T-junction is a crossing of the drawn curves (a crossing
        // gets none only when its near edge is no fold of the mesh).
        QVERIFY2(junctions <= curves, "a T-junction where the drawn curves do not cross");
        same += truth == junctions;
        sameAsCurves += curves == junctions;
        truthTotal += truth;
        junctionTotal += junctions;
        hiddenFoldTotal += hiddenFold;
        curveTotal += curves;
        apart += std::abs(truth - junctions);
    }
    const int n = static_cast<int>(views.size());
    qInfo("%s, consistent: T-junctions equal the ground truth's image crossings in %d/%d views; "
          "%d crossings in the ground truth, %d T-junctions, %d apart in all; %d crossings "
          "behind hidden mesh folds; the drawn contour curves cross %d times (as many as the "
          "T-junctions in %d/%d views)",
          qPrintable(name), same, n, truthTotal, junctionTotal, apart, hiddenFoldTotal, curveTotal,
          sameAsCurves, n);
    if (kComparisonSamples == 64) {
        QVERIFY2(same >= minSameViews, "fewer views whose T-junctions match the crossings");
        QVERIFY2(apart <= maxApart, "T-junction counts further from the crossings");
    }
}

void TestGroundTruth::timingOnSpot() {
    const auto cage = spotCage();
    const DenseGroundTruth dense(catmullClark(cage), {kComparisonSamples, 4});
    double total = 0.0, worst = 0.0;
    int loops = 0, cusps = 0;
    const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
    for (const Camera& camera : views) {
        const GroundTruth truth = dense.compute(camera);
        total += truth.seconds;
        worst = std::max(worst, truth.seconds);
        loops += int(truth.loops.size());
        cusps += int(truth.cusps.size());
    }
    qInfo("spot, N = %d: %d domain faces, %zu samples evaluated once in %.2f s; per view "
          "(26 views) %.3f s mean, %.3f s worst; %d loops and %d cusps in all",
          kComparisonSamples, int(dense.surface().domain().faceCount()), dense.sampleCount(),
          dense.samplingSeconds(), total / views.size(), worst, loops, cusps);
}

QTEST_APPLESS_MAIN(TestGroundTruth)
#include "test_ground_truth.moc"
