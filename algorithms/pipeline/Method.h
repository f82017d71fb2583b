#pragma once
// A contour method: its parameters, grouped by phase, its presets and its
// ordered phases. The GUI and the CLI step every method the same way through
// Runner.
#include "camera/Camera.h"
#include "pipeline/Branch.h"
#include "pipeline/MethodOutputs.h"
#include "pipeline/Parameters.h"
#include "pipeline/Snapshot.h"

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour {

class PhaseCancelled : public std::runtime_error {
public:
    PhaseCancelled() : std::runtime_error("cancelled") {}
};

class PhaseContext {
public:
    PhaseContext(const Camera& analysisCamera, const ParameterSet& parameterValues,
                 const std::atomic<bool>* cancelFlag = nullptr,
                 std::function<void(double)> progress = {},
                 std::shared_ptr<const BranchData> branchData = nullptr)
        : camera(analysisCamera), parameters(parameterValues), cancelFlag_(cancelFlag),
          progress_(std::move(progress)), branchData_(std::move(branchData)) {}

    const Camera& camera;
    const ParameterSet& parameters;

    // Long phases call this between chunks of work.
    void checkCancelled() const {
        if (cancelFlag_ && cancelFlag_->load())
            throw PhaseCancelled();
    }
    void reportProgress(double fraction) const {
        if (progress_)
            progress_(fraction);
    }
    // The data of the branch variant being run (Branch.h) as T, or null
    // outside a branch's variant run.
    template <typename T> const T* branchData() const {
        return dynamic_cast<const T*>(branchData_.get());
    }

private:
    const std::atomic<bool>* cancelFlag_;
    std::function<void(double)> progress_;
    std::shared_ptr<const BranchData> branchData_;
};

struct Phase {
    std::string name; // short, lower case: "facing", "extraction", "chaining"
    std::string description;
    // Reads and writes `snapshot`, a copy of the previous phase's snapshot.
    std::function<void(const PhaseContext&, Snapshot&)> run;
    // Post-conditions (the invariants of the notes), counted in every build.
    std::function<std::vector<InvariantCheck>(const PhaseContext&, const Snapshot&)> postconditions;
};

struct Method {
    std::string name;  // the CLI's --method value
    std::string label; // for the GUI
    std::string description;
    std::vector<ParameterSpec> parameters;
    std::vector<Phase> phases;
    // The first is "default" (the schema's defaults).
    std::vector<ParameterPreset> presets;

    // Appends a phase. The parameters declared before it without a group
    // join the group named after it, so a parameter's group is the phase
    // whose declaration follows its own. Throws std::logic_error when
    // phases were appended to `phases` directly while ungrouped parameters
    // wait: their group would be wrong.
    void addPhase(Phase phase);
    // The parameter groups in the order of the parameters (phase order).
    std::vector<std::string> parameterGroups() const;
    // The preset called `presetName`, or null.
    const ParameterPreset* preset(const std::string& presetName) const;
    MethodOutputs outputs; // what the method adds to the reports (MethodOutputs.h)
    // Decided by the runner after a phase (Branch.h); ranges do not overlap.
    std::vector<BranchRule> branches;

    const ParameterSpec* parameter(const std::string& parameterName) const;
    // Index in `phases` of the phase called `phaseName`, or -1. Phases are
    // found by name: their indices change when phases are inserted.
    int phaseIndex(const std::string& phaseName) const;

private:
    size_t phasesAdded_ = 0; // phases.size() after the last addPhase
};

} // namespace contour
