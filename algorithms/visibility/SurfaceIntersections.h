#pragma once
// Surface–surface intersection curves of a triangle mesh (tutorial §4.2, "surface intersections" as
// a third curve type next to contours and boundaries). Candidate face pairs (overlapping bounding
// boxes, no shared vertex) come from a uniform grid of cells two face boxes wide, searched cell by
// cell in parallel; a conservative double-precision plane test (Shewchuk's orient3d error bound)
// drops the pairs certainly on one side of each other's plane, and the others are sorted by face
// pair, so the result does not depend on the thread count. A pair in generic position is decided
// with CGAL's exact predicates (orient3d): its segment's two ends are where an edge of one face
// crosses the other face, named exactly by that (edge, face) pair; only their coordinates are
// rounded. Other pairs (a vertex on the other face's plane, edges meeting, coplanar faces) go to
// CGAL's exact triangle–triangle intersection (exact constructions kernel) and their ends are
// classified exactly onto a mesh vertex, edge or face. Segments are chained through these names
// (two ends with the same pair of simplices are the same point), never by comparing floating-point
// positions.
//
// Faces that share a vertex (or an edge) are skipped: they meet at that
// vertex/edge, which is not an intersection curve, and testing them would
// report every mesh edge as one. Consequence: two faces of one vertex's
// fan that fold through each other are not reported.
#include "mesh/TriangleMesh.h"
#include "pipeline/Curve.h"

#include <vector>

namespace contour {

// Intersection curves between non-adjacent triangles of the mesh (CGAL),
// chained into polylines: type SurfaceIntersection, source Face,
// segmentElement = first face; the second face of each segment in
// `secondFaces` (parallel to segmentElement).
struct SurfaceIntersectionCurves {
    std::vector<Polyline> curves;
    std::vector<std::vector<Index>> secondFaces;

    // Counters for snapshot notes (added fields; the two above are the fixed API).
    long long candidatePairs = 0;    // bounding boxes overlap, no shared vertex
    long long intersectingPairs = 0; // exact test: the triangles meet in a segment
    long long exactPairs = 0;        // not in generic position: CGAL exact constructions
    long long coplanarPairs = 0;     // coplanar overlaps (area): not curves, skipped
    long long touchingPairs = 0;     // the triangles meet in a single point: skipped
    long long duplicateSegments = 0; // a piece along a mesh edge, found by several pairs
    int branchPoints = 0;            // chain ends where more than two segments meet
    int openEnds = 0;                // chain ends met by a single segment
};
SurfaceIntersectionCurves surfaceIntersectionCurves(const TriangleMesh& mesh);

} // namespace contour
