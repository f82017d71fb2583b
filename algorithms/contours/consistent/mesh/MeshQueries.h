#pragma once
// Queries on the editable mesh that every layer above asks and that need
// nothing but the mesh: its scale (tolerances are relative to it), the faces
// around a set of vertices, and a face described for notes and invariant
// examples.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <string>
#include <vector>

namespace contour::consistent {

// Bounding-box diagonal of the initial mesh (the surface's level-1
// tessellation): tolerances are relative to it, the same in every phase.
double sceneScale(const ConsistentMesh& m);

// Whether vertex v's preimage is a singular point of the surface: the
// largest principal curvature radius is below kSingularRadius times `scale`
// (sceneScale), or the normal is undefined. Seen where a cage pinches the
// limit surface (f_u and f_v nearly parallel; pig's tail, bigguy, ogre):
// κr flips sign there in every view, a sign change §6.2 d takes for a cusp
// although the surface has no smooth fold there.
inline constexpr double kSingularRadius = 1e-6;
bool atSingularPoint(const ConsistentMesh& m, Index v, double scale);

// The faces around the given vertices, each once, sorted.
std::vector<Index> facesAround(const ConsistentMesh& m, const std::vector<Index>& vertices);

// "face f: v (domain face, u, v, label, provenance, phase) ..." for notes
// and invariant examples.
std::string describeFace(const ConsistentMesh& m, Index f);

} // namespace contour::consistent
