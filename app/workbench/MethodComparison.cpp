#include "MethodComparison.h"

#include "ProcessEventsWhile.h"
#include "contours/Methods.h"

#include <QtConcurrent/QtConcurrent>

namespace contour {

namespace {

// The primary's values of the parameters `other` has too.
ParameterSet sharedParameters(const Method& other, const ParameterSet& primary) {
    ParameterSet shared;
    for (const auto& [name, value] : primary.values())
        if (const ParameterSpec* spec = other.parameter(name);
            spec && spec->defaultValue.index() == value.index())
            shared.set(name, value);
    return shared;
}

} // namespace

MethodComparison::MethodComparison(QObject* parent) : QObject(parent) {
    connect(&watcher_, &QFutureWatcher<Outcome>::finished, this, &MethodComparison::onFinished);
}

MethodComparison::~MethodComparison() {
    cancelAndWait();
}

void MethodComparison::setOtherMethod(const QString& name) {
    if (name == otherName_)
        return;
    otherName_ = name;
    restart();
}

void MethodComparison::setPrimary(const std::optional<Snapshot>& input,
                                  const std::optional<Camera>& camera,
                                  const ParameterSet& primaryParameters) {
    const Method* other = findMethod(otherName_.toStdString());
    const ParameterSet shared =
        other ? sharedParameters(*other, primaryParameters) : ParameterSet{};
    const bool sameInput =
        input.has_value() == input_.has_value() && (!input || input->mesh == input_->mesh);
    if (sameInput && camera == camera_ && shared.values() == shared_.values())
        return;
    input_ = input;
    camera_ = camera;
    shared_ = shared;
    restart();
}

void MethodComparison::restart() {
    cancelAndWait();
    result_.reset();
    error_.clear();
    const Method* other = findMethod(otherName_.toStdString());
    if (!other || !input_ || !camera_) {
        if (!otherName_.isEmpty() && !other)
            error_ = tr("%1 is not a method that runs").arg(otherName_);
        emit changed();
        return;
    }
    ParameterSet parameters = ParameterSet::defaults(other->parameters);
    for (const auto& [name, value] : shared_.values())
        parameters.set(name, value);
    runner_ = std::make_unique<Runner>(*other, *input_, *camera_, parameters);
    running_ = true;
    Runner* runner = runner_.get();
    watcher_.setFuture(QtConcurrent::run([runner]() {
        Outcome outcome;
        try {
            runner->runToEnd();
            outcome.snapshot = runner->current();
        } catch (const PhaseCancelled&) {
        } catch (const std::exception& e) {
            outcome.error = QString::fromStdString(e.what());
        }
        return outcome;
    }));
}

void MethodComparison::cancelAndWait() {
    if (!running_)
        return;
    runner_->requestCancel();
    watcher_.waitForFinished();
    running_ = false; // its finished signal, still queued, is ignored
    runner_.reset();
}

void MethodComparison::onFinished() {
    if (!running_ || !watcher_.future().isFinished())
        return;
    running_ = false;
    const Outcome outcome = watcher_.result();
    result_ = outcome.snapshot;
    error_ = outcome.error;
    runner_.reset();
    emit changed();
}

bool MethodComparison::waitForResult(int timeoutMs) {
    return processEventsWhile([this] { return running_; }, timeoutMs);
}

} // namespace contour
