#pragma once
// Heuristic visibility of interpolated contours (Bénard & Hertzmann 2019,
// tutorial §6.2.4): interpolated contours do not lie on the mesh's
// front/back-face boundary, so a ray from them may hit their own surface;
// the tutorial's workarounds are to ignore the faces around the contour and
// to vote over several tests per chain. Deliberately approximate: it shows
// the gaps and halos that the exact methods fix.
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/ViewGraph.h"

namespace contour {

class RayCaster;

// Tutorial §6.2.4: every chain gets `votes` ray tests spread along it, ignoring the faces
// adjacent to the contour's face; majority decides; decidedBy = HeuristicVote.
void voteInterpolatedVisibility(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                                const RayCaster& rays, int votes, bool ignoreAdjacentFaces);

} // namespace contour
