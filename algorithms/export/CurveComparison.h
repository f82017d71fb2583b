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

} // namespace contour
