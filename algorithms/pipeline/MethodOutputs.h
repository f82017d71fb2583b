#pragma once
// What a method adds to the outputs every method shares. The exporters write
// what any method has (phases, counters, post-conditions, curves, the view
// graph, fields as PLY properties); what only one method computes (the
// consistent method's inconsistent faces and why each one is inconsistent)
// comes from the method itself through these functions, so a new method adds
// its own outputs without changing an exporter.
//
// Every member is optional: an empty function adds nothing. A JSON function
// returns an object (or null for nothing); its members are added to the
// exporter's object, and a member the exporter already writes is an error
// (std::logic_error), so a method can add but never overwrite.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <cstddef>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace contour {

struct Method;

// One method run from one camera, as the exporters see it.
struct MethodViewRun {
    const Method& method;
    const Camera& camera;
    // Runner::snapshots(): [0] the input, [i] the state after phase i.
    const std::vector<Snapshot>& snapshots;

    const Snapshot& last() const { return snapshots.back(); }
};

struct MethodOutputs {
    // Members added to the JSON report's entry of the phase that produced
    // run.snapshots[completed] (views[].phases[completed - 1]).
    std::function<nlohmann::json(const MethodViewRun& run, std::size_t completed)> phaseJson;
    // Members added to the view's "totals" (views[].totals).
    std::function<nlohmann::json(const MethodViewRun& run)> totalsJson;
    // Members added to the view's entry (views[]), for lists too long to sit
    // among the totals.
    std::function<nlohmann::json(const MethodViewRun& run)> viewJson;
    // Lines contour-batch prints after a view's totals (without a newline).
    std::function<std::vector<std::string>(const MethodViewRun& run)> summaryLines;
};

} // namespace contour
