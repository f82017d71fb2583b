#pragma once
// The view graph of the fitted spline's contours (Capouellez et al. 2023
// §4.2, "View graph construction"): the chained contour generator
// (ContourChains.h) is sampled into dense polylines, cut at every point where
// its visibility may change, and every piece gets one ray test.
//
// Nodes (pipeline/ViewGraph.h):
// - CurtainFold, smoothCusp = true, qiStep 1: interior cusps (PatchCusps.h,
//   eq. 5-6) and boundary cusps at joins across patch sides or corners (the
//   sign test of §4.2). nearChains[0] is the branch with the smaller QI,
//   farChains[1] the one with QI + 1: for an interior cusp the side the
//   contour leaves in the direction of eq. 5's t when tau . t > 0; for a
//   boundary cusp the branch that leaves the node away from the viewer
//   (unreliable when the two tangents disagree on that).
// - Bifurcation: a cone point where chains end (several contour loops may
//   share it, §4.2). The node type means "several curves meet here"; no QI
//   is propagated or checked through it, as the paper prescribes.
// - ContourBoundaryJunction: a chain end on the surface boundary (CurveEnd
//   instead when the caller draws no boundary curve, and for ends the
//   chaining left unmatched).
// - ImageIntersection, qiStep 2: T-junctions, from the exact crossings of
//   the sampled polylines (visibility/ImageIntersections.h), moved onto the
//   two curves by Newton's method; crossings at a cone point are the loops
//   meeting there and are left out. The curve with
//   the smaller depth at the crossing is the near one; both curves are cut
//   there, nearChains the two near pieces, farChains = {unoccluded far piece,
//   occluded far piece}. The occluded side is the side of the near contour
//   on which the near surface folds (the image of the second derivative of p
//   along tau in the tangent plane; §4.2: contour over contour gives + 2).
//
// QI: one ray test per chain of at least minRayChainPixels (§4.2: after the
// splitting one test per piece suffices) at its sample nearest half its
// image length, counting the spline's points on the ray along +z in front of
// it (PatchRayTest.h), with a uniform grid over the patches' control-point
// boxes in transformed xy (§4.2: "bounding-box tests and spatial grid").
// Shorter chains get their QI by propagation from their neighbours (§4.2:
// equal QI on the two near pieces of a T-junction, + 2 behind it, + 1 to a
// cusp's far branch; not through cone points nor through boundary cusps
// whose far side is uncertain), and a component without a long chain is
// seeded by a ray on its longest chain. The rules are then checked at every
// node: each disagreement is a VisibilityConflict and flags the chain, and
// no QI is changed. Boundary cusps whose far side is uncertain are neither
// propagated through nor checked.
//
// Coordinates: the spline lives in the transformed space of
// ProjectiveTransform.h (orthographic along +z, smaller z nearer). The
// chains' points are world points (transform.invert), their image the
// camera's pixels and their depth the camera depth (Camera::project), as for
// every other method's view graph. ViewChain::curve is the index of the
// chaining's chain the view chain lies on (as contourChain below); source is
// Face and segmentElement the patch of each chord.
#include "camera/Camera.h"
#include "contours/powell_sabin/ContourChains.h"
#include "contours/powell_sabin/PatchContour.h"
#include "contours/powell_sabin/PatchCusps.h"
#include "contours/powell_sabin/PatchRayTest.h"
#include "contours/powell_sabin/PowellSabinSpline.h"
#include "contours/powell_sabin/ProjectiveTransform.h"
#include "pipeline/ViewGraph.h"

#include <span>
#include <vector>

