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

#include <optional>
#include <string>

namespace contour {

class RayCaster;

// Which faces a ray test from a contour segment ignores (tutorial §6.2.4,
// "ignore faces adjacent to the contour's face"; the tutorial does not say
// how far "adjacent" reaches).
enum class IgnoredFaces {
    Face,            // the segment's own face only (the point lies on it)
    EdgeNeighbours,  // the face and the faces sharing an edge with it
    VertexNeighbours // every face sharing a vertex with it (its one-ring)
};

// "face", "edge-neighbours", "vertex-neighbours": the parameter's choices.
const char* toString(IgnoredFaces ignored);
std::optional<IgnoredFaces> ignoredFacesFromString(const std::string& name);

// Tutorial §6.2.4: every chain gets `votes` ray tests spread along it, ignoring the faces
// adjacent to the contour's face; majority decides; decidedBy = HeuristicVote.
// (ignoreAdjacentFaces: EdgeNeighbours when true, Face when false.)
void voteInterpolatedVisibility(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                                const RayCaster& rays, int votes, bool ignoreAdjacentFaces);

// The same with the ignored faces chosen explicitly.
void voteInterpolatedVisibility(ViewGraph& graph, const TriangleMesh& mesh, const Camera& camera,
                                const RayCaster& rays, int votes, IgnoredFaces ignored);

} // namespace contour
