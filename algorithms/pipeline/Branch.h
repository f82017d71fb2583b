#pragma once
// A branch of a method's phases, decided by the runner (Runner.h): once the
// phase `decideAfter` has run, the rule proposes variant runs of the phases
// `rerunFrom`..`decideAfter` (each with parameter overrides and immutable
// data for the re-run phases), the runner runs them from the snapshot
// before `rerunFrom` and adopts the first run strictly better than the best
// so far (by the rule's figure) that keeps every post-condition. The
// adopted run's snapshots then replace the range, so snapshot k is always
// snapshot k - 1 plus phase k.
#include "pipeline/Parameters.h"
#include "pipeline/RunInfo.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace contour {

class PhaseContext;
struct Snapshot;

struct BranchVariant {
    std::string label; // what the stepper shows: "rings 1, levels 2"
    std::vector<std::pair<std::string, ParameterValue>> overrides;
    std::shared_ptr<const BranchData> data; // PhaseContext::branchData of the re-run phases
};

struct BranchPlan {
    std::vector<BranchVariant> variants;    // in the order they are judged; empty: no branch
    std::shared_ptr<const BranchData> data; // for the rule's report (BranchSummary::data)
};

struct BranchRule {
    std::string name;
    std::string decideAfter; // phase name
    std::string rerunFrom;   // phase name, at or before decideAfter
    // Given the context and the first run's snapshot after decideAfter.
    std::function<BranchPlan(const PhaseContext&, const Snapshot&)> plan;
    // The figure a run is judged by (lower is better) from its last
    // snapshot; nullopt: the run cannot be judged and is not adopted.
    std::function<std::optional<double>(const Snapshot&)> figure;
    // A run reaching this figure is perfect: no later run is judged.
    double perfect = 0.0;
    // Called on the snapshot after decideAfter (the adopted run's, or the
    // first run's) once the branch is decided, also when the plan had no
    // variant: sets the rule's counters and returns its note ("" for none).
    std::function<std::string(const PhaseContext&, const BranchSummary&, Snapshot&)> report;
};

} // namespace contour
