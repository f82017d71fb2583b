#pragma once
// The consistent method's own outputs (Method::outputs, MethodOutputs.h).
// The JSON report's view entry gets, when the last snapshot has the
// "consistent" face field:
//
//   "inconsistent_faces": [{"face", "vertices" [3 ids],
//     "reason" (which condition of Bénard 2014 Definitions 1-2 fails),
//     "vbo" (F|B|undefined), "facing" (front|back|edge-on),
//     "vertex_labels" [F|B|C x3], "g" [x3], "radial_curvature" [x3],
//     "positions" [[x,y,z] x3], "preimages" [{"face", "uv" [u,v]} x3],
//     "provenance" [x3], "cusp" [x3], "vertex_changed_by_phase" [x3],
//     "radial", "standard_radial", "folded", "domain_face",
//     "changed_by_phase" (index, -1 input), "changed_by_phase_name",
//     "neighbours" [face across edge v0-v1, v1-v2, v2-v0; -1 boundary],
//     "inconsistent_neighbours"}]
//
// (a per-vertex or per-face field the snapshot lacks is left out).
#include "pipeline/Method.h"
#include "pipeline/MethodOutputs.h"

#include <nlohmann/json.hpp>

namespace contour::consistent {

MethodOutputs consistentOutputs();

// The "inconsistent_faces" array above: every face whose "consistent" field
// is 0, with its details (an empty array without that field). `method`
// names the phases in "changed_by_phase_name".
nlohmann::json inconsistentFacesJson(const Snapshot& snapshot, const Method& method);

} // namespace contour::consistent
