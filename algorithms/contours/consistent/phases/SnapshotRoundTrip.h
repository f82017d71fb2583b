#pragma once
// The snapshot round trip of the editable mesh (Bénard 2014 §6): every phase
// reloads the previous phase's snapshot and publishes its own. The snapshot
// is the only state passed between phases, so stepping back and re-running
// a phase is exact.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/MeshAnalysis.h"
#include "pipeline/Method.h"

#include <memory>

namespace contour::consistent {

// The method's appendix B chart parameters (ConsistentContourMethod.cpp),
// which every phase's editable mesh is built with.
struct ChartOptions {
    double tolerance = 0.0;   // chart-tolerance
    bool vertexRings = false; // chart-vertex-rings
    static ChartOptions read(const ParameterSet& p);
};

// The smooth surface the method's `surface` parameter selects for s.cage.
std::shared_ptr<const SmoothSurface> surfaceFor(const PhaseContext& ctx, const Snapshot& s);

// The editable mesh of the previous phase's snapshot. The vertices publish()
// attached to it (Snapshot::methodState) are reused instead of evaluating
// the surface again; without them every vertex is evaluated from the
// fields. Both give the same mesh (Debug builds check it).
ConsistentMesh reload(const PhaseContext& ctx, const Snapshot& s);

// Writes the mesh, every per-element field and the counters every phase
// reports (faces, vertices, inconsistent faces, undefined VBOs, FB edges
// left, degenerate CC edges, contour vertices, cusps, folded faces, folds
// introduced against the input snapshot). Compacts the mesh first.
void publish(Snapshot& s, ConsistentMesh& m);

// The analysis publish() made of s's mesh (without the per-face facing, VBO
// and consistency, which are s's fields), null when s was not published by
// publish().
std::shared_ptr<const Analysis> publishedAnalysis(const Snapshot& s);

} // namespace contour::consistent
