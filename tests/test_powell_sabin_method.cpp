// The Powell-Sabin method's phases up to the fitted surface (Capouellez et
// al. 2023 §3, §5): every phase runs with its post-conditions met on closed
// meshes of genus 0 and 1 and on spot, the preprocessing is cached across
// cameras, the projective transform is exact, an orthographic fit does not
// depend on the view, an OBJ's texture coordinates are read as the layout,
// and a mesh the conformal map cannot handle gets a message.
#include "ContourTestSupport.h"
#include "contours/powell_sabin/PowellSabinState.h"
#include "contours/powell_sabin/ProjectiveTransform.h"
#include "contours/powell_sabin/SplineTessellation.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/FieldNames.h"

#include <QTemporaryDir>
#include <QtTest>
#include <fstream>

using namespace contour;
using namespace contour::testing;

namespace {

const std::vector<std::string> kPhases{
    "cones", "conformal-map",  "layout",   "patches", "factorization",
    "fit",   "patch-contours", "chaining", "cusps",   "visibility"};

long long violations(const MethodRun& r) {
    long long n = 0;
    for (const Snapshot& s : r.snapshots)
        n += s.invariantViolations();
    return n;
}

std::string violationReport(const MethodRun& r) {
    std::string text;
    for (const Snapshot& s : r.snapshots)
        for (const InvariantCheck& c : s.invariants)
            if (c.violations > 0)
                text += s.phaseName + ": " + c.name + " (" + std::to_string(c.violations) + ", " +
                        c.firstExample + ")\n";
    return text;
}

Camera viewOf(const PolygonMesh& mesh, const Vec3& direction, bool orthographic = false) {
    Camera c = Camera::framing(mesh.boundingBox(), direction, Viewport{800, 600});
    if (orthographic)
        c.projection = Projection::Orthographic;
    return c;
}

int countLabel(const Snapshot& s, const char* field, int value) {
    const Field* f = s.field(field);
    if (!f || !f->labels())
        return -1;
    return static_cast<int>(std::count(f->labels()->begin(), f->labels()->end(), value));
}

} // namespace

class TestPowellSabinMethod : public QObject {
    Q_OBJECT
private slots:
    void projectiveTransformIsExactAndInvertible() {
        Camera c;
        c.eye = Vec3(1.0, 2.0, 5.0);
        c.target = Vec3(0.2, -0.1, 0.3);
        const powell_sabin::ProjectiveTransform t(c);
        QVERIFY(t.isPerspective());
        const Vec3 p(0.3, -0.4, 0.7);
        const Vec3 q = t.apply(p);
        QVERIFY((t.invert(q) - p).norm() < 1e-12);
        // The transformed point's x, y are the camera-space x/d, y/d (§3),
        // so orthographic projection along z gives the perspective image.
        const Vec3 d = p - c.eye;
        QVERIFY(std::abs(q.x() - d.dot(c.right()) / d.dot(c.forward())) < 1e-12);
        QVERIFY(std::abs(q.z() + 1.0 / d.dot(c.forward())) < 1e-12);
        // The inverse's Jacobian against central differences.
        const Eigen::Matrix3d j = t.inverseJacobian(q);
        for (int k = 0; k < 3; ++k) {
            const Vec3 step = 1e-6 * Vec3::Unit(k);
            const Vec3 fd = (t.invert(q + step) - t.invert(q - step)) / 2e-6;
            QVERIFY2((fd - j.col(k)).norm() < 1e-6 * (1.0 + fd.norm()),
                     qPrintable(QString("column %1").arg(k)));
        }
    }

