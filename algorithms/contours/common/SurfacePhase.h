#pragma once
// The first phase of the mesh-based methods: which surface the contours are
// computed on. With `surface` = none the working mesh stays the
// triangulated cage (the methods' original behaviour). Otherwise the phase
// builds the smooth surface of the cage (Catmull-Clark, Loop or vertex-normal
// patches; cached per cage), tessellates it uniformly at `tessellation-level`
// (cached per surface and level) and makes that the working mesh: every
// vertex is a point of the smooth surface with its exact limit normal
// (Hertzmann & Zorin 2000). It publishes per vertex: vertex_normal (exact),
// preimage_face and preimage_uv, gaussian_curvature, mean_curvature and the
// view-dependent radial_curvature (SurfaceFields.h for the sign conventions),
// and per face domain_face.
#include "mesh/VertexNormals.h"
#include "pipeline/Method.h"
#include "surface/SmoothSurface.h"

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace contour {

// `surface` (choice: none, auto, catmull-clark, loop, vertex-normal-patches;
// default none) and `tessellation-level` (int 1..16, default 4).
std::vector<ParameterSpec> surfaceParameters();

// The kind the `surface` parameter selects for this cage (auto: Catmull-Clark
// unless every face is a triangle, then Loop), or nothing for none.
std::optional<SurfaceKind> selectedSurfaceKind(const ParameterSet& parameters,
                                               const PolygonMesh& cage);

// What the phase does for `surface` = none besides keeping the mesh: a
// method that gives `weighting` (its own parameter read from the run's
// parameters: the interpolated method's normal-weighting) has the
// weighted-average vertex normals published there, so that every later
// phase reads the normals from one field whatever the surface. Empty: no
// normals are published.
struct NoneSurfaceNormals {
    std::function<NormalWeighting(const ParameterSet&)> weighting;
};
Phase makeSurfacePhase(NoneSurfaceNormals noneNormals);

// The work of the phase for a given surface: replaces s.mesh by the
// tessellation (through the cache) and publishes the fields and counters
// above. Exposed so tests can run methods on surfaces that do not come from a
// cage (analytic ones).
void applySmoothSurface(Snapshot& s, const std::shared_ptr<const SmoothSurface>& surface, int level,
                        const Camera& camera);

} // namespace contour
