// The phase model: stepping, going back, immutability of snapshots,
// cancellation, parameter validation and post-condition counting.
#include "contours/Methods.h"
#include "pipeline/Runner.h"

#include <QtTest>
#include <atomic>

using namespace contour;

namespace {
std::shared_ptr<const PolygonMesh> tetrahedron() {
    auto m = std::make_shared<PolygonMesh>();
    m->positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    m->addFace({0, 2, 1});
    m->addFace({0, 1, 3});
    m->addFace({0, 3, 2});
    m->addFace({1, 2, 3});
    return m;
}

Camera frontCamera() {
    Camera c;
    c.eye = Vec3(2, 1.5, 3);
    c.target = Vec3(0.25, 0.25, 0.25);
    return c;
}

// A method whose second phase can be cancelled and whose third phase always
// breaks its own post-condition, to test the Runner itself.
Method testMethod(std::atomic<int>* cancelChecks) {
    Method m;
    m.name = "test";
    m.parameters = {{"count", "Count", "a number", ParameterType::Int, 3, 0, 10, {}}};
    m.phases = {
        {"first",
         "adds a counter",
         [](const PhaseContext& ctx, Snapshot& s) {
             s.setCounter("count", ctx.parameters.getInt("count"));
         },
         {}},
        {"second",
         "checks for cancellation",
         [cancelChecks](const PhaseContext& ctx, Snapshot& s) {
             ++*cancelChecks;
             ctx.reportProgress(0.5);
             ctx.checkCancelled();
             s.setCounter("second", 1);
         },
         {}},
        {"third", "breaks its post-condition", [](const PhaseContext&, Snapshot&) {},
         [](const PhaseContext&, const Snapshot&) {
             return std::vector<InvariantCheck>{{"nothing is wrong", 2, "face 0"}};
         }},
    };
    return m;
}
} // namespace

class TestPipeline : public QObject {
    Q_OBJECT
private slots:
    void registryHasBothMethodsWithTheirPhases() {
        for (const char* name : {"mesh", "interpolated"}) {
            const Method* m = findMethod(name);
            QVERIFY(m);
            QVERIFY(m->phases.size() >= 4);
            QCOMPARE(QString::fromStdString(m->phases[0].name), QString("surface"));
            QCOMPARE(QString::fromStdString(m->phases[1].name), QString("facing"));
            QCOMPARE(QString::fromStdString(m->phases[2].name), QString("extraction"));
            QCOMPARE(QString::fromStdString(m->phases[3].name), QString("chaining"));
            QVERIFY(m->parameter("surface") && m->parameter("tessellation-level"));
            QVERIFY(
                validateParameters(m->parameters, ParameterSet::defaults(m->parameters)).empty());
        }
        QVERIFY(findMethod("consistent"));
        QVERIFY(!findPlannedMethod("consistent"));
        QVERIFY(findPlannedMethod("powell-sabin"));
        QVERIFY(findPlannedMethod("traced"));
        QVERIFY(!findMethod("traced"));
    }

    void stepBackAndSnapshotsStayUnchanged() {
        const Method& m = *findMethod("mesh");
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        QCOMPARE(r.completedPhases(), 0);
        QVERIFY(r.step()); // surface: none, the triangulated cage stays
        QVERIFY(!r.current().field("facing"));
        QVERIFY(r.current().mesh == r.snapshot(0).mesh);
        QVERIFY(r.step());
        const Snapshot afterFacing = r.current();
        QVERIFY(afterFacing.field("facing"));
        QVERIFY(!afterFacing.field("contour_edge"));
        r.runToEnd();
        QVERIFY(r.atEnd());
        QVERIFY(!r.step());
        // The earlier snapshot did not see later phases' fields.
        QVERIFY(!r.snapshot(2).field("contour_edge"));
        QVERIFY(r.snapshot(2).field("facing") == afterFacing.field("facing"));
        QVERIFY(r.current().curves && !r.current().curves->empty());
        QVERIFY(r.back());
        QCOMPARE(r.completedPhases(), static_cast<int>(m.phases.size()) - 1);
        r.reset();
        QCOMPARE(r.completedPhases(), 0);
        QVERIFY(!r.back());
        r.runTo(3);
        QCOMPARE(r.current().phaseName, std::string("extraction"));
        QCOMPARE(r.current().phaseIndex, 2);
        QVERIFY(r.current().phaseSeconds >= 0.0);
    }

