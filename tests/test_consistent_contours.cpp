// Consistent contours (Bénard, Hertzmann & Kass 2014), the basics: the VBO
// table (Definitions 1-3), appendix B interpolation, and the post-conditions
// of every phase (from contour insertion on: no FB edge, every VBO defined,
// §6.2) over the
// 26-view protocol on a Catmull-Clark sphere and torus and on spot; the
// sphere's contour generator is one closed loop. Reports the inconsistent
// faces after initialization and contour insertion; the later phases have
// their own suites (cusps, radialization, optimization).
#include "ContourTestSupport.h"
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/VertexBasedOrientation.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QtTest>
#include <filesystem>

using namespace contour;
using namespace contour::consistent;
using namespace contour::testing;

namespace {

// Unoptimized (Debug, ASan) builds check every third protocol view: the
// whole method with its post-conditions takes about 10 s per view there.
#ifdef __OPTIMIZE__
constexpr size_t kViewStride = 1;
#else
constexpr size_t kViewStride = 3;
#endif

MethodRun runCatmullClark(const std::shared_ptr<const PolygonMesh>& cage, const Camera& camera) {
    return run("consistent", cage, camera, {{"surface", "catmull-clark"}});
}

void verifyNoViolations(const Snapshot& s) {
    for (const InvariantCheck& c : s.invariants)
        QVERIFY2(c.violations == 0,
                 qPrintable(QString::fromStdString(s.phaseName + ": " + c.name + " violated " +
                                                   std::to_string(c.violations) + "x, first " +
                                                   c.firstExample)));
}

// Runs one protocol view of a mesh of ../shared/meshes and checks every
// phase's post-conditions; false when the mesh is absent.
bool postConditionsHoldOnView(const std::string& name, size_t view) {
    const auto cage = sharedMesh(name);
    if (!cage)
        return false;
    const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
    const MethodRun r = runCatmullClark(cage, views[view]);
    for (const Snapshot& s : r.snapshots)
        verifyNoViolations(s);
    return true;
}

// Per phase: total inconsistent faces, worst view, total faces.
struct Tally {
    double inconsistent[2] = {0, 0}, worst[2] = {0, 0}, faces[2] = {0, 0};
};

void report(const char* name, const Tally& t, int views) {
    const char* phases[2] = {"initialization", "contour-insertion"};
    for (int k = 0; k < 2; ++k)
        qInfo("%s, %d views, after %s: %.0f inconsistent of %.0f faces in total (%.3f %%), "
              "mean %.1f per view, worst view %.0f",
              name, views, phases[k], t.inconsistent[k], t.faces[k],
              100.0 * t.inconsistent[k] / t.faces[k], t.inconsistent[k] / views, t.worst[k]);
}

void tally(Tally& t, const MethodRun& r) {
    for (int k = 0; k < 2; ++k) {
        const Snapshot& s = r.phase(k == 0 ? "initialization" : "contour-insertion");
        const double n = s.counter(counters::kInconsistentFaces);
        t.inconsistent[k] += n;
        t.worst[k] = std::max(t.worst[k], n);
        t.faces[k] += s.counter(counters::kFaces);
    }
}

} // namespace

class TestConsistentContours : public QObject {
    Q_OBJECT
private slots:
    // Definition 1 for every label multiset (27 ordered triples).
    void vboTable() {
        const VertexLabel all[3] = {VertexLabel::Back, VertexLabel::Contour, VertexLabel::Front};
        for (VertexLabel a : all)
            for (VertexLabel b : all)
                for (VertexLabel c : all) {
                    int f = 0, bk = 0, cc = 0;
                    for (VertexLabel l : {a, b, c}) {
                        f += l == VertexLabel::Front;
                        bk += l == VertexLabel::Back;
                        cc += l == VertexLabel::Contour;
                    }
                    Vbo expected = Vbo::Undefined; // CCC, CFB, FBB, FFB
                    if (bk == 0 && f > 0)          // FFF, CFF, CCF
                        expected = Vbo::Front;
                    if (f == 0 && bk > 0) // BBB, CBB, CCB
                        expected = Vbo::Back;
                    QCOMPARE(vertexBasedOrientation(a, b, c), expected);
                }
        using L = VertexLabel;
        QCOMPARE(vertexBasedOrientation(L::Contour, L::Contour, L::Contour), Vbo::Undefined);
        QCOMPARE(vertexBasedOrientation(L::Contour, L::Front, L::Back), Vbo::Undefined);
        QCOMPARE(vertexBasedOrientation(L::Front, L::Back, L::Back), Vbo::Undefined);
        QCOMPARE(vertexBasedOrientation(L::Front, L::Front, L::Back), Vbo::Undefined);
        QCOMPARE(vertexBasedOrientation(L::Contour, L::Contour, L::Front), Vbo::Front);
        QCOMPARE(vertexBasedOrientation(L::Back, L::Contour, L::Back), Vbo::Back);
    }

