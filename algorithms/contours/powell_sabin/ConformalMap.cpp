// Discrete conformal map with fixed scale factors at cones and boundary
// (Capouellez et al. 2023 §5.1) by Newton's method on the convex energy of
// Springborn, Schroeder & Pinkall 2008, over an intrinsic triangulation kept
// Delaunay in the current metric (Gillespie, Springborn & Crane 2021).
#include "contours/powell_sabin/ConformalMap.h"

#include "core/UnionFind.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <unordered_set>

namespace contour::powell_sabin {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

Index nextHalfedge(Index h) {
    return TriangleMesh::next(h);
}
Index prevHalfedge(Index h) {
    return TriangleMesh::prev(h);
}

std::uint64_t edgeKey(Index a, Index b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (hi << 32) | lo;
}

// log(exp(a) + exp(b)) without overflow.
double logAddExp(double a, double b) {
    const double m = std::max(a, b);
    return m + std::log1p(std::exp(std::min(a, b) - m));
}

// The angle opposite side a in a triangle with sides a, b, c, by the
// half-angle formula tan(alpha / 2) = sqrt((s-b)(s-c) / (s(s-a))), which
// stays accurate for needle and cap triangles. A violated triangle
// inequality gives the limits 0 and pi (the extension of SSP 2008 §3).
double angleOpposite(double a, double b, double c) {
    const double num = (a - b + c) * (a + b - c);
    const double den = (a + b + c) * (b + c - a);
    return 2.0 * std::atan2(std::sqrt(std::max(num, 0.0)), std::sqrt(std::max(den, 0.0)));
}

// Cosine of the angle opposite a; defined for any positive lengths, also
// when they violate the triangle inequality (it is then below -1), which is
// what the Delaunay criterion of Gillespie et al. 2021 §4 needs.
double cosineOpposite(double a, double b, double c) {
    return (b * b + c * c - a * a) / (2.0 * b * c);
}

// Connectivity over the input's vertices with per half-edge log lengths of
// the original metric; flips update them by Ptolemy's relation.
class IntrinsicTriangulation {
public:
    IntrinsicTriangulation(const TriangleMesh& mesh) {
        const Index nf = mesh.faceCount();
        triangles_.assign(mesh.triangles().begin(), mesh.triangles().end());
        opposite_.resize(3 * static_cast<size_t>(nf));
        logLength0_.resize(3 * static_cast<size_t>(nf));
        for (Index h = 0; h < 3 * nf; ++h) {
            opposite_[h] = mesh.opposite(h);
            const double l = (mesh.position(mesh.to(h)) - mesh.position(mesh.from(h))).norm();
            if (!(l > 0.0) || !std::isfinite(l)) {
                std::ostringstream msg;
                msg << "conformal map: edge " << mesh.from(h) << "-" << mesh.to(h) << " has length "
                    << l << " (degenerate or non-finite positions)";
                throw ConformalMapError(msg.str());
            }
            logLength0_[h] = std::log(l);
            edges_.insert(edgeKey(mesh.from(h), mesh.to(h)));
        }
    }

    Index faceCount() const { return static_cast<Index>(triangles_.size()); }
    Index halfedgeCount() const { return 3 * faceCount(); }
    const std::vector<Triangle>& triangles() const { return triangles_; }
    Index from(Index h) const { return triangles_[h / 3][h % 3]; }
    Index to(Index h) const { return triangles_[h / 3][(h % 3 + 1) % 3]; }
    Index apex(Index h) const { return triangles_[h / 3][(h % 3 + 2) % 3]; }
    Index opposite(Index h) const { return opposite_[h]; }

    // log of the current length exp((u_i + u_j) / 2) * l0_ij.
    double logLength(Index h, const std::vector<double>& u) const {
        return logLength0_[h] + 0.5 * (u[from(h)] + u[to(h)]);
    }

    // The current side lengths of face f (side i from corner i to i + 1),
    // scaled so that the longest is 1: angles and cosines are scale free,
    // and the scaling keeps large conformal factors from overflowing.
    std::array<double, 3> normalizedSides(Index f, const std::vector<double>& u) const {
        std::array<double, 3> lg{};
        for (int i = 0; i < 3; ++i)
            lg[i] = logLength(3 * f + i, u);
        const double m = std::max({lg[0], lg[1], lg[2]});
        return {std::exp(lg[0] - m), std::exp(lg[1] - m), std::exp(lg[2] - m)};
    }

