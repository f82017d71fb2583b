#pragma once
// The facing phase shared by the mesh-based methods: each face's facing for
// the analysis camera from the exact orientation predicate (Facing.h).
#include "pipeline/Method.h"

namespace contour {

std::vector<int> faceFacing(const TriangleMesh& mesh, const Camera& camera);
void publishFaceFacing(const PhaseContext& ctx, Snapshot& s);
Phase makeFacingPhase();

} // namespace contour
