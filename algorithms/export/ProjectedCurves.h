#pragma once
// A snapshot's curves as the camera sees them: each polyline projected to
// pixels (Camera::project), split into visible pieces where a perspective
// camera would have to draw a point behind its eye. The SVG writer draws the
// pieces; the JSON report measures them.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"
#include "pipeline/ViewGraph.h"

#include <cstddef>
#include <vector>

namespace contour {

struct ProjectedPolyline {
    std::size_t index = 0; // position in Snapshot::curves
    CurveType type = CurveType::Contour;
    bool closed = false;          // the curve's own flag
    std::size_t pointCount = 0;   // points of the 3D curve
    std::size_t hiddenPoints = 0; // points behind a perspective eye (depth <= 0), not drawn
    // Runs of consecutive drawable points, in pixels (x right, y down). A
    // closed curve with no hidden point is one piece whose last point repeats
    // its first, so that drawing the piece as an open polyline closes it.
    std::vector<std::vector<Vec2>> pieces;
    double lengthPixels = 0.0; // total length of the pieces

    bool clipped() const { return hiddenPoints > 0; }
};

std::vector<ProjectedPolyline> projectCurves(const std::vector<Polyline>& curves,
                                             const Camera& camera);

// A view-graph chain's drawable pieces, the same way: runs of at least two
// points in front of a perspective eye, in pixels.
std::vector<std::vector<Vec2>> projectChain(const ViewChain& chain, const Camera& camera);

} // namespace contour
