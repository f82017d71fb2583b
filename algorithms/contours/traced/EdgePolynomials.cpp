#include "contours/traced/EdgePolynomials.h"

#include "contours/traced/BernsteinRoots.h"
#include "contours/traced/DomainFaceGeometry.h"
#include "core/SharedResultCache.h"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <numbers>
#include <tbb/parallel_for.h>
#include <tuple>

namespace contour::traced {

namespace {

double binomial(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i)
        r = r * (n - k + i) / i;
    return r;
}

double bernsteinBasis(int n, int k, double t) {
    return binomial(n, k) * std::pow(t, k) * std::pow(1.0 - t, n - k);
}

// Chebyshev-Lobatto nodes on [0, 1] (both ends included): a well-conditioned
// Bernstein-Vandermonde system.
std::vector<double> fitNodes(int degree) {
    std::vector<double> t(static_cast<size_t>(degree) + 1);
    for (int i = 0; i <= degree; ++i)
        t[static_cast<size_t>(i)] = 0.5 * (1.0 - std::cos(std::numbers::pi * i / degree));
    return t;
}

constexpr double kCheckPoints[] = {0.1234, 0.4321, 0.6789, 0.9012};

struct EdgeSample {
    Vec3 position, normal;
};

EdgeSample sampleEdge(const SmoothSurface& surface, const DomainEdge& e, double t) {
    const Vec2 uv = pointOnEdge(surface.isQuad(e.face), e.edge, t);
    const SurfacePoint sp = surface.evaluateFirstOrder({e.face, uv.x(), uv.y()});
    return {sp.position, sp.du.cross(sp.dv)};
}

std::vector<DomainEdge> domainEdges(const SmoothSurface& surface) {
    std::vector<DomainEdge> edges;
    const PolygonMesh& domain = surface.domain();
    for (Index f = 0; f < domain.faceCount(); ++f)
        for (int k = 0; k < static_cast<int>(domain.face(f).size()); ++k) {
            const SmoothSurface::EdgeNeighbor n = surface.neighbor(f, k);
            if (n.face != kInvalidIndex && n.face < f)
                continue;
            edges.push_back({f, k, n.face, n.edge});
        }
    return edges;
}

std::shared_ptr<const EdgePolynomials> build(const SmoothSurface& surface,
                                             const EdgePolynomialOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    auto out = std::make_shared<EdgePolynomials>();
    out->degree = edgeDegree(surface.kind());
    out->fallbackSamples = options.fallbackSamples;
    out->edges = domainEdges(surface);
    out->polynomials.resize(out->edges.size());
    const int d = out->degree;
    const std::vector<double> nodes = fitNodes(d);
    Eigen::MatrixXd vandermonde(d + 1, d + 1);
    for (int i = 0; i <= d; ++i)
        for (int k = 0; k <= d; ++k)
            vandermonde(i, k) = bernsteinBasis(d, k, nodes[static_cast<size_t>(i)]);
    const Eigen::MatrixXd inverse = vandermonde.fullPivLu().inverse();
    tbb::parallel_for(size_t(0), out->edges.size(), [&](size_t i) {
        const DomainEdge& e = out->edges[i];
        EdgePolynomial& poly = out->polynomials[i];
        Eigen::MatrixXd values(d + 1, 4);
        for (int j = 0; j <= d; ++j) {
            const EdgeSample s = sampleEdge(surface, e, nodes[static_cast<size_t>(j)]);
            values.block<1, 3>(j, 0) = s.normal.transpose();
            values(j, 3) = s.position.dot(s.normal);
        }
        const Eigen::MatrixXd coefficients = inverse * values;
        poly.normal.resize(static_cast<size_t>(d) + 1);
        poly.positionDotNormal.resize(static_cast<size_t>(d) + 1);
        for (int k = 0; k <= d; ++k) {
            poly.normal[static_cast<size_t>(k)] = coefficients.block<1, 3>(k, 0).transpose();
            poly.positionDotNormal[static_cast<size_t>(k)] = coefficients(k, 3);
        }
        // The fit must reproduce every function at points it was not fitted to.
        bool exact = true;
        for (int c = 0; c < 4 && exact; ++c) {
            std::vector<double> b(static_cast<size_t>(d) + 1);
            double scale = 0.0;
            for (int k = 0; k <= d; ++k) {
                b[static_cast<size_t>(k)] = coefficients(k, c);
                scale = std::max(scale, std::abs(coefficients(k, c)));
            }
            // A component that is zero everywhere has scale 0; compare
            // against the normal's size then.
            const double reference =
                std::max(scale, 1e-3 * coefficients.leftCols(3).cwiseAbs().maxCoeff());
            for (double t : kCheckPoints) {
                const EdgeSample s = sampleEdge(surface, e, t);
                const double truth = c < 3 ? s.normal[c] : s.position.dot(s.normal);
                if (!(std::abs(bernsteinValue(b, t) - truth) <= options.fitTolerance * reference)) {
                    exact = false;
                    break;
                }
            }
        }
        poly.polynomial = exact;
        if (!exact) {
            const int n = options.fallbackSamples;
            poly.samplePositions.resize(static_cast<size_t>(n) + 1);
            poly.sampleNormals.resize(static_cast<size_t>(n) + 1);
            for (int j = 0; j <= n; ++j) {
                const EdgeSample s = sampleEdge(surface, e, static_cast<double>(j) / n);
                poly.samplePositions[static_cast<size_t>(j)] = s.position;
                poly.sampleNormals[static_cast<size_t>(j)] = s.normal;
            }
        }
    });
    for (const EdgePolynomial& p : out->polynomials)
        out->polynomialEdges += p.polynomial;
    out->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace

int edgeDegree(SurfaceKind kind) {
    return kind == SurfaceKind::Loop ? 10 : 8;
}

std::shared_ptr<const EdgePolynomials>
sharedEdgePolynomials(const std::shared_ptr<const SmoothSurface>& surface,
                      const EdgePolynomialOptions& options) {
    using Key = std::tuple<double, int>;
    static SharedResultCache<SmoothSurface, Key, EdgePolynomials> cache(4);
    return cache
        .get(surface, Key{options.fitTolerance, options.fallbackSamples},
             [&] { return build(*surface, options); })
        .first;
}

} // namespace contour::traced
