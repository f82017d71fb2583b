#pragma once
// Boundary edges (one face only, tutorial §3.2) chained into polylines.
#include "pipeline/Snapshot.h"

#include <vector>

namespace contour {

std::vector<Index> boundaryEdges(const TriangleMesh& mesh);
std::vector<Polyline> boundaryPolylines(const TriangleMesh& mesh);

} // namespace contour
