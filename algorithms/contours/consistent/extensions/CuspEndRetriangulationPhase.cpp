// Re-triangulation of discs of faces at the far ends of the cusps' radial
// edges (not in the paper; CuspEndRetriangulation.h, Bénard 2014 §6.3
// Fig. 18e): once after the normal wiggle and the cusps' final push, and
// again after contour refinement, whose new C vertices give the discs new
// outlines.
#include "contours/consistent/edits/CuspEndRetriangulation.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/NormalWiggle.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/MeshAnalysis.h"

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
         "Not in the paper: after the normal wiggle and after contour refinement, each "
         "face still inconsistent at the far end of a cusp's radial edge (Fig. 18e) is "
         "searched for a disc of up to this many faces whose re-triangulation has fewer "
         "inconsistent faces. 0: off.",
         ParameterType::Int,
         6,
         0,
         8,
         {}});
    m.addPhase({"cusp-end-retriangulation",
                "Not in the paper: each face still inconsistent with a corner at the far end of a "
                "cusp's radial edge (Fig. 18e) is searched for a disc of up to "
                "cusp-end-retriangulation-faces faces around it whose best re-triangulation has "
                "strictly fewer inconsistent faces; the best disc is re-triangulated by flips.",
                [](const PhaseContext& ctx, Snapshot& s) { runRetriangulation(ctx, s, false); },
                normalWiggleChecks});
}

void addContourRefinementRetriangulationPhase(Method& m) {
    m.addPhase(
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
