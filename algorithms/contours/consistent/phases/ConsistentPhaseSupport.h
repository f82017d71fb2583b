#pragma once
// What every phase of the consistent method shares (Bénard 2014 §6): the
// snapshot round trip of the editable mesh, the per-face classification
// (facing, VBO, consistency, radial, standard radial, folds), the published
// fields and counters, and the post-conditions common to every phase
// (notes §6.1 items 1, 2 and 4). The snapshot is the only state passed
// between phases, so stepping back and re-running a phase is exact.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/VertexBasedOrientation.h"
#include "pipeline/Method.h"

#include <memory>
#include <string>
#include <vector>

namespace contour::consistent {

// The smooth surface the method's `surface` parameter selects for s.cage.
std::shared_ptr<const SmoothSurface> surfaceFor(const PhaseContext& ctx, const Snapshot& s);
// Bounding-box diagonal of the vertices (tolerances are relative to it).
double sceneScale(const ConsistentMesh& m);

// The editable mesh of the previous phase's snapshot. The vertices publish()
// attached to it (Snapshot::methodState) are reused instead of evaluating
// the surface again; without them every vertex is evaluated from the
// fields. Both give the same mesh (Debug builds check it).
ConsistentMesh reload(const PhaseContext& ctx, const Snapshot& s);

// "face f: v (domain face, u, v, label, provenance, phase) ..." for notes
// and invariant examples.
std::string describeFace(const ConsistentMesh& m, Index f);

// Definition 2 for one face: the VBO of its labels against its exact facing.
Vbo faceVbo(const ConsistentMesh& m, Index f);
Facing faceFacing(const ConsistentMesh& m, Index f);
bool faceIsConsistent(const ConsistentMesh& m, Index f);
// The domain face holding the face's centroid (appendix B interpolation),
// kInvalidIndex when its corners have no common chart.
Index faceDomainFace(const ConsistentMesh& m, Index f);
// The faces around the given vertices, each once, sorted.
std::vector<Index> facesAround(const ConsistentMesh& m, const std::vector<Index>& vertices);
// Inconsistent faces among the faces around the given vertices (each face
// once): the local objective of the optimization phases (§6.4).
int inconsistentFacesAround(const ConsistentMesh& m, const std::vector<Index>& vertices);

// Definition 5 and §6.3: a face is radial when one of its edges is a radial
// edge p-r; standard radial when, in addition, it has a CC edge or its third
// vertex is an endpoint of another radial edge.
struct RadialClassification {
    std::vector<int> radial, standard;
};
RadialClassification classifyRadialFaces(const ConsistentMesh& m);

struct Analysis {
    std::vector<int> facing, vbo, consistent, folded;
    std::vector<char> noChart; // 1 where the corners have no common chart
    long long inconsistent = 0, undefinedVbo = 0, fbEdges = 0, degenerate = 0, contourVertices = 0,
              cusps = 0, foldedFaces = 0;
    std::string firstFb, firstUndefined, firstDegenerate, firstFolded;
};
Analysis analyse(const ConsistentMesh& m);

// Writes the mesh, every per-element field and the counters every phase
// reports (faces, vertices, inconsistent faces, undefined VBOs, FB edges
// left, degenerate CC edges, contour vertices, cusps, folded faces, folds
// introduced against the input snapshot). Compacts the mesh first.
void publish(Snapshot& s, ConsistentMesh& m);

InvariantCheck check(const std::string& name);
void violate(InvariantCheck& c, const std::string& example);

// Notes §6.1 items 1, 2 and 4: embedding (pos = f(u) + offset n(u)), no
// parameter-space folds, a common chart for every face, no degenerate CC
// edge.
std::vector<InvariantCheck> commonChecks(const PhaseContext& ctx, const Snapshot& s,
                                         const ConsistentMesh& m, const Analysis& a);

// Notes §6.1 item 3: no FB edge, no undefined VBO, |g| below tolerance at
// every C vertex, every cusp vertex of valence 4. Holds after contour
// insertion and every later phase.
std::vector<InvariantCheck> contourInsertionChecks(const PhaseContext& ctx, const ConsistentMesh& m,
                                                   const Analysis& a);

// commonChecks, and from contour insertion on also contourInsertionChecks,
// of the mesh m reloaded from s.
std::vector<InvariantCheck> phaseChecks(const PhaseContext& ctx, const Snapshot& s,
                                        const ConsistentMesh& m, bool afterContourInsertion);
// Before contour insertion: every vertex's label is sign(g) at its preimage.
InvariantCheck labelsFollowG(const ConsistentMesh& m);
// How many of the triangle's edges are cusp edges (§6.2 d).
int cuspEdgesOf(const ConsistentMesh& m, const Triangle& t);
// Between cusp detection and contour insertion (§6.2 d, Fig. 18b-d): every
// cusp edge is an interior FB edge, and no face has two cusp edges (each
// cusp vertex gets valence 4).
std::vector<InvariantCheck> cuspEdgeChecks(const ConsistentMesh& m);
// The post-conditions of cusp detection and of cusp refinement: phaseChecks
// before contour insertion, labelsFollowG and cuspEdgeChecks.
std::vector<InvariantCheck> cuspPhaseChecks(const PhaseContext& ctx, const Snapshot& s);

} // namespace contour::consistent
