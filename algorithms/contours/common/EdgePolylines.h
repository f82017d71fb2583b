#pragma once
// Mesh edges (contour edges, boundary edges) chained into polylines through
// the vertices where exactly two of them meet, and the one place that
// publishes a method's final curves and chain counters.
#include "pipeline/Method.h"

#include <span>
#include <vector>

namespace contour {

// Each polyline's points are mesh vertices; its segments name their edges.
std::vector<Polyline> edgePolylines(const TriangleMesh& mesh, std::span<const Index> edges,
                                    CurveType type);

// Sets s.curves to `contours` plus, with `includeBoundaries` (the calling
// method's include-boundaries parameter), the mesh's boundary polylines;
// sets the counters "contour chains", "closed loops", "open chains" and
// "boundary curves".
void publishCurves(Snapshot& s, std::vector<Polyline> contours, bool includeBoundaries);

} // namespace contour
