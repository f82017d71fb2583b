#pragma once
// Stable keys of the counters phases publish in a Snapshot, with the label a
// user reads (the stepper, the JSON report, the CLI summary). Declared in one
// place, as FieldNames.h does for fields: tests and readers look counters up
// by key, so a label can be reworded without breaking them.
#include <string_view>

namespace contour {

struct CounterName {
    std::string_view key;   // kebab-case, never changes once published
    std::string_view label; // what the stepper and the reports show
};

namespace counters {

// Every snapshot (makeInputSnapshot and the phases that rebuild the mesh).
inline constexpr CounterName kFaces{"faces", "faces"};
inline constexpr CounterName kVertices{"vertices", "vertices"};
inline constexpr CounterName kEdges{"edges", "edges"};
inline constexpr CounterName kBoundaryEdges{"boundary-edges", "boundary edges"};

// Surface (contours/common/SurfacePhase.cpp)
inline constexpr CounterName kDomainFaces{"domain-faces", "domain faces"};
inline constexpr CounterName kTessellationFaces{"tessellation-faces", "tessellation faces"};
inline constexpr CounterName kSurfaceSetupSeconds{"surface-setup-seconds", "surface setup seconds"};
inline constexpr CounterName kSurfaceBuildSeconds{"surface-build-seconds", "surface build seconds"};
inline constexpr CounterName kSurfaceCached{"surface-cached", "surface cached"};
inline constexpr CounterName kDomainBoundaryEdges{"domain-boundary-edges", "domain boundary edges"};
inline constexpr CounterName kTessellationLevel{"tessellation-level", "tessellation level"};
inline constexpr CounterName kTessellationSeconds{"tessellation-seconds", "tessellation seconds"};
inline constexpr CounterName kTessellationCached{"tessellation-cached", "tessellation cached"};
inline constexpr CounterName kWeldingSeconds{"welding-seconds",
                                             "seconds welding the drawing tessellation"};

// Facing (contours/common/FacingPhase.cpp)
inline constexpr CounterName kFrontFaces{"front-faces", "front faces"};
inline constexpr CounterName kBackFaces{"back-faces", "back faces"};
inline constexpr CounterName kEdgeOnFaces{"edge-on-faces", "edge-on faces"};

// Contour chains (contours/common/EdgePolylines.cpp)
inline constexpr CounterName kContourChains{"contour-chains", "contour chains"};
inline constexpr CounterName kClosedLoops{"closed-loops", "closed loops"};
inline constexpr CounterName kOpenChains{"open-chains", "open chains"};
inline constexpr CounterName kBoundaryCurves{"boundary-curves", "boundary curves"};

// Mesh contours (contours/mesh/MeshContourMethod.cpp)
inline constexpr CounterName kContourEdges{"contour-edges", "contour edges"};
inline constexpr CounterName kConvexContourEdges{"convex-contour-edges", "convex contour edges"};
inline constexpr CounterName kConcaveContourEdges{"concave-contour-edges", "concave contour edges"};
inline constexpr CounterName kBifurcationVertices{"bifurcation-vertices", "bifurcation vertices"};

// Interpolated contours (contours/interpolated/InterpolatedContourMethod.cpp)
inline constexpr CounterName kFrontVertices{"front-vertices", "front vertices"};
inline constexpr CounterName kBackVertices{"back-vertices", "back vertices"};
inline constexpr CounterName kVerticesWithG0{"vertices-with-g-0", "vertices with g = 0"};
inline constexpr CounterName kCrossingEdges{"crossing-edges", "crossing edges"};
inline constexpr CounterName kContourSegments{"contour-segments", "contour segments"};

// Consistent contours: what every phase publishes (phases/SnapshotRoundTrip.cpp)
inline constexpr CounterName kInconsistentFaces{"inconsistent-faces", "inconsistent faces"};
inline constexpr CounterName kUndefinedVBOs{"undefined-vbos", "undefined VBOs"};
inline constexpr CounterName kFBEdgesLeft{"fb-edges-left", "FB edges left"};
inline constexpr CounterName kDegenerateCCEdges{"degenerate-cc-edges", "degenerate CC edges"};
inline constexpr CounterName kContourVertices{"contour-vertices", "contour vertices"};
inline constexpr CounterName kCusps{"cusps", "cusps"};
inline constexpr CounterName kFoldedFaces{"folded-faces", "folded faces"};
inline constexpr CounterName kFoldsIntroduced{"folds-introduced", "folds introduced"};
inline constexpr CounterName kRadialEdges{"radial-edges", "radial edges"};
inline constexpr CounterName kRadialFaces{"radial-faces", "radial faces"};
inline constexpr CounterName kStandardRadialFaces{"standard-radial-faces", "standard radial faces"};

// Consistent contours: the §6.4 sweeps (phases/OptimizationPhaseSupport.cpp)
inline constexpr CounterName kInconsistentFacesBefore{"inconsistent-faces-before",
                                                      "inconsistent faces before"};
inline constexpr CounterName kSweeps{"sweeps", "sweeps"};
inline constexpr CounterName kVerticesTried{"vertices-tried", "vertices tried"};
inline constexpr CounterName kVerticesAccepted{"vertices-accepted", "vertices accepted"};
inline constexpr CounterName kFacesTried{"faces-tried", "faces tried"};
inline constexpr CounterName kFacesAccepted{"faces-accepted", "faces accepted"};
inline constexpr CounterName kRadialEdgesTried{"radial-edges-tried", "radial edges tried"};
inline constexpr CounterName kRadialEdgesAccepted{"radial-edges-accepted", "radial edges accepted"};

// Consistent contours: initialization (§6.1)
inline constexpr CounterName kInitialFaces{"initial-faces", "initial faces"};
inline constexpr CounterName kSignCrossingSplits{"sign-crossing-splits", "sign-crossing splits"};
inline constexpr CounterName kSignCrossingSplitsOnNewEdges{"sign-crossing-splits-on-new-edges",
                                                           "sign-crossing splits on new edges"};
inline constexpr CounterName kCancelledInterpolations{"cancelled-interpolations",
                                                      "cancelled interpolations"};

// Consistent contours: cusp detection (§6.2 d)
inline constexpr CounterName kCuspSeparations{"cusp-separations", "cusp separations"};
inline constexpr CounterName kCuspsFound{"cusps-found", "cusps found"};
inline constexpr CounterName kCuspSplits{"cusp-splits", "cusp splits"};
inline constexpr CounterName kCuspShifts{"cusp-shifts", "cusp shifts"};
inline constexpr CounterName kCuspsOnAnEdge{"cusps-on-an-edge", "cusps on an edge"};
inline constexpr CounterName kCuspsMovedOffAJumpOfG{"cusps-moved-off-a-jump-of-g",
                                                    "cusps moved off a jump of g"};
inline constexpr CounterName kCuspsSkipped{"cusps-skipped", "cusps skipped"};
inline constexpr CounterName kCuspSearchEvaluations{"cusp-search-evaluations",
                                                    "cusp search evaluations"};
inline constexpr CounterName kCuspSignChangesAcrossAGap{"cusp-sign-changes-across-a-gap",
                                                        "cusp sign changes across a gap"};
inline constexpr CounterName kCuspDoubleCrossingSplits{"cusp-double-crossing-splits",
                                                       "double crossings of g = 0 split"};
inline constexpr CounterName kCuspSignChangesByAJump{"cusp-sign-changes-by-a-jump",
                                                     "cusp sign changes by a jump"};

// Consistent contours: contour insertion (§6.2 e-f)
inline constexpr CounterName kInsertedContourVertices{"inserted-contour-vertices",
                                                      "inserted contour vertices"};
inline constexpr CounterName kInsertedCuspVertices{"inserted-cusp-vertices",
                                                   "inserted cusp vertices"};
inline constexpr CounterName kSnappedVertices{"snapped-vertices", "snapped vertices"};
inline constexpr CounterName kCancelledInsertions{"cancelled-insertions", "cancelled insertions"};
inline constexpr CounterName kSnapsAgainstFolds{"snaps-against-folds",
                                                "snaps instead of a folding split"};
inline constexpr CounterName kRootsInAnotherChart{"roots-in-another-chart",
                                                  "roots found in another chart"};
inline constexpr CounterName kFoldingSplits{"folding-splits", "folding splits kept"};
inline constexpr CounterName kUnconvergedRoots{"unconverged-roots", "unconverged roots"};

// Consistent contours: radial edge insertion (§6.3 g)
inline constexpr CounterName kRadialInsertionsSkipped{"radial-insertions-skipped",
                                                      "radial insertions skipped"};
inline constexpr CounterName kJointRadialVerticesTwoC{"joint-radial-vertices-two-c",
                                                      "joint radial vertices (two C)"};
inline constexpr CounterName kJointSearchesWithoutAUsableRoot{
    "joint-searches-without-a-usable-root", "joint searches without a usable root"};
inline constexpr CounterName kFoldPreventionFlips{"fold-prevention-flips", "fold-prevention flips"};
inline constexpr CounterName kRadialRootsPastTheMidpoints{"radial-roots-past-the-midpoints",
                                                          "radial roots past the midpoints"};
inline constexpr CounterName kCVerticesBetweenOppositeCuspsBothSides{
    "c-vertices-between-opposite-cusps-both-sides",
    "C vertices between opposite cusps (both sides)"};
inline constexpr CounterName kCuspRadialEdgesOnTheOppositeEdge{
    "cusp-radial-edges-on-the-opposite-edge", "cusp radial edges on the opposite edge"};
inline constexpr CounterName kRadialEdgesInAFartherCrossingFace{
    "radial-edges-in-a-farther-crossing-face", "radial edges in a farther crossing face"};
inline constexpr CounterName kInsertionsUndoneVBODefect{"insertions-undone-vbo-defect",
                                                        "insertions undone (VBO defect)"};
inline constexpr CounterName kCVerticesWithTheirRadialEdges{"c-vertices-with-their-radial-edges",
                                                            "C vertices with their radial edges"};
inline constexpr CounterName kCVertexSidesWithoutARadialEdge{
    "c-vertex-sides-without-a-radial-edge", "C vertex sides without a radial edge"};
inline constexpr CounterName kMaxHPRPerDiagonal{"max-h-p-r-per-diagonal",
                                                "max |h_p(r)| / diagonal"};
inline constexpr CounterName kFacesTouchingNonCuspCVertices{"faces-touching-non-cusp-c-vertices",
                                                            "faces touching non-cusp C vertices"};
inline constexpr CounterName kStandardRadialSharePercent{"standard-radial-share-percent",
                                                         "standard radial share (%)"};
inline constexpr CounterName kRadialEdgesInserted{"radial-edges-inserted", "radial edges inserted"};
inline constexpr CounterName kSkippedNoCrossingFace{"skipped-no-crossing-face",
                                                    "skipped: no crossing face"};
inline constexpr CounterName kSkippedNoSignChangeBetweenMidpoints{
    "skipped-no-sign-change-between-midpoints", "skipped: no sign change between midpoints"};
inline constexpr CounterName kSkippedRootAcrossTheContour{"skipped-root-across-the-contour",
                                                          "skipped: root across the contour"};
inline constexpr CounterName kSkippedFoldNoFlipFixesIt{"skipped-fold-no-flip-fixes-it",
                                                       "skipped: fold (no flip fixes it)"};
inline constexpr CounterName kSkippedParameterSpaceFold{"skipped-parameter-space-fold",
                                                        "skipped: parameter-space fold"};
inline constexpr CounterName kSkippedNoCommonChart{"skipped-no-common-chart",
                                                   "skipped: no common chart"};
inline constexpr CounterName kSkippedUnconvergedRoot{"skipped-unconverged-root",
                                                     "skipped: unconverged root"};
inline constexpr CounterName kSkippedVBODefect{"skipped-vbo-defect", "skipped: VBO defect"};
inline constexpr CounterName kSkippedCuspOutsideRegionAmbiguous{
    "skipped-cusp-outside-region-ambiguous", "skipped: cusp outside region ambiguous"};
inline constexpr CounterName kSkippedMoreInconsistentFaces{"skipped-more-inconsistent-faces",
                                                           "skipped: more inconsistent faces"};
inline constexpr CounterName kSkippedNextToACuspWithoutRadialEdges{
    "skipped-next-to-a-cusp-without-radial-edges", "skipped: next to a cusp without radial edges"};
inline constexpr CounterName kSkippedInsideRegionOfANearbyCusp{
    "skipped-inside-region-of-a-nearby-cusp", "skipped: inside region of a nearby cusp"};

// Consistent contours: radial flips (§6.3 h)
inline constexpr CounterName kStandardRadialFacesBefore{"standard-radial-faces-before",
                                                        "standard radial faces before"};
inline constexpr CounterName kRadialFlips{"radial-flips", "radial flips"};
inline constexpr CounterName kFlipsRejectedFold{"flips-rejected-fold", "flips rejected (fold)"};
inline constexpr CounterName kFoldFallbacksTried{"fold-fallbacks-tried", "fold fallbacks tried"};
inline constexpr CounterName kFoldFallbacksNotApplicable{"fold-fallbacks-not-applicable",
                                                         "fold fallbacks not applicable"};
inline constexpr CounterName kFoldFallbacksUndone{"fold-fallbacks-undone", "fold fallbacks undone"};
inline constexpr CounterName kFoldFallbackFlips{"fold-fallback-flips", "fold fallback flips"};
inline constexpr CounterName kVertexDeletions{"vertex-deletions", "vertex deletions"};
inline constexpr CounterName kFanSequencesTried{"fan-sequences-tried", "fan sequences tried"};
inline constexpr CounterName kFanSequencesUndone{"fan-sequences-undone", "fan sequences undone"};
inline constexpr CounterName kFanSequencesFlipped{"fan-sequences-flipped", "fan sequences flipped"};
inline constexpr CounterName kFanSequenceFlips{"fan-sequence-flips", "fan sequence flips"};
inline constexpr CounterName kStandardRadialShareBeforePercent{
    "standard-radial-share-before-percent", "standard radial share before (%)"};

// Consistent contours: radial extension (§6.4 i)
inline constexpr CounterName kRadialPlaneCrossingsFound{"radial-plane-crossings-found",
                                                        "radial plane crossings found"};
inline constexpr CounterName kRadialCurveSamples{"radial-curve-samples", "radial curve samples"};
inline constexpr CounterName kSamplesRejectedFoldAppendixCVBOOrDegenerateEdge{
    "samples-rejected-fold-appendix-c-vbo-or-degenerate-edge",
    "samples rejected (fold, appendix C, VBO or degenerate edge)"};
inline constexpr CounterName kSamplesOnTheOtherSideOfTheContour{
    "samples-on-the-other-side-of-the-contour", "samples on the other side of the contour"};
inline constexpr CounterName kMovesWithoutFewerInconsistentFaces{
    "moves-without-fewer-inconsistent-faces", "moves without fewer inconsistent faces"};
inline constexpr CounterName kRejectedUndefinedVBOOrDegenerateCCEdge{
    "rejected-undefined-vbo-or-degenerate-cc-edge",
    "rejected: undefined VBO or degenerate CC edge"};
inline constexpr CounterName kRejectedParameterFold{"rejected-parameter-fold",
                                                    "rejected: parameter fold"};
inline constexpr CounterName kRejectedAppendixC{"rejected-appendix-c", "rejected: appendix C"};
inline constexpr CounterName kRejectedFaceTurnedOverIn3D{"rejected-face-turned-over-in-3d",
                                                         "rejected: face turned over in 3D"};
inline constexpr CounterName kFlips{"flips", "flips"};
inline constexpr CounterName kFaceWithTwoRadialEndsPairsSampled{
    "face-with-two-radial-ends-pairs-sampled", "face with two radial ends: pairs sampled"};
inline constexpr CounterName kFaceWithTwoRadialEndsBothMoved{
    "face-with-two-radial-ends-both-moved", "face with two radial ends: both moved"};
inline constexpr CounterName kUnconvergedRadialRoots{"unconverged-radial-roots",
                                                     "unconverged radial roots"};
inline constexpr CounterName kFaceWithTwoRadialEndsRejectedUndefinedVBOOrDegenerateCCEdge{
    "face-with-two-radial-ends-rejected-undefined-vbo-or-degenerate-cc-edge",
    "face with two radial ends: rejected: undefined VBO or degenerate CC edge"};
inline constexpr CounterName kFaceWithTwoRadialEndsRejectedParameterFold{
    "face-with-two-radial-ends-rejected-parameter-fold",
    "face with two radial ends: rejected: parameter fold"};
inline constexpr CounterName kFaceWithTwoRadialEndsRejectedAppendixC{
    "face-with-two-radial-ends-rejected-appendix-c",
    "face with two radial ends: rejected: appendix C"};
inline constexpr CounterName kFaceWithTwoRadialEndsRejectedFaceTurnedOverIn3D{
    "face-with-two-radial-ends-rejected-face-turned-over-in-3d",
    "face with two radial ends: rejected: face turned over in 3D"};

// Consistent contours: optimization flips (§6.4)
inline constexpr CounterName kFlipsRejectedTinyTriangle{"flips-rejected-tiny-triangle",
                                                        "flips rejected (tiny triangle)"};
inline constexpr CounterName kFlipsRejectedVBOOrDegenerateEdge{
    "flips-rejected-vbo-or-degenerate-edge", "flips rejected (VBO or degenerate edge)"};
inline constexpr CounterName kTwoFlipSequences{"two-flip-sequences", "two-flip sequences"};

// Consistent contours: parameter wiggle (§6.4)
inline constexpr CounterName kSamplesPerFace{"samples-per-face", "samples per face"};
inline constexpr CounterName kRadialEdgeEndsMovedAlongTheirRadialPlane{
    "radial-edge-ends-moved-along-their-radial-plane",
    "radial-edge ends moved along their radial plane"};
inline constexpr CounterName kRadialPlaneRootsWithoutAChartOrUnconverged{
    "radial-plane-roots-without-a-chart-or-unconverged",
    "radial-plane roots without a chart or unconverged"};
inline constexpr CounterName kVerticesSkippedCBoundaryCuspEdgeTwoRadialEdges{
    "vertices-skipped-c-boundary-cusp-edge-two-radial-edges",
    "vertices skipped (C, boundary, cusp edge, two radial edges)"};
inline constexpr CounterName kSamplesRejectedFoldAppendixCDegenerateEdge{
    "samples-rejected-fold-appendix-c-degenerate-edge",
    "samples rejected (fold, appendix C, degenerate edge)"};
inline constexpr CounterName kSamplesWithoutAChart{"samples-without-a-chart",
                                                   "samples without a chart"};
inline constexpr CounterName kRadialEdgeEndsMovedOffTheirRadialPlaneWiggleRadialEnds{
    "radial-edge-ends-moved-off-their-radial-plane-wiggle-radial-ends",
    "radial-edge ends moved off their radial plane (wiggle-radial-ends)"};
inline constexpr CounterName kRadialEdgeTagsDroppedWiggleRadialEnds{
    "radial-edge-tags-dropped-wiggle-radial-ends", "radial edge tags dropped (wiggle-radial-ends)"};

// Consistent contours: edge splits (§6.4)
inline constexpr CounterName kSplits{"splits", "splits"};
inline constexpr CounterName kSamplesRejectedFoldVBOOrDegenerateEdge{
    "samples-rejected-fold-vbo-or-degenerate-edge",
    "samples rejected (fold, VBO or degenerate edge)"};
inline constexpr CounterName kSplitsWithTheNewVertexWiggled{"splits-with-the-new-vertex-wiggled",
                                                            "splits with the new vertex wiggled"};

// Consistent contours: vertex removal (extension of §6.4)
inline constexpr CounterName kVerticesRemoved{"vertices-removed", "vertices removed"};
inline constexpr CounterName kRingsReTriangulated{"rings-re-triangulated", "rings re-triangulated"};
inline constexpr CounterName kRingsWithoutAnAllowedTriangulation{
    "rings-without-an-allowed-triangulation", "rings without an allowed triangulation"};
inline constexpr CounterName kRingsWithoutFewerInconsistentFaces{
    "rings-without-fewer-inconsistent-faces", "rings without fewer inconsistent faces"};
inline constexpr CounterName kRejectedDegenerateCCEdgeOrFold{
    "rejected-degenerate-cc-edge-or-fold", "rejected (degenerate CC edge or fold)"};
inline constexpr CounterName kRemovalsSkippedTheMeshWouldRefuseAnEdit{
    "removals-skipped-the-mesh-would-refuse-an-edit",
    "removals skipped (the mesh would refuse an edit)"};

// Consistent contours: patch search (extension of §6.4)
inline constexpr CounterName kPatchesSearched{"patches-searched", "patches searched"};
inline constexpr CounterName kPatchSamples{"patch-samples", "patch samples"};
inline constexpr CounterName kVerticesInserted{"vertices-inserted", "vertices inserted"};
inline constexpr CounterName kVerticesRelocated{"vertices-relocated", "vertices relocated"};
inline constexpr CounterName kCVerticesSlidAlongTheContour{"c-vertices-slid-along-the-contour",
                                                           "C vertices slid along the contour"};
inline constexpr CounterName kNewRadialEdges{"new-radial-edges", "new radial edges"};
inline constexpr CounterName kNewRadialEdgesAtCusps{"new-radial-edges-at-cusps",
                                                    "new radial edges at cusps"};
inline constexpr CounterName kFacesSkippedNothingChangedNearThem{
    "faces-skipped-nothing-changed-near-them", "faces skipped (nothing changed near them)"};
inline constexpr CounterName kMovesSkippedTheMeshWouldRefuseAnEdit{
    "moves-skipped-the-mesh-would-refuse-an-edit", "moves skipped (the mesh would refuse an edit)"};

// Consistent contours: chaining (§8)
inline constexpr CounterName kContourGeneratorEdges{"contour-generator-edges",
                                                    "contour generator edges"};
inline constexpr CounterName kMeshContourEdges{"mesh-contour-edges", "mesh contour edges"};

// Visibility (visibility/VisibilityPhase.cpp)
inline constexpr CounterName kSurfaceIntersectionsCached{"surface-intersections-cached",
                                                         "surface intersections cached"};
inline constexpr CounterName kChains{"chains", "chains"};
inline constexpr CounterName kVisibleChains{"visible-chains", "visible chains"};
inline constexpr CounterName kConcaveContourChains{"concave-contour-chains",
                                                   "concave contour chains"};
inline constexpr CounterName kNodes{"nodes", "nodes"};
inline constexpr CounterName kTJunctions{"t-junctions", "T-junctions"};
inline constexpr CounterName kCurtainFolds{"curtain-folds", "curtain folds"};
inline constexpr CounterName kSurfaceIntersectionCurves{"surface-intersection-curves",
                                                        "surface-intersection curves"};
inline constexpr CounterName kConnectedComponents{"connected-components", "connected components"};
inline constexpr CounterName kRayTests{"ray-tests", "ray tests"};
inline constexpr CounterName kConflicts{"conflicts", "conflicts"};
inline constexpr CounterName kRayCheckConflicts{"ray-check-conflicts", "ray-check conflicts"};
// ... whose propagation source agrees with its own ray: the first wrong
// step of each path (VisibilityConflict::root).
inline constexpr CounterName kRootRayCheckConflicts{"root-ray-check-conflicts",
                                                    "root ray-check conflicts"};
inline constexpr CounterName kCheckRaysRecountedExactly{"check-rays-recounted-exactly",
                                                        "check rays recounted exactly"};
inline constexpr CounterName kCheckRaysCorrectedByTheExactRecount{
    "check-rays-corrected-by-the-exact-recount", "check rays corrected by the exact recount"};
inline constexpr CounterName kPropagationCycleDisagreements{"propagation-cycle-disagreements",
                                                            "propagation cycle disagreements"};
inline constexpr CounterName kChainsPropagatedBelowTheirBound{
    "chains-propagated-below-their-bound", "chains propagated below their bound"};
inline constexpr CounterName kVisibleLengthPx{"visible-length-px", "visible length px"};
inline constexpr CounterName kHiddenLengthPx{"hidden-length-px", "hidden length px"};
inline constexpr CounterName kImageSegments{"image-segments", "image segments"};
inline constexpr CounterName kImageSegmentsSwept{"image-segments-swept", "image segments swept"};
inline constexpr CounterName kImageCrossings{"image-crossings", "image crossings"};
inline constexpr CounterName kLogicalCrossingsIgnored{"logical-crossings-ignored",
                                                      "logical crossings ignored"};
inline constexpr CounterName kEndpointTouchesIgnored{"endpoint-touches-ignored",
                                                     "endpoint touches ignored"};
inline constexpr CounterName kOverlappingSegmentPairs{"overlapping-segment-pairs",
                                                      "overlapping segment pairs"};
inline constexpr CounterName kCrossingsBehindNonFoldEdges{"crossings-behind-non-fold-edges",
                                                          "crossings behind non-fold edges"};
inline constexpr CounterName kFoldEdgesOffTheCurves{"fold-edges-off-the-curves",
                                                    "fold edges off the curves"};
inline constexpr CounterName kCurtainFoldsByTheOneRingTestAlone{
    "curtain-folds-by-the-one-ring-test-alone", "curtain folds by the one-ring test alone"};
inline constexpr CounterName kCurtainFoldsWithoutALocalStep{"curtain-folds-without-a-local-step",
                                                            "curtain folds without a local step"};
inline constexpr CounterName kCurtainFoldsOccludingTheConvexSide{
    "curtain-folds-occluding-the-convex-side", "curtain folds occluding the convex side"};
inline constexpr CounterName kMixedConvexityChains{"mixed-convexity-chains",
                                                   "mixed-convexity chains"};
// Consistent contours, curtain folds from the surface's cusps.
inline constexpr CounterName kCurtainFoldsAtCusps{"curtain-folds-at-cusps",
                                                  "curtain folds at cusps"};
inline constexpr CounterName kCurtainFoldsAtSingularPoints{"curtain-folds-at-singular-points",
                                                           "curtain folds at singular points"};
inline constexpr CounterName kCuspFoldsSidedByCurvature{"cusp-folds-sided-by-curvature",
                                                        "cusp folds sided by curvature"};
inline constexpr CounterName kCurtainFoldsByTheNearFaceFallback{
    "curtain-folds-by-the-near-face-fallback", "curtain folds by the near-face fallback"};
inline constexpr CounterName kChainsKeptFromPropagation{"chains-kept-from-propagation",
                                                        "chains kept from propagation"};
inline constexpr CounterName kChainsDecidedByVotes{"chains-decided-by-votes",
                                                   "chains decided by votes"};
inline constexpr CounterName kZigZagVerticesIgnored{"zig-zag-vertices-ignored",
                                                    "zig-zag vertices ignored"};
// Consistent contours: T-junctions flagged as bounding a sub-pixel loop
// (t-junction-min-loop, ViewNode::smallLoop).
inline constexpr CounterName kSmallLoopCrossings{"small-loop-crossings", "small-loop crossings"};
inline constexpr CounterName kUnreliableNearFaceNodes{"unreliable-near-face-nodes",
                                                      "unreliable near-face nodes"};
inline constexpr CounterName kSurfaceIntersectionsSeconds{"surface-intersections-seconds",
                                                          "surface intersections seconds"};
inline constexpr CounterName kViewGraphSeconds{"view-graph-seconds", "view graph seconds"};
inline constexpr CounterName kSweepSeconds{"sweep-seconds", "sweep seconds"};
inline constexpr CounterName kRaySceneSeconds{"ray-scene-seconds", "ray scene seconds"};
inline constexpr CounterName kRayAndQISeconds{"ray-and-qi-seconds", "ray and QI seconds"};
inline constexpr CounterName kCheckRaysSeconds{"check-rays-seconds", "check rays seconds"};
inline constexpr CounterName kConsistentVisibilitySeconds{"consistent-visibility-seconds",
                                                          "consistent visibility seconds"};
inline constexpr CounterName kVisibilitySeconds{"visibility-seconds", "visibility seconds"};
inline constexpr CounterName kNodesCurtainFold{"nodes-curtain-fold", "nodes: curtain-fold"};
inline constexpr CounterName kNodesBoundaryCurtainFold{"nodes-boundary-curtain-fold",
                                                       "nodes: boundary-curtain-fold"};
inline constexpr CounterName kNodesImageIntersection{"nodes-image-intersection",
                                                     "nodes: image-intersection"};
inline constexpr CounterName kNodesContourBoundaryJunction{"nodes-contour-boundary-junction",
                                                           "nodes: contour-boundary-junction"};
inline constexpr CounterName kNodesBifurcation{"nodes-bifurcation", "nodes: bifurcation"};
inline constexpr CounterName kNodesSurfaceIntersectionEnd{"nodes-surface-intersection-end",
                                                          "nodes: surface-intersection-end"};
inline constexpr CounterName kNodesCurveEnd{"nodes-curve-end", "nodes: curve-end"};
inline constexpr CounterName kNodesHiddenFoldCrossing{"nodes-hidden-fold-crossing",
                                                      "nodes: hidden-fold-crossing"};
inline constexpr CounterName kVoteSeconds{"vote-seconds", "vote seconds"};
inline constexpr CounterName kPropagationSeconds{"propagation-seconds", "propagation seconds"};

// Simplification (visibility/SimplificationPhase.cpp)
inline constexpr CounterName kChainsHiddenBySimplification{"chains-hidden-by-simplification",
                                                           "chains hidden by simplification"};
inline constexpr CounterName kSimplificationIterations{"simplification-iterations",
                                                       "simplification iterations"};
inline constexpr CounterName kVisibleLengthBeforeSimplificationPx{
    "visible-length-before-simplification-px", "visible length before simplification (px)"};
inline constexpr CounterName kVisibleLengthAfterSimplificationPx{
    "visible-length-after-simplification-px", "visible length after simplification (px)"};

// The consistent method's cusp retry (a branch decided after
// contour-refinement-retriangulation), the cusp-end-push,
// cusp-end-retriangulation and contour-refinement-retriangulation phases,
// and the normal offsets every phase of §6.4's final step publishes
// (inconsistent faces before: the optimization section).
inline constexpr CounterName kCuspRetryTargets{"cusp-retry-targets",
                                               "cusp retry: cusps at inconsistent faces"};
inline constexpr CounterName kCuspRetryRuns{"cusp-retry-runs", "cusp retry: runs"};
inline constexpr CounterName kCuspRetryAdopted{"cusp-retry-adopted",
                                               "cusp retry: run adopted (0: none)"};
inline constexpr CounterName kCuspRetryBroken{"cusp-retry-broken",
                                              "cusp retry: better runs breaking a post-condition"};
inline constexpr CounterName kCuspRetryCusps{"cusp-retry-cusps",
                                             "cusp retry: cusps refined around"};
inline constexpr CounterName kCuspRetryEdgesHalved{"cusp-retry-edges-halved",
                                                   "cusp retry: edges halved"};
inline constexpr CounterName kVerticesOffSurface{"vertices-off-surface",
                                                 "vertices off the surface"};
inline constexpr CounterName kLargestNormalOffsetRatio{"largest-normal-offset-ratio",
                                                       "largest offset / mean one-ring distance"};
inline constexpr CounterName kLargestContourShift{
    "largest-contour-shift", "largest image shift of a C vertex off the surface (px)"};
inline constexpr CounterName kCuspEndsPushed{"cusp-ends-pushed",
                                             "cusp radial ends pushed (extension-cusp-push-final)"};
inline constexpr CounterName kOtherEndsPushed{
    "other-ends-pushed", "other radial ends pushed (extension-push-every-end-final)"};
inline constexpr CounterName kPushWiggleTried{"push-wiggle-tried", "vertices tried after the push"};
inline constexpr CounterName kPushWiggleAccepted{"push-wiggle-accepted",
                                                 "vertices accepted after the push"};
inline constexpr CounterName kPushWiggleRejectedFold{"push-wiggle-rejected-fold",
                                                     "offsets rejected (3D fold) after the push"};
inline constexpr CounterName kCuspEndFacesSearched{
    "cusp-end-faces-searched",
    "faces at a cusp's radial end searched (cusp-end-retriangulation-faces)"};
inline constexpr CounterName kCuspEndFacesSearchedAfterRefinement{
    "cusp-end-faces-searched-after-refinement",
    "faces at a cusp's radial end searched after contour refinement"};
inline constexpr CounterName kCuspEndDiscs{"cusp-end-discs",
                                           "discs re-triangulated at a cusp's radial end"};

// Cusp refinement (edits/CuspRefinement.cpp, the cusp-refinement phase).
inline constexpr CounterName kCuspsRefinedAround{"cusps-refined-around", "cusps refined around"};
inline constexpr CounterName kFacesRefined{"faces-refined", "faces refined"};
inline constexpr CounterName kEdgesHalved{"edges-halved", "edges halved"};
inline constexpr CounterName kCuspEdgesHalved{"cusp-edges-halved", "cusp edges halved"};
inline constexpr CounterName kHalvingsCancelledNoChart{
    "halvings-cancelled-no-chart", "halvings cancelled (no chart or parameter fold)"};
inline constexpr CounterName kHalvingsCancelled3DFold{"halvings-cancelled-3d-fold",
                                                      "halvings cancelled (3D fold)"};
inline constexpr CounterName kHalvingsCancelledOnContour{"halvings-cancelled-on-contour",
                                                         "halvings cancelled (midpoint on g = 0)"};
inline constexpr CounterName kFlipsToThe14Pattern{"flips-to-the-1-4-pattern",
                                                  "flips to the 1-4 pattern"};
inline constexpr CounterName kSignCrossingSplitsAfterHalving{"sign-crossing-splits-after-halving",
                                                             "sign-crossing splits after halving"};

// Contour refinement.
inline constexpr CounterName kContourEdgesMeasured{"contour-edges-measured",
                                                   "contour edges measured"};
inline constexpr CounterName kContourEdgesFarther{
    "contour-edges-farther", "contour edges farther than contour-refinement-pixels"};
inline constexpr CounterName kContourEdgesSplit{"contour-edges-split", "contour edges split"};
inline constexpr CounterName kContourSplitsRejected{"contour-splits-rejected",
                                                    "splits rejected (consistency, fold or VBO)"};
inline constexpr CounterName kEdgesLeftAtDepth{"edges-left-at-depth",
                                               "edges left at contour-refinement-depth"};
inline constexpr CounterName kEdgesWithoutContourPoint{
    "edges-without-contour-point",
    "edges without a contour point (no chart, no sign change or unconverged)"};
inline constexpr CounterName kLargestChordDistanceBefore{
    "largest-chord-distance-before", "largest chord-to-contour distance before (px)"};
inline constexpr CounterName kLargestChordDistanceAfter{
    "largest-chord-distance-after", "largest chord-to-contour distance after (px)"};

// Normal wiggle: rejected offsets and pair moves.
inline constexpr CounterName kOffsetsRejected3DFold{"offsets-rejected-3d-fold",
                                                    "offsets rejected (3D fold)"};
inline constexpr CounterName kVertexPairsTried{"vertex-pairs-tried", "vertex pairs tried"};
inline constexpr CounterName kVertexPairsMoved{"vertex-pairs-moved", "vertex pairs moved"};
inline constexpr CounterName kRingPairsMoved{
    "ring-pairs-moved",
    "of them, a corner and a neighbour off the face (normal-wiggle-ring-pairs)"};

// Radial extension: the cusps' radial ends pushed.
inline constexpr CounterName kCuspRadialEndsPushesTried{"cusp-radial-ends-pushes-tried",
                                                        "cusp radial ends: pushes tried"};
inline constexpr CounterName kCuspRadialEndsPushed{"cusp-radial-ends-pushed",
                                                   "cusp radial ends: pushed"};
inline constexpr CounterName kCuspRadialEndsFlipsOfPushes{"cusp-radial-ends-flips-of-pushes",
                                                          "cusp radial ends: flips of pushes"};

// Powell-Sabin method (contours/powell_sabin, Capouellez et al. 2023 §5).
inline constexpr CounterName kComponents{"components", "components"};
inline constexpr CounterName kGenus{"genus", "genus (sum over components)"};
inline constexpr CounterName kCones{"cones", "cones"};
inline constexpr CounterName kConeTrianglesSplit{"cone-triangles-split",
                                                 "triangles split 1-to-4 around cones"};
inline constexpr CounterName kConeTrianglesBisected{"cone-triangles-bisected",
                                                    "neighbours split to conform"};
inline constexpr CounterName kNewtonIterations{"newton-iterations", "Newton iterations"};
inline constexpr CounterName kIntrinsicFlips{"intrinsic-flips", "intrinsic flips"};
inline constexpr CounterName kMaxAngleSumError{"max-angle-sum-error",
                                               "largest angle-sum error, free vertices (rad)"};
inline constexpr CounterName kCutEdges{"cut-edges", "cut edges"};
inline constexpr CounterName kLayoutAngleSumError{"layout-angle-sum-error",
                                                  "largest uv angle-sum error (rad)"};
inline constexpr CounterName kCutLengthMismatch{"cut-length-mismatch",
                                                "largest cut-edge length mismatch (relative)"};
inline constexpr CounterName kSideLengthError{"side-length-error",
                                              "largest uv side-length error (relative)"};
inline constexpr CounterName kFlippedUvTriangles{"flipped-uv-triangles", "flipped uv triangles"};
inline constexpr CounterName kMinLogAreaRatio{"min-log-area-ratio",
                                              "area distortion: smallest log(uv/3D area)"};
inline constexpr CounterName kMaxLogAreaRatio{"max-log-area-ratio",
                                              "area distortion: largest log(uv/3D area)"};
inline constexpr CounterName kPatches{"patches", "quadratic patches"};
inline constexpr CounterName kMacroPatches{"macro-patches", "macro-patches"};
inline constexpr CounterName kQuadraticPrecisionError{
    "quadratic-precision-error", "largest quadratic-precision error of a macro-patch"};
inline constexpr CounterName kScalarDofs{"scalar-dofs", "DOFs per coordinate"};
inline constexpr CounterName kHessianNonzeros{"hessian-nonzeros", "Hessian nonzeros"};
inline constexpr CounterName kPreprocessingCached{"preprocessing-cached",
                                                  "taken from the preprocessing cache"};
inline constexpr CounterName kStageSeconds{"stage-seconds", "seconds of this stage's work"};
inline constexpr CounterName kFitResidual{"fit-residual",
                                          "backward error |Hq - b| / (|H| |q| + |b|)"};
inline constexpr CounterName kFitMaxDistance{
    "fit-max-distance", "max distance to the input vertices (/ bbox diagonal)"};
inline constexpr CounterName kPatchesWithContour{"patches-with-contour", "patches with a contour"};
inline constexpr CounterName kEllipseSegments{"ellipse-segments", "segments on ellipses"};
inline constexpr CounterName kHyperbolaSegments{"hyperbola-segments", "segments on hyperbolas"};
inline constexpr CounterName kLineSegments{"line-segments",
                                           "segments on lines (cone patches, cylinders)"};
inline constexpr CounterName kParabolaSegments{"parabola-segments", "segments on parabolas"};
inline constexpr CounterName kContourLoops{"contour-loops", "closed contour loops"};
inline constexpr CounterName kOpenContourChains{"open-contour-chains",
                                                "open chains (ending at cones or boundaries)"};
inline constexpr CounterName kConeChainEnds{"cone-chain-ends", "chain ends at cones"};
inline constexpr CounterName kUnmatchedSegmentEnds{"unmatched-segment-ends",
                                                   "segment ends without a partner"};
inline constexpr CounterName kInteriorCusps{"interior-cusps", "interior cusps (eq. 5-6)"};
inline constexpr CounterName kBoundaryCusps{"boundary-cusps", "cusps on patch boundaries"};
inline constexpr CounterName kDegenerateCuspPatches{"degenerate-cusp-patches",
                                                    "patches with a non-generic cusp curve"};
// Powell-Sabin view graph (SplineViewGraph.h).
inline constexpr CounterName kUnreliableBoundaryCusps{
    "unreliable-boundary-cusps", "boundary cusps with their far side from the rays"};
inline constexpr CounterName kUncheckedCuspSteps{
    "unchecked-cusp-steps", "uncertain boundary cusps whose branches differ by other than 1"};
inline constexpr CounterName kPropagatedChains{"propagated-chains",
                                               "chains given their QI by propagation"};
inline constexpr CounterName kChordOnlyCrossings{
    "chord-only-crossings", "crossings of the sampled chords the curves do not have"};
inline constexpr CounterName kTouchingCrossings{
    "touching-crossings", "places where the curves meet without crossing, left out"};
// Its steps' seconds, in the order they run.
inline constexpr CounterName kCuspPlacementSeconds{"cusp-placement-seconds",
                                                   "seconds placing cusps on the chains"};
inline constexpr CounterName kSamplingSeconds{"sampling-seconds", "seconds sampling the chains"};
inline constexpr CounterName kIntersectionSeconds{"intersection-seconds",
                                                  "seconds finding T-junctions"};
inline constexpr CounterName kChainCuttingSeconds{"chain-cutting-seconds",
                                                  "seconds cutting the chains at nodes"};
inline constexpr CounterName kRayTestSeconds{"ray-test-seconds",
                                             "seconds of ray tests and propagation"};
inline constexpr CounterName kRuleCheckSeconds{"rule-check-seconds",
                                               "seconds checking the propagation rules"};
inline constexpr CounterName kFitRmsDistance{
    "fit-rms-distance", "RMS distance to the input vertices (/ bbox diagonal)"};

// Traced contours (contours/traced, Summers 2016).
inline constexpr CounterName kTracedSeeds{"seeds", "seeds (edge roots and interior seeds)"};
inline constexpr CounterName kEdgeRoots{"edge-roots", "edge roots of g"};
inline constexpr CounterName kCertifiedEdges{"certified-edges",
                                             "edges isolated by Descartes' rule"};
inline constexpr CounterName kSampledEdges{"sampled-edges", "edges sampled (not one polynomial)"};
inline constexpr CounterName kUnresolvedRootClusters{"unresolved-root-clusters",
                                                     "root clusters not isolated"};
inline constexpr CounterName kVanishingEdges{"vanishing-edges", "edges where g vanishes"};
inline constexpr CounterName kTangentRoots{"tangent-roots", "roots tangent to their edge"};
inline constexpr CounterName kEdgeSetupSeconds{"edge-setup-seconds",
                                               "edge polynomial setup seconds"};
inline constexpr CounterName kCriticalPointCandidates{"critical-point-candidates",
                                                      "lattice extrema of g"};
inline constexpr CounterName kCriticalPoints{"critical-points", "critical points of g"};
inline constexpr CounterName kCriticalExtrema{"critical-extrema", "extrema of g"};
inline constexpr CounterName kCriticalSaddles{"critical-saddles", "saddles of g"};
inline constexpr CounterName kInteriorSeeds{"interior-seeds", "interior seeds"};
inline constexpr CounterName kLoops{"loops", "closed loops traced"};
inline constexpr CounterName kOpenCurves{"open-curves", "curves left open"};
inline constexpr CounterName kInteriorLoops{"interior-loops", "loops inside one face"};
inline constexpr CounterName kTracingSteps{"steps", "tracing steps"};
inline constexpr CounterName kRejectedSteps{"rejected-steps", "rejected tracing steps"};
inline constexpr CounterName kStalls{"stalls", "steps below the minimum"};
inline constexpr CounterName kRecoveredStalls{"recovered-stalls", "stalls recovered"};
inline constexpr CounterName kCollisions{"collisions", "curves reaching a used root"};
inline constexpr CounterName kSingularPoints{"singular-points", "points where grad g vanishes"};
inline constexpr CounterName kJoinedPieces{"joined-pieces", "open pieces joined"};
inline constexpr CounterName kRootlessCrossings{"rootless-crossings",
                                                "edges crossed without a root"};
inline constexpr CounterName kUnreachedRoots{"unreached-roots", "edge roots no curve passed"};
inline constexpr CounterName kInteriorSeedsOnCurves{"interior-seeds-on-curves",
                                                    "interior seeds on traced curves"};
inline constexpr CounterName kInteriorSeedsLeavingFace{"interior-seeds-leaving-face",
                                                       "interior seeds whose curve left the face"};
inline constexpr CounterName kMaxAbsG{"max-abs-g", "largest |g| on the curve (/ bbox diagonal)"};
inline constexpr CounterName kCuspsAtJumps{"cusps-at-jumps", "cusps at a jump of kr"};
inline constexpr CounterName kCuspSamples{"cusp-samples", "radial curvature samples"};

} // namespace counters
} // namespace contour
