#include "RunController.h"

#include "pipeline/Method.h"

#include <QEventLoop>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>

namespace contour {

RunController::RunController(QObject* parent) : QObject(parent) {
    connect(&watcher_, &QFutureWatcher<JobResult>::finished, this, &RunController::onJobFinished);
}

RunController::~RunController() {
    // Nobody listens any more: only stop the job.
    disconnect(this, nullptr, nullptr, nullptr);
    cancelAndWait();
}

void RunController::setInput(std::optional<Snapshot> input) {
    dropRunner();
    input_ = std::move(input);
}

void RunController::setMethod(const Method* method) {
    dropRunner();
    method_ = method;
}

void RunController::setParameters(ParameterSet parameters) {
    dropRunner();
    parameters_ = std::move(parameters);
}

void RunController::setCamera(std::optional<Camera> camera) {
    dropRunner();
    camera_ = std::move(camera);
}

void RunController::dropRunner() {
    cancelAndWait();
    runner_.reset();
    targetPhases_ = 0;
}

bool RunController::restart(int completed) {
    dropRunner();
    if (!method_ || !input_ || !camera_) {
        emit snapshotReady();
        return true;
    }
    try {
        runner_ = std::make_unique<Runner>(*method_, *input_, *camera_, parameters_);
    } catch (const std::exception& e) {
        emit snapshotReady();
        emit failed(tr("Cannot run %1").arg(QString::fromStdString(method_->label)),
                    QString::fromStdString(e.what()));
        return false;
    }
    emit snapshotReady();
    const int target = completed < 0 ? phaseCount() : std::min(completed, phaseCount());
    if (target > 0)
        runTo(target);
    return true;
}

void RunController::step() {
    if (busy_ || !runner_ || runner_->atEnd())
        return;
    runTo(runner_->completedPhases() + 1);
}

void RunController::back() {
    if (busy_ || !runner_)
        return;
    runner_->back();
    targetPhases_ = runner_->completedPhases();
    emit snapshotReady();
}

void RunController::reset() {
    if (busy_ || !runner_)
        return;
    runner_->reset();
    targetPhases_ = 0;
    emit snapshotReady();
}

void RunController::runToEnd() {
    if (busy_ || !runner_)
        return;
    runTo(runner_->phaseCount());
}

void RunController::runTo(int completed) {
    if (busy_ || !runner_)
        return;
    completed = std::clamp(completed, 0, runner_->phaseCount());
    if (completed <= runner_->completedPhases()) {
        while (runner_->completedPhases() > completed)
            runner_->back();
        targetPhases_ = completed;
        emit snapshotReady();
        return;
    }
    startJob(completed, completed == runner_->completedPhases() + 1
                            ? tr("Running phase %1").arg(completed)
                            : tr("Running to phase %1").arg(completed));
}

void RunController::startJob(int completed, const QString& what) {
    busy_ = true;
    cancelRequested_ = false;
    const unsigned generation = ++generation_;
    jobName_ = what;
    targetPhases_ = completed;
    runningPhase_ = runner_->completedPhases();
    emit busyChanged(true);
    // Progress reaches the controller's thread queued; a job of an older
    // generation is ignored there.
    const auto report = [this, generation](int phase, double fraction) {
        QMetaObject::invokeMethod(
            this, [this, phase, fraction, generation] { onProgress(phase, fraction, generation); },
            Qt::QueuedConnection);
    };
    runner_->setProgressCallback(report);
    Runner* runner = runner_.get();
    watcher_.setFuture(QtConcurrent::run([this, runner, completed, report]() {
        JobResult result;
        try {
            while (runner->completedPhases() < completed) {
                if (cancelRequested_)
                    throw PhaseCancelled();
                report(runner->completedPhases(), 0.0);
                runner->step();
            }
        } catch (const PhaseCancelled&) {
            result.cancelled = true;
        } catch (const std::exception& e) {
            result.error = QString::fromStdString(e.what());
        } catch (...) {
            result.error = QStringLiteral("unknown error");
        }
        return result;
    }));
}

void RunController::onProgress(int phase, double fraction, unsigned generation) {
    if (!busy_ || generation != generation_)
        return;
    runningPhase_ = phase;
    emit progress(phase, fraction);
}

void RunController::onJobFinished() {
    // A late signal of a job that cancelAndWait() already finished.
    if (!busy_ || !watcher_.future().isFinished())
        return;
    const JobResult result = watcher_.result();
    busy_ = false;
    if (runner_)
        runner_->setProgressCallback({});
    emit busyChanged(false);
    emit snapshotReady();
    if (!result.error.isEmpty())
        emit failed(tr("Phase failed"), result.error);
    else if (result.cancelled)
        emit cancelled();
    emit idle();
}

void RunController::cancel() {
    if (!busy_)
        return;
    cancelRequested_ = true;
    if (runner_)
        runner_->requestCancel();
}

void RunController::cancelAndWait() {
    if (!busy_)
        return;
    cancel();
    watcher_.waitForFinished();
    onJobFinished();
}

bool RunController::waitForIdle(int timeoutMs) {
    if (!busy_)
        return true;
    QEventLoop loop;
    QTimer timer;
    timer.setSingleShot(true);
    connect(this, &RunController::idle, &loop, &QEventLoop::quit);
    connect(&timer, &QTimer::timeout, &loop, &QEventLoop::quit);
    timer.start(timeoutMs);
    while (busy_ && timer.isActive())
        loop.exec();
    return !busy_;
}

int RunController::completedPhases() const {
    return runner_ && !busy_ ? runner_->completedPhases() : 0;
}

int RunController::reachedPhases() const {
    if (!runner_)
        return 0;
    // While a job runs the runner belongs to the worker thread: use the job's
    // target instead of reading it.
    return busy_ ? targetPhases_ : runner_->completedPhases();
}

int RunController::phaseCount() const {
    return method_ ? static_cast<int>(method_->phases.size()) : 0;
}

Snapshot RunController::currentSnapshot() const {
    if (runner_ && !busy_)
        return runner_->current();
    if (input_)
        return *input_;
    return {};
}

} // namespace contour
