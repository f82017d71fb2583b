#pragma once
// The JSON report of a batch run: what was run, on what, from where, and what
// every phase did. One report covers one mesh and one method with its
// parameters, run from one or more cameras ("views"):
//
// {
//   "tool":   {"name", "version"},
//   "mesh":   {"path", "vertices", "faces" (as loaded), "polygon_faces" (faces
//              with more than three corners), "triangles" (after
//              triangulation), "edges", "boundary_edges", "bounding_box",
//              "notes" [text] (the input snapshot's: what loading the mesh
//              noted, e.g. its orientation, mesh/Orientation.h)},
//   "method": {"name", "label", "parameters" (ParameterSet::toJson),
//              "preset": {"name" (the preset the run started from,
//                         Method::presets), "changed" {name: value; the
//                         parameters that differ from it, changedFromPreset}},
//              "phases" (the method's phase names, in order)},
//   "views": [{
//     "index", "camera" (Camera::toJson),
//     "completed_phases", "phase_count",
//     "phases": [{"index", "name", "description", "seconds",
//                 "counters" {name: value; the counters this phase set or changed},
//                 "invariants" [{"name", "violations", "first_example"}],
//                 "violations", "notes" [text],
//                 ... and the members the method adds}],
//     "totals": {"seconds", "invariant_violations", "curves", "contour_chains",
//                "closed_loops", "open_chains", "boundary_curves",
//                "contour_points", "contour_length_px", "boundary_length_px",
//                "clipped_curves", "counters" (every counter of the last snapshot),
//                ... and the members the method adds},
//     "curves": [{"index", "type", "closed", "points", "length_px", "pieces",
//                 "hidden_points"}],
//     "view_graph": (only when the last snapshot has a view graph) {
//       "totals": {"chains", "visible_chains", "hidden_chains",
//                  "simplified_chains", "ambiguous_chains", "conflict_chains",
//                  "nodes", "nodes_by_type" {type: count}, "conflicts",
//                  "ray_tests", "visible_length_px", "hidden_length_px",
//                  "simplified_length_px"},
//       "chains": [{"index", "type", "curve", "closed", "qi", "qi_lower_bound",
//                   "rule" (toString(VisibilityRule)), "ambiguous", "concave",
//                   "conflict", "ray_qi", "simplified_away", "visible",
//                   "length_px", "start_node", "end_node" (-1: none),
//                   "segments", "ray_tested_segments",
//                   "ambiguous_segments",
//                   "points" [[x, y], ...] (pixels, 0.01 px)}],
//       "nodes": [{"index", "type" (toString(ViewNodeType)),
//                  "class" (ViewGraph::nodeClass), "image" [x, y],
//                  "position" [x, y, z], "mesh_vertex", "chains",
//                  "near_chains", "far_chains", "qi_step", "unreliable",
//                  "local_occluders"}],
//       "conflicts": [{"chain", "propagated_qi", "ray_qi", "reason"}]
//     },
//     ... and the members the method adds (Method::outputs, MethodOutputs.h)
//   }]
// }
//
// Lengths are in pixels of the view's viewport, measured on the projected
// curve (ProjectedCurves.h: parts behind a perspective eye are not counted).
#include "camera/Camera.h"
#include "pipeline/Method.h"
#include "pipeline/Snapshot.h"
#include "pipeline/ViewGraph.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace contour {

// The per-phase entry: `snapshot` is the state after the phase, `previous`
// the one before it (to tell which counters the phase set).
nlohmann::json phaseJson(const Phase& phase, const Snapshot& snapshot, const Snapshot& previous);
// The per-curve summary of a snapshot seen by `camera`.
nlohmann::json curvesJson(const Snapshot& snapshot, const Camera& camera);
// The "view_graph" object above (points in pixels as stored in the graph).
nlohmann::json viewGraphJson(const ViewGraph& graph);

class JsonReport {
public:
    // `input` is the method's input snapshot (makeInputSnapshot);
    // `presetName` the method's preset the parameters started from. Throws
    // std::invalid_argument when the method has no such preset.
    JsonReport(const std::string& toolName, const std::string& toolVersion,
               const std::string& meshPath, const Snapshot& input, const Method& method,
               const ParameterSet& parameters, const std::string& presetName = "default");

    // Adds one camera's run: `snapshots[0]` is the input, `snapshots[i]` the
    // state after phase i (Runner::snapshots()).
    void addView(const Camera& camera, const std::vector<Snapshot>& snapshots);

    const nlohmann::json& json() const { return report_; }
    std::string text() const { return report_.dump(2) + "\n"; }
    // Writes text() atomically; throws std::runtime_error naming the file.
    void write(const std::string& path) const;

private:
    const Method* method_;
    nlohmann::json report_;
};

} // namespace contour