    // The angles at the corners of face f in the current metric.
    std::array<double, 3> cornerAngles(Index f, const std::vector<double>& u) const {
        const std::array<double, 3> s = normalizedSides(f, u);
        // The corner i is opposite the side from corner i + 1 to i + 2.
        return {angleOpposite(s[1], s[2], s[0]), angleOpposite(s[2], s[0], s[1]),
                angleOpposite(s[0], s[1], s[2])};
    }

    // Cosine of the angle opposite half-edge h in its face.
    double cosineOppositeHalfedge(Index h, const std::vector<double>& u) const {
        const std::array<double, 3> s = normalizedSides(h / 3, u);
        const int i = h % 3;
        return cosineOpposite(s[i], s[(i + 1) % 3], s[(i + 2) % 3]);
    }

    // Whether flipping the interior edge of h keeps the complex simplicial.
    bool canFlip(Index h) const {
        const Index o = opposite_[h];
        if (o == kInvalidIndex)
            return false;
        const Index k = apex(h);
        const Index l = apex(o);
        return k != l && !edges_.contains(edgeKey(k, l));
    }

    // Flips the interior edge of h: faces (i, j, k) and (j, i, l) become
    // (k, i, l) and (l, j, k), which keeps their orientation. The new
    // diagonal's original length follows from Ptolemy's relation
    // l0_kl = (l0_ki l0_lj + l0_il l0_jk) / l0_ij (Gillespie et al. 2021 §3),
    // which commutes with the conformal scaling.
    void flip(Index h) {
        const Index o = opposite_[h];
        const Index f0 = h / 3;
        const Index f1 = o / 3;
        const Index i = from(h);
        const Index j = to(h);
        const Index k = apex(h);
        const Index l = apex(o);
        const Index hjk = nextHalfedge(h), hki = prevHalfedge(h);
        const Index oil = nextHalfedge(o), olj = prevHalfedge(o);
        const Index oppJk = opposite_[hjk], oppKi = opposite_[hki];
        const Index oppIl = opposite_[oil], oppLj = opposite_[olj];
        const double lij = logLength0_[h];
        const double ljk = logLength0_[hjk], lki = logLength0_[hki];
        const double lil = logLength0_[oil], llj = logLength0_[olj];
        const double lkl = logAddExp(lki + llj, lil + ljk) - lij;

        triangles_[f0] = {k, i, l};
        triangles_[f1] = {l, j, k};
        const Index a0 = 3 * f0, a1 = 3 * f1;
        setHalfedge(a0 + 0, oppKi, lki);
        setHalfedge(a0 + 1, oppIl, lil);
        setHalfedge(a0 + 2, a1 + 2, lkl);
        setHalfedge(a1 + 0, oppLj, llj);
        setHalfedge(a1 + 1, oppJk, ljk);
        setHalfedge(a1 + 2, a0 + 2, lkl);
        edges_.erase(edgeKey(i, j));
        edges_.insert(edgeKey(k, l));
    }

private:
    void setHalfedge(Index h, Index opposite, double logLength0) {
        opposite_[h] = opposite;
        logLength0_[h] = logLength0;
        if (opposite != kInvalidIndex)
            opposite_[opposite] = h;
    }