namespace contour::powell_sabin {

struct SplineViewGraphOptions {
    // Largest distance in pixels between a sampled chord and the curve at the
    // chord's parameter midpoint (adaptive bisection).
    double maxChordPixels = 0.25;
    // Uniform pieces of every segment before the adaptive bisection, so that
    // a chord test cannot miss a wiggle that returns to the chord, and
    // deepest bisection of a piece. Not from the paper.
    int initialPiecesPerSegment = 4;
    int maxBisectionDepth = 24;
    // An interior cusp lies on a segment of its patch when the segment
    // passes within this times the domain's longest side of the cusp's uv.
    double cuspOnSegmentTolerance = 1e-6;
    // Two nodes on one chain closer than this in chain parameter (one unit
    // per link) are one node: a cusp on a side shared by two patches is
    // reported by both.
    double nodeMergeParameter = 1e-7;
    // Chain ends on the surface boundary meet a drawn boundary curve
    // (ContourBoundaryJunction) or nothing (CurveEnd).
    bool boundaryCurves = true;
    // Newton steps that move a crossing of two chords onto the two curves
    // (0: the chords' crossing, within maxChordPixels of the curves).
    int crossingNewtonSteps = 8;
    // A chord crossing is a T-junction only where Newton brings both curves
    // within this distance (pixels) of each other, and where the second
    // curve's points this far (pixels) on either side, at most half way to
    // its nearest node, lie on opposite sides of the first: two branches
    // that touch within the residual do not cross.
    double crossingResidualPixels = 1e-6;
    double crossingSidePixels = 1e-3;
    // Crossings of the sampled chords closer than this (pixels) to a cone
    // point are the loops meeting at the cone (§4.2), not T-junctions: they
    // are left out and counted. Not from the paper.
    double coneCrossingPixels = 0.5;
    // Chains shorter than this in the image (pixels) take their QI by
    // propagation instead of a ray of their own. Not from the paper, which
    // casts a ray only where propagation leaves a chain without a QI. Next to
    // a cusp the sheet that covers the far branch passes within a depth of
    // order d^(3/2) of it (d the distance to the cusp), below what the ray
    // test's depth tolerance resolves, and sub-pixel chains lie there. 0:
    // a ray on every chain.
    double minRayChainPixels = 1.0;
    // Cells of the ray-test grid per patch (cells = this * patches).
    double gridCellsPerPatch = 1.0;
    PatchCuspOptions cusp;
    PatchRayOptions ray;
};

// Where a sample lies: segment `segment` of the input at its parameter t.
struct SplineSampleRef {
    Index segment = kInvalidIndex;
    double t = 0.0;
};

struct SplineViewGraphStats {
    Index contourChains = 0; // chains of the chaining
    Index chains = 0;        // view chains
    Index loops = 0;         // closed view chains (loops without a node)
    Index interiorCusps = 0;
    Index boundaryCusps = 0;
    Index unreliableCusps = 0; // boundary cusps whose far side is uncertain
    // Of those, the ones whose branches' QIs do not differ by one (not
    // conflicts: §4.2 has no rule there).
    Index uncheckedCuspSteps = 0;
    // Interior cusps of patchCusps on no segment of their patch (the
    // contour filter of PatchCusps accepted a root the trimming dropped),
    // and patches whose cusp computation was degenerate: both left out.
    Index unplacedCusps = 0;
    Index degenerateCuspPatches = 0;
    Index tJunctions = 0;
    Index unreliableTJunctions = 0; // near surface's fold side undetermined
    Index imageOverlaps = 0;        // collinear overlapping chords (not split)
    Index coneCrossings = 0;        // chord crossings at a cone point, left out
    Index chordOnlyCrossings = 0;   // chord crossings the exact curves do not have, left out
    Index touchingCrossings = 0;    // curves that meet there without crossing, left out
    Index conePoints = 0;
    Index boundaryEnds = 0;
    Index curveEnds = 0;
    long long samples = 0;
    long long rays = 0;
    Index propagatedChains = 0; // chains whose QI came from a neighbour
    Index conflicts = 0;
    double secondsCusps = 0.0;
    double secondsSampling = 0.0;
    double secondsIntersections = 0.0;
    double secondsChains = 0.0;
    double secondsRays = 0.0;
    double secondsChecks = 0.0;
    double secondsTotal = 0.0;
};

struct SplineViewGraph {
    ViewGraph graph;
    SplineViewGraphStats stats;
    // Per view chain: the chain of the chaining it lies on, and per point
    // of the chain the segment and parameter it was evaluated at.
    std::vector<Index> contourChain;
    std::vector<std::vector<SplineSampleRef>> samples;
    // Per view chain: the index of the point its ray started from.
    std::vector<Index> raySample;
};

// `segments` and `chaining` as patchContours / chainContours gave them for
// tau = (0, 0, 1) on `spline` (in transformed coordinates). Throws
// std::invalid_argument for options out of range, a chaining that names a
// segment outside `segments` or a segment whose patch is not in the spline,
// and std::runtime_error when a ray lies in the surface (PatchRayTest.h).
SplineViewGraph buildSplineViewGraph(const PowellSabinSpline& spline,
                                     std::span<const ContourSegment> segments,
                                     const ContourChaining& chaining, const Camera& camera,
                                     const ProjectiveTransform& transform,
                                     const SplineViewGraphOptions& options = {});

} // namespace contour::powell_sabin
