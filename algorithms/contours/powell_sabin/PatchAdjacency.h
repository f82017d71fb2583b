#pragma once
// Which patch of the fitted spline continues across each side of each patch
// (Capouellez et al. 2023 §4.2: the contours are continuous across patch
// boundaries because the spline is C1, §5.2). Built from the combinatorics
// only: the 12-split numbering of docs/methods/powell-sabin-ps12.md inside a
// face and the layout's half-edges across mesh edges (cut or not), never by
// matching coordinates, which differ between the uv frames of a cut edge.
//
// Side s of a patch runs from its domain corner s to corner s + 1; a point on
// it has the parameter t in [0, 1] from corner s. All patch domains are
// counter-clockwise, so a shared side runs the opposite way in the two
// patches and t on one side is 1 - t on the other (uv scale and rotation
// between cut-edge frames do not change the fraction along the side).
//
// The patch corners are the split points of the faces: the mesh vertices,
// the edge midpoints M, the points Q on the medians and the centroids C.
// Each gets one node id shared by all patches that touch it, across faces.
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/PowellSabinSpline.h"

#include <array>
#include <span>
#include <vector>

namespace contour::powell_sabin {

enum class PatchSideKind {
    MacroPatch, // inside one face's 12-split
    MeshEdge,   // across an uncut mesh edge: the same uv frame
    CutEdge,    // across a cut edge: the two uv images differ by a rigid motion
    Boundary    // on a surface boundary: no neighbour
};
const char* toString(PatchSideKind kind);

struct PatchSideNeighbour {
    Index patch = kInvalidIndex; // kInvalidIndex on a surface boundary
    int side = -1;
    PatchSideKind kind = PatchSideKind::Boundary;
    // The parameter on the neighbour's side of the point at parameter t on
    // this side (always 1 - t: both domains are counter-clockwise).
    double map(double t) const { return 1.0 - t; }
};

enum class PatchNodeKind { Vertex, EdgeMidpoint, MedianPoint, Centroid };
const char* toString(PatchNodeKind kind);

struct PatchCorner {
    Index patch = kInvalidIndex;
    int corner = -1;
};

class PatchAdjacency {
public:
    PatchAdjacency() = default;
    // Throws std::invalid_argument when the spline does not have 12 patches
    // per face of the layout, or the layout's per-edge / per-vertex arrays do
    // not match its mesh.
    PatchAdjacency(const ConeLayout& layout, const PowellSabinSpline& spline);

    Index patchCount() const { return static_cast<Index>(neighbours_.size()); }
    // Side s in 0..2 of `patch`; throws std::out_of_range otherwise.
    const PatchSideNeighbour& neighbour(Index patch, int side) const;

    // Nodes: mesh vertices 0..V-1, then one per edge midpoint, then the
    // three Q points of every face, then every face's centroid.
    Index nodeCount() const { return static_cast<Index>(nodeKind_.size()); }
    Index cornerNode(Index patch, int corner) const;
    PatchNodeKind nodeKind(Index node) const;
    // The mesh vertex, edge or face the node belongs to.
    Index nodeElement(Index node) const;
    bool isConeNode(Index node) const;
    // A boundary vertex or the midpoint of a boundary edge.
    bool isBoundaryNode(Index node) const;
    bool isConeCorner(Index patch, int corner) const {
        return isConeNode(cornerNode(patch, corner));
    }
    // Every (patch, corner) at the node.
    std::span<const PatchCorner> patchesAt(Index node) const;

private:
    Index checkedNode(Index node) const;

    std::vector<std::array<PatchSideNeighbour, 3>> neighbours_;
    std::vector<std::array<Index, 3>> cornerNodes_;
    std::vector<PatchNodeKind> nodeKind_;
    std::vector<Index> nodeElement_;
    std::vector<char> coneNode_;
    std::vector<char> boundaryNode_;
    std::vector<Index> cornerStart_; // CSR offsets into corners_
    std::vector<PatchCorner> corners_;
};

// The parameter in [0, 1] along side `side` of `domain` (from corner `side`)
// of the orthogonal projection of `uv` onto the side's line; not clamped.
double sideParameter(const std::array<Vec2, 3>& domain, int side, const Vec2& uv);

} // namespace contour::powell_sabin
