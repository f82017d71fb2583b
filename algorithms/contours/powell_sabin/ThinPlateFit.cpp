// Thin-plate fit of the PS-12 spline (Capouellez et al. 2023 §5.2-§5.3).
// Scalar DOFs per coordinate: per vertex p, then g^u g^v in the vertex's
// chart unless it is a cone (eliminated: zero gradients, §5.2 "Cone
// vertices"), then one g^m per edge. Each face sees them through a 12 x 12
// local map: identity on p, the chart-to-face rotation on the gradients and
// the sign of the edge normal on g^m (the stored half-edge's left normal is
// the inward normal of its own face and the outward one of the other).
#include "contours/powell_sabin/ThinPlateFit.h"

#include "core/UnionFind.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

namespace contour::powell_sabin {

namespace {

using Matrix12 = Eigen::Matrix<double, kPs12LocalDofs, kPs12LocalDofs>;
using Matrix36 = Eigen::Matrix<double, 3, 6>;

double cross2(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// The rotation taking direction a to direction b (both nonzero).
Eigen::Matrix2d rotationBetween(const Vec2& a, const Vec2& b) {
    const double s = a.norm() * b.norm();
    const double c = a.dot(b) / s;
    const double n = cross2(a, b) / s;
    const double r = std::hypot(c, n); // renormalize against rounding
    Eigen::Matrix2d q;
    q << c / r, -n / r, n / r, c / r;
    return q;
}

// Second uv derivatives (rows uu, uv, vv) of a quadratic Bezier triangle as a
// linear map of its 6 control points [b0, b1, b2, b01, b12, b20]: with
// barycentric gradients G_i, Hess = 2 sum_i b_i G_i G_i^T
// + 2 sum_{i<j} b_ij (G_i G_j^T + G_j G_i^T).
Matrix36 secondDerivativeMap(const std::array<Vec2, 3>& d, double& area) {
    const double twiceArea = cross2(d[1] - d[0], d[2] - d[0]);
    area = 0.5 * twiceArea;
    std::array<Vec2, 3> g;
    for (int i = 0; i < 3; ++i) {
        const Vec2& a = d[(i + 1) % 3];
        const Vec2& b = d[(i + 2) % 3];
        g[i] = Vec2(a.y() - b.y(), b.x() - a.x()) / twiceArea;
    }
    Matrix36 m;
    for (int i = 0; i < 3; ++i) {
        m(0, i) = 2.0 * g[i].x() * g[i].x();
        m(1, i) = 2.0 * g[i].x() * g[i].y();
        m(2, i) = 2.0 * g[i].y() * g[i].y();
        const Vec2& a = g[i];
        const Vec2& b = g[(i + 1) % 3]; // b_{i,i+1} is control 3 + i
        m(0, 3 + i) = 4.0 * a.x() * b.x();
        m(1, 3 + i) = 2.0 * (a.x() * b.y() + b.x() * a.y());
        m(2, 3 + i) = 4.0 * a.y() * b.y();
    }
    return m;
}

double signedArea(const std::array<Vec2, 3>& t) {
    return 0.5 * cross2(t[1] - t[0], t[2] - t[0]);
}

} // namespace

struct ThinPlateFit::Impl {
    TriangleMesh mesh;
    std::vector<std::array<Vec2, 3>> cornerUv;
    std::vector<char> isCone;
    double weight = 1.0;
    Index dofs = 0;
    std::vector<Index> vertexDof; // p slot
    std::vector<Index> gradDof;   // g^u slot or kInvalidIndex
    Index firstEdgeDof = 0;       // g^m of edge e is firstEdgeDof + e
    // Per half-edge 3f+i: the rotation from the chart of corner i's vertex
    // to face f's uv (identity at cones, unused).
    std::vector<Eigen::Matrix2d> chartToCorner;
    Eigen::SparseMatrix<double> hs, hf;
    double hessianNorm = 0.0; // |H|, Frobenius
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> solver;
    // Per face, the Bezier ordinates as a function of the global values at
    // slots(): ps12BezierMatrix * localMap, kept from the assembly so that a
    // view's spline costs one small product per face (§5.3: everything but
    // q0 is view-independent).
    std::vector<Ps12Matrix> faceBasis;
    // The view-independent part of every spline: the patches' domains and
    // cone flags.
    PowellSabinSpline patchLayout;

