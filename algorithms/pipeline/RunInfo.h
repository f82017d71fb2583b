#pragma once
// Which run of a branch (Branch.h) a snapshot belongs to, and what the
// branch tried: the stepper marks the phases of the adopted range with it
// and lists the runs that were not adopted.
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace contour {

// Immutable data a branch rule hands to the phases it re-runs (read through
// PhaseContext::branchData) and to its own report; rules derive their type.
struct BranchData {
    virtual ~BranchData() = default;
};

// One variant run as the judge saw it.
struct BranchRunSummary {
    std::string label;
    std::optional<double> figure;    // the judge's figure of its last snapshot
    bool better = false;             // strictly better than the best run before it
    bool postconditionsKept = false; // every re-run phase kept its post-conditions
    bool adopted = false;
};

// A decided branch: the first run's figure, every variant run judged (in
// order), which one was adopted and the rule's note.
struct BranchSummary {
    std::string rule;
    std::string rerunFrom, decideAfter; // phase names
    double firstFigure = 0.0;
    std::vector<BranchRunSummary> runs;
    int adopted = 0; // 1-based index into runs; 0: the first run is kept
    std::string note;
    // The rule's data for its report (BranchPlan::data).
    std::shared_ptr<const BranchData> data;

    const BranchRunSummary* adoptedRun() const {
        return adopted > 0 ? &runs[static_cast<size_t>(adopted - 1)] : nullptr;
    }
};

// Set on the snapshots of a branch's range (rerunFrom..decideAfter); empty
// elsewhere.
struct RunInfo {
    std::shared_ptr<const BranchSummary> branch;
    int run = 0; // 0: the first run; k >= 1: branch->runs[k - 1]

    bool inBranch() const { return branch != nullptr; }
    // "run 2 of 3, adopted (rings 1, levels 2)" or "first run, kept (3 runs rejected)".
    std::string describe() const;
};

} // namespace contour