    void sphereRunsEveryPhaseWithItsChecks() {
        const auto sphere = shape("sphere", 12);
        const MethodRun r = run("powell-sabin", sphere, viewOf(*sphere, Vec3(0.3, 0.4, 1.0)));
        QCOMPARE(static_cast<int>(r.snapshots.size()), static_cast<int>(kPhases.size()) + 1);
        for (size_t i = 0; i < kPhases.size(); ++i)
            QCOMPARE(QString::fromStdString(r.snapshots[i + 1].phaseName),
                     QString::fromStdString(kPhases[i]));
        QVERIFY2(violations(r) == 0, violationReport(r).c_str());
        const Snapshot& cones = r.phase("cones");
        QCOMPARE(cones.counter(counters::kGenus), 0.0);
        QCOMPARE(cones.counter(counters::kCones), 8.0);
        QCOMPARE(countLabel(cones, fields::kCone, 1), 8);
        QVERIFY(cones.counter(counters::kConeTrianglesSplit) > 0.0);
        const Snapshot& map = r.phase("conformal-map");
        QVERIFY(map.counter(counters::kMaxAngleSumError) <= 1e-9);
        const Snapshot& layout = r.phase("layout");
        QCOMPARE(layout.counter(counters::kFlippedUvTriangles), 0.0);
        QVERIFY(layout.counter(counters::kCutEdges) > 0.0);
        QVERIFY(layout.field(fields::kCornerUv0) && layout.field(fields::kLogAreaRatio));
        const Snapshot& patches = r.phase("patches");
        QCOMPARE(patches.counter(counters::kPatches), 12.0 * layout.mesh->faceCount());
        QVERIFY(patches.counter(counters::kQuadraticPrecisionError) < 1e-9);
        const Snapshot& fit = r.phase("fit");
        QVERIFY(fit.counter(counters::kFitResidual) < 1e-12);
        // A fitted sphere stays close to its input (w = 1: 3.0 % of the
        // diagonal at most, measured; the thin-plate term pulls the coarse
        // mesh in a little).
        QVERIFY2(fit.counter(counters::kFitMaxDistance) < 0.04,
                 qPrintable(QString::number(fit.counter(counters::kFitMaxDistance))));
        QCOMPARE(fit.counter(counters::kTessellationFaces),
                 12.0 * 4.0 * layout.mesh->faceCount()); // level 2: 4 per patch
        QVERIFY(fit.field(fields::kPatch) && fit.field(fields::kPatchEdge) &&
                fit.field(fields::kFitOffset) && fit.field(fields::kVertexNormal));
        QCOMPARE(countLabel(fit, fields::kCone, 1), 8);
        QVERIFY(countLabel(fit, fields::kPatchEdge, 3) > 0); // the cut
        QVERIFY(fit.viewGraph == nullptr);
        // §4: the contour of a sphere is one loop (through cones, where the
        // cone patches' lines cross, it is chained cone to cone), no cusps.
        const Snapshot& chains = r.phase("chaining");
        QCOMPARE(chains.counter(counters::kUnmatchedSegmentEnds), 0.0);
        QVERIFY(chains.counter(counters::kContourLoops) +
                    chains.counter(counters::kOpenContourChains) >=
                1.0);
        QVERIFY(chains.counter(counters::kContourSegments) > 0.0);
        QCOMPARE(r.last().counter(counters::kInteriorCusps), 0.0);
        QCOMPARE(r.last().counter(counters::kBoundaryCusps), 0.0);
        QVERIFY(r.last().curves && !r.last().curves->empty());
        // §4.2: a sphere's contour is visible everywhere, with no T-junction,
        // fold or conflict.
        const Snapshot& visibility = r.last();
        QVERIFY(visibility.viewGraph);
        QVERIFY(!visibility.viewGraph->chains.empty());
        for (const ViewChain& chain : visibility.viewGraph->chains)
            QCOMPARE(chain.qi, 0);
        QCOMPARE(visibility.counter(counters::kTJunctions), 0.0);
        QCOMPARE(visibility.counter(counters::kConflicts), 0.0);
    }

