// The workbench's runner and background jobs without any window
// (app/workbench/RunController.h): a sample mesh run with the interpolated
// and the consistent method, stepping forward and back, running to a phase
// and to the end (the snapshots equal a Runner's driven directly), a
// cancelled job, and inputs that cannot run reporting failure.
#include "RunController.h"
#include "contours/Methods.h"
#include "mesh/io/MeshReader.h"

#include <QCoreApplication>
#include <QSignalSpy>
#include <QtTest>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 600000;

std::shared_ptr<const PolygonMesh> sample(const char* name) {
    return std::make_shared<const PolygonMesh>(
        readMesh(std::string(CONTOUR_SOURCE_DIR) + "/samples/" + name));
}

Camera framingCamera(const PolygonMesh& mesh) {
    return Camera::framing(mesh.boundingBox(), Vec3(0.55, 0.45, 1.0), Viewport{800, 600});
}

// Sets every input of `run` for `method` on `mesh` with its defaults.
void configure(RunController& run, const std::shared_ptr<const PolygonMesh>& mesh,
               const std::string& method) {
    const Method* m = findMethod(method);
    QVERIFY(m);
    run.setInput(makeInputSnapshot(mesh));
    run.setMethod(m);
    run.setParameters(ParameterSet::defaults(m->parameters));
    run.setCamera(framingCamera(*mesh));
}

// The same run driven directly, to `completed` phases.
Snapshot directRun(const std::shared_ptr<const PolygonMesh>& mesh, const std::string& method,
                   int completed) {
    const Method& m = *findMethod(method);
    Runner runner(m, makeInputSnapshot(mesh), framingCamera(*mesh),
                  ParameterSet::defaults(m.parameters));
    runner.runTo(completed);
    return runner.current();
}

size_t curveCount(const Snapshot& s) {
    return s.curves ? s.curves->size() : 0;
}

} // namespace

class TestRunController : public QObject {
    Q_OBJECT

private slots:
    void nothingToRunWithoutInput();
    void interpolatedStepBackAndRunToEnd();
    void consistentRunToPhaseThenEnd();
    void cancelStopsAJob();
    void inputWithoutMeshFails();
    void phaseFailureIsReported();
};

void TestRunController::nothingToRunWithoutInput() {
    RunController run;
    QSignalSpy ready(&run, &RunController::snapshotReady);
    run.setMethod(findMethod("mesh"));
    QVERIFY(run.restart());
    QVERIFY(!run.hasRunner());
    QCOMPARE(ready.count(), 1);
    QVERIFY(!run.currentSnapshot().mesh);
    run.step(); // nothing to step
    QVERIFY(!run.isBusy());
}

void TestRunController::interpolatedStepBackAndRunToEnd() {
    const auto mesh = sample("torus.obj");
    RunController run;
    configure(run, mesh, "interpolated");
    QSignalSpy ready(&run, &RunController::snapshotReady);
    QSignalSpy busy(&run, &RunController::busyChanged);
    QSignalSpy progress(&run, &RunController::progress);
    QSignalSpy failed(&run, &RunController::failed);

    QVERIFY(run.restart(0));
    QVERIFY(run.hasRunner());
    QVERIFY(!run.isBusy());
    QCOMPARE(run.completedPhases(), 0);
    QCOMPARE(ready.count(), 1);
    QCOMPARE(run.currentSnapshot().phaseName, std::string("input"));
    const int phases = run.phaseCount();
    QVERIFY(phases >= 3);

    run.step();
    QVERIFY(run.isBusy());
    QVERIFY(!run.runner()); // the worker thread owns it now
    QCOMPARE(run.reachedPhases(), 1);
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(run.completedPhases(), 1);
    QCOMPARE(busy.count(), 2);
    QCOMPARE(busy.at(0).at(0).toBool(), true);
    QCOMPARE(busy.at(1).at(0).toBool(), false);
    QVERIFY(progress.count() >= 1);
    QCOMPARE(progress.at(0).at(0).toInt(), 0);
    QCOMPARE(run.currentSnapshot().phaseName, run.method()->phases[0].name);

    ready.clear();
    run.back();
    QVERIFY(!run.isBusy()); // going back runs nothing
    QCOMPARE(run.completedPhases(), 0);
    QCOMPARE(ready.count(), 1);

    run.runToEnd();
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(run.completedPhases(), phases);
    QVERIFY(run.runner()->atEnd());
    QCOMPARE(failed.count(), 0);
    const Snapshot expected = directRun(mesh, "interpolated", phases);
    const Snapshot& got = run.runner()->current();
    QVERIFY(curveCount(got) > 0);
    QCOMPARE(curveCount(got), curveCount(expected));
    QCOMPARE(got.mesh->faceCount(), expected.mesh->faceCount());

    run.reset();
    QCOMPARE(run.completedPhases(), 0);
}