    // Definitions 2 and 3.
    void consistencyAndDegenerateEdges() {
        QVERIFY(isConsistent(Vbo::Front, Facing::Front));
        QVERIFY(isConsistent(Vbo::Back, Facing::Back));
        QVERIFY(!isConsistent(Vbo::Front, Facing::Back));
        QVERIFY(!isConsistent(Vbo::Back, Facing::Front));
        QVERIFY(!isConsistent(Vbo::Undefined, Facing::Front));
        QVERIFY(!isConsistent(Vbo::Front, Facing::EdgeOn));
        using L = VertexLabel;
        QVERIFY(isDegenerateEdge(L::Contour, L::Contour, Vbo::Front, Vbo::Front));
        QVERIFY(isDegenerateEdge(L::Contour, L::Contour, Vbo::Back, Vbo::Back));
        QVERIFY(!isDegenerateEdge(L::Contour, L::Contour, Vbo::Front, Vbo::Back));
        QVERIFY(!isDegenerateEdge(L::Contour, L::Front, Vbo::Front, Vbo::Front));
        QVERIFY(!isDegenerateEdge(L::Contour, L::Contour, Vbo::Undefined, Vbo::Undefined));
    }

    // Appendix B: interpolation inside a face, across a domain edge, and
    // cancelled when the faces share no chart.
    void preimageInterpolation() {
        const auto cage = shape("sphere", 8);
        const auto surface = makeSmoothSurface(*cage, SurfaceKind::CatmullClark);
        const Camera camera = Camera::views26(cage->boundingBox(), Viewport{800, 600})[0];
        const ConsistentMesh m(surface, camera, 1e-9);
        const auto same = m.interpolate({0, 0.2, 0.2}, {0, 0.6, 0.8}, 0.5);
        QVERIFY(same && same->face == 0);
        QVERIFY(std::abs(same->u - 0.4) < 1e-15 && std::abs(same->v - 0.5) < 1e-15);
        // Across edge 0 of face 0: a point inside the neighbour.
        const SmoothSurface::EdgeNeighbor nb = surface->neighbor(0, 0);
        QVERIFY(nb.face != kInvalidIndex);
        const Preimage outside = surface->transferAcrossEdge({0, 0.5, -0.3}, 0);
        QCOMPARE(outside.face, nb.face);
        QVERIFY(surface->contains(outside));
        const auto across = m.interpolate({0, 0.5, 0.3}, outside, 0.5);
        QVERIFY(across);
        // The midpoint is on the shared edge: the same surface point as (0.5, 0) in face 0.
        const Vec3 expected = surface->evaluate({0, 0.5, 0.0}).position;
        QVERIFY((surface->evaluate(*across).position - expected).norm() < 1e-9);
        // Two faces far apart share no chart: cancelled, never guessed.
        Index far = kInvalidIndex;
        const Vec3 p0 = surface->evaluate({0, 0.5, 0.5}).position;
        for (Index f = 0; f < surface->domain().faceCount(); ++f)
            if ((surface->evaluate({f, 0.5, 0.5}).position - p0).norm() > 1.5)
                far = f;
        QVERIFY(far != kInvalidIndex);
        QVERIFY(!m.interpolate({0, 0.5, 0.5}, {far, 0.5, 0.5}, 0.5));
    }

