// Method-specific outputs (MethodOutputs.h): a method adds its own members
// to the JSON report (per phase, in the totals, in the view) and its own
// summary lines through Method::outputs, without any exporter knowing its
// fields; a member the exporter already writes is refused. The consistent
// method's contribution is the list of inconsistent faces (Bénard 2014
// Definitions 1-2), checked here against the face fields it comes from.
#include "ContourTestSupport.h"
#include "Summary.h"
#include "contours/consistent/ConsistentOutputs.h"
#include "export/JsonReport.h"
#include "pipeline/FieldNames.h"
#include "pipeline/MethodOutputs.h"

#include <QtTest>
#include <nlohmann/json.hpp>
#include <sstream>

using namespace contour;

namespace {

constexpr const char* kMarked = "toy_marked";

// A method of two phases: "mark" marks every third face in a face field of
// its own and counts them; "count" counts the marked faces again.
Method toyMethod() {
    Method m;
    m.name = "toy";
    m.label = "Toy";
    m.description = "Marks every third face.";
    m.phases.push_back({"mark",
                        "marks every third face",
                        [](const PhaseContext&, Snapshot& s) {
                            std::vector<int> marks(static_cast<size_t>(s.mesh->faceCount()), 0);
                            for (size_t f = 0; f < marks.size(); f += 3)
                                marks[f] = 1;
                            s.setField(kMarked, Field{FieldLocation::Face, marks, "marked"});
                            s.setCounter("marked faces",
                                         static_cast<double>((marks.size() + 2) / 3));
                        },
                        {}});
    m.phases.push_back(
        {"count", "counts the marked faces", [](const PhaseContext&, Snapshot&) {}, {}});
    return m;
}

std::vector<Index> markedFaces(const Snapshot& s) {
    std::vector<Index> faces;
    if (const auto* marks = fieldValues<int>(s, kMarked, FieldLocation::Face, s.mesh->faceCount()))
        for (size_t f = 0; f < marks->size(); ++f)
            if ((*marks)[f])
                faces.push_back(static_cast<Index>(f));
    return faces;
}

// The toy method's own outputs, all four kinds.
MethodOutputs toyOutputs() {
    MethodOutputs o;
    o.phaseJson = [](const MethodViewRun& run, std::size_t completed) -> nlohmann::json {
        return {{"toy_marked_after_phase", markedFaces(run.snapshots.at(completed)).size()}};
    };
    o.totalsJson = [](const MethodViewRun& run) -> nlohmann::json {
        return {{"toy_marked", markedFaces(run.last()).size()}};
    };
    o.viewJson = [](const MethodViewRun& run) -> nlohmann::json {
        if (run.snapshots.size() < 2)
            return nullptr; // nothing marked yet: adds nothing
        return {{"toy_marked_faces", markedFaces(run.last())},
                {"toy_phases", run.method.phases.size()}};
    };
    o.summaryLines = [](const MethodViewRun& run) {
        return std::vector<std::string>{
            "toy     " + std::to_string(markedFaces(run.last()).size()) + " marked faces"};
    };
    return o;
}

struct ToyRun {
    Method method;
    Camera camera;
    std::vector<Snapshot> snapshots;
};

ToyRun runToy(MethodOutputs outputs, int phases = 2) {
    ToyRun r{toyMethod(), {}, {}};
    r.method.outputs = std::move(outputs);
    auto cage = std::make_shared<const PolygonMesh>(makeSphere(1.0, 6));
    Snapshot input = makeInputSnapshot(cage);
    r.camera = Camera::framing(input.mesh->boundingBox(), Vec3(1, 0.5, 2), Viewport{320, 240});
    Runner runner(r.method, input, r.camera, ParameterSet::defaults(r.method.parameters));
    runner.runTo(phases);
    r.snapshots = runner.snapshots();
    return r;
}

nlohmann::json reportView(const ToyRun& r) {
    JsonReport report("test", "0", "sphere", r.snapshots.front(), r.method,
                      ParameterSet::defaults(r.method.parameters));
    report.addView(r.camera, r.snapshots);
    return report.json()["views"][0];
}

} // namespace

