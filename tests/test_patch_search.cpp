// The patch search of the consistent method (PatchSearchPhase.cpp, an
// extension of Bénard 2014 §6.4 past the fixed point of its one-edit moves):
// over the 26-view protocol on spot, bob and the procedural tori, the phase
// never increases the inconsistent faces of a view, violates no
// post-condition (Debug builds enforce them: a violation throws), publishes
// a valid mesh (two more faces per inserted vertex), and lowers the
// inconsistent faces where it helps to a fraction of its input (what the
// mesh would be without it) below a ceiling. Switched off, it passes the
// mesh through.
#include "ContourTestSupport.h"
#include "pipeline/FieldNames.h"

#include <QtTest>
#include <algorithm>
#include <stdexcept>

using namespace contour;
using namespace contour::testing;

namespace {

std::shared_ptr<const PolygonMesh> loadShape(const std::string& name) {
    return sampleOrShape(name, 12);
}

PhaseRun runView(const std::shared_ptr<const PolygonMesh>& cage, const Camera& camera,
                 bool patchSearch, bool cornerCharts = false, bool radialEnds = false,
                 bool contourSlide = true, bool newRadialEnds = true, bool newRadialCusps = true,
                 bool cuspTies = true, int cuspEndDiscs = -1) {
    const Method& m = *findMethod("consistent");
    ParameterSet p = ParameterSet::defaults(m.parameters);
    p.set("patch-search", patchSearch);
    p.set("chart-vertex-rings", cornerCharts);
    p.set("patch-radial-ends", radialEnds);
    p.set("patch-contour-slide", contourSlide);
    p.set("patch-new-radial-ends", newRadialEnds);
    p.set("patch-new-radial-cusps", newRadialCusps);
    p.set("patch-new-radial-cusp-ties", cuspTies);
    if (cuspEndDiscs >= 0)
        p.set("cusp-end-retriangulation-faces", cuspEndDiscs);
    // The cusp retry (last) reruns the method when faces remain: off, so the
    // final counts show the patch search's own effect.
    p.set("cusp-retry", false);
    Runner runner(m, makeInputSnapshot(cage), camera, p);
    // A phase that fails (a PhaseError) fails the slot, with its message.
    runner.runToEnd();
    if (!runner.atEnd())
        throw std::runtime_error("the method stopped after phase " +
                                 std::to_string(runner.completedPhases()));
    PhaseRun out;
    for (int i = 0; i <= runner.completedPhases(); ++i)
        out.snapshots.push_back(runner.snapshot(i));
    return out;
}

// The first post-condition a phase of the run violates, or empty.
QString firstViolation(const PhaseRun& run) {
    for (const Snapshot& s : run.snapshots)
        for (const InvariantCheck& c : s.invariants)
            if (c.violations != 0)
                return QString("%1: %2 (%3)")
                    .arg(QString::fromStdString(s.phaseName))
                    .arg(QString::fromStdString(c.name))
                    .arg(QString::fromStdString(c.firstExample));
    return {};
}

std::vector<Camera> views(const PolygonMesh& cage) {
    std::vector<Camera> all = Camera::views26(cage.boundingBox(), Viewport{800, 600});
#ifndef __OPTIMIZE__
    // Debug: every post-condition enforced, at many times the time.
    all.resize(3);
#endif
    return all;
}

} // namespace

class TestPatchSearch : public QObject {
    Q_OBJECT
private slots:
    void neverWorseOverTheProtocol_data() {
        QTest::addColumn<QString>("shapeName");
        // Ceiling on the inconsistent faces after the phase as a fraction
        // of those before it, summed over the 26 views (Release only).
        // Without the phase the fraction is 1.
        QTest::addColumn<double>("ceiling");
        // Measured (Release, 26 views, before -> after the phase): spot
        // 184 -> 92 (0.50), bob 152 -> 38 (0.25), bumpy torus 40 -> 20
        // (0.50), torus 16 -> 12 (16 -> 0 with patch-radial-ends: see
        // radialEndsClearTheTorus). Session 8 (crossing-search-rounds, the
        // cusp pushes, new radial ends): spot 191 -> 85 (0.45), bob 145 -> 31
        // (0.21), bumpy torus 33 -> 16 (0.48), torus 4 -> 4: the earlier
        // phases now leave the torus only faces that need patch-radial-ends
        // (off here; radialEndsClearTheTorus), so its row checks that no
        // view gets worse.
        QTest::addRow("spot") << QString("spot") << 0.5;
        QTest::addRow("bob") << QString("bob") << 0.25;
        QTest::addRow("bumpy-torus") << QString("bumpy-torus") << 0.55;
        QTest::addRow("torus") << QString("torus") << 1.0;
    }