    void postconditionsOverTheProtocol_data() {
        QTest::addColumn<QString>("shapeName");
        for (const char* name : {"sphere", "torus"})
            QTest::addRow("%s", name) << QString(name);
    }
    void postconditionsOverTheProtocol() {
        QFETCH(QString, shapeName);
        const auto cage = shape(shapeName.toStdString(), shapeName == "sphere" ? 8 : 12);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        Tally t;
        for (size_t v = 0; v < views.size(); v += kViewStride) {
            const MethodRun r = runCatmullClark(cage, views[v]);
            // The input and one snapshot per phase of the method.
            QCOMPARE(r.snapshots.size(), findMethod("consistent")->phases.size() + 1);
            for (const Snapshot& s : r.snapshots)
                verifyNoViolations(s);
            const Snapshot& ins = r.phase("contour-insertion");
            QCOMPARE(ins.counter(counters::kFBEdgesLeft), 0.0);
            QCOMPARE(ins.counter(counters::kUndefinedVBOs), 0.0);
            QCOMPARE(ins.counter(counters::kDegenerateCCEdges), 0.0);
            QVERIFY(ins.counter(counters::kContourVertices) > 0);
            // |g| at C vertices, recomputed here from the published fields.
            const auto& label = *ins.field(fields::kLabel)->labels();
            const auto& g = *ins.field(fields::kG)->scalars();
            const double tol = 1e-10 * ins.mesh->boundingBox().diagonal();
            for (size_t i = 0; i < label.size(); ++i)
                if (label[i] == 0)
                    QVERIFY2(std::abs(g[i]) <= tol, qPrintable(QString("g = %1").arg(g[i])));
            int open = 0;
            const int loops = contourLoops(r.phase("chaining"), &open);
            QCOMPARE(open, 0);
            if (shapeName == "sphere")
                QCOMPARE(loops, 1);
            else
                QVERIFY(loops >= 1);
            tally(t, r);
        }
        report(qPrintable(shapeName), t,
               static_cast<int>((views.size() + kViewStride - 1) / kViewStride));
    }

    // At a crease the normal, and so g, jumps: bisection on an FB edge across
    // it stops next to the jump with |g| far above the root tolerance, yet
    // the C vertex is on the contour (g changes sign within the tolerance).
    // The post-condition holds there on the creased, open rook, and the
    // case is exercised: some C vertices have |g| above the tolerance.
    void creaseContourVertices() {
        const auto cage = sharedMesh("rook");
        if (!cage)
            QSKIP("../shared/meshes/rook.obj is absent");
        QVERIFY(!cage->creases.empty());
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        int atJumps = 0;
        for (size_t v = 0; v < views.size(); v += 5 * kViewStride) {
            const MethodRun r = runCatmullClark(cage, views[v]);
            for (const Snapshot& s : r.snapshots)
                verifyNoViolations(s);
            const Snapshot& ins = r.phase("contour-insertion");
            const auto& label = *ins.field(fields::kLabel)->labels();
            const auto& g = *ins.field(fields::kG)->scalars();
            const double tol = 1e-10 * ins.mesh->boundingBox().diagonal();
            for (size_t i = 0; i < label.size(); ++i)
                atJumps += label[i] == 0 && !(std::abs(g[i]) <= tol);
        }
        qInfo("rook: %d C vertices next to a jump of g", atJumps);
        QVERIFY(atJumps > 0);
    }

    // Tolerances given times the diagonal are the same number in every
    // phase: monsterfrog's view 23 moves a vertex on the working mesh's
    // box in the parameter wiggle, and a radial root accepted at the
    // wiggle's tolerance (7.846e-9) failed the next check, which had
    // measured a smaller box (7.843e-9), in every phase after it.
    void toleranceScaleIsTheSameInEveryPhase() {
        if (!postConditionsHoldOnView("monsterfrog", 23))
            QSKIP("../shared/meshes/monsterfrog.obj is absent");
    }

    // Appendix B's chart of a face extended across its edges is cut at a
    // domain vertex of valence 3 (DomainCharts::cutBetweenNeighbours).
    // Read in such a chart, a face of ogre's view 6 with corners in the
    // three domain faces around such a vertex looked folded in parameter
    // space from contour insertion on (8 violations over the phases). On
    // view 3 a face has a corner in each of the three faces around such a
    // vertex: every chart of it is cut, and it must still have one. On
    // view 16 the root of an FB edge next to such a vertex, bisected in one
    // chart, made a face folded in the chart it is read in; contour
    // insertion takes the root in another common chart instead.
    void noFoldReadInACutChart() {
        for (const size_t view : {3, 6, 16})
            if (!postConditionsHoldOnView("ogre_controlmesh", view))
                QSKIP("../shared/meshes/ogre_controlmesh.obj is absent");
    }

