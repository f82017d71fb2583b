#pragma once
// The post-conditions of the consistent method's phases (Bénard 2014 §6;
// the invariants each phase keeps): embedding, no parameter fold, common
// charts and no degenerate CC edge after every phase; from contour
// insertion on no FB edge, defined VBOs, |g| at C vertices, cusp valence 4;
// the cusp edges between cusp detection and contour insertion; the radial
// edges from radial edge insertion on.
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/predicates/MeshAnalysis.h"
#include "pipeline/Method.h"

#include <string>
#include <vector>

namespace contour::consistent {

InvariantCheck check(const std::string& name);
void violate(InvariantCheck& c, const std::string& example);

// Embedding (pos = f(u) + offset n(u)), no parameter-space folds, a common
// chart for every face, no degenerate CC edge.
std::vector<InvariantCheck> commonChecks(const PhaseContext& ctx, const Snapshot& s,
                                         const ConsistentMesh& m, const Analysis& a);

// No FB edge, no undefined VBO, |g| below tolerance at every C vertex, every
// cusp vertex of valence 4. Holds after contour insertion and every later
// phase.
std::vector<InvariantCheck> contourInsertionChecks(const PhaseContext& ctx, const ConsistentMesh& m,
                                                   const Analysis& a);

// commonChecks, and from contour insertion on also contourInsertionChecks,
// of the mesh m reloaded from s.
std::vector<InvariantCheck> phaseChecks(const PhaseContext& ctx, const Snapshot& s,
                                        const ConsistentMesh& m, bool afterContourInsertion);
// Before contour insertion: every vertex's label is sign(g) at its preimage.
InvariantCheck labelsFollowG(const ConsistentMesh& m);
// Between cusp detection and contour insertion (§6.2 d, Fig. 18b-d): every
// cusp edge is an interior FB edge, and no face has two cusp edges (each
// cusp vertex gets valence 4).
std::vector<InvariantCheck> cuspEdgeChecks(const ConsistentMesh& m);
// The post-conditions of cusp detection and of cusp refinement: phaseChecks
// before contour insertion, labelsFollowG and cuspEdgeChecks.
std::vector<InvariantCheck> cuspPhaseChecks(const PhaseContext& ctx, const Snapshot& s);

// Post-condition of §6.3 (g) that every later phase keeps: each radial edge
// joins a C vertex p to an F or B vertex r with |h_p(r)| (as a distance)
// below `radial-root-tolerance` times the bounding-box diagonal.
InvariantCheck radialEdgeCheck(const PhaseContext& ctx, const ConsistentMesh& m);

} // namespace contour::consistent
