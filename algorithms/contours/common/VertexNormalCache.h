#pragma once
// Vertex normals do not depend on the camera, but the interpolated method's
// facing phase runs once per view. This cache keeps the normals field of the
// last few (mesh, weighting) pairs, so a session or a 26-view batch computes
// them once per mesh (at 1M faces that is about 30 ms saved per view).
// Entries die with their mesh. Thread-safe.
#include "mesh/VertexNormals.h"
#include "pipeline/Snapshot.h"

#include <memory>

namespace contour {

std::shared_ptr<const Field> cachedVertexNormals(const std::shared_ptr<const TriangleMesh>& mesh,
                                                 NormalWeighting weighting);

} // namespace contour
