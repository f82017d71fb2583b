#include "contours/traced/EdgeSeeds.h"

#include "contours/traced/BernsteinRoots.h"
#include "contours/traced/ContourCorrector.h"
#include "contours/traced/DomainFaceGeometry.h"
#include "surface/SurfaceFields.h"

#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>

namespace contour::traced {

namespace {

struct EdgeRoots {
    std::vector<double> t;
    bool certified = true;
    int unresolved = 0;
    bool vanishes = false;
};

EdgeRoots polynomialRoots(const EdgePolynomial& poly, const Camera& camera,
                          const EdgeSeedOptions& options) {
    const size_t n = poly.normal.size();
    std::vector<double> g(n);
    double scale = 0.0;
    for (size_t k = 0; k < n; ++k) {
        g[k] = camera.isOrthographic() ? camera.toCamera(Vec3::Zero()).dot(poly.normal[k])
                                       : camera.eye.dot(poly.normal[k]) - poly.positionDotNormal[k];
        scale = std::max(scale, std::abs(g[k]));
    }
    BernsteinRootOptions o;
    // Coefficients below the rounding of their terms count as zero.
    double terms = 0.0;
    for (size_t k = 0; k < n; ++k)
        terms = std::max(terms, camera.isOrthographic()
                                    ? camera.toCamera(Vec3::Zero()).norm() * poly.normal[k].norm()
                                    : camera.eye.norm() * poly.normal[k].norm() +
                                          std::abs(poly.positionDotNormal[k]));
    o.zeroTolerance = 1e-13 * terms;
    o.maxDepth = options.maxDepth;
    // The coefficients bound g (times |N|) on the edge: below the tolerance
    // everywhere, the contour runs along the edge (Summers 2016 §3.4.2.2:
    // infinitely many roots).
    const double normal = std::min(poly.normal.front().norm(), poly.normal.back().norm());
    if (scale <= options.gTolerance * normal)
        return {{}, true, 0, true};
    const BernsteinRoots found = isolateRoots(g, o);
    return {found.roots, true, found.unresolved, found.vanishes};
}

EdgeRoots sampledRoots(const SmoothSurface& surface, const DomainEdge& e,
                       const EdgePolynomial& poly, const Camera& camera, double gTolerance) {
    EdgeRoots out;
    out.certified = false;
    const size_t n = poly.samplePositions.size();
    std::vector<double> g(n);
    bool vanishes = true;
    for (size_t j = 0; j < n; ++j) {
        g[j] = camera.toCamera(poly.samplePositions[j]).dot(poly.sampleNormals[j]);
        vanishes = vanishes && std::abs(g[j]) <= gTolerance * poly.sampleNormals[j].norm();
    }
    if (vanishes) {
        out.vanishes = true;
        return out;
    }
    const bool quad = surface.isQuad(e.face);
    const auto gAt = [&](double t) {
        const Vec2 uv = pointOnEdge(quad, e.edge, t);
        const SurfacePoint sp = surface.evaluateFirstOrder({e.face, uv.x(), uv.y()});
        return camera.toCamera(sp.position).dot(sp.du.cross(sp.dv));
    };
    for (size_t j = 0; j + 1 < n; ++j) {
        if ((g[j] > 0.0) == (g[j + 1] > 0.0))
            continue;
        double lo = static_cast<double>(j) / static_cast<double>(n - 1);
        double hi = static_cast<double>(j + 1) / static_cast<double>(n - 1);
        const bool loFront = g[j] > 0.0;
        for (int i = 0; i < 50; ++i) {
            const double mid = 0.5 * (lo + hi);
            ((gAt(mid) > 0.0) == loFront ? lo : hi) = mid;
        }
        out.t.push_back(0.5 * (lo + hi));
    }
    return out;
}

} // namespace

EdgeSeeds findEdgeSeeds(const SmoothSurface& surface, const EdgePolynomials& polynomials,
                        const Camera& camera, const EdgeSeedOptions& options) {
    const size_t edgeCount = polynomials.edges.size();
    std::vector<EdgeRoots> perEdge(edgeCount);
    tbb::parallel_for(size_t(0), edgeCount, [&](size_t i) {
        const EdgePolynomial& poly = polynomials.polynomials[i];
        perEdge[i] = poly.polynomial ? polynomialRoots(poly, camera, options)
                                     : sampledRoots(surface, polynomials.edges[i], poly, camera,
                                                    options.gTolerance);
    });
    EdgeSeeds seeds;
    struct Pending {
        Index edge;
        double t;
        bool certified;
    };
    std::vector<Pending> pending;
    for (size_t i = 0; i < edgeCount; ++i) {
        const EdgeRoots& r = perEdge[i];
        (r.certified ? seeds.certifiedEdges : seeds.sampledEdges)++;
        seeds.unresolvedClusters += r.unresolved;
        seeds.vanishingEdges += r.vanishes;
        for (double t : r.t)
            pending.push_back({static_cast<Index>(i), t, r.certified});
    }
    // Polish on the true g and orient, in parallel (each root on its own).
    std::vector<EdgeRoot> roots(pending.size());
    std::vector<std::uint8_t> tangent(pending.size(), 0);
    tbb::parallel_for(size_t(0), pending.size(), [&](size_t i) {
        const Pending& p = pending[i];
        const DomainEdge& e = polynomials.edges[static_cast<size_t>(p.edge)];
        const bool quad = surface.isQuad(e.face);
        const Vec2 a = SmoothSurface::cornerCoordinates(quad, e.edge);
        const Vec2 b = SmoothSurface::cornerCoordinates(quad, (e.edge + 1) % cornerCount(quad));
        double t = p.t;
        ContourSample s = sampleContourField(
            surface, camera, {e.face, a.x() + t * (b - a).x(), a.y() + t * (b - a).y()});
        for (int k = 0; k < options.polishIterations && std::abs(s.g) > options.gTolerance; ++k) {
            const double slope = s.gradient.dot(b - a);
            if (!(std::abs(slope) > 0.0))
                break;
            const double next = std::clamp(t - s.g / slope, 0.0, 1.0);
            const Vec2 uv = a + next * (b - a);
            const ContourSample ns = sampleContourField(surface, camera, {e.face, uv.x(), uv.y()});
            if (!(std::abs(ns.g) < std::abs(s.g)))
                break;
            t = next;
            s = ns;
        }
        EdgeRoot& root = roots[i];
        root.edge = p.edge;
        root.t = t;
        root.certified = p.certified;
        root.position = s.point.position;
        root.g = s.g;
        const Vec2 uv = a + t * (b - a);
        const Preimage here{e.face, uv.x(), uv.y()};
        Preimage across{kInvalidIndex, 0.0, 0.0};
        if (e.otherFace != kInvalidIndex)
            across = surface.transferAcrossEdge(here, e.edge);
        const double crossing = contourTangent(s.gradient).dot(outwardNormal(quad, e.edge));
        tangent[i] = crossing == 0.0;
        // Leaving the first face when the tangent points out of it.
        root.exitSide = crossing > 0.0 ? here : across;
        root.entrySide = crossing > 0.0 ? across : here;
    });
    seeds.exitsOfFace.assign(static_cast<size_t>(surface.domain().faceCount()), {});
    for (size_t i = 0; i < roots.size(); ++i) {
        seeds.tangentRoots += tangent[i];
        if (roots[i].exitSide.face != kInvalidIndex)
            seeds.exitsOfFace[static_cast<size_t>(roots[i].exitSide.face)].push_back(
                static_cast<Index>(i));
    }
    seeds.roots = std::move(roots);
    return seeds;
}

} // namespace contour::traced
