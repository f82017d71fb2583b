// The phase model: stepping, going back, immutability of snapshots,
// cancellation, parameter validation and post-condition counting.
#include "contours/Methods.h"
#include "pipeline/Runner.h"

#include <QtTest>
#include <atomic>
#include <memory>
#include <optional>

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
// The runner whose cancel the toy branch's plan requests (null: none), as
// the GUI's cancel button would while the variants run.
Runner* gCancelDuringBranch = nullptr;

// Branch data of the toy branch: the variant's tag, read by the re-run phase.
struct ToyTag : BranchData {
    explicit ToyTag(int t) : tag(t) {}
    int tag;
};

// A method with a branch: "start" sets value 10, "adjust" adds the
// parameter "offset" (and records the branch data's tag), "finish" keeps the
// value and breaks its post-condition when it equals "bad", "after" records
// the offset it sees. The branch, decided after "finish" and re-running from
// "adjust", tries the offsets +1, -3, -2, -10 and -4 (and -5 with
// "offer-broken" first) and judges the runs by their value; 0 is perfect.
Method branchingMethod(std::atomic<int>* adjustRuns) {
    Method m;
    m.name = "branching";
    m.parameters = {{"offset", "Offset", "", ParameterType::Int, 0, -20, 20, {}},
                    {"bad", "Bad", "", ParameterType::Int, -100, -100, 100, {}},
                    {"offer-broken", "Offer broken", "", ParameterType::Bool, false, 0, 0, {}}};
    m.phases = {
        {"start", "", [](const PhaseContext&, Snapshot& s) { s.setCounter("value", 10); }, {}},
        {"adjust", "",
         [adjustRuns](const PhaseContext& ctx, Snapshot& s) {
             ++*adjustRuns;
             ctx.checkCancelled();
             s.setCounter("value", s.counter("value") + ctx.parameters.getInt("offset"));
             const ToyTag* tag = ctx.branchData<ToyTag>();
             s.setCounter("tag", tag ? tag->tag : -1);
         },
         [](const PhaseContext&, const Snapshot&) {
             return std::vector<InvariantCheck>{{"adjusted", 0, ""}};
         }},
        {"finish", "", [](const PhaseContext&, Snapshot& s) { s.setCounter("finished", 1); },
         [](const PhaseContext& ctx, const Snapshot& s) {
             const bool bad = s.counter("value") == ctx.parameters.getInt("bad");
             return std::vector<InvariantCheck>{{"value is not bad", bad ? 1 : 0, "value"}};
         }},
        {"after",
         "",
         [](const PhaseContext& ctx, Snapshot& s) {
             s.setCounter("offset after", ctx.parameters.getInt("offset"));
         },
         {}},
    };
    BranchRule rule;
    rule.name = "toy";
    rule.decideAfter = "finish";
    rule.rerunFrom = "adjust";
    rule.plan = [](const PhaseContext& ctx, const Snapshot&) {
        if (gCancelDuringBranch)
            gCancelDuringBranch->requestCancel();
        BranchPlan plan;
        std::vector<int> offsets{1, -3, -2, -10, -4};
        if (ctx.parameters.getBool("offer-broken"))
            offsets.insert(offsets.begin(), -5);
        for (int offset : offsets)
            plan.variants.push_back({"offset " + std::to_string(offset),
                                     {{"offset", offset}},
                                     std::make_shared<const ToyTag>(100 + offset)});
        return plan;
    };
    rule.figure = [](const Snapshot& s) {
        return std::optional<double>(s.counter("value"));
    };
    rule.perfect = 0.0;
    rule.report = [](const PhaseContext&, const BranchSummary& b, Snapshot& s) {
        s.setCounter("toy runs", static_cast<double>(b.runs.size()));
        s.setCounter("toy adopted", b.adopted);
        return std::string("toy branch: run ") + std::to_string(b.adopted) + " adopted";
    };
    m.branches.push_back(rule);
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
        // Powell-Sabin runs up to its fitted surface; its contours are part of
        // its description's "not computed yet".
        const Method* ps = findMethod("powell-sabin");
        QVERIFY(ps);
        QVERIFY(!findPlannedMethod("powell-sabin"));
        QCOMPARE(QString::fromStdString(ps->phases.front().name), QString("cones"));
        QVERIFY(ps->phaseIndex("fit") > 0);
        QCOMPARE(QString::fromStdString(ps->phases.back().name), QString("visibility"));
        QVERIFY(validateParameters(ps->parameters, ParameterSet::defaults(ps->parameters)).empty());
        // Summers 2016's traced curves run, on the limit surface, to the
        // common view graph.
        const Method* tracedMethod = findMethod("traced");
        QVERIFY(tracedMethod);
        QVERIFY(!findPlannedMethod("traced"));
        QVERIFY(tracedMethod->phaseIndex("edge-seeds") > 0);
        QVERIFY(tracedMethod->phaseIndex("tracing") > tracedMethod->phaseIndex("interior-seeds"));
        QVERIFY(tracedMethod->phaseIndex("visibility") > tracedMethod->phaseIndex("cusps"));
        QVERIFY(validateParameters(tracedMethod->parameters,
                                   ParameterSet::defaults(tracedMethod->parameters))
                    .empty());
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

    // The branch runs its variants from the snapshot before rerunFrom,
    // judges them in order (a run adopted when strictly better than the best
    // so far; none judged after a perfect one), and the adopted run's own
    // snapshots replace the range; later phases see the base parameters.
    void branchAdoptsFirstBetterRunsInOrder() {
        std::atomic<int> adjustRuns{0};
        const Method m = branchingMethod(&adjustRuns);
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        r.runTo(2);
        QCOMPARE(r.current().counter("value"), 10.0);
        QVERIFY(!r.current().run.inBranch());
        QVERIFY(r.step()); // finish: the branch is decided
        QCOMPARE(r.completedPhases(), 3);
        const auto summaries = r.branchSummaries();
        QCOMPARE(summaries.size(), size_t{1});
        const BranchSummary& b = *summaries[0];
        QCOMPARE(b.firstFigure, 10.0);
        // +1 (11) no better, -3 (7) adopted, -2 (8) no better than 7,
        // -10 (0) adopted and perfect: -4 is not judged.
        QCOMPARE(b.runs.size(), size_t{4});
        QCOMPARE(b.adopted, 4);
        QCOMPARE(QString::fromStdString(b.runs[3].label), QString("offset -10"));
        QVERIFY(!b.runs[0].better && !b.runs[0].adopted);
        QVERIFY(b.runs[1].better && !b.runs[1].adopted); // superseded by run 4
        QVERIFY(!b.runs[2].better);
        QVERIFY(b.runs[3].better && b.runs[3].adopted && b.runs[3].postconditionsKept);
        QCOMPARE(*b.runs[1].figure, 7.0);
        // The range is the adopted run's: value, tag (its branch data),
        // post-conditions of every re-run phase, and the run marks.
        for (int completed : {2, 3}) {
            const Snapshot& s = r.snapshot(completed);
            QCOMPARE(s.counter("value"), 0.0);
            QCOMPARE(s.counter("tag"), 90.0);
            QVERIFY(s.run.inBranch());
            QCOMPARE(s.run.run, 4);
            QCOMPARE(s.invariants.size(), size_t{1});
            QCOMPARE(s.invariants[0].violations, 0LL);
        }
        QCOMPARE(QString::fromStdString(r.snapshot(2).run.describe()),
                 QString("run 4 of 4, adopted (offset -10)"));
        QVERIFY(!r.snapshot(1).run.inBranch());
        QCOMPARE(r.snapshot(1).counter("value"), 10.0);
        // The report on the decided snapshot, and the branch's note.
        QCOMPARE(r.current().counter("toy runs"), 4.0);
        QCOMPARE(r.current().counter("toy adopted"), 4.0);
        QCOMPARE(r.current().notes.size(), size_t{1});
        QCOMPARE(QString::fromStdString(r.current().notes[0]),
                 QString("toy branch: run 4 adopted"));
        QVERIFY(r.step());
        QVERIFY(!r.current().run.inBranch());
        QCOMPARE(r.current().counter("offset after"), 0.0);
        QCOMPARE(r.current().counter("value"), 0.0);
    }

    // Going back inside the adopted range and stepping again re-runs with
    // the adopted run's overrides (same snapshots, same report); going back
    // before rerunFrom forgets the branch, and it is decided again.
    void branchBackAndStepStayCoherent() {
        std::atomic<int> adjustRuns{0};
        const Method m = branchingMethod(&adjustRuns);
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        r.runToEnd();
        const int afterFirst = adjustRuns.load();
        QVERIFY(afterFirst >= 5); // the first run and 4 judged variants at least
        r.runTo(2);
        QCOMPARE(r.branchSummaries().size(), size_t{1});
        QCOMPARE(r.current().counter("value"), 0.0);
        QVERIFY(r.step()); // finish again: not re-decided
        QCOMPARE(adjustRuns.load(), afterFirst);
        QCOMPARE(r.current().counter("value"), 0.0);
        QCOMPARE(r.current().counter("toy adopted"), 4.0);
        QCOMPARE(r.current().notes.size(), size_t{1});
        QCOMPARE(r.current().run.run, 4);
        r.runTo(1);
        QVERIFY(r.branchSummaries().empty());
        QVERIFY(r.step()); // adjust with the base parameters
        QCOMPARE(adjustRuns.load(), afterFirst + 1);
        QCOMPARE(r.current().counter("value"), 10.0);
        QCOMPARE(r.current().counter("tag"), -1.0);
        QVERIFY(!r.current().run.inBranch());
        QVERIFY(r.step()); // decided again, the same way
        QCOMPARE(r.branchSummaries().size(), size_t{1});
        QCOMPARE(r.branchSummaries()[0]->adopted, 4);
        QCOMPARE(r.current().counter("value"), 0.0);
        r.reset();
        QVERIFY(r.branchSummaries().empty());
    }

    // A run strictly better that breaks a re-run phase's post-condition is
    // not adopted (Release; builds that check invariants fail the step and
    // keep the state).
    void branchRejectsRunsBreakingPostconditions() {
        std::atomic<int> adjustRuns{0};
        const Method m = branchingMethod(&adjustRuns);
        ParameterSet p = ParameterSet::defaults(m.parameters);
        p.set("offer-broken", true);
        p.set("bad", 5); // offset -5 ends at value 5
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(), p);
        r.runTo(2);
#ifdef CONTOUR_CHECK_INVARIANTS
        QVERIFY_THROWS_EXCEPTION(PhaseError, r.step());
        QCOMPARE(r.completedPhases(), 2);
        QVERIFY(r.branchSummaries().empty());
#else
        QVERIFY(r.step());
        const BranchSummary& b = *r.branchSummaries().at(0);
        QCOMPARE(b.runs.size(), size_t{5});
        QVERIFY(b.runs[0].better && !b.runs[0].postconditionsKept && !b.runs[0].adopted);
        QVERIFY(b.runs[2].adopted == false && b.runs[4].adopted);
        QCOMPARE(b.adopted, 5);
        QCOMPARE(r.current().counter("value"), 0.0);
#endif
    }

    // A cancel request reaches the variant runs; the state is unchanged
    // and a new step decides the branch.
    void branchCancellation() {
        std::atomic<int> adjustRuns{0};
        const Method m = branchingMethod(&adjustRuns);
        Runner r(m, makeInputSnapshot(tetrahedron()), frontCamera(),
                 ParameterSet::defaults(m.parameters));
        r.runTo(2);
        gCancelDuringBranch = &r;
        QVERIFY_THROWS_EXCEPTION(PhaseCancelled, r.step());
        gCancelDuringBranch = nullptr;
        QCOMPARE(r.completedPhases(), 2);
        QVERIFY(r.branchSummaries().empty());
        QCOMPARE(r.current().counter("value"), 10.0);
        QVERIFY(!r.current().run.inBranch());
        QVERIFY(r.step());
        QCOMPARE(r.branchSummaries().size(), size_t{1});
        QCOMPARE(r.current().counter("value"), 0.0);
    }
};

QTEST_APPLESS_MAIN(TestPipeline)
#include "test_pipeline.moc"