    // Global slot of local DOF k of face f, kInvalidIndex when eliminated.
    std::array<Index, kPs12LocalDofs> slots(Index f) const {
        std::array<Index, kPs12LocalDofs> s;
        const Triangle& t = mesh.triangle(f);
        for (int i = 0; i < 3; ++i) {
            s[3 * i] = vertexDof[t[i]];
            const Index g = gradDof[t[i]];
            s[3 * i + 1] = g;
            s[3 * i + 2] = g == kInvalidIndex ? kInvalidIndex : g + 1;
            s[9 + i] = firstEdgeDof + mesh.edge(TriangleMesh::halfedge(f, i));
        }
        return s;
    }

    // Local DOFs (Ps12Patch.h order) = localMap * (global values at slots()).
    Matrix12 localMap(Index f) const {
        Matrix12 l = Matrix12::Zero();
        const Triangle& t = mesh.triangle(f);
        for (int i = 0; i < 3; ++i) {
            l(3 * i, 3 * i) = 1.0;
            if (gradDof[t[i]] != kInvalidIndex)
                l.block<2, 2>(3 * i + 1, 3 * i + 1) = chartToCorner[TriangleMesh::halfedge(f, i)];
            const Index h = TriangleMesh::halfedge(f, i);
            l(9 + i, 9 + i) = mesh.edgeHalfedge(mesh.edge(h)) == h ? 1.0 : -1.0;
        }
        return l;
    }