    void neverWorseOverTheProtocol() {
        QFETCH(QString, shapeName);
        QFETCH(double, ceiling);
        const std::shared_ptr<const PolygonMesh> cage = loadShape(shapeName.toStdString());
        const std::vector<Camera> cameras = views(*cage);
        long long before = 0, after = 0, inserted = 0, relocated = 0, finalFaces = 0;
        for (size_t v = 0; v < cameras.size(); ++v) {
            const PhaseRun run = runView(cage, cameras[v], true);
            const QString violation = firstViolation(run);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            const Snapshot& s = run.after("patch-search");
            const Snapshot& previous = run.after("vertex-removal");
            const double in = s.counter(counters::kInconsistentFacesBefore, -1.0);
            const double out = s.counter(counters::kInconsistentFaces, -1.0);
            QVERIFY(in >= 0.0 && out >= 0.0);
            // The phase's input is what the previous phase published.
            QCOMPARE(in, previous.counter(counters::kInconsistentFaces, -2.0));
            QVERIFY2(out <= in, qPrintable(QString("view %1: %2 -> %3").arg(v).arg(in).arg(out)));
            const TriangleMesh& mesh = *s.mesh;
            for (Index f = 0; f < mesh.faceCount(); ++f) {
                const Triangle& t = mesh.triangle(f);
                QVERIFY(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
            }
            QCOMPARE(static_cast<Index>(s.field(fields::kConsistent)->labels()->size()),
                     mesh.faceCount());
            // A new vertex adds two faces; a relocation none.
            QCOMPARE(static_cast<double>(mesh.faceCount()),
                     previous.counter(counters::kFaces) +
                         2.0 * s.counter(counters::kVerticesInserted));
            before += static_cast<long long>(in);
            after += static_cast<long long>(out);
            inserted += static_cast<long long>(s.counter(counters::kVerticesInserted));
            relocated += static_cast<long long>(s.counter(counters::kVerticesRelocated));
            finalFaces +=
                static_cast<long long>(run.snapshots.back().counter(counters::kInconsistentFaces));
        }
        qInfo("%s, %d views: inconsistent faces %lld before the patch search, %lld after it "
              "(%lld vertices inserted, %lld relocated), %lld at the end",
              qPrintable(shapeName), static_cast<int>(cameras.size()), before, after, inserted,
              relocated, finalFaces);
#ifdef __OPTIMIZE__
        QVERIFY(before > 0);
        QVERIFY2(static_cast<double>(after) <= ceiling * static_cast<double>(before),
                 qPrintable(QString("%1 > %2 x %3").arg(after).arg(ceiling).arg(before)));
#else
        Q_UNUSED(ceiling);
#endif
    }

    // Every view completes, also with corner charts (chart-vertex-rings),
    // which change the meshes the phase gets. Each move is planned on a
    // copy of the patch first (RingRetriangulation) and skipped when the
    // mesh would refuse an edit or the edits end elsewhere than the judged
    // triangulation: a refused flip used to make the phase throw (spot_control
    // view 5 with corner charts, an earlier tree), and a patch with a corner
    // inside it was applied as another triangulation than the one judged
    // (bob_control view 7). The phase never raises a view's inconsistent
    // faces and keeps every post-condition (enforced in Debug). Defaults
    // (corner charts off) are neverWorseOverTheProtocol's runs.
    void everyViewCompletes_data() {
        QTest::addColumn<QString>("shapeName");
        QTest::addColumn<bool>("cornerCharts");
        QTest::addRow("spot, corner charts") << QString("spot") << true;
        QTest::addRow("bob, corner charts") << QString("bob") << true;
        QTest::addRow("bumpy-torus, corner charts") << QString("bumpy-torus") << true;
    }

    void everyViewCompletes() {
        QFETCH(QString, shapeName);
        QFETCH(bool, cornerCharts);
        const std::shared_ptr<const PolygonMesh> cage = loadShape(shapeName.toStdString());
        const std::vector<Camera> cameras = views(*cage);
        long long before = 0, after = 0, skipped = 0;
        for (size_t v = 0; v < cameras.size(); ++v) {
            PhaseRun run;
            try {
                run = runView(cage, cameras[v], true, cornerCharts);
            } catch (const std::exception& e) {
                QFAIL(qPrintable(QString("view %1: %2").arg(v).arg(e.what())));
            }
            const QString violation = firstViolation(run);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            const Snapshot& s = run.after("patch-search");
            const double in = s.counter(counters::kInconsistentFacesBefore, -1.0);
            const double out = s.counter(counters::kInconsistentFaces, -1.0);
            QVERIFY(in >= 0.0 && out >= 0.0);
            QVERIFY2(out <= in, qPrintable(QString("view %1: %2 -> %3").arg(v).arg(in).arg(out)));
            const double refused = s.counter(counters::kMovesSkippedTheMeshWouldRefuseAnEdit, -1.0);
            QVERIFY(refused >= 0.0);
            before += static_cast<long long>(in);
            after += static_cast<long long>(out);
            skipped += static_cast<long long>(refused);
        }
        qInfo("%s, corner charts %s, %d views: inconsistent faces %lld -> %lld in the patch "
              "search, %lld moves skipped (the mesh would refuse an edit)",
              qPrintable(shapeName), cornerCharts ? "on" : "off", static_cast<int>(cameras.size()),
              before, after, skipped);
    }

    // With patch-radial-ends, the torus's last faces (F-F-F faces beyond a
    // cusp's radial end, two corners radial ends) go: a radial end slides
    // along its radial plane, its star re-triangulated, its radial edge kept
    // (the post-condition |h_p(r)| <= radial-root-tolerance holds).
    // Measured (Release, 26 views): final inconsistent faces 12 -> 0.
    void radialEndsClearTheTorus() {
        const std::shared_ptr<const PolygonMesh> cage = loadShape("torus");
        const std::vector<Camera> cameras = views(*cage);
        long long relocated = 0, finalFaces = 0;
        for (size_t v = 0; v < cameras.size(); ++v) {
            const PhaseRun run = runView(cage, cameras[v], true, false, true);
            const QString violation = firstViolation(run);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            const Snapshot& s = run.after("patch-search");
            QVERIFY(s.counter(counters::kInconsistentFaces) <=
                    s.counter(counters::kInconsistentFacesBefore));
            relocated += static_cast<long long>(s.counter(counters::kVerticesRelocated));
            const double left = run.snapshots.back().counter(counters::kInconsistentFaces, -1.0);
            QVERIFY2(left == 0.0, qPrintable(QString("view %1: %2 faces left").arg(v).arg(left)));
            finalFaces += static_cast<long long>(left);
        }
        qInfo("torus with patch-radial-ends, %d views: %lld vertices relocated, %lld "
              "inconsistent faces at the end",
              static_cast<int>(cameras.size()), relocated, finalFaces);
    }

    // With patch-contour-slide, a C vertex without tagged edges slides along
    // the contour (a root of g) with its star re-triangulated: the CC edges
    // stay (same contour edges before and after the phase), every C vertex
    // keeps |g| <= root-tolerance (a post-condition, enforced in Debug), no
    // view ends with more inconsistent faces than without the slide, and
    // some end with fewer. Measured (Release, 26 views, final inconsistent
    // faces without -> with, normal-wiggle pairs on): spot 35 -> 33 here;
    // bench_consistent bob_control 19 -> 17, bigguy 184 -> 182, killeroo
    // 685 -> 678, no view worse. Spot alone keeps the suite's time.
    void contourSlideRemovesFaces() {
        const QString shapeName = "spot";
        const std::shared_ptr<const PolygonMesh> cage = loadShape(shapeName.toStdString());
        std::vector<Camera> cameras = views(*cage);
#ifndef __OPTIMIZE__
        // Debug: view 2 alone (2 -> 1 final faces), the suite's time.
        cameras = {cameras[2]};
#endif
        const auto contourEdges = [](const Snapshot& s) {
            const auto& label = *s.field(fields::kLabel)->labels();
            long long n = 0;
            for (Index e = 0; e < s.mesh->edgeCount(); ++e) {
                const Index h = s.mesh->edgeHalfedge(e);
                n += label[static_cast<size_t>(s.mesh->from(h))] == 0 &&
                     label[static_cast<size_t>(s.mesh->to(h))] == 0;
            }
            return n;
        };
        long long slid = 0;
        OnOffCounts tally;
        for (size_t v = 0; v < cameras.size(); ++v) {
            // The slide alone, as when the figures were measured: the discs
            // re-triangulated at cusps' radial ends after the normal wiggle
            // (session 10) fix the same faces either way.
            const PhaseRun off =
                runView(cage, cameras[v], true, false, true, false, true, true, true, 0);
            const PhaseRun on =
                runView(cage, cameras[v], true, false, true, true, true, true, true, 0);
            const QString violation = firstViolation(on);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            const Snapshot& s = on.after("patch-search");
            QCOMPARE(contourEdges(s), contourEdges(on.after("vertex-removal")));
            QCOMPARE(off.after("patch-search").counter(counters::kCVerticesSlidAlongTheContour),
                     0.0);
            slid += static_cast<long long>(s.counter(counters::kCVerticesSlidAlongTheContour));
            const std::string worse = tally.add(off.snapshots.back(), on.snapshots.back(), v);
            QVERIFY2(worse.empty(), worse.c_str());
        }
        qInfo("%s, %d views: %lld C vertices slid; final inconsistent faces %.0f without the "
              "slide, %.0f with it (%d views better)",
              qPrintable(shapeName), static_cast<int>(cameras.size()), slid, tally.without,
              tally.with, tally.better);
        QVERIFY(slid > 0);
        QVERIFY(tally.better > 0);
    }

    // With patch-new-radial-ends, a C vertex that radial edge insertion left
    // with fewer than two radial edges gets one in the patch search: the
    // free vertex sampled on its radial plane only, joined to it, the edge
    // tagged radial (the radial post-conditions, |h_p(r)| within
    // radial-root-tolerance, enforced in Debug). No view ends with more
    // inconsistent faces than without it, some with fewer, and the radial
    // edges grow by the counter. Measured (Release, 26 views, final
    // inconsistent faces without -> with): spot 25 -> 24 (view 5: 3 -> 2),
    // 3 new radial edges; bench_consistent bigguy 156 -> 149, killeroo
    // 501 -> 492, no view worse.
    void newRadialEndsRemoveFaces() {
        const std::shared_ptr<const PolygonMesh> cage = loadShape("spot");
        std::vector<Camera> cameras = views(*cage);
#ifndef __OPTIMIZE__
        // Debug: one view where it helps, the suite's time.
        cameras = {Camera::views26(cage->boundingBox(), Viewport{800, 600})[5]};
#endif
        const auto radialEdges = [](const Snapshot& s) {
            const auto& radial = *s.field(fields::kRadialEdge)->labels();
            return std::count_if(radial.begin(), radial.end(), [](int r) { return r != 0; });
        };
        long long added = 0;
        OnOffCounts tally;
        for (size_t v = 0; v < cameras.size(); ++v) {
            const PhaseRun off = runView(cage, cameras[v], true, false, true, true, false);
            const PhaseRun on = runView(cage, cameras[v], true, false, true, true, true);
            const QString violation = firstViolation(on);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            const Snapshot& s = on.after("patch-search");
            const double n = s.counter(counters::kNewRadialEdges, -1.0);
            QVERIFY(n >= 0.0);
            QCOMPARE(off.after("patch-search").counter(counters::kNewRadialEdges), 0.0);
            QCOMPARE(static_cast<double>(radialEdges(s)),
                     static_cast<double>(radialEdges(on.after("vertex-removal"))) + n);
            added += static_cast<long long>(n);
            const std::string worse = tally.add(off.snapshots.back(), on.snapshots.back(), v);
            QVERIFY2(worse.empty(), worse.c_str());
        }
        qInfo("spot, %d views: %lld new radial edges; final inconsistent faces %.0f without "
              "them, %.0f with them (%d views better)",
              static_cast<int>(cameras.size()), added, tally.without, tally.with, tally.better);
        QVERIFY(added > 0);
        QVERIFY(tally.better > 0);
    }

    // With patch-new-radial-cusps, a cusp without radial edges (radial edge
    // insertion found no outside region, Fig. 18e) may get one in the patch
    // search, its valence-4 fan (Fig. 18d) re-triangulated around the new
    // radial end. Bigguy views 4 and 11 (bench_consistent, 26 views: 49 ->
    // 47, no view worse): fewer final inconsistent faces with it, radial
    // edges at cusps added, no post-condition violated (Debug: the cusp
    // valence and radial-edge checks enforced).
    void newRadialCuspsRemoveFaces() {
        const auto cage = sharedMesh("bigguy");
        if (!cage)
            QSKIP("../shared/meshes/bigguy.obj is absent");
        const std::vector<Camera> all = Camera::views26(cage->boundingBox(), Viewport{800, 600});
#ifdef __OPTIMIZE__
        const std::vector<Camera> cameras = {all[4], all[11]};
#else
        const std::vector<Camera> cameras = {all[4]};
#endif
        double added = 0.0;
        OnOffCounts tally;
        for (size_t v = 0; v < cameras.size(); ++v) {
            const PhaseRun off = runView(cage, cameras[v], true, false, true, true, true, false);
            const PhaseRun on = runView(cage, cameras[v], true, false, true, true, true, true);
            const QString violation = firstViolation(on);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            QCOMPARE(off.after("patch-search").counter(counters::kNewRadialEdgesAtCusps), 0.0);
            added += on.after("patch-search").counter(counters::kNewRadialEdgesAtCusps, 0.0);
            const std::string worse = tally.add(off.snapshots.back(), on.snapshots.back(), v);
            QVERIFY2(worse.empty(), worse.c_str());
        }
        qInfo("bigguy, %d views: %.0f new radial edges at cusps; final inconsistent faces %.0f "
              "without them, %.0f with them (%d views better)",
              static_cast<int>(cameras.size()), added, tally.without, tally.with, tally.better);
        QVERIFY(added > 0.0);
        QVERIFY(tally.better > 0);
    }

    // patch-new-radial-cusp-ties: a cusp without radial edges gets its first
    // one even when the patch keeps as many inconsistent faces (a
    // tie-break). Spot view 16 has two cusps whose valence-4 fan has a single
    // F corner (the F side must cover 372 degrees around the cusp's image, two
    // faces cannot): with the tie-break both get a radial edge and the later
    // moves clear the view (final inconsistent faces 2 -> 0); no spot view is
    // worse (bench_consistent, 26 views: spot 10 -> 8, bigguy view 8 2 -> 3).
    void newRadialCuspTiesClearSpotView16() {
        const std::shared_ptr<const PolygonMesh> cage = loadShape("spot");
        const std::vector<Camera> all = Camera::views26(cage->boundingBox(), Viewport{800, 600});
#ifdef __OPTIMIZE__
        const std::vector<Camera> cameras = all;
#else
        const std::vector<Camera> cameras = {all[16]};
#endif
        OnOffCounts tally;
        double ties = 0.0, view16 = -1.0;
        for (size_t v = 0; v < cameras.size(); ++v) {
            const PhaseRun off =
                runView(cage, cameras[v], true, false, true, true, true, true, false);
            const PhaseRun on =
                runView(cage, cameras[v], true, false, true, true, true, true, true);
            const QString violation = firstViolation(on);
            QVERIFY2(violation.isEmpty(), qPrintable(QString("view %1, %2").arg(v).arg(violation)));
            ties += on.after("patch-search").counter(counters::kNewRadialEdgesAtCusps, 0.0) -
                    off.after("patch-search").counter(counters::kNewRadialEdgesAtCusps, 0.0);
            const std::string worse = tally.add(off.snapshots.back(), on.snapshots.back(), v);
            QVERIFY2(worse.empty(), worse.c_str());
            if (cameras.size() == 1 || v == 16)
                view16 = on.snapshots.back().counter(counters::kInconsistentFaces, -1.0);
        }
        qInfo("spot, %d views: %.0f more radial edges at cusps; final inconsistent faces %.0f "
              "without the tie-break, %.0f with it (%d views better; view 16: %.0f)",
              static_cast<int>(cameras.size()), ties, tally.without, tally.with, tally.better,
              view16);
        QVERIFY(ties > 0.0);
        QCOMPARE(view16, 0.0);
    }

    // Off, the phase passes the mesh through and says so.
    void offPassesThrough() {
        const std::shared_ptr<const PolygonMesh> cage = loadShape("spot");
        const PhaseRun run = runView(cage, views(*cage)[2], false);
        const Snapshot& s = run.after("patch-search");
        const Snapshot& previous = run.after("vertex-removal");
        QVERIFY(previous.counter(counters::kInconsistentFaces) > 0.0);
        QCOMPARE(s.counter(counters::kInconsistentFaces),
                 previous.counter(counters::kInconsistentFaces));
        QCOMPARE(s.mesh->faceCount(), previous.mesh->faceCount());
        QCOMPARE(s.mesh->vertexCount(), previous.mesh->vertexCount());
        QCOMPARE(s.counter(counters::kVerticesInserted), 0.0);
        bool noted = false;
        for (const std::string& n : s.notes)
            noted = noted || n.find("patch-search = false") != std::string::npos;
        QVERIFY(noted);
    }
};

QTEST_APPLESS_MAIN(TestPatchSearch)
#include "test_patch_search.moc"
