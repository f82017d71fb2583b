#include "pipeline/Runner.h"

#include <chrono>
#include <cstdio>

namespace contour {

Runner::Runner(const Method& method, Snapshot input, Camera camera, ParameterSet parameters)
    : method_(&method), camera_(std::move(camera)), parameters_(std::move(parameters)) {
    if (const std::string problem = camera_.validate(); !problem.empty())
        throw std::invalid_argument("camera: " + problem);
    const auto problems = validateParameters(method.parameters, parameters_);
    if (!problems.empty()) {
        std::string all;
        for (const std::string& p : problems)
            all += (all.empty() ? "" : "; ") + p;
        throw std::invalid_argument(all);
    }
    if (!input.mesh)
        throw std::invalid_argument("the input snapshot has no mesh");
    snapshots_.push_back(std::move(input));
}

bool Runner::step() {
    if (atEnd())
        return false;
    cancel_ = false;
    const int index = completedPhases();
    const Phase& phase = method_->phases[index];
    Snapshot next = snapshots_.back();
    next.phaseIndex = index;
    next.phaseName = phase.name;
    next.invariants.clear();
    next.notes.clear();
    const PhaseContext context(camera_, parameters_, &cancel_, [this, index](double fraction) {
        if (progress_)
            progress_(index, fraction);
    });
    const auto start = std::chrono::steady_clock::now();
    try {
        phase.run(context, next);
    } catch (const PhaseCancelled&) {
        throw;
    } catch (const std::exception& e) {
        throw PhaseError(phase.name, e.what());
    }
    next.phaseSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (phase.postconditions)
        next.invariants = phase.postconditions(context, next);
#ifdef CONTOUR_CHECK_INVARIANTS
    for (const InvariantCheck& check : next.invariants)
        if (check.violations > 0)
            throw PhaseError(phase.name, "post-condition \"" + check.name + "\" violated " +
                                             std::to_string(check.violations) +
                                             " times (first: " + check.firstExample + ")");
#endif
    snapshots_.push_back(std::move(next));
    return true;
}

bool Runner::back() {
    if (snapshots_.size() <= 1)
        return false;
    snapshots_.pop_back();
    return true;
}

void Runner::reset() {
    snapshots_.resize(1);
}

void Runner::runTo(int completed) {
    if (completed < 0 || completed > phaseCount())
        throw std::out_of_range("no phase " + std::to_string(completed));
    while (completedPhases() > completed)
        back();
    while (completedPhases() < completed)
        step();
}

} // namespace contour
