#pragma once
// Patch search: compound moves of the optimization, not in the paper. It
// extends the one-edit moves of Bénard 2014 §6.4 (flips, parameter wiggle,
// edge split) and the vertex deletion of §6.3 h past their fixed point:
// after those sweeps, re-running them changes nothing, since each changes
// one edge, one vertex's position or one split point, and a face that only
// becomes consistent when a vertex appears (or moves) AND the faces around
// it are re-connected is out of their reach.
//
// The move: a small patch of faces (a topological disc) around an
// inconsistent face gets one free vertex x, placed at sampled points of the
// patch in parameter space, and the patch is re-triangulated with x
// optimally (fewest inconsistent faces, then the best minimum Bank-Smith
// quality). Two kinds of patch, each also grown by the faces across its
// open boundary edges:
//  - insertion: the face plus its neighbours across its untagged, non-CC
//    edges (also centred on each such neighbour); x is a NEW vertex. This
//    contains the edge split followed by flips of the new vertex's opposite
//    edges (x on an edge) and the 1->3 face split followed by flips (x
//    inside a face).
//  - relocation: the star of a vertex v of the face that vertex removal
//    could remove (not C, not a cusp, no tagged edge, and off the bounding
//    box unless another vertex keeps that side); x is v's new position: a
//    parameter wiggle and flips around v as one move. With `radialEnds`,
//    the far end r of one radial edge p-r also moves, sampled on p's radial
//    plane only (roots of h_p between lattice points) and kept joined to p,
//    so the edge stays radial (§6.3 g). With `contourSlide`, a C vertex
//    without tagged edges and with exactly two CC edges also moves, sampled
//    on the contour only (roots of g between lattice points, §6.2) and kept
//    joined to both contour neighbours, so its CC edges stay.
//  - new radial ends (`newRadialEnds`): a C vertex p on the patch's
//    boundary with fewer than two radial edges (radial edge insertion,
//    §6.3 g, skipped one, e.g. to avoid a fold) gets one: x (inserted, or a
//    relocated vertex without tagged edges) is sampled on p's radial plane
//    only, kept joined to p, and p-x is tagged radial. Most faces touching
//    such a C vertex on its bare side are F-F-C or B-B-C slivers of the
//    wrong facing; a vertex on p's radial plane gives that side the
//    standard radial triangles of §6.3 h.
// Slides and new radial ends are the late moves: they are tried only once
// the other moves are at their fixed point (a second pass of sweeps; faces
// whose surroundings did not change search their late moves alone), so
// that they never pre-empt one of those moves.
//
// Every triangulation of a polygon with one interior point x is a fan of x
// over some of the polygon's corners, the pockets between consecutive fan
// corners triangulated without x: the pockets' best triangulations do not
// depend on x (computed once per patch, by the dynamic programme of vertex
// removal), the fan is chosen per sample by a cyclic dynamic programme. The
// move is judged like every §6.4 move, on the faces it changes
// (LocalEdit): strictly fewer inconsistent faces, every VBO defined (no FB
// edge, no CCC face), no degenerate CC edge, no new CC edge (a contour edge
// the root finding did not make), no CC edge removed, no fold in parameter
// space or 3D. Tagged (radial, cusp) edges and cusps never move; C vertices
// only along the contour. Each move is planned on a copy of the patch
// (RingRetriangulation) and applied through the mesh's own edits.
#include "contours/consistent/edits/OptimizationSweep.h"
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <functional>

namespace contour::consistent {

struct PatchSearchSettings {
    int rows = 6;         // lattice step 1/rows on every face of the patch
    int maxCorners = 16;  // largest patch polygon (the re-triangulation is cubic in it)
    bool insert = true;   // insertion patches
    bool relocate = true; // relocation patches
    bool grow = true;     // also the patches grown by one layer of faces
    // Moves may change a cusp's valence once it has radial edges
    // (lockedCusp of LocalEdit.h).
    bool cuspEdits = true;
    bool radialEnds = false;      // relocate radial ends along their radial planes
    double radialTolerance = 0.0; // |h_p(r)| of a radial end (a distance)
    bool contourSlide = false;    // late: relocate C vertices along the contour g = 0
    bool newRadialEnds = false;   // late: x on the radial plane of a C vertex lacking a radial edge
    bool newRadialCusps = false;  // ... also of a cusp, whose valence then changes
    bool cuspTies = false;        // a cusp's first radial edge also without a gain
    double rootTolerance = 0.0;   // |g| of a slid C vertex (a distance)
    int maxSweeps = 20;           // sweeps over the inconsistent faces, per pass
};

// What the search did, summed over both passes.
struct PatchSearchStats {
    long long patches = 0;          // candidate patches searched
    long long samples = 0;          // positions of x evaluated
    long long cancelledSamples = 0; // lattice points or roots without a chart
    // Best triangulations the whole edit rejected (degenerate CC edge, fold).
    long long rejected = 0;
    long long inserted = 0;       // moves that inserted x
    long long relocated = 0;      // moves that relocated a vertex (slides included)
    long long skipped = 0;        // faces not searched: nothing changed near them since they failed
    long long unplanned = 0;      // moves skipped: the mesh would refuse one of their edits
    long long slid = 0;           // relocations of a C vertex along the contour
    long long newRadial = 0;      // new radial edges
    long long newRadialCusps = 0; // ... of them at cusps
};

struct PatchSearchResult {
    // The sweeps over the inconsistent faces: `before` when the search
    // starts, faces tried and moves accepted over both passes, the last
    // pass's sweep-limit flag.
    OptimizationTally faces;
    PatchSearchStats moves;
};

// Sweeps the inconsistent faces of `m`, applying the best patch move around
// each (only moves that leave strictly fewer inconsistent faces, or the
// same with `cuspTies` for a cusp's first radial edge), until a sweep
// applies nothing or `maxSweeps`; then, with a late move on, a second pass
// with the late moves. `phase` is recorded on what the edits change.
// `checkCancelled` (may be empty) runs before each face and stops the search
// by throwing. m stays an oriented manifold whose inconsistent faces never
// grow.
PatchSearchResult searchPatches(ConsistentMesh& m, const PatchSearchSettings& settings, int phase,
                                const std::function<void()>& checkCancelled = {});

} // namespace contour::consistent