    void torusHasNoConesAndACut() {
        const auto torus = shape("torus", 16);
        const MethodRun r = run("powell-sabin", torus, viewOf(*torus, Vec3(0.2, 1.0, 0.6)));
        QVERIFY2(violations(r) == 0, violationReport(r).c_str());
        QCOMPARE(r.phase("cones").counter(counters::kGenus), 1.0);
        QCOMPARE(r.phase("cones").counter(counters::kCones), 0.0);
        QVERIFY(r.phase("layout").counter(counters::kCutEdges) > 0.0);
        // No cones: every chain is a closed loop.
        QCOMPARE(r.phase("chaining").counter(counters::kOpenContourChains), 0.0);
        QVERIFY(r.phase("chaining").counter(counters::kContourLoops) >= 1.0);
        // Cusps come in pairs on a closed loop of a generic view.
        const double cusps =
            r.last().counter(counters::kInteriorCusps) + r.last().counter(counters::kBoundaryCusps);
        QVERIFY2(std::fmod(cusps, 2.0) == 0.0, qPrintable(QString::number(cusps)));
        // A coarse torus (16 x 16): measured 5.7 % of the diagonal.
        const double distance = r.last().counter(counters::kFitMaxDistance);
        QVERIFY2(distance < 0.08, qPrintable(QString::number(distance)));
    }

    void spotRunsWithoutViolations() {
        const auto spot = sampleOrShape("spot", 0);
        const MethodRun r = run("powell-sabin", spot, viewOf(*spot, Vec3(1.0, 0.3, 0.5)));
        QVERIFY2(violations(r) == 0, violationReport(r).c_str());
        QCOMPARE(r.phase("cones").counter(counters::kCones), 8.0);
        QCOMPARE(r.phase("layout").counter(counters::kFlippedUvTriangles), 0.0);
        // The coarse cage's horns and ears lie where the conformal scale is
        // smallest, so the thin-plate term is strongest there (measured 11 %).
        const double distance = r.last().counter(counters::kFitMaxDistance);
        QVERIFY2(distance < 0.15, qPrintable(QString::number(distance)));
    }

    void paperPresetKeepsTheUvThinPlate() {
        // The paper's eq. 8 integrates the thin plate over uv; by default each
        // face's term is measured in the surface's metric. The ellipsoid's
        // conformal scale varies, so the two fits differ; both are C1 fits
        // with their checks met.
        const auto ellipsoid = shape("ellipsoid", 10);
        const Camera camera = viewOf(*ellipsoid, Vec3(0.3, 0.2, 1.0));
        const Method& m = *findMethod("powell-sabin");
        const ParameterSet paper = presetValues(m.parameters, *m.preset("paper"));
        QVERIFY(!paper.getBool("thin-plate-in-surface-metric"));
        Runner r(m, makeInputSnapshot(ellipsoid), camera, paper);
        r.runToEnd();
        const MethodRun asWritten{r.snapshots()};
        QVERIFY2(violations(asWritten) == 0, violationReport(asWritten).c_str());
        const MethodRun byDefault = run("powell-sabin", ellipsoid, camera);
        const double a = asWritten.last().counter(counters::kFitMaxDistance);
        const double b = byDefault.last().counter(counters::kFitMaxDistance);
        QVERIFY2(std::abs(a - b) > 1e-6 * std::max(a, b),
                 qPrintable(QString("%1 %2").arg(a).arg(b)));
    }

    void aNewCameraReusesThePreprocessing() {
        const auto sphere = shape("sphere", 10);
        const MethodRun first = run("powell-sabin", sphere, viewOf(*sphere, Vec3(0, 0, 1)));
        const MethodRun second = run("powell-sabin", sphere, viewOf(*sphere, Vec3(1, 0.5, 0)));
        for (const char* phase : {"cones", "conformal-map", "layout", "patches", "factorization"})
            QVERIFY2(second.phase(phase).counter(counters::kPreprocessingCached) == 1.0, phase);
        QCOMPARE(first.phase("factorization").counter(counters::kPreprocessingCached), 0.0);
        // The perspective fits differ (the surface is view-dependent, §3).
        const TriangleMesh& a = *first.last().mesh;
        const TriangleMesh& b = *second.last().mesh;
        QCOMPARE(a.vertexCount(), b.vertexCount());
        double largest = 0.0;
        for (Index v = 0; v < a.vertexCount(); ++v)
            largest = std::max(largest, (a.position(v) - b.position(v)).norm());
        QVERIFY(largest > 1e-6);
    }