    std::vector<Triangle> triangles_;
    std::vector<Index> opposite_;
    std::vector<double> logLength0_;
    std::unordered_set<std::uint64_t> edges_;
};

struct FlipPass {
    int flips = 0;
    int refused = 0; // distinct non-Delaunay edges left because of simpliciality
};

// Flips to the Delaunay triangulation of the current metric (Gillespie et
// al. 2021 §4): an interior edge is flipped while the cosines of its two
// opposite angles sum below -tolerance, i.e. the angles sum above pi. The
// criterion is defined for lengths that violate triangle inequalities, and
// the Delaunay triangulation of such a decorated metric satisfies them, so
// this also repairs what a Newton step broke.
FlipPass makeDelaunay(IntrinsicTriangulation& tri, const std::vector<double>& u, double tolerance) {
    FlipPass pass;
    const Index nh = tri.halfedgeCount();
    std::vector<Index> stack;
    std::vector<char> queued(static_cast<size_t>(nh), 0);
    for (Index h = 0; h < nh; ++h) {
        const Index o = tri.opposite(h);
        if (o != kInvalidIndex && h < o) {
            stack.push_back(h);
            queued[h] = 1;
        }
    }
    // Each flip of a strictly non-Delaunay edge lowers a bounded energy
    // (Gillespie et al. 2021 §4.2); the cap only guards against rounding.
    const long long maxFlips = 1000LL + 50LL * nh;
    std::unordered_set<std::uint64_t> refused;
    while (!stack.empty()) {
        const Index h = stack.back();
        stack.pop_back();
        queued[h] = 0;
        const Index o = tri.opposite(h);
        if (o == kInvalidIndex)
            continue;
        const double c = tri.cosineOppositeHalfedge(h, u) + tri.cosineOppositeHalfedge(o, u);
        if (!(c < -tolerance))
            continue;
        if (!tri.canFlip(h)) {
            refused.insert(edgeKey(tri.from(h), tri.to(h)));
            continue;
        }
        tri.flip(h);
        if (++pass.flips > maxFlips) {
            std::ostringstream msg;
            msg << "conformal map: Delaunay flipping did not terminate after " << pass.flips
                << " flips";
            throw ConformalMapError(msg.str());
        }
        // The new faces hold the flipped edge at side 2; sides 0 and 1 of
        // both are the quadrilateral's edges, which may have become
        // non-Delaunay.
        for (const Index f : {h / 3, o / 3}) {
            for (int s = 0; s < 2; ++s) {
                const Index e = 3 * f + s;
                if (!queued[e] && tri.opposite(e) != kInvalidIndex) {
                    stack.push_back(e);
                    queued[e] = 1;
                }
            }
        }
    }
    // Count only edges that are still non-Delaunay at the end.
    for (Index h = 0; h < nh; ++h) {
        const Index o = tri.opposite(h);
        if (o == kInvalidIndex || o < h)
            continue;
        const double c = tri.cosineOppositeHalfedge(h, u) + tri.cosineOppositeHalfedge(o, u);
        if (c < -tolerance && refused.contains(edgeKey(tri.from(h), tri.to(h))))
            ++pass.refused;
    }
    return pass;
}

struct Validity {
    Index brokenTriangleInequalities = 0;
    Index smallAngles = 0;
    double minAngle = std::numbers::pi;
    bool ok() const { return brokenTriangleInequalities == 0 && smallAngles == 0; }
};

Validity checkTriangles(const IntrinsicTriangulation& tri, const std::vector<double>& u,
                        double minCornerAngle) {
    Validity v;
    for (Index f = 0; f < tri.faceCount(); ++f) {
        const std::array<double, 3> s = tri.normalizedSides(f, u);
        const bool broken = !(s[0] < s[1] + s[2]) || !(s[1] < s[2] + s[0]) || !(s[2] < s[0] + s[1]);
        if (broken) {
            ++v.brokenTriangleInequalities;
            v.minAngle = 0.0;
            continue;
        }
        const std::array<double, 3> a = tri.cornerAngles(f, u);
        const double m = std::min({a[0], a[1], a[2]});
        v.minAngle = std::min(v.minAngle, m);
        if (m < minCornerAngle)
            ++v.smallAngles;
    }
    return v;
}

std::vector<double> angleSums(const IntrinsicTriangulation& tri, const std::vector<double>& u) {
    std::vector<double> sums(u.size(), 0.0);
    for (Index f = 0; f < tri.faceCount(); ++f) {
        const std::array<double, 3> a = tri.cornerAngles(f, u);
        const Triangle& t = tri.triangles()[f];
        for (int i = 0; i < 3; ++i)
            sums[t[i]] += a[i];
    }
    return sums;
}

// Gradient of the SSP 2008 energy, 2*pi - angle sum, at the unknowns.
Eigen::VectorXd residual(const std::vector<double>& sums, const std::vector<Index>& unknown,
                         Index unknownCount) {
    Eigen::VectorXd g(unknownCount);
    for (size_t v = 0; v < sums.size(); ++v)
        if (unknown[v] != kInvalidIndex)
            g[unknown[v]] = kTwoPi - sums[v];
    return g;
}

// The Hessian of the energy: the cotangent Laplacian with weights
// (cot alpha + cot beta) / 2 of the current metric (SSP 2008 §4),
// restricted to the unknowns (fixed neighbours only add to the diagonal).
Eigen::SparseMatrix<double> hessian(const IntrinsicTriangulation& tri, const std::vector<double>& u,
                                    const std::vector<Index>& unknown, Index unknownCount) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(12 * static_cast<size_t>(tri.faceCount()));
    for (Index f = 0; f < tri.faceCount(); ++f) {
        const std::array<double, 3> a = tri.cornerAngles(f, u);
        const Triangle& t = tri.triangles()[f];
        for (int i = 0; i < 3; ++i) {
            // Side i (corner i to i + 1) is opposite corner i + 2.
            const double w = 0.5 / std::tan(a[(i + 2) % 3]);
            const Index p = unknown[t[i]];
            const Index q = unknown[t[(i + 1) % 3]];
            if (p != kInvalidIndex)
                entries.emplace_back(p, p, w);
            if (q != kInvalidIndex)
                entries.emplace_back(q, q, w);
            if (p != kInvalidIndex && q != kInvalidIndex) {
                entries.emplace_back(p, q, -w);
                entries.emplace_back(q, p, -w);
            }
        }
    }
    Eigen::SparseMatrix<double> h(unknownCount, unknownCount);
    h.setFromTriplets(entries.begin(), entries.end());
    return h;
}

