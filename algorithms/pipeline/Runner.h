#pragma once
// Keeps the list of snapshots of one method run on one camera, so a user can
// step forward and back, jump to a phase, run to the end, or cancel. Not
// thread-safe: the GUI calls it from one worker thread at a time and reads
// the snapshots (which are immutable) once a call returns.
#include "pipeline/Method.h"

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour {

class PhaseError : public std::runtime_error {
public:
    PhaseError(const std::string& phase, const std::string& what)
        : std::runtime_error("phase \"" + phase + "\" failed: " + what), phase_(phase) {}
    const std::string& phase() const { return phase_; }

private:
    std::string phase_;
};

class Runner {
public:
    // Throws std::invalid_argument when the parameters do not fit the schema
    // or the camera is invalid.
    Runner(const Method& method, Snapshot input, Camera camera, ParameterSet parameters);

    const Method& method() const { return *method_; }
    const Camera& camera() const { return camera_; }
    const ParameterSet& parameters() const { return parameters_; }

    int phaseCount() const { return static_cast<int>(method_->phases.size()); }
    // Number of phases run so far (0 = only the input snapshot).
    int completedPhases() const { return static_cast<int>(snapshots_.size()) - 1; }
    bool atEnd() const { return completedPhases() == phaseCount(); }
    const Snapshot& current() const { return snapshots_.back(); }
    // Snapshot after `completed` phases; 0 is the input.
    const Snapshot& snapshot(int completed) const { return snapshots_.at(completed); }
    const std::vector<Snapshot>& snapshots() const { return snapshots_; }

    // Runs the next phase. Returns false when already at the end. Throws
    // PhaseError (or PhaseCancelled) and leaves the state unchanged on failure.
    bool step();
    // Drops the last snapshot; returns false at the input.
    bool back();
    void reset();
    void runTo(int completed);
    void runToEnd() { runTo(phaseCount()); }

    void requestCancel() { cancel_ = true; }
    // Called with (phase index, fraction done) from the running thread.
    void setProgressCallback(std::function<void(int, double)> callback) {
        progress_ = std::move(callback);
    }

private:
    const Method* method_;
    Camera camera_;
    ParameterSet parameters_;
    std::vector<Snapshot> snapshots_;
    std::atomic<bool> cancel_{false};
    std::function<void(int, double)> progress_;
};

} // namespace contour