    void aNewCameraReevaluatesTheTessellation() {
        // The welding of the drawing tessellation is built once per layout,
        // in the preprocessing, and re-evaluated for each view: the result
        // must be the tessellation of the view's spline made from scratch,
        // and the view-independent fields are shared between views.
        const auto sphere = shape("ellipsoid", 8);
        const MethodRun first =
            run("powell-sabin", sphere, viewOf(*sphere, Vec3(0, 0, 1)), {}, "fit");
        QVERIFY(first.phase("factorization").counter(counters::kWeldingSeconds) > 0.0);
        const Camera camera = viewOf(*sphere, Vec3(1, 0.4, -0.3));
        const MethodRun second = run("powell-sabin", sphere, camera, {}, "fit");
        QCOMPARE(second.phase("factorization").counter(counters::kWeldingSeconds), 0.0);
        QCOMPARE(second.phase("factorization").counter(counters::kPreprocessingCached), 1.0);
        for (const char* name :
             {fields::kPatch, fields::kPatchEdge, fields::kCornerUv0, fields::kCone})
            QVERIFY2(first.last().fields.at(name) == second.last().fields.at(name), name);
        QVERIFY(first.last().fields.at(fields::kVertexNormal) !=
                second.last().fields.at(fields::kVertexNormal));
        const Snapshot& fit = second.last();
        const powell_sabin::PowellSabinState* state = powell_sabin::powellSabinState(fit);
        QVERIFY(state && state->spline && state->layout);
        const powell_sabin::ProjectiveTransform transform(camera);
        powell_sabin::SplineToWorld toWorld;
        toWorld.point = [&](const Vec3& p) {
            return transform.invert(p);
        };
        toWorld.jacobian = [&](const Vec3& p) {
            return transform.inverseJacobian(p);
        };
        const powell_sabin::SplineTessellation fresh = powell_sabin::tessellateSpline(
            *state->spline, *state->layout, state->tessellationLevel, toWorld);
        const TriangleMesh& drawn = *fit.mesh;
        QCOMPARE(drawn.vertexCount(), fresh.mesh.vertexCount());
        QCOMPARE(drawn.faceCount(), fresh.mesh.faceCount());
        for (Index f = 0; f < drawn.faceCount(); ++f)
            QVERIFY(drawn.triangle(f) == fresh.mesh.triangle(f));
        for (Index v = 0; v < drawn.vertexCount(); ++v)
            QVERIFY(drawn.position(v) == fresh.mesh.position(v));
        const std::vector<Vec3>* normals = fit.field(fields::kVertexNormal)->vectors();
        QVERIFY(normals && *normals == fresh.normals);
        QCOMPARE(*fit.field(fields::kPatch)->labels(), fresh.patch);
        QVERIFY(fit.counter(counters::kTessellationSeconds) >= 0.0);
        // A spline of another layout is refused.
        powell_sabin::PowellSabinSpline other = *state->spline;
        other.patches.resize(other.patches.size() / 2);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 powell_sabin::evaluateTessellationPoints(fresh, other, toWorld));
    }

    void shortChainsTakeTheirQiByPropagation() {
        // Sub-pixel chains next to cusps take their QI from their neighbours
        // (min-ray-chain-pixels); with 0 every chain has its own ray. The
        // nodes and the longer chains' rays are the same either way, and the
        // propagated values follow the rule of the node they came through.
        const auto spot = sampleOrShape("spot", 0);
        const std::vector<Camera> views = Camera::views26(spot->boundingBox(), Viewport{800, 600});
        long long conflictsEveryRay = 0, conflictsPropagated = 0, propagated = 0;
        for (const Camera& camera : views) {
            const Snapshot everyRay =
                run("powell-sabin", spot, camera, {{"min-ray-chain-pixels", 0.0}}).last();
            const ViewGraph& all = *everyRay.viewGraph;
            const Snapshot last = run("powell-sabin", spot, camera).last();
            const ViewGraph& g = *last.viewGraph;
            QCOMPARE(g.chains.size(), all.chains.size());
            QCOMPARE(g.nodes.size(), all.nodes.size());
            conflictsEveryRay += static_cast<long long>(all.conflicts.size());
            conflictsPropagated += static_cast<long long>(g.conflicts.size());
            for (size_t c = 0; c < g.chains.size(); ++c) {
                const ViewChain& a = all.chains[c];
                const ViewChain& b = g.chains[c];
                QCOMPARE(a.decidedBy, VisibilityRule::RayTest);
                QVERIFY(b.qi >= 0);
                if (b.closed || b.lengthPixels >= 1.0) {
                    QCOMPARE(b.decidedBy, VisibilityRule::RayTest);
                    QCOMPARE(b.qi, a.qi);
                    continue;
                }
                if (b.decidedBy != VisibilityRule::Propagation)
                    continue; // a seed ray on the longest chain of a component
                ++propagated;
                QCOMPARE(b.rayQi, -1);
                const ViewNode& via = g.nodes[b.propagatedVia];
                const int from = g.chains[b.propagatedFrom].qi;
                const Index self = static_cast<Index>(c);
                if (via.type == ViewNodeType::CurtainFold) {
                    QVERIFY(!via.unreliable);
                    QCOMPARE(b.qi - from, self == via.farChains[1] ? 1 : -1);
                } else {
                    QCOMPARE(via.type, ViewNodeType::ImageIntersection);
                    const bool near = self == via.nearChains[0] || self == via.nearChains[1];
                    QCOMPARE(b.qi - from, near ? 0 : self == via.farChains[1] ? 2 : -2);
                }
            }
            long long propagatedHere = 0;
            for (const ViewChain& c : g.chains)
                propagatedHere += c.decidedBy == VisibilityRule::Propagation;
            QCOMPARE(last.counter(counters::kPropagatedChains),
                     static_cast<double>(propagatedHere));
        }
        qInfo("spot, 26 views: conflicts %lld with a ray on every chain, %lld with %lld "
              "sub-pixel chains propagated",
              conflictsEveryRay, conflictsPropagated, propagated);
        QVERIFY(propagated > 0);
        // The sub-pixel chains' own rays are what disagreed (89 against 47
        // when measured).
        QVERIFY(conflictsPropagated < conflictsEveryRay);
    }

    void touchingBranchesAreNotTJunctions() {
        // Where the contour runs along a patch side, a boundary cusp's two
        // branches run back along each other within 1e-9 px, and their
        // chords cross where the curves only touch (Newton stalls 1e-9 to
        // 1e-6 px short). Before the far curve had to change sides of the
        // near one, spot's view 4 had 3 conflicts (touching branches taken
        // as T-junctions, each failing its +2 against the rays), and 11 of
        // the 26 views had none.
        const auto spot = sampleOrShape("spot", 0);
        const std::vector<Camera> views = Camera::views26(spot->boundingBox(), Viewport{800, 600});
        int clean = 0;
        double touching = 0.0;
        for (size_t v = 0; v < views.size(); ++v) {
            const Snapshot last = run("powell-sabin", spot, views[v]).last();
            const ViewGraph& g = *last.viewGraph;
            clean += g.conflicts.empty();
            touching += last.counter(counters::kTouchingCrossings);
            if (v != 4)
                continue;
            QCOMPARE(g.conflicts.size(), size_t(0));
            // The graph's T-junctions are crossings of the curves: the rays
            // on every chain, however short, follow the rules at them.
            const Snapshot everyRay =
                run("powell-sabin", spot, views[v], {{"min-ray-chain-pixels", 0.0}}).last();
            for (const ViewNode& node : everyRay.viewGraph->nodes) {
                if (node.type != ViewNodeType::ImageIntersection)
                    continue;
                const auto& c = everyRay.viewGraph->chains;
                QCOMPARE(c[node.nearChains[0]].qi, c[node.nearChains[1]].qi);
                QCOMPARE(c[node.farChains[1]].qi - c[node.farChains[0]].qi, node.qiStep);
            }
        }
        qInfo("spot, 26 views: %d without conflicts; %.0f touching meetings left out", clean,
              touching);
        QVERIFY(touching > 0.0);
        QVERIFY(clean >= baseline("test_powell_sabin_method", "spot: views without conflicts"));
    }

    void orthographicFitDoesNotDependOnTheView() {
        // The thin-plate energy and the fit are invariant under rotations, so
        // two orthographic views give the same surface in world coordinates.
        const auto sphere = shape("ellipsoid", 10);
        const Snapshot a =
            run("powell-sabin", sphere, viewOf(*sphere, Vec3(0, 0, 1), true), {}, "fit").last();
        const Snapshot b =
            run("powell-sabin", sphere, viewOf(*sphere, Vec3(0.7, 0.2, -0.4), true), {}, "fit")
                .last();
        double largest = 0.0;
        for (Index v = 0; v < a.mesh->vertexCount(); ++v)
            largest = std::max(largest, (a.mesh->position(v) - b.mesh->position(v)).norm());
        QVERIFY2(largest < 1e-9, qPrintable(QString::number(largest)));
    }

    void textureCoordinatesAreTheLayout() {
        // Write the computed layout as an OBJ with per-corner vt, read it back:
        // the method takes its cones and cut from the texture coordinates.
        const auto sphere = shape("sphere", 10);
        const Camera camera = viewOf(*sphere, Vec3(0.2, 0.3, 1.0));
        const MethodRun computed = run("powell-sabin", sphere, camera, {}, "layout");
        const Snapshot& layout = computed.last();
        QTemporaryDir dir;
        const std::string path = dir.filePath("layout.obj").toStdString();
        {
            std::ofstream out(path);
            out.precision(17);
            for (const Vec3& p : layout.mesh->positions())
                out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
            const std::array<const char*, 3> names{fields::kCornerUv0, fields::kCornerUv1,
                                                   fields::kCornerUv2};
            for (Index f = 0; f < layout.mesh->faceCount(); ++f)
                for (const char* name : names) {
                    const Vec3& uv = (*layout.field(name)->vectors())[f];
                    out << "vt " << uv.x() << ' ' << uv.y() << '\n';
                }
            for (Index f = 0; f < layout.mesh->faceCount(); ++f) {
                out << 'f';
                for (int c = 0; c < 3; ++c)
                    out << ' ' << layout.mesh->triangle(f)[c] + 1 << '/' << 3 * f + c + 1;
                out << '\n';
            }
        }
        auto loaded = std::make_shared<const PolygonMesh>(readMesh(path));
        QVERIFY(loaded->hasTextureCoordinates());
        const MethodRun fromUv = run("powell-sabin", loaded, camera);
        QVERIFY2(violations(fromUv) == 0, violationReport(fromUv).c_str());
        QCOMPARE(fromUv.phase("cones").counter(counters::kCones),
                 computed.phase("cones").counter(counters::kCones));
        QCOMPARE(fromUv.phase("layout").counter(counters::kCutEdges),
                 layout.counter(counters::kCutEdges));
        QCOMPARE(fromUv.phase("conformal-map").counter(counters::kNewtonIterations), 0.0);
        bool said = false;
        for (const std::string& note : fromUv.phase("conformal-map").notes)
            said |= note.find("texture coordinates") != std::string::npos;
        QVERIFY(said);
        // Asking for texture coordinates on a mesh without them is an error.
        QVERIFY_THROWS_EXCEPTION(std::exception,
                                 run("powell-sabin", sphere, camera,
                                     Overrides().set("parameterization", "texture-coordinates")));
    }

    void anUnmappableMeshSaysWhy() {
        // No cones on a sphere: Gauss-Bonnet leaves no flat metric.
        const auto sphere = shape("sphere", 8);
        try {
            run("powell-sabin", sphere, viewOf(*sphere, Vec3(0, 0, 1)),
                Overrides().set("cones-per-component", 0));
            QFAIL("the conformal map of a sphere without cones succeeded");
        } catch (const std::exception& e) {
            const std::string what = e.what();
            QVERIFY2(what.find("conformal map") != std::string::npos, what.c_str());
        }
    }
};

QTEST_GUILESS_MAIN(TestPowellSabinMethod)
#include "test_powell_sabin_method.moc"
