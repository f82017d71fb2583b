#include "MethodComparison.h"

#include "ProcessEventsWhile.h"
#include "contours/Methods.h"

#include <QtConcurrent/QtConcurrent>
#include <stdexcept>

namespace contour {

namespace {

// The primary's values of the parameters `other` has too, where they are in
// `other`'s range: a shared name may allow other values in each method.
ParameterSet sharedParameters(const Method& other, const ParameterSet& primary) {
    ParameterSet shared;
    for (const auto& [name, value] : primary.values()) {
        const ParameterSpec* spec = other.parameter(name);
        if (!spec || spec->defaultValue.index() != value.index())
            continue;
        ParameterSet one;
        one.set(name, value);
        if (validateParameters({*spec}, one).empty())
            shared.set(name, value);
    }
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
    try {
        runner_ = std::make_unique<Runner>(*other, *input_, *camera_, parameters);
    } catch (const std::invalid_argument& e) {
        error_ = QString::fromStdString(e.what());
        emit changed();
        return;
    }
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
