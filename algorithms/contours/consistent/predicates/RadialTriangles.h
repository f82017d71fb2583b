#pragma once
// Radial edges and standard radial triangles of the editable mesh (Bénard
// 2014 §5 Definition 5, §6.3): what radial edge insertion
// creates and what the radial flips count.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <vector>

namespace contour::consistent {

// Signed distance from q to the radial plane of the contour vertex p:
// h_p(q) / |n_p × (c - p)| (h_p of RadialPlane.h made a length, so that its
// tolerance scales with the scene). NaN when the plane is undefined.
double radialPlaneDistance(const Camera& camera, const MeshVertex& p, const Vec3& q);

bool isRadialEdge(const ConsistentMesh& m, Index a, Index b);
// v is an endpoint of a radial edge other than a-b.
bool onOtherRadialEdge(const ConsistentMesh& m, Index v, Index a, Index b);
bool onRadialEdge(const ConsistentMesh& m, Index v);
// Radial edges p-r of the C vertex p whose far end r is labelled `side`.
int radialEdgesOnSide(const ConsistentMesh& m, Index p, VertexLabel side);

// §6.3: a triangle (existing or proposed; an edge that does not exist yet
// carries no tag) is standard radial when it has a radial edge p-r and its
// third vertex q either makes p-q a CC edge or lies on another radial edge.
// Same rule as classifyRadialFaces().
bool isStandardRadial(const ConsistentMesh& m, const Triangle& t);

// Definition 5 and §6.3 for every face: a face is radial when one of its
// edges is a radial edge p-r; standard radial when, in addition, it has a CC
// edge or its third vertex is an endpoint of another radial edge.
struct RadialClassification {
    std::vector<int> radial, standard;
};
RadialClassification classifyRadialFaces(const ConsistentMesh& m);

// Faces touching a C vertex that is not a cusp, and how many of them are
// standard radial: the §6.3 (h) target ("all radial triangles touching
// non-cusp contours are standard"), reported, not guaranteed.
struct StandardRadialShare {
    long long contourFaces = 0, standard = 0;
    double percent() const { return contourFaces > 0 ? 100.0 * standard / contourFaces : 100.0; }
};
StandardRadialShare standardRadialShare(const ConsistentMesh& m);

// The C vertices' radial edges: per non-cusp C vertex, whether each side
// (F, B) has one; per cusp, whether it has two (Fig. 18e).
struct RadialCoverage {
    long long contourVertices = 0, complete = 0, missingSides = 0;
};
RadialCoverage radialCoverage(const ConsistentMesh& m);

} // namespace contour::consistent
