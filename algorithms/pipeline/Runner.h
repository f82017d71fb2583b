#pragma once
// Keeps the list of snapshots of one method run on one camera, so a user can
// step forward and back, jump to a phase, run to the end, or cancel. Not
// thread-safe: the GUI calls it from one worker thread at a time and reads
// the snapshots (which are immutable) once a call returns.
//
// A method's branch rules (Branch.h) are decided here: the step that runs a
// rule's `decideAfter` phase also runs the rule's variants of the phases
// `rerunFrom`..`decideAfter` from the snapshot before `rerunFrom` and, when
// one is adopted, replaces that range with the adopted run's snapshots.
// Stepping again through the range (after back()) re-runs its phases with
// the adopted run's overrides and data, so every snapshot stays the one
// before it plus its phase; stepping back before `rerunFrom` forgets the
// decision.
#include "pipeline/Method.h"

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
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

    // The branches decided so far (their runs, figures and post-conditions,
    // which one was adopted), in the order of their ranges.
    std::vector<std::shared_ptr<const BranchSummary>> branchSummaries() const;

    void requestCancel() { cancel_ = true; }
    // Called with (phase index, fraction done) from the running thread.
    void setProgressCallback(std::function<void(int, double)> callback) {
        progress_ = std::move(callback);
    }

private:
    struct Range {
        int from = 0, to = 0; // phase indices of rerunFrom and decideAfter
    };
    struct Decision {
        size_t rule = 0;
        std::shared_ptr<const BranchSummary> summary;
        std::optional<BranchVariant> adopted; // none: the first run is kept
        ParameterSet parameters;              // parameters_ with the adopted overrides
    };

    // Phase `index` on a copy of `previous`: timed, post-conditions counted
    // (and enforced in builds that check invariants).
    Snapshot runPhase(int index, const PhaseContext& context, const Snapshot& previous) const;
    std::function<void(double)> progressOf(int index);
    const Decision* decisionContaining(int index) const;
    // Runs rule `rule`'s variants; `decided` is the first run's snapshot
    // after decideAfter, replaced by the adopted run's when one is adopted
    // (then `replaced` gets the adopted run's earlier snapshots of the range).
    Decision decide(size_t rule, const PhaseContext& baseContext, Snapshot& decided,
                    std::vector<Snapshot>& replaced);

    const Method* method_;
    Camera camera_;
    ParameterSet parameters_;
    std::vector<Snapshot> snapshots_;
    std::vector<Range> ranges_; // one per method_->branches
    std::vector<Decision> decisions_;
    std::atomic<bool> cancel_{false};
    std::function<void(int, double)> progress_;
};

} // namespace contour