    void numberDofs();
    void buildCharts(const ThinPlateFitOptions& options, const std::vector<char>& cutEdge);
    void assemble(bool relativeAreaWeights, bool surfaceMetric);
    void buildPatchLayout();
    void checkTargets(std::span<const Vec3> targets) const;
};

void ThinPlateFit::Impl::numberDofs() {
    const Index n = mesh.vertexCount();
    vertexDof.assign(n, kInvalidIndex);
    gradDof.assign(n, kInvalidIndex);
    Index next = 0;
    for (Index v = 0; v < n; ++v) {
        vertexDof[v] = next++;
        if (!isCone[v]) {
            gradDof[v] = next;
            next += 2;
        }
    }
    firstEdgeDof = next;
    dofs = next + mesh.edgeCount();
}

// §5.2 charts: walk counter-clockwise around each free vertex from
// vertexHalfedge (for a boundary vertex its first face), composing the
// rotation between the two uv images of every cut edge crossed; across an
// uncut edge both faces share uv, so the frame carries over unchanged.
void ThinPlateFit::Impl::buildCharts(const ThinPlateFitOptions& options,
                                     const std::vector<char>& cutEdge) {
    const Index n = mesh.vertexCount();
    if (!options.chartReferenceFace.empty() &&
        static_cast<Index>(options.chartReferenceFace.size()) != n)
        throw std::invalid_argument(
            "ThinPlateFit: chartReferenceFace must have one entry per vertex");
    chartToCorner.assign(static_cast<std::size_t>(mesh.halfedgeCount()),
                         Eigen::Matrix2d::Identity());
    std::vector<Index> fan;
    for (Index v = 0; v < n; ++v) {
        const Index h0 = mesh.vertexHalfedge(v);
        if (h0 == kInvalidIndex)
            throw std::invalid_argument("ThinPlateFit: vertex " + std::to_string(v) +
                                        " has no incident face (its fit is undetermined)");
        if (isCone[v])
            continue; // gradients are zero: no frame needed
        fan.clear();
        Eigen::Matrix2d r = Eigen::Matrix2d::Identity();
        double angleSum = 0.0;
        Index h = h0;
        for (Index step = 0;; ++step) {
            if (step > mesh.halfedgeCount())
                throw std::invalid_argument("ThinPlateFit: the fan of vertex " + std::to_string(v) +
                                            " does not close");
            chartToCorner[h] = r;
            fan.push_back(h);
            const auto& uv = cornerUv[TriangleMesh::face(h)];
            const int c = h % 3;
            const Vec2 e0 = uv[(c + 1) % 3] - uv[c], e1 = uv[(c + 2) % 3] - uv[c];
            angleSum += std::atan2(cross2(e0, e1), e0.dot(e1));
            const Index in = TriangleMesh::prev(h); // other -> v in face(h)
            const Index o = mesh.opposite(in);      // v -> other in the next face
            if (o == kInvalidIndex)
                break;
            if (cutEdge[mesh.edge(in)]) {
                const auto& a = cornerUv[TriangleMesh::face(in)];
                const auto& b = cornerUv[TriangleMesh::face(o)];
                const Vec2 da = a[in % 3] - a[h % 3];
                const Vec2 db = b[TriangleMesh::next(o) % 3] - b[o % 3];
                r = rotationBetween(da, db) * r;
            }
            if (o == h0)
                break;
            h = o;
        }
        // Around a free interior vertex the frames only close up, and the
        // chart is only a flat disk, when the uv angles sum to 2*pi (a 6*pi
        // vertex also closes up, as a branch point).
        if (!mesh.isBoundaryVertex(v) &&
            std::abs(angleSum - 2.0 * std::numbers::pi) > options.angleSumTolerance)
            throw std::invalid_argument("ThinPlateFit: free vertex " + std::to_string(v) +
                                        " has uv angle sum " + std::to_string(angleSum) +
                                        " instead of 2*pi: it must be flagged a cone");
        if (!options.chartReferenceFace.empty()) {
            const Index ref = options.chartReferenceFace[v];
            Index found = kInvalidIndex;
            for (Index k : fan)
                if (TriangleMesh::face(k) == ref)
                    found = k;
            if (found == kInvalidIndex)
                throw std::invalid_argument("ThinPlateFit: chartReferenceFace of vertex " +
                                            std::to_string(v) + " is not incident to it");
            const Eigen::Matrix2d back = chartToCorner[found].transpose();
            for (Index k : fan)
                chartToCorner[k] = chartToCorner[k] * back;
        }
    }
}

// eq. 8-9: E = 1/2 q^T H^s q + w/2 (q - q0)^T H^f (q - q0), so both Hessians
// carry a factor 2 on the energy's quadratic forms.
void ThinPlateFit::Impl::assemble(bool relativeAreaWeights, bool surfaceMetric) {
    faceBasis.resize(static_cast<std::size_t>(mesh.faceCount()));
    std::vector<Eigen::Triplet<double>> ts, tf;
    ts.reserve(static_cast<std::size_t>(mesh.faceCount()) * kPs12LocalDofs * kPs12LocalDofs);
    std::vector<double> vertexArea(static_cast<std::size_t>(mesh.vertexCount()), 0.0);
    // The surface metric's weight of each face's thin-plate term: its uv
    // area over its 3D area, relative to the whole layout's (1 everywhere
    // for an isometric layout).
    std::vector<double> metricWeight(static_cast<std::size_t>(mesh.faceCount()), 1.0);
    if (surfaceMetric) {
        double uvTotal = 0.0, surfaceTotal = 0.0;
        for (Index f = 0; f < mesh.faceCount(); ++f) {
            uvTotal += signedArea(cornerUv[f]);
            surfaceTotal += 0.5 * mesh.faceAreaNormal(f).norm();
        }
        for (Index f = 0; f < mesh.faceCount(); ++f) {
            const double surface = 0.5 * mesh.faceAreaNormal(f).norm();
            if (surface > 0.0 && uvTotal > 0.0)
                metricWeight[f] = (signedArea(cornerUv[f]) / surface) / (uvTotal / surfaceTotal);
        }
    }
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const auto& uv = cornerUv[f];
        if (!(signedArea(uv) > 0.0))
            throw std::invalid_argument("ThinPlateFit: face " + std::to_string(f) +
                                        " has a non-positive uv area");
        const Ps12Matrix b = ps12BezierMatrix(uv);
        const auto sub = ps12SubTriangles(uv);
        Matrix12 k = Matrix12::Zero();
        for (int l = 0; l < kPs12Patches; ++l) {
            double area = 0.0;
            const Matrix36 d = secondDerivativeMap(sub[l], area);
            // Thin-plate density |p_uu|^2 + 2|p_uv|^2 + |p_vv|^2, constant on a patch.
            const Eigen::Matrix<double, 3, kPs12LocalDofs> dl =
                d * b.block<6, kPs12LocalDofs>(6 * l, 0);
            const Eigen::Vector3d wts(1.0, 2.0, 1.0);
            k.noalias() += area * dl.transpose() * wts.asDiagonal() * dl;
        }
        const Matrix12 lm = localMap(f);
        faceBasis[static_cast<std::size_t>(f)] = b * lm;
        Matrix12 kg = 2.0 * metricWeight[f] * lm.transpose() * k * lm;
        kg = 0.5 * (kg + kg.transpose()).eval(); // exactly symmetric for CHOLMOD's one triangle
        const auto s = slots(f);
        for (int i = 0; i < kPs12LocalDofs; ++i) {
            if (s[i] == kInvalidIndex)
                continue;
            for (int j = 0; j < kPs12LocalDofs; ++j)
                if (s[j] != kInvalidIndex && kg(i, j) != 0.0)
                    ts.emplace_back(s[i], s[j], kg(i, j));
        }
        // A_i: one third of the incident 3D face areas (barycentric area; the
        // paper does not define A_i).
        const double a3 = 0.5 * mesh.faceAreaNormal(f).norm() / 3.0;
        for (Index v : mesh.triangle(f))
            vertexArea[v] += a3;
    }
    // Without fitting area a component keeps the affine null space of the
    // thin-plate term; name it instead of leaving it to CHOLMOD's pivots.
    UnionFind components(static_cast<std::size_t>(mesh.vertexCount()));
    for (const Triangle& t : mesh.triangles()) {
        components.unite(t[0], t[1]);
        components.unite(t[0], t[2]);
    }
    std::vector<double> componentArea(static_cast<std::size_t>(mesh.vertexCount()), 0.0);
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        componentArea[components.find(v)] += vertexArea[v];
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (!(componentArea[components.find(v)] > 0.0))
            throw std::runtime_error("ThinPlateFit: the component of vertex " + std::to_string(v) +
                                     " has no fitting area (zero 3D area), so H is singular");
    double meanArea = 0.0;
    for (double a : vertexArea)
        meanArea += a / static_cast<double>(vertexArea.size());
    const double areaScale = relativeAreaWeights ? 1.0 / meanArea : 1.0;
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        tf.emplace_back(vertexDof[v], vertexDof[v], 2.0 * areaScale * vertexArea[v]);
    hs.resize(dofs, dofs);
    hs.setFromTriplets(ts.begin(), ts.end());
    hf.resize(dofs, dofs);
    hf.setFromTriplets(tf.begin(), tf.end());
    const Eigen::SparseMatrix<double> h = hs + weight * hf;
    hessianNorm = h.norm();
    solver.compute(h);
    if (solver.info() != Eigen::Success)
        throw std::runtime_error("ThinPlateFit: CHOLMOD could not factor H = H^s + w H^f (" +
                                 std::string(solver.info() == Eigen::NumericalIssue
                                                 ? "not positive definite"
                                                 : "factorization failed") +
                                 "): a component without fitting area, or degenerate uv triangles");
}

void ThinPlateFit::Impl::checkTargets(std::span<const Vec3> targets) const {
    if (static_cast<Index>(targets.size()) != mesh.vertexCount())
        throw std::invalid_argument("ThinPlateFit: " + std::to_string(targets.size()) +
                                    " targets for " + std::to_string(mesh.vertexCount()) +
                                    " vertices");
}

void ThinPlateFit::Impl::buildPatchLayout() {
    const Index nf = mesh.faceCount();
    patchLayout.patches.resize(static_cast<std::size_t>(nf) * kPs12Patches);
    patchLayout.conePatch.assign(patchLayout.patches.size(), 0);
    for (Index f = 0; f < nf; ++f) {
        const auto& uv = cornerUv[f];
        const auto sub = ps12SubTriangles(uv);
        const Triangle& t = mesh.triangle(f);
        const double size =
            (uv[1] - uv[0]).norm() + (uv[2] - uv[1]).norm() + (uv[0] - uv[2]).norm();
        for (int l = 0; l < kPs12Patches; ++l) {
            const std::size_t p = static_cast<std::size_t>(f) * kPs12Patches + l;
            patchLayout.patches[p].domain = sub[l];
            for (int i = 0; i < 3; ++i) {
                if (!isCone[t[i]])
                    continue;
                // The split copies the corners; the margin only absorbs rounding.
                for (const Vec2& d : sub[l])
                    if ((d - uv[i]).norm() <= 1e-12 * size)
                        patchLayout.conePatch[p] = 1;
            }
        }
    }
}

ThinPlateFit::ThinPlateFit(const ConeLayout& layout, const ThinPlateFitOptions& options)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    if (!(options.fittingWeight > 0.0) || !std::isfinite(options.fittingWeight))
        throw std::invalid_argument("ThinPlateFit: fittingWeight must be positive and finite");
    const TriangleMesh& mesh = layout.mesh;
    if (static_cast<Index>(layout.cornerUv.size()) != mesh.faceCount() ||
        static_cast<Index>(layout.cutEdge.size()) != mesh.edgeCount() ||
        static_cast<Index>(layout.isCone.size()) != mesh.vertexCount())
        throw std::invalid_argument("ThinPlateFit: the layout needs cornerUv per face, cutEdge per "
                                    "edge, isCone per vertex");
    if (mesh.faceCount() == 0)
        throw std::invalid_argument("ThinPlateFit: the layout has no faces");
    m.mesh = mesh;
    m.cornerUv = layout.cornerUv;
    m.isCone = layout.isCone;
    m.weight = options.fittingWeight;
    m.numberDofs();
    m.buildCharts(options, layout.cutEdge);
    m.assemble(options.relativeAreaWeights, options.surfaceMetric);
    m.buildPatchLayout();
}

