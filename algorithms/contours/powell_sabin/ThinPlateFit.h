#pragma once
// The thin-plate fit of the Powell-Sabin spline to the mesh (Capouellez et
// al. 2023 §5.3, eq. 8-10): E(q) = 1/2 (q^T H^s q + w (q - q0)^T H^f (q - q0))
// over the global DOFs q (eq. 7: per vertex p, g^u, g^v; per edge g^m).
// H^s is the smoothing (thin-plate) term, H^f the fitting term (the prose of
// §5.3 swaps the two names; eq. 9 decides). H = H^s + w H^f depends only on
// the layout, so it is assembled and factored once per mesh (CHOLMOD); each
// view then costs one back-substitution per coordinate for H q = w H^f q0.
//
// Charts (§5.2): the gradient DOFs of a vertex are stored in the uv frame of
// one face around it (the chart); the other faces see them through the
// rigid rotation between their uv and the chart's, which crosses cut edges.
// Edge DOFs g^m are the derivative along the unit normal to the left of the
// edge's stored half-edge (TriangleMesh::edgeHalfedge). Gradients at cones
// are zero (eliminated from q).
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/PowellSabinSpline.h"

#include <Eigen/SparseCore>
#include <memory>
#include <span>
#include <vector>

namespace contour::powell_sabin {

struct ThinPlateFitOptions {
    double fittingWeight = 1.0; // w of eq. 8; the paper uses 1 throughout
    // A_i of eq. 8 (the paper does not define it): the vertex's barycentric
    // 3D area divided by the mean over the vertices (true), so that w is
    // dimensionless and the fit does not depend on the mesh's size or
    // density; false: the barycentric area itself.
    bool relativeAreaWeights = true;
    // Not in the paper: the thin-plate term of each face measured in the
    // surface's metric instead of the uv's. In conformal coordinates with
    // ds = lambda |dr|, |d2p/ds2|^2 dA = |p_uu|^2 / lambda^2 du dv, so each
    // face's term is weighted by its uv area over its 3D area (relative to
    // the layout's). A conformal map with few cones shrinks long
    // protrusions exponentially (killeroo's tail: uv areas e^-36 of the
    // mean), where the paper's energy flattens them away; false: eq. 8 as
    // written.
    bool surfaceMetric = true;
    // Largest |2*pi - uv angle sum| (radians) accepted at a free interior
    // vertex: its chart needs a flat neighbourhood (§5.1-§5.2); more means
    // the vertex should have been flagged a cone.
    double angleSumTolerance = 1e-6;
    // Optional, per vertex: the incident face whose uv frame holds the
    // vertex's gradient DOFs (§5.2: the choice is arbitrary). Empty: the face
    // of TriangleMesh::vertexHalfedge.
    std::vector<Index> chartReferenceFace;
};

class ThinPlateFit {
public:
    // Assembles H^s and H^f and factors H. Throws std::invalid_argument for
    // a malformed layout (sizes, a uv triangle of non-positive area, a
    // vertex without faces, a free interior vertex whose angle sum is not
    // 2*pi) and std::runtime_error naming the reason when H cannot be
    // factored (a component without fitting area).
    ThinPlateFit(const ConeLayout& layout, const ThinPlateFitOptions& options = {});
    ~ThinPlateFit();
    ThinPlateFit(const ThinPlateFit&) = delete;
    ThinPlateFit& operator=(const ThinPlateFit&) = delete;

    // The spline whose vertex values best fit `targets` (one per vertex of
    // the layout's mesh): one back-substitution per coordinate.
    PowellSabinSpline fit(std::span<const Vec3> targets) const;
    // The global DOFs of that fit, one row per scalar DOF, x y z columns.
    Eigen::MatrixX3d solveDofs(std::span<const Vec3> targets) const;
    // The spline of given global DOFs (for tests of the basis).
    PowellSabinSpline splineOf(const Eigen::MatrixX3d& dofs) const;

    // Scalar DOF numbering: per vertex p then, unless it is a cone, g^u g^v
    // (chart frame); then one g^m per edge.
    Index dofCount() const;
    Index positionDof(Index vertex) const;
    Index gradientDof(Index vertex) const; // g^u; g^v is next; kInvalidIndex at cones
    Index edgeDof(Index edge) const;
    const Eigen::SparseMatrix<double>& smoothingHessian() const; // H^s
    const Eigen::SparseMatrix<double>& fittingHessian() const;   // H^f
    // q0 of eq. 9 for `targets`: positions in the p slots, zeros elsewhere.
    Eigen::MatrixX3d targetDofs(std::span<const Vec3> targets) const;
    double fittingWeight() const;
    // eq. 10's normwise backward error |Hq - b| / (|H| |q| + |b|), b = w H^f q0,
    // of `dofs` for `targets`: what a stable direct solve bounds by a small
    // multiple of the rounding unit whatever H's conditioning (the conformal
    // scale spreads its entries over orders of magnitude). |H| (Frobenius)
    // is kept from the factorization.
    double backwardError(const Eigen::MatrixX3d& dofs, std::span<const Vec3> targets) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace contour::powell_sabin
