// Cusp refinement around every cusp (not in the paper; CuspRefinement.h),
// between cusp detection (§6.2 d) and contour insertion (§6.2 e).
#include "contours/consistent/edits/CuspRefinement.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"

namespace contour::consistent {

namespace {

void runCuspRefinement(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    CuspRefinementCounts n;
    if (ctx.parameters.getBool("cusp-refinement"))
        refineAroundCusps(
            m, cuspRefinementSettings(ctx.parameters), [](const Vec3&) { return true; },
            s.phaseIndex, n);
    publish(s, m);
    publishCuspRefinementCounts(s, n);
}

std::vector<InvariantCheck> checkCuspRefinement(const PhaseContext& ctx, const Snapshot& s) {
    return cuspPhaseChecks(ctx, s);
}

} // namespace

void addCuspRefinementPhase(Method& m) {
    m.parameters.push_back(
        {"cusp-refinement",
         "Cusp refinement",
         "Not in the paper: before contour insertion, the edges of the faces near every cusp "
         "edge (§6.2 d) are halved at their parameter-space midpoints (new vertices on the "
         "limit surface), so the cusp's wedge has more, smaller triangles for the contour, the "
         "radial edges and the moves of §6.4. Off by default: around every cusp it makes more "
         "views worse than better (26 views, rings 1: 75 worse, 28 better over the 7 meshes); "
         "cusp-retry uses the same refinement around the cusps of the faces left inconsistent.",
         ParameterType::Bool,
         false,
         0,
         0,
         {}});
    m.parameters.push_back({"cusp-refinement-rings",
                            "Cusp refinement: rings",
                            "The faces refined around a cusp edge: its two faces and those "
                            "within this many face rings of its ends (1: every face at either "
                            "end).",
                            ParameterType::Int,
                            1,
                            0,
                            8,
                            {}});
    m.parameters.push_back({"cusp-refinement-pixels",
                            "Cusp refinement: pixels",
                            "Only faces with a corner within this many pixels of the cusp are "
                            "refined (0: no limit).",
                            ParameterType::Double,
                            0.0,
                            0.0,
                            1000.0,
                            {}});
    m.parameters.push_back({"cusp-refinement-levels",
                            "Cusp refinement: levels",
                            "How many times the refinement around a cusp is repeated (each "
                            "time on the finer mesh, so the region shrinks with the faces).",
                            ParameterType::Int,
                            2,
                            1,
                            6,
                            {}});
    m.parameters.push_back({"cusp-refinement-cusp-edges",
                            "Cusp refinement: halve cusp edges",
                            "Also halve the cusp edges themselves; the half that still changes "
                            "sign (which holds the cusp) keeps the cusp-edge tag.",
                            ParameterType::Bool,
                            true,
                            0,
                            0,
                            {}});
    m.phases.push_back(
        {"cusp-refinement",
         "Not in the paper: with cusp-refinement, the edges of the faces within "
         "cusp-refinement-rings face rings (and cusp-refinement-pixels) of every cusp edge are "
         "halved at their parameter-space midpoints, each fully halved face completed to the "
         "regular 1-4 split by a flip, and the new FF and BB edges searched for sign crossings "
         "as in §6.1.",
         runCuspRefinement, checkCuspRefinement});
}

} // namespace contour::consistent