double maxAbs(const std::vector<double>& sums, const std::vector<char>& free) {
    double m = 0.0;
    for (size_t v = 0; v < sums.size(); ++v)
        if (free[v])
            m = std::max(m, std::abs(kTwoPi - sums[v]));
    return m;
}

std::string invalidMessage(const char* when, const Validity& v, int refusedFlips) {
    std::ostringstream msg;
    msg << "conformal map: " << when << ", " << v.brokenTriangleInequalities
        << " triangle(s) violate a triangle inequality and " << v.smallAngles
        << " have a corner angle below the threshold (smallest " << v.minAngle << " rad); "
        << refusedFlips
        << " non-Delaunay edge(s) were not flipped because a flip would create a second edge "
           "between two vertices";
    return msg.str();
}

} // namespace

ConformalMap computeConformalMap(const TriangleMesh& mesh, std::span<const Index> cones,
                                 const ConformalMapOptions& options) {
    const Index nv = mesh.vertexCount();
    const Index nf = mesh.faceCount();
    if (!(options.angleTolerance > 0.0))
        throw ConformalMapError("conformal map: angleTolerance must be positive");
    if (options.maxNewtonIterations < 0 || options.maxLineSearchHalvings < 0)
        throw ConformalMapError("conformal map: iteration limits must not be negative");
    if (!(options.hessianShift > 0.0) || !(options.lineSearchDecrease >= 0.0) ||
        !(options.lineSearchDecrease < 0.5) || !(options.delaunayTolerance >= 0.0) ||
        !(options.minCornerAngle >= 0.0))
        throw ConformalMapError("conformal map: hessianShift must be positive, "
                                "lineSearchDecrease in [0, 0.5), delaunayTolerance and "
                                "minCornerAngle not negative");
    for (const Index c : cones)
        if (c < 0 || c >= nv) {
            std::ostringstream msg;
            msg << "conformal map: cone index " << c << " is out of range (" << nv << " vertices)";
            throw ConformalMapError(msg.str());
        }

    // Fixed scale: cones, boundary vertices and vertices in no triangle.
    std::vector<char> used(static_cast<size_t>(nv), 0);
    std::vector<char> fixed(static_cast<size_t>(nv), 0);
    for (Index f = 0; f < nf; ++f)
        for (const Index v : mesh.triangle(f))
            used[v] = 1;
    for (Index v = 0; v < nv; ++v)
        fixed[v] = !used[v];
    for (const Index c : cones)
        fixed[c] = 1;
    for (Index h = 0; h < mesh.halfedgeCount(); ++h)
        if (mesh.isBoundary(h)) {
            fixed[mesh.from(h)] = 1;
            fixed[mesh.to(h)] = 1;
        }

    // Components without a fixed vertex: Gauss-Bonnet (the angle defects
    // 2*pi - angle sum add up to 2*pi*chi) allows a flat metric only for
    // chi = 0, and then u is determined up to a constant, fixed by holding
    // one vertex at 0 (its angle sum follows from the others').
    UnionFind components(static_cast<size_t>(nv));
    for (Index f = 0; f < nf; ++f) {
        const Triangle& t = mesh.triangle(f);
        components.unite(t[0], t[1]);
        components.unite(t[0], t[2]);
    }
    std::vector<char> componentFixed(static_cast<size_t>(nv), 0);
    std::vector<long long> chi(static_cast<size_t>(nv), 0);
    for (Index v = 0; v < nv; ++v) {
        if (!used[v])
            continue;
        const Index r = components.find(v);
        chi[r] += 1;
        if (fixed[v])
            componentFixed[r] = 1;
    }
    for (Index f = 0; f < nf; ++f)
        chi[components.find(mesh.triangle(f)[0])] += 1;
    for (Index e = 0; e < mesh.edgeCount(); ++e)
        chi[components.find(mesh.from(mesh.edgeHalfedge(e)))] -= 1;
    std::vector<char> gauge(static_cast<size_t>(nv), 0);
    for (Index v = 0; v < nv; ++v) {
        if (!used[v] || components.find(v) != v || componentFixed[v])
            continue;
        if (chi[v] != 0) {
            std::ostringstream msg;
            msg << "conformal map: the closed component of vertex " << v
                << " has Euler characteristic " << chi[v]
                << " and no cones; Gauss-Bonnet requires the angle defects to sum to 2*pi*"
                << chi[v] << ", so a flat metric needs cones there";
            throw ConformalMapError(msg.str());
        }
        gauge[v] = 1; // the root is the component's smallest vertex
    }

    std::vector<char> free(static_cast<size_t>(nv), 0);
    std::vector<Index> unknown(static_cast<size_t>(nv), kInvalidIndex);
    Index unknownCount = 0;
    for (Index v = 0; v < nv; ++v) {
        free[v] = !fixed[v];
        if (free[v] && !gauge[v])
            unknown[v] = unknownCount++;
    }

    IntrinsicTriangulation tri(mesh);
    std::vector<double> u(static_cast<size_t>(nv), 0.0);
    ConformalMap map;

    auto flipToDelaunay = [&](const std::vector<double>& at) {
        if (!options.intrinsicFlips)
            return 0;
        const FlipPass pass = makeDelaunay(tri, at, options.delaunayTolerance);
        map.flips += pass.flips;
        return pass.refused;
    };

    int refused = flipToDelaunay(u);
    Validity valid = checkTriangles(tri, u, options.minCornerAngle);
    if (!valid.ok())
        throw ConformalMapError(invalidMessage("the input metric is degenerate", valid, refused));

    std::vector<double> sums = angleSums(tri, u);
    Eigen::VectorXd g = residual(sums, unknown, unknownCount);
    double error = maxAbs(sums, free);

    for (int iteration = 0;; ++iteration) {
        if (error <= options.angleTolerance) {
            map.newtonIterations = iteration;
            break;
        }
        if (iteration >= options.maxNewtonIterations) {
            std::ostringstream msg;
            msg << "conformal map: Newton's method did not converge in " << iteration
                << " iterations; the largest |2*pi - angle sum| at a free vertex is " << error
                << " (tolerance " << options.angleTolerance << ")";
            throw ConformalMapError(msg.str());
        }
        if (options.checkCancelled)
            options.checkCancelled();

        // Newton direction H d = -g; H is positive definite on a Delaunay
        // triangulation with a fixed vertex per component. Otherwise (refused
        // flips, or no flips at all) a growing multiple of the identity is
        // added until CHOLMOD's Cholesky succeeds.
        Eigen::SparseMatrix<double> h = hessian(tri, u, unknown, unknownCount);
        Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> solver;
        solver.compute(h);
        if (solver.info() != Eigen::Success) {
            ++map.regularizedSteps;
            const double scale = std::max(h.diagonal().cwiseAbs().maxCoeff(), 1e-300);
            // Beyond twice the largest absolute column sum (Gershgorin; H is symmetric) the
            // shifted matrix is positive definite, so the loop ends there.
            double rowBound = 0.0;
            for (Index r = 0; r < unknownCount; ++r)
                rowBound = std::max(rowBound, h.col(r).cwiseAbs().sum());
            double shift = options.hessianShift * scale;
            Eigen::SparseMatrix<double> identity(unknownCount, unknownCount);
            identity.setIdentity();
            for (;;) {
                solver.compute(h + shift * identity);
                if (solver.info() == Eigen::Success)
                    break;
                if (!(shift <= 2.0 * rowBound + scale))
                    throw ConformalMapError("conformal map: the Hessian could not be factored "
                                            "even after regularization (non-finite entries?)");
                shift *= 10.0;
            }
        }
        const Eigen::VectorXd d = solver.solve(-g);
        if (!d.allFinite())
            throw ConformalMapError("conformal map: the Newton direction is not finite");

        // Backtracking on |g|^2: since dg/du = H, its derivative along d at
        // t = 0 is 2 g^T H d = -2 |g|^2 < 0 for the unregularized H, so a
        // short enough step always decreases it. (The SSP energy itself would need Milnor's
        // Lobachevsky function, and its rounding hides decreases of order
        // |g|^2 near the solution, where Newton needs the full step.)
        const double merit0 = g.squaredNorm();
        double t = 1.0;
        bool accepted = false;
        Index invalidTrials = 0;
        Validity lastInvalid;
        int lastInvalidRefused = 0;
        std::vector<double> trial = u;
        for (int halving = 0; halving <= options.maxLineSearchHalvings; ++halving, t *= 0.5) {
            for (Index v = 0; v < nv; ++v)
                if (unknown[v] != kInvalidIndex)
                    trial[v] = u[v] + t * d[unknown[v]];
            refused = flipToDelaunay(trial);
            const Validity trialValid = checkTriangles(tri, trial, options.minCornerAngle);
            if (!trialValid.ok()) {
                ++invalidTrials;
                lastInvalid = trialValid;
                lastInvalidRefused = refused;
                continue;
            }
            std::vector<double> trialSums = angleSums(tri, trial);
            Eigen::VectorXd trialG = residual(trialSums, unknown, unknownCount);
            if (trialG.squaredNorm() <= (1.0 - 2.0 * options.lineSearchDecrease * t) * merit0) {
                u = trial;
                sums = std::move(trialSums);
                g = std::move(trialG);
                error = maxAbs(sums, free);
                accepted = true;
                break;
            }
        }
        if (!accepted) {
            std::ostringstream msg;
            msg << "conformal map: the line search found no decrease of the residual in "
                << options.maxLineSearchHalvings + 1 << " trials at iteration " << iteration + 1
                << "; the largest |2*pi - angle sum| at a free vertex is " << error
                << " (tolerance " << options.angleTolerance << ")";
            if (invalidTrials > 0)
                msg << "; " << invalidTrials << " trial(s) left invalid triangles (last: "
                    << lastInvalid.brokenTriangleInequalities
                    << " violating a triangle inequality, " << lastInvalid.smallAngles
                    << " with a corner angle below the threshold, " << lastInvalidRefused
                    << " non-Delaunay edge(s) not flipped because the flip would create a "
                       "second edge between two vertices)";
            throw ConformalMapError(msg.str());
        }
    }

    // The accepted step's flips left the connectivity Delaunay for u.
    valid = checkTriangles(tri, u, options.minCornerAngle);
    if (!valid.ok())
        throw ConformalMapError(invalidMessage("the flat metric is degenerate", valid, refused));

    map.refusedFlips = refused;
    map.triangles = tri.triangles();
    map.sideLengths.resize(static_cast<size_t>(nf));
    for (Index f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i)
            map.sideLengths[f][i] = std::exp(tri.logLength(3 * f + i, u));
    map.logScale = std::move(u);
    map.fixedScale = std::move(fixed);
    map.angleSum = std::move(sums);
    map.maxAngleError = error;
    return map;
}

} // namespace contour::powell_sabin