ThinPlateFit::~ThinPlateFit() = default;

Index ThinPlateFit::dofCount() const {
    return impl_->dofs;
}
Index ThinPlateFit::positionDof(Index vertex) const {
    return impl_->vertexDof.at(vertex);
}
Index ThinPlateFit::gradientDof(Index vertex) const {
    return impl_->gradDof.at(vertex);
}
Index ThinPlateFit::edgeDof(Index edge) const {
    if (edge < 0 || edge >= impl_->mesh.edgeCount())
        throw std::out_of_range("ThinPlateFit::edgeDof: no edge " + std::to_string(edge));
    return impl_->firstEdgeDof + edge;
}
const Eigen::SparseMatrix<double>& ThinPlateFit::smoothingHessian() const {
    return impl_->hs;
}
const Eigen::SparseMatrix<double>& ThinPlateFit::fittingHessian() const {
    return impl_->hf;
}
double ThinPlateFit::fittingWeight() const {
    return impl_->weight;
}

double ThinPlateFit::backwardError(const Eigen::MatrixX3d& dofs,
                                   std::span<const Vec3> targets) const {
    const Impl& m = *impl_;
    const Eigen::MatrixX3d rhs = m.weight * (m.hf * targetDofs(targets));
    const Eigen::MatrixX3d residual = m.hs * dofs + m.weight * (m.hf * dofs) - rhs;
    return residual.norm() / std::max(m.hessianNorm * dofs.norm() + rhs.norm(), 1e-300);
}

