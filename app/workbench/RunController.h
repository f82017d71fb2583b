#pragma once
// The runner of the workbench and its background jobs, without any window:
// holds the input snapshot, the method, its parameters and the analysis
// camera, makes the contour::Runner from them, and runs phases on a worker
// thread (QtConcurrent) one job at a time, with cancellation and progress.
// MainWindow shows what it reports; tests drive it alone
// (tests/test_run_controller.cpp).
//
// Signals arrive on the controller's thread. After a job: busyChanged(false),
// snapshotReady(), then failed() or cancelled() if so, and idle() last.
#include "camera/Camera.h"
#include "pipeline/Parameters.h"
#include "pipeline/Runner.h"
#include "pipeline/Snapshot.h"

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>

namespace contour {

struct Method;

class RunController : public QObject {
    Q_OBJECT

public:
    explicit RunController(QObject* parent = nullptr);
    // Cancels a running job and waits for it.
    ~RunController() override;

    // What the runner is made from. Each setter cancels a running job and
    // drops the runner; restart() makes the next one.
    void setInput(std::optional<Snapshot> input);
    void setMethod(const Method* method);
    void setParameters(ParameterSet parameters);
    void setCamera(std::optional<Camera> camera);
    const std::optional<Snapshot>& input() const { return input_; }
    const Method* method() const { return method_; }
    const ParameterSet& parameters() const { return parameters_; }
    const std::optional<Camera>& camera() const { return camera_; }

    // Makes a runner of the input, method, parameters and camera (when all
    // four are set), reports its input snapshot, then runs to `completed`
    // phases (-1: to the end) in the background. False, with failed(), when
    // the runner cannot be made (parameters or camera do not fit); true
    // without a runner when something is missing.
    bool restart(int completed = -1);
    bool hasRunner() const { return static_cast<bool>(runner_); }

    // Phase control; each does nothing while a job runs or without a runner.
    // Going back is immediate; going forward starts a job.
    void step();
    void back();
    void reset();
    void runTo(int completed);
    void runToEnd();
    // Asks the running job to stop (between phases, or inside one through
    // the runner's flag); returns at once.
    void cancel();
    // Cancels and waits until the job has stopped (its signals are sent).
    void cancelAndWait();
    // Processes events until no job runs; false on timeout.
    bool waitForIdle(int timeoutMs = 120000);

    bool isBusy() const { return busy_; }
    // The runner, valid while idle (null while a job runs or without one).
    const Runner* runner() const { return busy_ ? nullptr : runner_.get(); }
    // Phases completed (0 while busy or without a runner).
    int completedPhases() const;
    // Phases completed, or aimed for by the running job (0 without runner).
    int reachedPhases() const;
    int phaseCount() const;
    // The phase index a running job is in (the last one reported).
    int runningPhase() const { return runningPhase_; }
    // What the running job does ("Running phase 3"), for a status line.
    const QString& jobName() const { return jobName_; }
    // The runner's current snapshot while idle, else the input (empty when
    // there is none).
    Snapshot currentSnapshot() const;

signals:
    // The runner's snapshots changed (a new runner, a job ended, back or
    // reset): read currentSnapshot() and runner().
    void snapshotReady();
    void busyChanged(bool busy);
    // A running job entered phase `phase` (fraction 0) or reported how far
    // the phase is (fraction in (0, 1]).
    void progress(int phase, double fraction);
    // The runner could not be made, or a phase failed (`title` says which).
    void failed(const QString& title, const QString& message);
    void cancelled();
    // A job ended and every signal about it has been sent.
    void idle();

private:
    struct JobResult {
        bool cancelled = false;
        QString error;
    };
    void dropRunner();
    void startJob(int completed, const QString& what);
    void onJobFinished();
    void onProgress(int phase, double fraction, unsigned generation);

    std::optional<Snapshot> input_;
    const Method* method_ = nullptr;
    ParameterSet parameters_;
    std::optional<Camera> camera_;

    std::unique_ptr<Runner> runner_;
    QFutureWatcher<JobResult> watcher_;
    bool busy_ = false;
    // Checked by a job between phases (the runner's own flag covers the
    // inside of a phase).
    std::atomic<bool> cancelRequested_{false};
    // The phase count the running job (or the last one) aims for.
    int targetPhases_ = 0;
    int runningPhase_ = 0;
    // Incremented per job, so that late progress messages of an old job are
    // ignored.
    unsigned generation_ = 0;
    QString jobName_;
};

} // namespace contour
