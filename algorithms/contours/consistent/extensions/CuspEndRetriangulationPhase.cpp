// Re-triangulation of discs of faces at the far ends of the cusps' radial
// edges (not in the paper; CuspEndRetriangulation.h, Bénard 2014 §6.3
// Fig. 18e): once after the normal wiggle and the cusps' final push, and
// again after contour refinement, whose new C vertices give the discs new
// outlines.
#include "contours/consistent/ConsistentPhases.h"
#include "contours/consistent/edits/CuspEndRetriangulation.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/phases/ConsistentPhaseSupport.h"
#include "contours/consistent/phases/NormalWiggle.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"

namespace contour::consistent {

namespace {

struct CuspEndRetriangulationOptions {
    int faces = 6; // cusp-end-retriangulation-faces (0: off)
};

CuspEndRetriangulationOptions cuspEndRetriangulationOptions(const ParameterSet& p) {
    return {p.getInt("cusp-end-retriangulation-faces")};
}

// Vertices do not move, only edges inside a disc, so no face outside the
// discs changes.
void runRetriangulation(const PhaseContext& ctx, Snapshot& s, bool afterContourRefinement) {
    const CuspEndRetriangulationOptions o = cuspEndRetriangulationOptions(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const auto before = static_cast<double>(inconsistentFaces(m).size());
    const CuspEndRetriangulationCounts retri =
        retriangulateAtCuspEnds(ctx, m, o.faces, s.phaseIndex);
    // The end of §6.4's final step: the one-rings the offsets are bounded
    // by have changed.
    const NormalOffsetStats offsets = normalOffsetStats(m);
    publish(s, m);
    s.setCounter(counters::kInconsistentFacesBefore, before);
    s.setCounter(afterContourRefinement ? counters::kCuspEndFacesSearchedAfterRefinement
                                        : counters::kCuspEndFacesSearched,
                 static_cast<double>(retri.faces));
    s.setCounter(counters::kCuspEndDiscs, static_cast<double>(retri.applied));
    if (!afterContourRefinement)
        publishNormalOffsetStats(s, offsets);
}

} // namespace

void addCuspEndRetriangulationPhase(Method& m) {
    m.parameters.push_back(
        {"cusp-end-retriangulation-faces",
         "Cusp radial ends: disc re-triangulation",
         "Not in the paper. After the normal wiggle (and again after contour refinement, whose "
         "new C vertices give new outlines), each face still inconsistent with a corner "
         "at the far end c of a cusp's radial edge (Fig. 18e) is searched for a disc of up to "
         "this many faces around it (grown across untagged, non-CC edges, every vertex on its "
         "outline) whose best re-triangulation has strictly fewer inconsistent faces (every "
         "VBO defined, no degenerate CC edge, no new edge at a cusp, no fold); the best disc is "
         "re-triangulated by flips. Beside a cusp the image of the surface is a thin curved "
         "strip, and a face r-x-c whose chord r-x passes on the wrong side of c (bumpy torus "
         "view 4: 1.2 px) has an outline facing the wrong way: no single vertex move fixes it, "
         "other edges of a few faces around do. 0: off. Over 26 views, final inconsistent "
         "faces 0 -> 6: bumpy torus 5 -> 2, spot_control 10 -> 9, bob_control 1 -> 0, bigguy "
         "49 -> 41, spot_quad 11 -> 8, bob_quad 17 -> 14, fertility 19 -> 16, killeroo 163 -> "
         "131, no view worse; 7 or 8 gain nothing more on spot, bob and the bumpy torus.",
         ParameterType::Int,
         6,
         0,
         8,
         {}});
    m.phases.push_back(
        {"cusp-end-retriangulation",
         "Not in the paper: each face still inconsistent with a corner at the far end of a "
         "cusp's radial edge (Fig. 18e) is searched for a disc of up to "
         "cusp-end-retriangulation-faces faces around it whose best re-triangulation has "
         "strictly fewer inconsistent faces; the best disc is re-triangulated by flips.",
         [](const PhaseContext& ctx, Snapshot& s) { runRetriangulation(ctx, s, false); },
         normalWiggleChecks});
}

void addContourRefinementRetriangulationPhase(Method& m) {
    m.phases.push_back(
        {"contour-refinement-retriangulation",
         "Not in the paper: the discs at the cusps' radial ends searched again as in "
         "cusp-end-retriangulation, since the C vertices contour refinement added give them new "
         "outlines.",
         [](const PhaseContext& ctx, Snapshot& s) { runRetriangulation(ctx, s, true); },
         [](const PhaseContext& ctx, const Snapshot& s) {
             return optimizationChecks(ctx, s, false);
         }});
}

} // namespace contour::consistent