Eigen::MatrixX3d ThinPlateFit::targetDofs(std::span<const Vec3> targets) const {
    impl_->checkTargets(targets);
    Eigen::MatrixX3d q0 = Eigen::MatrixX3d::Zero(impl_->dofs, 3);
    for (Index v = 0; v < impl_->mesh.vertexCount(); ++v)
        q0.row(impl_->vertexDof[v]) = targets[v].transpose();
    return q0;
}

// eq. 10: H q = w H^f q0, one back-substitution for x, y and z together.
Eigen::MatrixX3d ThinPlateFit::solveDofs(std::span<const Vec3> targets) const {
    const Eigen::MatrixX3d rhs = impl_->weight * (impl_->hf * targetDofs(targets));
    Eigen::MatrixX3d q = impl_->solver.solve(rhs);
    if (impl_->solver.info() != Eigen::Success)
        throw std::runtime_error("ThinPlateFit: CHOLMOD back-substitution failed");
    return q;
}

PowellSabinSpline ThinPlateFit::splineOf(const Eigen::MatrixX3d& dofs) const {
    const Impl& m = *impl_;
    if (dofs.rows() != m.dofs)
        throw std::invalid_argument("ThinPlateFit::splineOf: " + std::to_string(dofs.rows()) +
                                    " DOF rows, expected " + std::to_string(m.dofs));
    PowellSabinSpline spline = m.patchLayout;
    // Faces are independent: one task per range of faces.
    tbb::parallel_for(Index(0), m.mesh.faceCount(), [&](Index f) {
        const auto s = m.slots(f);
        Eigen::Matrix<double, kPs12LocalDofs, 3> global;
        for (int k = 0; k < kPs12LocalDofs; ++k)
            global.row(k) = s[k] == kInvalidIndex ? Eigen::RowVector3d::Zero()
                                                  : Eigen::RowVector3d(dofs.row(s[k]));
        const Eigen::Matrix<double, 6 * kPs12Patches, 3> control =
            m.faceBasis[static_cast<std::size_t>(f)] * global;
        for (int l = 0; l < kPs12Patches; ++l) {
            QuadraticBezier<Vec3>& patch =
                spline.patches[static_cast<std::size_t>(f) * kPs12Patches + l];
            for (int c = 0; c < 6; ++c)
                patch.control[c] = control.row(6 * l + c).transpose();
        }
    });
    return spline;
}

PowellSabinSpline ThinPlateFit::fit(std::span<const Vec3> targets) const {
    return splineOf(solveDofs(targets));
}

} // namespace contour::powell_sabin
