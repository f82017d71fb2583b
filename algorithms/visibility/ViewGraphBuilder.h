#pragma once
// Builds the view graph (tutorial §4.5–4.6; Bénard 2014 §8.1–8.3) of a
// snapshot's curves: every point where a curve's visibility may change
// becomes a node (curtain folds, boundary curtain folds, contour–boundary
// junctions, bifurcations, surface-intersection ends, image-space
// T-junctions), and the curves are cut there into chains. QI is not decided
// here (QiPropagation.h); only the facts known without a ray test are set
// (concave contour chains, their lower bound, the nodes' QI steps).
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/ViewGraph.h"

#include <cstdint>
#include <vector>

namespace contour {

// How contour edges are told exterior (locally visible) from interior at
// curtain folds (tutorial §4.3 item 3; Bénard 2014 §8.1).
enum class CurtainFoldTest {
    Convexity, // mesh contours: concave iff FRONTSIDE(a, b, d, e) > 0 (tutorial app. C)
    NearFace,  // the near face's VBO (Bénard 2014 §8.1, footnote 3) at every vertex
    // Consistent contours: the curtain folds are the smooth surface's cusps
    // (the mesh's cusp vertices, g = 0 and κr changing sign, §6.2 d), each
    // sided by the one-ring overlap test at the cusp vertex (tutorial
    // app. C.2) and stepping one sheet. Other contour vertices are no nodes
    // (zig-zags of the polyline), except next to an inconsistent face, where
    // the near-face test of §8.1 still applies (the mesh may fold where the
    // surface does not, §8.4).
    SmoothCusps,
    None, // interpolated contours lie inside faces: no mesh curtain folds
};

struct ViewGraphOptions {
    CurtainFoldTest foldTest = CurtainFoldTest::Convexity;
    // Bénard 2014 footnote 3: a near-face test with |v · (w1 − w2)| below
    // this is unreliable (the node is flagged, the decision is kept).
    double nearFaceEpsilon = 1.0;
    // Also use the mesh's fold edges (faces facing opposite ways) that lie
    // on no curve as occluders in the sweep: the far curve is split behind
    // them like behind a contour. Needed for exact propagation when the
    // curves are not all of the mesh's folds (consistent contours: the
    // generator follows the VBO, not the facing; mesh contours with
    // concave edges dropped).
    bool meshFoldOccluders = false;
    // Tutorial theorem B.0.1 (concave contours are never visible, QI ≥ 1)
    // holds on closed meshes that do not intersect themselves; where the
    // mesh does, a concave edge can sit in an inverted region and be seen.
    bool concaveLowerBound = true;
    // Image crossings of two drawn curves that bound a loop with less than
    // this image arc on each side (pixels) are zig-zags of the polylines:
    // their T-junctions are flagged ViewNode::smallLoop
    // (core/SmallLoopCrossings.h); 0 flags none.
    double smallLoopPixels = 0.0;
};

struct ViewGraphInput {
    const TriangleMesh* mesh = nullptr;
    // The curves to cut (ViewChain::curve indexes this list).
    const std::vector<Polyline>* curves = nullptr;
    // Per curve, possibly empty: for surface-intersection curves the second
    // face of each segment (SurfaceIntersections.h).
    const std::vector<std::vector<Index>>* secondFaces = nullptr;
    // Per face: > 0 front, < 0 back, 0 undefined. Mesh contours: the exact
    // facing; consistent contours: the VBO (Bénard 2014 §8.1).
    const std::vector<int>* faceOrientation = nullptr;
    // Per face, optional: the exact geometric facing (> 0 front), which
    // decides which edges are folds that occlude. Defaults to
    // faceOrientation.
    const std::vector<int>* facing = nullptr;
    // CurtainFoldTest::SmoothCusps: per vertex, a cusp of the smooth surface
    // (non-zero) and the radial curvature (NaN where undefined); per face,
    // inconsistent (non-zero: the near-face test applies at its corners).
    const std::vector<std::uint8_t>* cuspVertex = nullptr;
    // Optional, per vertex: a cusp vertex at a singular point of the surface
    // (fields::kSingularCusp). Its curtain fold is stepped by the one-ring
    // test, not by one sheet: the smooth surface's fold does not exist there.
    const std::vector<std::uint8_t>* singularCusp = nullptr;
    const std::vector<double>* radialCurvature = nullptr;
    const std::vector<std::uint8_t>* faceInconsistent = nullptr;
};

// What the builder saw, for the phase's counters and notes.
struct ViewGraphBuildStats {
    long long segments = 0;
    long long sweptSegments = 0;         // ... with a box overlap that may be a crossing
    long long imageCrossings = 0;        // pairs of segments meeting in the image
    long long logicalCrossings = 0;      // ... that share a mesh vertex (app. C.1): ignored
    long long endpointTouches = 0;       // ... meeting at a segment's endpoint: not split
    long long nonIndicatingNear = 0;     // ... whose near segment is a surface intersection
    long long equalDepthCrossings = 0;   // ... with no near one (same depth): not split
    long long ambiguousOccludedSide = 0; // near contour whose two faces disagree on the side
    long long overlaps = 0;              // collinear overlapping segment pairs: not split
    long long degenerateSegments = 0;    // zero length in the image
    long long unreliableFolds = 0;       // curtain folds with an unreliable near-face test
    long long foldsWithoutStep = 0;      // curtain folds whose one-ring occludes neither side more
    long long convexFarFolds = 0;        // curtain folds whose occluded side is the convex edge
    long long mixedConvexityChains = 0;  // contour chains with convex and concave edges
    long long nonFoldNear = 0;           // ... whose near contour edge is no mesh fold
    long long foldOccluderEdges = 0;     // mesh fold edges on no curve, added as occluders
    long long localOnlyFolds = 0;        // curtain folds found by the one-ring test alone
    // SmoothCusps: curtain folds at the surface's cusps; those whose one-ring
    // covers both branches alike (κr chose the interior one); folds by the
    // near-face fallback next to inconsistent faces; and contour vertices
    // away from them where the near-face or one-ring test alone would have
    // made a fold (zig-zags of the polyline: no node).
    long long smoothCuspFolds = 0;
    long long singularCuspFolds = 0; // at cusps on singular points: one-ring step
    long long cuspFoldsSidedByCurvature = 0;
    long long fallbackFolds = 0;
    long long zigZagsIgnored = 0;
    long long smallLoopCrossings = 0; // T-junctions flagged as bounding a sub-pixel loop
    double sweepSeconds = 0.0;
};

ViewGraph buildViewGraph(const ViewGraphInput& input, const Camera& camera,
                         const ViewGraphOptions& options, ViewGraphBuildStats* stats = nullptr);

// The faces adjacent to segment `segment` of a chain: the edge's faces, the
// face itself, or both faces of a surface-intersection segment. Ray tests
// ignore them (tutorial app. C.1). None for a segment with no element.
std::vector<Index> segmentFaces(const TriangleMesh& mesh, const ViewChain& chain, size_t segment);

} // namespace contour
