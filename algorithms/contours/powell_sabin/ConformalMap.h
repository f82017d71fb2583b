#pragma once
// Discrete conformal map with prescribed cones (Springborn, Schroeder &
// Pinkall 2008; Capouellez et al. 2023 §5.1): per-vertex log scale factors u
// with l_ij = exp((u_i + u_j) / 2) * l0_ij, u fixed to 0 at the cones and on
// the boundary, and angle sums 2*pi at every other vertex. The convex energy
// of SSP 2008 is minimized by Newton's method (its Hessian is the cotangent
// Laplacian of the current metric, factored by CHOLMOD) with a backtracking
// line search. Before the first step and after each trial step the
// triangulation is made Delaunay in the current metric by intrinsic flips
// with Ptolemy's length update, which keeps the metric in the same discrete
// conformal class and repairs the triangle inequalities a step broke
// (Gillespie, Springborn & Crane 2021; Campen, Capouellez et al. 2021). A
// flip that would create a second edge between two vertices is refused (the
// spline needs a simplicial connectivity). The vertices never move: only the
// connectivity of the flat metric changes, and the spline of §5.2 is built
// on that connectivity.
#include "mesh/TriangleMesh.h"

#include <array>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour::powell_sabin {

struct ConformalMapOptions {
    double angleTolerance = 1e-9; // max |2*pi - angle sum| at free vertices
    int maxNewtonIterations = 100;
    bool intrinsicFlips = true;
    // Backtracking line search on the squared residual |2*pi - angle sum|^2
    // (the Newton direction descends it for any invertible Hessian): a step
    // t is accepted when the residual drops to (1 - 2 c t) of its value.
    double lineSearchDecrease = 1e-4; // c
    int maxLineSearchHalvings = 40;
    // An edge is flipped when the cosines of its two opposite angles sum
    // below -delaunayTolerance (angles summing above pi).
    double delaunayTolerance = 1e-12;
    // A triangulation is refused (a trial step rejected; at the start or the
    // end, ConformalMapError) when a corner angle is below this (radians) or
    // a triangle inequality fails.
    double minCornerAngle = 1e-10;
    // A Hessian that CHOLMOD's Cholesky rejects is shifted by this times its
    // largest diagonal entry times the identity, the shift growing tenfold
    // until the factorization succeeds.
    double hessianShift = 1e-10;
    // Called between Newton iterations; may throw to cancel.
    std::function<void()> checkCancelled;
};

struct ConformalMap {
    // The connectivity after intrinsic flips: the input's vertices, the
    // triangles of the flat metric (the input's when nothing was flipped).
    std::vector<Triangle> triangles;
    // Per face: the flat length of the side from corner i to corner i + 1.
    std::vector<std::array<double, 3>> sideLengths;
    std::vector<double> logScale; // u per vertex
    std::vector<char> fixedScale; // per vertex: cone or boundary vertex
    std::vector<double> angleSum; // per vertex, in the flat metric
    int newtonIterations = 0;
    int flips = 0;
    double maxAngleError = 0.0; // over the free vertices
    // Flips the Delaunay criterion asked for but that would have created a
    // second edge between two vertices (or a loop), left undone.
    int refusedFlips = 0;
    // Newton steps whose Hessian was not positive definite (edges left non
    // Delaunay, or intrinsicFlips off) and was shifted by a multiple of the
    // identity before factoring.
    int regularizedSteps = 0;
};

// Thrown when the map cannot be computed: its message names the reason
// (for example "a flip would create a second edge between two vertices").
class ConformalMapError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Vertices in no triangle keep u = 0, count as fixed and have angle sum 0.
// A closed component without cones is solved up to its global scale (one
// vertex is held at u = 0) when its Euler characteristic is 0; otherwise
// Gauss-Bonnet forbids a flat metric and ConformalMapError is thrown.
ConformalMap computeConformalMap(const TriangleMesh& mesh, std::span<const Index> cones,
                                 const ConformalMapOptions& options = {});

} // namespace contour::powell_sabin
