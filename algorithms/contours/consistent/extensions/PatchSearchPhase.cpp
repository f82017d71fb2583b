// The patch search phase: compound moves of the optimization, not in the
// paper; an extension of Bénard 2014 §6.4 that escapes the fixed point of its
// one-edit-at-a-time local search. The move and its search:
// edits/PatchSearch.h. This file reads the parameters, runs the search on the
// reloaded mesh, publishes it with the search's counters and declares the
// post-conditions.
//
// Placed after vertex removal, before the normal wiggle (which then works on
// what is left): after the normal wiggle instead it removes less, and running
// it in both places removed nothing more. With patch-radial-ends (on by
// default) a radial end slides along its radial plane with its star
// re-triangulated: the only move that removes the torus's last faces (F-F-F
// faces facing away beyond a cusp's radial end, two corners radial ends,
// where a new F vertex inside the face leaves one part facing away). Figures:
// docs/results/consistent-parameter-figures.md.
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/extensions/PatchSearchOptions.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "pipeline/FieldNames.h"

namespace contour::consistent {

PatchSearchOptions PatchSearchOptions::read(const ParameterSet& p) {
    PatchSearchOptions o;
    o.enabled = p.getBool("patch-search");
    o.maxSweeps = p.getInt("patch-max-sweeps");
    o.rows = p.getInt("patch-rows");
    o.maxCorners = p.getInt("patch-max-corners");
    o.relocate = p.getBool("patch-relocate");
    o.grow = p.getBool("patch-grow");
    o.radialEnds = p.getBool("patch-radial-ends");
    o.contourSlide = p.getBool("patch-contour-slide");
    o.newRadialEnds = p.getBool("patch-new-radial-ends");
    o.newRadialCusps = p.getBool("patch-new-radial-cusps");
    o.cuspTies = p.getBool("patch-new-radial-cusp-ties");
    o.cusps = CuspEditOptions::read(p);
    o.radial = RadialEdgeOptions::read(p);
    o.root = ContourRootOptions::read(p);
    return o;
}

PatchSearchSettings PatchSearchOptions::settings(const ConsistentMesh& m) const {
    PatchSearchSettings set;
    set.rows = rows;
    set.maxCorners = maxCorners;
    set.relocate = relocate;
    set.grow = grow;
    set.cuspEdits = cusps.cuspEdits;
    set.radialEnds = radialEnds;
    set.radialTolerance = radial.rootTolerance * sceneScale(m);
    set.contourSlide = contourSlide;
    set.newRadialEnds = newRadialEnds;
    set.newRadialCusps = newRadialCusps;
    set.cuspTies = cuspTies;
    set.rootTolerance = 0.5 * root.tolerance * sceneScale(m);
    set.maxSweeps = maxSweeps;
    return set;
}

namespace {

void runPatchSearch(const PhaseContext& ctx, Snapshot& s) {
    const PatchSearchOptions options = PatchSearchOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    PatchSearchResult result;
    if (options.enabled)
        result =
            searchPatches(m, options.settings(m), s.phaseIndex, [&ctx] { ctx.checkCancelled(); });
    else
        result.faces.before = static_cast<long long>(inconsistentFaces(m).size());
    publish(s, m);
    publishTally(s, result.faces, counters::kFacesTried, counters::kFacesAccepted,
                 "patch-max-sweeps");
    const PatchSearchStats& st = result.moves;
    s.setCounter(counters::kPatchesSearched, static_cast<double>(st.patches));
    s.setCounter(counters::kPatchSamples, static_cast<double>(st.samples));
    s.setCounter(counters::kSamplesWithoutAChart, static_cast<double>(st.cancelledSamples));
    s.setCounter(counters::kRejectedDegenerateCCEdgeOrFold, static_cast<double>(st.rejected));
    s.setCounter(counters::kVerticesInserted, static_cast<double>(st.inserted));
    s.setCounter(counters::kVerticesRelocated, static_cast<double>(st.relocated));
    s.setCounter(counters::kCVerticesSlidAlongTheContour, static_cast<double>(st.slid));
    s.setCounter(counters::kNewRadialEdges, static_cast<double>(st.newRadial));
    s.setCounter(counters::kNewRadialEdgesAtCusps, static_cast<double>(st.newRadialCusps));
    s.setCounter(counters::kFacesSkippedNothingChangedNearThem, static_cast<double>(st.skipped));
    s.setCounter(counters::kMovesSkippedTheMeshWouldRefuseAnEdit,
                 static_cast<double>(st.unplanned));
    if (!options.enabled)
        s.notes.push_back("patch search is off (patch-search = false): mesh passed through");
}

std::vector<InvariantCheck> checkPatchSearch(const PhaseContext& ctx, const Snapshot& s) {
    // After the normal wiggle, vertices sit off the surface, where h_p is
    // no longer evaluated at f(u) (as for the normal wiggle's own checks).
    bool onSurface = true;
    if (const Field* offset = s.field(fields::kNormalOffset); offset && offset->scalars())
        for (double a : *offset->scalars())
            onSurface = onSurface && a == 0.0;
    return optimizationChecks(ctx, s, onSurface);
}

} // namespace

void addPatchSearchPhase(Method& m) {
    m.parameters.push_back(
        {"patch-search",
         "Patch search: on",
         "Not in the paper (extends §6.4 past the fixed point of its one-edit moves): a "
         "new or moved vertex anywhere in a small patch around an inconsistent face, the "
         "patch re-triangulated around it, kept when the patch has strictly fewer "
         "inconsistent faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-rows",
         "Patch search: lattice rows",
         "With patch-search (not in the paper): the free vertex is sampled on the "
         "lattice of step 1/rows on every face of the patch. Cost grows with rows².",
         ParameterType::Int,
         6,
         1,
         64,
         {}});
    m.parameters.push_back(
        {"patch-max-corners",
         "Patch search: largest patch",
         "With patch-search (not in the paper): patches whose boundary has more corners "
         "are skipped (the re-triangulation is cubic in it).",
         ParameterType::Int,
         16,
         4,
         32,
         {}});
    m.parameters.push_back(
        {"patch-relocate",
         "Patch search: relocate vertices",
         "With patch-search (not in the paper): also move a vertex of the face over its "
         "whole star, the star re-triangulated (a wiggle and flips as one move). Off: "
         "new vertices only.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-radial-ends",
         "Patch search: relocate radial ends",
         "With patch-search (not in the paper): also relocate the far end r of a radial "
         "edge p-r over its star, kept on p's radial plane (within "
         "radial-root-tolerance) and joined to p, the star re-triangulated.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-contour-slide",
         "Patch search: slide C vertices",
         "With patch-search (not in the paper): also slide a C vertex (no cusp, no "
         "tagged edge, two CC edges) over its star along the contour (a root of g, §6.2 "
         "e), joined to both contour neighbours, the star re-triangulated.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-ends",
         "Patch search: new radial ends",
         "With patch-search (not in the paper): also put the free vertex on the radial "
         "plane of a C vertex p of the patch boundary that has fewer than two radial "
         "edges, joined to p as a new radial edge (the edge §6.3 g did not insert).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-cusps",
         "Patch search: new radial ends at cusps",
         "With patch-search and patch-new-radial-ends (not in the paper): a cusp with "
         "fewer than two radial edges may get one too, which changes its valence (Fig. "
         "18d keeps it 4 only until the cusp has radial edges, Fig. 18e).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-new-radial-cusp-ties",
         "Patch search: a cusp's first radial edge on a tie",
         "With patch-search and patch-new-radial-cusps (not in the paper): a new radial "
         "end at a cusp without radial edges is accepted when the patch keeps as many "
         "inconsistent faces, not only fewer (it adds the radial edge Fig. 18e gives "
         "every cusp).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-grow",
         "Patch search: grown patches",
         "With patch-search (not in the paper): also try each patch grown by the faces "
         "across its open boundary edges (a wider choice of re-triangulations).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"patch-max-sweeps",
         "Patch search: sweeps",
         "With patch-search (not in the paper): largest number of sweeps over the "
         "inconsistent faces.",
         ParameterType::Int,
         20,
         1,
         10000,
         {}});
    m.addPhase(
        {"patch-search",
         "Extension of §6.4 (not in the paper): around each inconsistent face, one free vertex "
         "(new, or a non-C vertex of the face) sampled over a small patch in parameter space, "
         "the patch re-triangulated around it (fewest inconsistent faces, then the best "
         "minimum Bank-Smith quality), accepted when the patch has strictly fewer inconsistent "
         "faces; no fold, every VBO defined, no new or removed CC edge, no degenerate CC edge, "
         "tagged edges unchanged, C vertices moved only along the contour "
         "(patch-contour-slide), a new radial edge only from a C vertex that lacks one "
         "(patch-new-radial-ends).",
         runPatchSearch, checkPatchSearch});
}

} // namespace contour::consistent
