#pragma once
// The human-readable output of contour-batch on stdout: the method list
// (--list-methods) and the per-run summary (per phase: name, time, counters,
// notes, invariant violations).
#include "camera/Camera.h"
#include "pipeline/Method.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace contour::batch {

void printMethodList(std::ostream& out);

void printRunHeader(std::ostream& out, const std::string& meshPath, const Snapshot& input,
                    const Method& method, const ParameterSet& parameters);
void printViewHeader(std::ostream& out, int view, int viewCount, const Camera& camera);
// One phase: `snapshot` after it, `previous` before it.
void printPhase(std::ostream& out, const Method& method, const Snapshot& snapshot,
                const Snapshot& previous);
// The totals line, and the view-graph line when `last` has a view graph.
void printViewTotals(std::ostream& out, const Snapshot& last, const Camera& camera);
// Chains visible / hidden / simplified away, T-junctions, curtain folds, ray
// tests, conflicts and the visible length in pixels.
void printViewGraphTotals(std::ostream& out, const ViewGraph& graph);
// The lines the method adds after a view's totals (MethodOutputs::summaryLines).
void printMethodSummary(std::ostream& out, const MethodViewRun& run);
void printWritten(std::ostream& out, const std::vector<std::string>& paths);

} // namespace contour::batch