class TestMethodOutputs : public QObject {
    Q_OBJECT

private slots:
    void toyMethodAddsItsOwnJson() {
        const ToyRun r = runToy(toyOutputs());
        const std::vector<Index> marked = markedFaces(r.snapshots.back());
        QVERIFY(!marked.empty());
        const nlohmann::json view = reportView(r);
        QCOMPARE(view["phases"].size(), size_t(2));
        for (const nlohmann::json& phase : view["phases"]) {
            QVERIFY(phase.contains("name")); // the generic members stay
            QCOMPARE(phase["toy_marked_after_phase"].get<size_t>(), marked.size());
        }
        QCOMPARE(view["totals"]["toy_marked"].get<size_t>(), marked.size());
        QCOMPARE(view["totals"]["counters"]["marked faces"].get<size_t>(), marked.size());
        QCOMPARE(view["toy_marked_faces"].get<std::vector<Index>>(), marked);
        QCOMPARE(view["toy_phases"].get<int>(), 2);
    }

    void toyMethodWithoutOutputsAddsNothing() {
        const nlohmann::json with = reportView(runToy(toyOutputs()));
        nlohmann::json without = reportView(runToy({}));
        for (const char* key : {"toy_marked_faces", "toy_phases"})
            QVERIFY2(!without.contains(key), key);
        QVERIFY(!without["totals"].contains("toy_marked"));
        QVERIFY(!without["phases"][0].contains("toy_marked_after_phase"));
        // Apart from the method's members (and times), the reports are equal.
        nlohmann::json stripped = with;
        stripped.erase("toy_marked_faces");
        stripped.erase("toy_phases");
        stripped["totals"].erase("toy_marked");
        for (nlohmann::json& phase : stripped["phases"])
            phase.erase("toy_marked_after_phase");
        for (nlohmann::json* j : {&stripped, &without}) {
            (*j)["totals"].erase("seconds");
            for (nlohmann::json& phase : (*j)["phases"])
                phase.erase("seconds");
        }
        QCOMPARE(stripped.dump(), without.dump());
    }

    void nullContributionAddsNothing() {
        // Stopped before any phase: viewJson returns null.
        const nlohmann::json view = reportView(runToy(toyOutputs(), 0));
        QVERIFY(!view.contains("toy_marked_faces"));
        QCOMPARE(view["totals"]["toy_marked"].get<size_t>(), size_t(0));
    }

    void memberOfTheExporterIsRefused() {
        MethodOutputs phaseClash;
        phaseClash.phaseJson = [](const MethodViewRun&, std::size_t) -> nlohmann::json {
            return {{"name", "overwritten"}};
        };
        QVERIFY_THROWS_EXCEPTION(std::logic_error, reportView(runToy(phaseClash)));
        MethodOutputs totalsClash;
        totalsClash.totalsJson = [](const MethodViewRun&) -> nlohmann::json {
            return {{"curves", 0}};
        };
        QVERIFY_THROWS_EXCEPTION(std::logic_error, reportView(runToy(totalsClash)));
        MethodOutputs viewClash;
        viewClash.viewJson = [](const MethodViewRun&) -> nlohmann::json {
            return {{"camera", 0}};
        };
        QVERIFY_THROWS_EXCEPTION(std::logic_error, reportView(runToy(viewClash)));
        MethodOutputs notAnObject;
        notAnObject.viewJson = [](const MethodViewRun&) -> nlohmann::json {
            return 3;
        };
        QVERIFY_THROWS_EXCEPTION(std::logic_error, reportView(runToy(notAnObject)));
    }

    void toyMethodAddsSummaryLines() {
        const ToyRun r = runToy(toyOutputs());
        std::ostringstream out;
        batch::printMethodSummary(out, {r.method, r.camera, r.snapshots});
        QCOMPARE(out.str(), "toy     " + std::to_string(markedFaces(r.snapshots.back()).size()) +
                                " marked faces\n");
        std::ostringstream none;
        const ToyRun plain = runToy({});
        batch::printMethodSummary(none, {plain.method, plain.camera, plain.snapshots});
        QCOMPARE(none.str(), std::string());
    }