void TestRunController::consistentRunToPhaseThenEnd() {
    const auto mesh = sample("spot_control_mesh.obj");
    RunController run;
    configure(run, mesh, "consistent");
    QSignalSpy failed(&run, &RunController::failed);
    QVERIFY(run.restart(0));
    const int phases = run.phaseCount();
    QVERIFY(phases > 4);
    const int middle = phases / 2;
    run.runTo(middle);
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(run.completedPhases(), middle);
    QCOMPARE(run.currentSnapshot().phaseName, run.method()->phases[middle - 1].name);

    // Back to an earlier phase is immediate.
    run.runTo(2);
    QVERIFY(!run.isBusy());
    QCOMPARE(run.completedPhases(), 2);

    run.runToEnd();
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(failed.count(), 0);
    QCOMPARE(run.completedPhases(), phases);
    const Snapshot expected = directRun(mesh, "consistent", phases);
    const Snapshot got = run.currentSnapshot();
    QCOMPARE(got.counter("inconsistent faces"), expected.counter("inconsistent faces"));
    QVERIFY(got.counter("inconsistent faces") >= 0.0);
    QCOMPARE(got.mesh->faceCount(), expected.mesh->faceCount());
    QCOMPARE(curveCount(got), curveCount(expected));

    // New parameters drop the runner until restart().
    run.setParameters(ParameterSet::defaults(run.method()->parameters));
    QVERIFY(!run.hasRunner());
    QCOMPARE(run.reachedPhases(), 0);
}

void TestRunController::cancelStopsAJob() {
    const auto mesh = sample("bob_controlmesh.obj");
    RunController run;
    configure(run, mesh, "consistent");
    QVERIFY(run.restart(0));
    QSignalSpy cancelled(&run, &RunController::cancelled);
    QSignalSpy failed(&run, &RunController::failed);
    QSignalSpy idle(&run, &RunController::idle);
    run.runToEnd();
    QVERIFY(run.isBusy());
    // At once: the job is in its first phases, far from the end.
    run.cancel();
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(failed.count(), 0);
    QCOMPARE(idle.count(), 1);
    QVERIFY(run.completedPhases() < run.phaseCount());
    // The finished phases stay, and the run goes on from them.
    const int kept = run.completedPhases();
    run.runToEnd();
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QVERIFY(run.completedPhases() > kept);
    QCOMPARE(run.completedPhases(), run.phaseCount());
    QCOMPARE(cancelled.count(), 1);
}

void TestRunController::inputWithoutMeshFails() {
    RunController run;
    const Method* m = findMethod("mesh");
    run.setInput(Snapshot{});
    run.setMethod(m);
    run.setParameters(ParameterSet::defaults(m->parameters));
    run.setCamera(framingCamera(*sample("sphere.obj")));
    QSignalSpy failed(&run, &RunController::failed);
    QVERIFY(!run.restart());
    QVERIFY(!run.hasRunner());
    QCOMPARE(failed.count(), 1);
    QVERIFY(failed.at(0).at(1).toString().contains(QStringLiteral("no mesh")));
}

void TestRunController::phaseFailureIsReported() {
    // The consistent method needs the control cage to build its smooth
    // surface: an input that lost it fails in its first phase.
    const auto mesh = sample("sphere.obj");
    RunController run;
    configure(run, mesh, "consistent");
    Snapshot input = makeInputSnapshot(mesh);
    input.cage.reset();
    run.setInput(input);
    QSignalSpy failed(&run, &RunController::failed);
    QSignalSpy idle(&run, &RunController::idle);
    QVERIFY(run.restart());
    QVERIFY(run.waitForIdle(kIdleTimeoutMs));
    QCOMPARE(failed.count(), 1);
    QCOMPARE(idle.count(), 1);
    QVERIFY(failed.at(0).at(1).toString().contains(QStringLiteral("control cage")));
    // The failed phase left nothing behind.
    QCOMPARE(run.completedPhases(), 0);
    QVERIFY(run.hasRunner());
}

QTEST_GUILESS_MAIN(TestRunController)
#include "test_run_controller.moc"