    // §6.2 e's snap rule with chart-vertex-rings (appendix B's charts of a
    // regular corner's one-ring): a vertex is snapped onto a root only when
    // each of its faces keeps a chart of one domain face and its edge
    // neighbours, or its new edges would cut diagonally across a domain
    // corner and the contour would stray from the true one (on the bumpy
    // torus, crossed-face sets then stray beyond 1 px of the dense ground
    // truth).
    // With the rule the charts change nothing up to contour insertion on
    // these shapes: the same snaps, the same inserted vertices, the same
    // mesh (the charts serve the later phases). Also the regression check of
    // snap-across-corners, which allows those snaps.
    void snapNeverCrossesCornerCharts() {
        long long snaps = 0, snapsAcross = 0;
        for (const auto& [name, resolution] :
             {std::pair{"bumpy-torus", 12}, {"ellipsoid", 12}, {"torus", 16}}) {
            const auto cage = shape(name, resolution);
            const std::vector<Camera> views =
                Camera::views26(cage->boundingBox(), Viewport{800, 600});
            for (size_t v = 0; v < views.size(); v += kViewStride) {
                // Without corner charts, with them, with them and snaps across
                // corners allowed (the rule off).
                Snapshot runs[3];
                for (int k = 0; k < 3; ++k) {
                    runs[k] = run("consistent", cage, views[v],
                                  {{"surface", "catmull-clark"},
                                   {"chart-vertex-rings", k > 0},
                                   {"snap-across-corners", k == 2}},
                                  "contour-insertion")
                                  .last();
                    QCOMPARE(runs[k].phaseName, std::string("contour-insertion"));
                    verifyNoViolations(runs[k]);
                }
                const std::string where = std::string(name) + " view " + std::to_string(v);
                QVERIFY2(runs[1].counter(counters::kSnappedVertices) ==
                             runs[0].counter(counters::kSnappedVertices),
                         qPrintable(QString::fromStdString(where) +
                                    QString(": %1 snaps with corner charts, %2 without")
                                        .arg(runs[1].counter(counters::kSnappedVertices))
                                        .arg(runs[0].counter(counters::kSnappedVertices))));
                QCOMPARE(runs[1].counter(counters::kInsertedContourVertices),
                         runs[0].counter(counters::kInsertedContourVertices));
                QCOMPARE(runs[1].mesh->faceCount(), runs[0].mesh->faceCount());
                snaps += static_cast<long long>(runs[1].counter(counters::kSnappedVertices));
                snapsAcross += static_cast<long long>(runs[2].counter(counters::kSnappedVertices));
                // The same mesh: every vertex's preimage and every face.
                QCOMPARE(runs[1].mesh->vertexCount(), runs[0].mesh->vertexCount());
                const auto& uv0 = *runs[0].field(fields::kPreimageUv)->vectors();
                const auto& uv1 = *runs[1].field(fields::kPreimageUv)->vectors();
                QVERIFY(*runs[1].field(fields::kPreimageFace)->labels() ==
                        *runs[0].field(fields::kPreimageFace)->labels());
                QVERIFY(uv1 == uv0);
                for (Index f = 0; f < runs[0].mesh->faceCount(); ++f)
                    QVERIFY(runs[1].mesh->triangle(f) == runs[0].mesh->triangle(f));
            }
        }
        // The shapes do offer snaps across corners: the rule is exercised.
        QVERIFY(snaps > 0);
        QVERIFY(snapsAcross > snaps);
        qInfo("snapped vertices over the views: %lld with and without corner charts, %lld when "
              "snaps may cross corners",
              snaps, snapsAcross);
    }

    void spotInconsistentFaces() {
        const std::string path = std::string(CONTOUR_SOURCE_DIR) + "/samples/spot_control_mesh.obj";
        // A bundled sample: its absence is a failure, not a reason to skip.
        QVERIFY2(std::filesystem::exists(path), "samples/spot_control_mesh.obj is absent");
        const auto cage = std::make_shared<const PolygonMesh>(readMesh(path));
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        Tally t;
        for (size_t v = 0; v < views.size(); v += kViewStride) {
            const Camera& camera = views[v];
            const MethodRun r = runCatmullClark(cage, camera);
            for (const Snapshot& s : r.snapshots)
                verifyNoViolations(s);
            QCOMPARE(r.phase("contour-insertion").counter(counters::kFBEdgesLeft), 0.0);
            QCOMPARE(r.phase("contour-insertion").counter(counters::kUndefinedVBOs), 0.0);
            tally(t, r);
        }
        report("spot_control_mesh", t,
               static_cast<int>((views.size() + kViewStride - 1) / kViewStride));
    }
};

QTEST_APPLESS_MAIN(TestConsistentContours)
#include "test_consistent_contours.moc"