    // The consistent method lists its inconsistent faces through its own
    // outputs: after initialization (§6.1) a sphere has some, each with the
    // reason its fields give (Definitions 1-2).
    void consistentMethodListsInconsistentFaces() {
        const Method& method = *findMethod("consistent");
        QVERIFY(method.outputs.viewJson);
        auto cage = std::make_shared<const PolygonMesh>(makeSphere(1.0, 8));
        const Snapshot input = makeInputSnapshot(cage);
        const Camera camera =
            Camera::framing(input.mesh->boundingBox(), Vec3(1, 0.5, 2), Viewport{800, 600});
        ParameterSet p = ParameterSet::defaults(method.parameters);
        p.set("surface", std::string("catmull-clark"));
        Runner runner(method, input, camera, p);
        const int initialization = method.phaseIndex("initialization");
        QVERIFY(initialization >= 0);
        runner.runTo(initialization + 1);
        const Snapshot& s = runner.current();

        JsonReport report("test", "0", "sphere", input, method, p);
        report.addView(camera, runner.snapshots());
        const nlohmann::json& view = report.json()["views"][0];
        QVERIFY(view.contains("inconsistent_faces"));
        const nlohmann::json& faces = view["inconsistent_faces"];
        QCOMPARE(faces, consistent::inconsistentFacesJson(s, method));

        const Index nf = s.mesh->faceCount();
        const auto* isConsistent =
            fieldValues<int>(s, fields::kConsistent, FieldLocation::Face, nf);
        const auto* vbo = fieldValues<int>(s, fields::kVbo, FieldLocation::Face, nf);
        const auto* facing = fieldValues<int>(s, fields::kFacing, FieldLocation::Face, nf);
        QVERIFY(isConsistent && vbo && facing);
        std::vector<Index> expected;
        for (Index f = 0; f < nf; ++f)
            if ((*isConsistent)[static_cast<size_t>(f)] == 0)
                expected.push_back(f);
        QCOMPARE(static_cast<double>(expected.size()), s.counter("inconsistent faces"));
        QVERIFY2(!expected.empty(), "the test needs a view with inconsistent faces");
        QCOMPARE(faces.size(), expected.size());
        for (size_t i = 0; i < faces.size(); ++i) {
            const nlohmann::json& face = faces[i];
            const Index f = expected[i];
            QCOMPARE(face["face"].get<Index>(), f);
            const Triangle& t = s.mesh->triangle(f);
            QCOMPARE(face["vertices"], nlohmann::json({t[0], t[1], t[2]}));
            const int v = (*vbo)[static_cast<size_t>(f)];
            const int fa = (*facing)[static_cast<size_t>(f)];
            QCOMPARE(face["vbo"].get<std::string>(), std::string(v > 0   ? "F"
                                                                 : v < 0 ? "B"
                                                                         : "undefined"));
            QCOMPARE(face["facing"].get<std::string>(), std::string(fa > 0   ? "front"
                                                                    : fa < 0 ? "back"
                                                                             : "edge-on"));
            const std::string reason = face["reason"];
            if (v == 0)
                QVERIFY2(reason.rfind("VBO undefined", 0) == 0, reason.c_str());
            else
                QVERIFY2(reason.find("Definition 2") != std::string::npos, reason.c_str());
            const int changed = face["changed_by_phase"].get<int>();
            QVERIFY(changed <= initialization);
            QCOMPARE(face["changed_by_phase_name"].get<std::string>(),
                     changed < 0 ? std::string("input")
                                 : method.phases[static_cast<size_t>(changed)].name);
        }

        // Before any phase there is nothing to classify, so nothing is added.
        JsonReport early("test", "0", "sphere", input, method, p);
        early.addView(camera, {input});
        QVERIFY(!early.json()["views"][0].contains("inconsistent_faces"));
    }

    void otherMethodsListNoInconsistentFaces() {
        auto cage = std::make_shared<const PolygonMesh>(makeSphere(1.0, 8));
        const Snapshot input = makeInputSnapshot(cage);
        const Camera camera =
            Camera::framing(input.mesh->boundingBox(), Vec3(1, 0.5, 2), Viewport{800, 600});
        for (const char* name : {"mesh", "interpolated"}) {
            const Method& method = *findMethod(name);
            const ParameterSet p = ParameterSet::defaults(method.parameters);
            Runner runner(method, input, camera, p);
            runner.runToEnd();
            JsonReport report("test", "0", "sphere", input, method, p);
            report.addView(camera, runner.snapshots());
            QVERIFY2(!report.json()["views"][0].contains("inconsistent_faces"), name);
        }
    }
};

QTEST_APPLESS_MAIN(TestMethodOutputs)
#include "test_method_outputs.moc"