    // Stepping again after going back gives the same result.
    void deterministic() {
        const Method& m = *findMethod("interpolated");
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        r.runToEnd();
        const auto counters = r.current().counters;
        r.back();
        r.back();
        r.runToEnd();
        QCOMPARE(r.current().counters.size(), counters.size());
        // Timings and cache hits are not results: they may differ.
        for (size_t i = 0; i < counters.size(); ++i) {
            const std::string& name = counters[i].name;
            if (name.find("seconds") != std::string::npos ||
                name.find("cached") != std::string::npos)
                continue;
            QCOMPARE(r.current().counters[i].value, counters[i].value);
        }
    }

    void badParametersAndCameraAreRejected() {
        const Method& m = *findMethod("interpolated");
        ParameterSet p = ParameterSet::defaults(m.parameters);
        p.set("normal-weighting", std::string("cotangent"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 Runner(m, makeInputSnapshot(tetrahedron()), frontCamera(), p));
        ParameterSet q = ParameterSet::defaults(m.parameters);
        q.set("drop-concave", true); // belongs to the mesh method
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 Runner(m, makeInputSnapshot(tetrahedron()), frontCamera(), q));
        Camera bad = frontCamera();
        bad.target = bad.eye;
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            Runner(m, makeInputSnapshot(tetrahedron()), bad, ParameterSet::defaults(m.parameters)));
    }

    void parseParameters() {
        const Method& m = *findMethod("interpolated");
        QCOMPARE(std::get<std::string>(parseParameter(*m.parameter("normal-weighting"), "angle")),
                 std::string("angle"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 parseParameter(*m.parameter("normal-weighting"), "cot"));
        QCOMPARE(std::get<bool>(parseParameter(*m.parameter("include-boundaries"), "false")),
                 false);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 parseParameter(*m.parameter("include-boundaries"), "maybe"));
        ParameterSpec n{"n", "n", "", ParameterType::Int, 1, 0, 10, {}};
        QCOMPARE(std::get<int>(parseParameter(n, "7")), 7);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseParameter(n, "11"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseParameter(n, "7.5"));
        ParameterSpec x{"x", "x", "", ParameterType::Double, 0.5, 0, 1, {}};
        QCOMPARE(std::get<double>(parseParameter(x, "0.25")), 0.25);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseParameter(x, "nan"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseParameter(x, "0.25abc"));
    }

    void cancellationLeavesStateUnchanged() {
        std::atomic<int> checks{0};
        const Method m = testMethod(&checks);
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        QVERIFY(r.step());
        QCOMPARE(r.current().counter("count"), 3.0);
        double progress = -1;
        r.setProgressCallback([&](int phase, double fraction) {
            QCOMPARE(phase, 1);
            progress = fraction;
            r.requestCancel(); // as the GUI's cancel button would, mid-phase
        });
        QVERIFY_THROWS_EXCEPTION(PhaseCancelled, r.step());
        QCOMPARE(progress, 0.5);
        QCOMPARE(r.completedPhases(), 1);
        r.setProgressCallback({});
        QVERIFY(r.step()); // a new step clears the cancel request
        QCOMPARE(r.current().counter("second"), 1.0);
    }

    // Post-conditions are counted in every build; debug builds fail the phase.
    void postconditionViolations() {
        std::atomic<int> checks{0};
        const Method m = testMethod(&checks);
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        r.runTo(2);
#ifdef CONTOUR_CHECK_INVARIANTS
        QVERIFY_THROWS_EXCEPTION(PhaseError, r.step());
        QCOMPARE(r.completedPhases(), 2);
#else
        QVERIFY(r.step());
        QCOMPARE(r.current().invariantViolations(), 2LL);
        QCOMPARE(QString::fromStdString(r.current().invariants[0].firstExample), QString("face 0"));
#endif
    }
};

QTEST_APPLESS_MAIN(TestPipeline)
#include "test_pipeline.moc"
