#pragma once
// Two methods' drawings of the same view compared in the image: which parts
// of the curves one method draws have no curve of the other within a
// tolerance (in pixels). The workbench highlights those parts when it
// overlays a second method in the 2D view; the batch CLI reports the lengths.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <vector>

namespace contour {

using ImagePolyline = std::vector<Vec2>; // pixels, x right, y down

// What a snapshot draws as visible lines: with a view graph, its visible
// chains (QI 0, not simplified away); without one, every curve projected
// with the camera (ProjectedCurves).
std::vector<ImagePolyline> drawnCurves(const Snapshot& snapshot, const Camera& camera);

struct CurveDifference {
    double tolerancePixels = 0.0;
    double lengthA = 0.0; // total drawn length of each side, pixels
    double lengthB = 0.0;
    // The pieces of one side farther than the tolerance from every curve of
    // the other, as polylines, and their total length.
    std::vector<ImagePolyline> onlyInA;
    std::vector<ImagePolyline> onlyInB;
    double onlyInALength = 0.0;
    double onlyInBLength = 0.0;
};

// Samples every polyline of each side at most every tolerance/4 pixels and
// keeps the runs of samples with no segment of the other side within the
// tolerance. Symmetric: swapping a and b swaps the results.
CurveDifference compareCurves(const std::vector<ImagePolyline>& a,
                              const std::vector<ImagePolyline>& b, double tolerancePixels);

// The distance from points along each curve of `lines` to the nearest
// curve of `other`, in pixels, capped at `cap` (a point with no curve of the
// other side within the cap reads cap): a distance field along the curves.
// Points are taken at most every `step` pixels, each curve's vertices
// included.
struct CurveDistanceField {
    double cap = 0.0;
    std::vector<ImagePolyline> points;          // per curve, the points measured
    std::vector<std::vector<double>> distances; // per curve, per point
    double mean = 0.0, p95 = 0.0, max = 0.0;    // over the points, weighted alike
    long long count = 0;
};
CurveDistanceField distanceAlongCurves(const std::vector<ImagePolyline>& lines,
                                       const std::vector<ImagePolyline>& other, double cap,
                                       double step);

// Where two drawings' topology differs: the nodes a view graph draws
// (curtain folds, T-junctions) and its closed and open visible curves.
struct DrawingNodes {
    std::vector<Vec2> cusps;      // curtain folds (boundary ones included) with a visible chain
    std::vector<Vec2> tJunctions; // image intersections with a visible chain
    int curves = 0;               // visible strokes' connected components
};
// What a snapshot draws: without a view graph no node, and one component
// per projected curve piece.
DrawingNodes drawnNodes(const Snapshot& snapshot, const Camera& camera);

struct NodeDifference {
    double tolerancePixels = 0.0;
    // Nodes of one side with none of the same kind on the other within the
    // tolerance.
    std::vector<Vec2> cuspsOnlyInA, cuspsOnlyInB, tJunctionsOnlyInA, tJunctionsOnlyInB;
    DrawingNodes a, b;
};
NodeDifference compareNodes(const DrawingNodes& a, const DrawingNodes& b, double tolerancePixels);

} // namespace contour
