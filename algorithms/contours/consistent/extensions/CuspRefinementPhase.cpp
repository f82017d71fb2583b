// Cusp refinement (not in the paper; CuspRefinement.h), between cusp
// detection (§6.2 d) and contour insertion (§6.2 e): around every cusp with
// cusp-refinement, and in a cusp retry's run (CuspRetryBranch.cpp) first
// around the cusps its branch data selects.
#include "contours/consistent/edits/CuspRefinement.h"
#include "contours/consistent/extensions/CuspRefinementTargets.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/Initialization.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"

#include <string>

namespace contour::consistent {

namespace {

struct CuspRefinementOptions {
    bool everyCusp = false; // cusp-refinement
    CuspRefinementSettings settings;
};

// The cusp-refinement-* parameters, with initialization's crossing search
// (§6.1) and contour insertion's root iterations (§6.2 e) read through those
// phases' own options.
CuspRefinementSettings cuspRefinementSettings(const ParameterSet& p) {
    CuspRefinementSettings set;
    set.rings = p.getInt("cusp-refinement-rings");
    set.levels = p.getInt("cusp-refinement-levels");
    set.pixels = p.getDouble("cusp-refinement-pixels");
    set.cuspEdges = p.getBool("cusp-refinement-cusp-edges");
    const CrossingSearchOptions crossing = CrossingSearchOptions::read(p);
    set.crossingSamples = crossing.samples;
    set.crossingRounds = crossing.rounds;
    set.rootIterations = ContourRootOptions::read(p).maxIterations;
    return set;
}

CuspRefinementOptions cuspRefinementOptions(const ParameterSet& p) {
    return {p.getBool("cusp-refinement"), cuspRefinementSettings(p)};
}

void runCuspRefinement(const PhaseContext& ctx, Snapshot& s) {
    const CuspRefinementOptions o = cuspRefinementOptions(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    if (const auto* targets = ctx.branchData<CuspRefinementTargets>()) {
        CuspRefinementCounts t;
        refineAroundCusps(
            m, o.settings, [&](const Vec3& cusp) { return targets->selects(ctx.camera, cusp); },
            s.phaseIndex, t);
        s.setCounter(counters::kCuspRetryCusps, static_cast<double>(t.cusps));
        s.setCounter(counters::kCuspRetryEdgesHalved, static_cast<double>(t.splits));
    }
    CuspRefinementCounts n;
    if (o.everyCusp)
        refineAroundCusps(
            m, o.settings, [](const Vec3&) { return true; }, s.phaseIndex, n);
    publish(s, m);
    publishCuspRefinementCounts(s, n);
}

std::vector<InvariantCheck> checkCuspRefinement(const PhaseContext& ctx, const Snapshot& s) {
    return cuspPhaseChecks(ctx, s);
}

} // namespace

bool CuspRefinementTargets::selects(const Camera& camera, const Vec3& cusp) const {
    const Vec2 q = camera.project(cusp).pixel;
    for (const Vec2& p : at)
        if ((p - q).norm() <= pixels)
            return true;
    return false;
}

std::vector<BranchVariant>
cuspRefinementVariants(const ParameterSet& p, bool every,
                       std::shared_ptr<const CuspRefinementTargets> targets) {
    const CuspRefinementSettings set = cuspRefinementOptions(p).settings;
    const auto variant = [&](int rings, int levels) {
        return BranchVariant{"rings " + std::to_string(rings) + ", levels " +
                                 std::to_string(levels),
                             {{"cusp-refinement-rings", rings}, {"cusp-refinement-levels", levels}},
                             targets};
    };
    std::vector<BranchVariant> out{variant(set.rings, set.levels)};
    if (every)
        for (int levels = 1; levels <= set.levels; ++levels)
            for (int rings = 0; rings <= set.rings; ++rings)
                if (rings != set.rings || levels != set.levels)
                    out.push_back(variant(rings, levels));
    return out;
}

void addCuspRefinementPhase(Method& m) {
    m.parameters.push_back(
        {"cusp-refinement",
         "Cusp refinement",
         "Not in the paper: before contour insertion (§6.2 e), the edges of the faces "
         "near every cusp edge are halved at their parameter-space midpoints, giving the "
         "cusp's wedge smaller triangles. cusp-retry uses the same refinement around "
         "cusps at faces left inconsistent.",
         ParameterType::Bool,
         false,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"cusp-refinement-rings",
         "Cusp refinement: rings",
         "With cusp-refinement or cusp-retry (not in the paper): the faces refined "
         "around a cusp edge are its two faces and those within this many face rings of "
         "its ends (1: every face at either end).",
         ParameterType::Int,
         1,
         0,
         8,
         {}});
    m.parameters.push_back(
        {"cusp-refinement-pixels",
         "Cusp refinement: pixels",
         "With cusp-refinement or cusp-retry (not in the paper): only faces with a "
         "corner within this many pixels of the cusp are refined (0: no limit).",
         ParameterType::Double,
         0.0,
         0.0,
         1000.0,
         {}});
    m.parameters.push_back(
        {"cusp-refinement-levels",
         "Cusp refinement: levels",
         "With cusp-refinement or cusp-retry (not in the paper): how many times the "
         "refinement around a cusp is repeated, each time on the finer mesh, so the "
         "region shrinks with the faces.",
         ParameterType::Int,
         2,
         1,
         6,
         {}});
    m.parameters.push_back(
        {"cusp-refinement-cusp-edges",
         "Cusp refinement: halve cusp edges",
         "With cusp-refinement or cusp-retry (not in the paper): also halve the cusp "
         "edges themselves; the half that still changes sign keeps the cusp-edge tag.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"cusp-refinement",
         "Not in the paper: with cusp-refinement, the edges of the faces within "
         "cusp-refinement-rings face rings (and cusp-refinement-pixels) of every cusp edge are "
         "halved at their parameter-space midpoints, each fully halved face completed to the "
         "regular 1-4 split by a flip, and the new FF and BB edges searched for sign crossings "
         "as in §6.1.",
         runCuspRefinement, checkCuspRefinement});
}

} // namespace contour::consistent
