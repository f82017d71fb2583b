#pragma once
// The cut to a disk through the cones and the greedy layout of the flat
// metric to uv per corner (Capouellez et al. 2023 §5.1, layout as in
// Springborn et al. 2008). Per component the cut is a tree of mesh edges that
// joins the cones and the boundary loops, plus the 2g loops of a tree-cotree
// decomposition for handles; faces are then unfolded breadth first across
// uncut edges from the side lengths of the flat metric.
#include "contours/powell_sabin/ConformalMap.h"

#include <array>
#include <span>
#include <vector>

namespace contour::powell_sabin {

struct ConeLayout {
    // The flat metric's connectivity with the input's vertex positions.
    TriangleMesh mesh;
    std::vector<std::array<Vec2, 3>> cornerUv; // per face, per corner
    std::vector<char> cutEdge;                 // per edge of `mesh`; boundary edges are 0
    std::vector<char> isCone;                  // per vertex
    // Checks, reported as counters and post-conditions by the method.
    double maxAngleSumError = 0.0;     // |2*pi - uv angle sum| at free interior vertices
    double maxCutLengthMismatch = 0.0; // relative, between the two uv images of a cut edge
    // Relative, uv side length vs the flat metric. For layoutFromCornerUv the
    // metric is the uv's own: the relative length difference of the two uv
    // images of every uncut interior edge.
    double maxSideLengthError = 0.0;
    Index flippedTriangles = 0; // uv triangles of non-positive signed area
    // Distortion: per face, log(uv area / 3D area), and its extremes
    // (-infinity for a uv triangle of non-positive area).
    std::vector<double> logAreaRatio;
    double minLogAreaRatio = 0.0;
    double maxLogAreaRatio = 0.0;
};

// Tolerances of the input checks (none is from the paper: they only tell
// round-off from broken input).
struct ConeLayoutOptions {
    // Relative: the two lengths one edge gets from its two faces in the flat
    // metric, and the two uv images of a cut edge, must agree to this.
    double edgeLengthTolerance = 1e-6;
    // Two faces agree on the uv of an edge's endpoint when the two points are
    // closer than this times the edge's uv length (layoutFromCornerUv).
    double uvMatchTolerance = 1e-9;
    // A uv triangle is degenerate when |2 * signed area| <= this times its
    // longest side squared (layoutFromCornerUv).
    double degenerateUvTolerance = 1e-12;
};

// Throws std::invalid_argument naming the reason: sizes that do not match,
// non-positive or non-finite lengths, a violated triangle inequality, an edge
// whose two faces give it different lengths, a cone out of range or without
// a face, a non-manifold vertex, a face that cannot be reached, or a
// component that is not a disk after cutting (for example a closed genus-0
// component with fewer than two cones).
ConeLayout layoutConformalMap(std::span<const Vec3> positions, const ConformalMap& map,
                              std::span<const Index> cones, const ConeLayoutOptions& options = {});

// The layout an OBJ's texture coordinates already carry (what the paper's
// code reads): a cut edge is one whose two faces give its ends different
// uv; a cone is a vertex whose uv angle sum differs from 2*pi by more than
// `coneAngleTolerance` (interior vertices only). The checks are filled in
// the same way. Throws std::invalid_argument naming the problem (missing or
// degenerate uv, mismatched cut-edge lengths beyond tolerance).
ConeLayout layoutFromCornerUv(const TriangleMesh& mesh,
                              std::span<const std::array<Vec2, 3>> cornerUv,
                              double coneAngleTolerance = 1e-6,
                              const ConeLayoutOptions& options = {});

} // namespace contour::powell_sabin
