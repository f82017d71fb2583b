#pragma once
// Cones of the flat metric (Capouellez et al. 2023 §5.1): per closed
// component 8 cones for genus 0, 4(g-1) for genus g > 1 and none for a torus,
// one per cluster of close size, at the cluster's vertex of smallest discrete
// (Gaussian) curvature. Components with a boundary get no cones: their
// boundary vertices keep their scale factor and absorb the curvature
// (ConformalMap.h), so the flat metric needs no interior singularity there.
#include "mesh/TriangleMesh.h"

#include <span>
#include <vector>

namespace contour::powell_sabin {

struct ConeOptions {
    // Cones per closed component; -1 takes the paper's count from the genus.
    int conesPerComponent = -1;
    // Lloyd-like re-centering passes of the clustering (balanced region
    // growing from farthest-point seeds; the paper asks only for clusters
    // "of close size" and gives no number). 0 keeps the farthest-point seeds.
    int lloydIterations = 5;
    // What "close size" measures: the clusters' vertex counts, or (true) their
    // areas (a third of each incident triangle per vertex), which spreads the
    // cones more evenly over meshes of uneven density.
    bool balanceByArea = false;
    // Cones are kept apart by at least one vertex. When a cluster has no
    // vertex left that is not a cone's neighbour (a mesh too coarse for its
    // cone count, such as a cube with 8 cones), selectCones throws; false
    // lets such a cluster take its smallest-curvature vertex anyway.
    bool requireNonAdjacent = true;
};

struct ComponentTopology {
    Index firstFace = kInvalidIndex; // a face of the component
    Index faceCount = 0;
    Index vertexCount = 0;
    int boundaryLoops = 0;
    int genus = 0; // from the Euler characteristic: chi = 2 - 2g - b
    // The paper's count from meshComponents(); the count used, options
    // applied, in Cones::components.
    int coneCount = 0;
};

struct Cones {
    std::vector<Index> vertices; // the cone vertices, all components
    std::vector<ComponentTopology> components;
    // Per vertex: the cluster it belongs to (index into `vertices`), or
    // kInvalidIndex in components without cones.
    std::vector<Index> cluster;
};

// Connected components (faces joined across edges) with their genus and
// boundary loops, ordered by their smallest face index (= firstFace).
// Throws std::invalid_argument at a non-manifold vertex (two fans of faces
// meeting at one vertex), where the genus is not defined.
std::vector<ComponentTopology> meshComponents(const TriangleMesh& mesh);

// Angle defect 2*pi - (sum of corner angles) at interior vertices,
// pi - (sum) at boundary vertices, 0 at vertices without faces.
std::vector<double> angleDefects(const TriangleMesh& mesh);

// Cones in component order, within a component in cluster order. Each cone
// is the vertex of smallest signed angle defect of its cluster (the most
// negative, i.e. most saddle-like) that is not adjacent to a cone already
// placed (see requireNonAdjacent); clusters choose in order of their
// smallest defect. Deterministic. Throws std::invalid_argument when a
// component has fewer vertices than cones, when a cluster has no vertex left
// that is not adjacent to another cone and requireNonAdjacent is set, or for
// options out of range (conesPerComponent < -1, lloydIterations < 0).
Cones selectCones(const TriangleMesh& mesh, const ConeOptions& options = {});

// One Loop subdivision step on the triangles incident to the cones (§5.1:
// "to further reduce artifacts"): those triangles are split 1-to-4 with
// Loop's edge rule for the new vertices, and each neighbour that shares a
// split edge is bisected (1-to-2 for one split edge, 1-to-3 for two, with
// the shorter diagonal), so that the result is a conforming triangle mesh. The cones
// keep their positions (their one-ring shrinks towards them). A neighbour
// with all three edges split (surrounded by split triangles) is split 1-to-4
// as well and counted as bisected. Each input vertex keeps its index; the
// new edge vertices follow, in edge order. Face count:
// F + 3 * splitTriangles + (sum over bisected triangles of their split edges).
// Throws std::invalid_argument for a cone index out of range, listed twice,
// or without an incident triangle.
struct ConeRefinement {
    TriangleMesh mesh;
    std::vector<Index> cones;    // the cones' indices in `mesh` (unchanged)
    Index splitTriangles = 0;    // input triangles incident to a cone, split 1-to-4
    Index bisectedTriangles = 0; // other input triangles refined to conform
    // Per face of `mesh`: the input face it lies in.
    std::vector<Index> parentFace;
};
ConeRefinement refineAroundCones(const TriangleMesh& mesh, std::span<const Index> cones);

} // namespace contour::powell_sabin
