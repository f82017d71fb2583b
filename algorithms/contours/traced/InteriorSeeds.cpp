#include "contours/traced/InteriorSeeds.h"

#include "camera/Facing.h"
#include "contours/traced/ContourCorrector.h"
#include "contours/traced/DomainFaceGeometry.h"
#include "core/SharedResultCache.h"
#include "surface/SurfaceFields.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <tbb/parallel_for.h>

namespace contour::traced {

namespace {

std::shared_ptr<const FaceLattice> buildLattice(const SmoothSurface& surface, int steps) {
    auto out = std::make_shared<FaceLattice>();
    out->steps = steps;
    const Index faces = surface.domain().faceCount();
    std::vector<Preimage> preimages;
    for (Index f = 0; f < faces; ++f) {
        out->offset.push_back(out->uv.size());
        const bool quad = surface.isQuad(f);
        for (int j = 0; j <= steps; ++j)
            for (int i = 0; i <= steps; ++i) {
                if (!quad && i + j > steps)
                    continue;
                const Vec2 uv(static_cast<double>(i) / steps, static_cast<double>(j) / steps);
                out->uv.push_back(uv);
                preimages.push_back({f, uv.x(), uv.y()});
            }
    }
    out->offset.push_back(out->uv.size());
    std::vector<SurfacePoint> points(preimages.size());
    surface.evaluate(preimages, points);
    out->positions.resize(points.size());
    out->normals.resize(points.size());
    for (size_t k = 0; k < points.size(); ++k) {
        out->positions[k] = points[k].position;
        out->normals[k] = points[k].normal();
    }
    return out;
}

// Node (i, j) of a face's lattice, or -1 outside it.
long long nodeIndex(bool quad, int steps, int i, int j) {
    if (i < 0 || j < 0 || i > steps || j > steps || (!quad && i + j > steps))
        return -1;
    if (quad)
        return static_cast<long long>(j) * (steps + 1) + i;
    // Rows j = 0.. of lengths steps + 1 - j.
    long long before = 0;
    for (int r = 0; r < j; ++r)
        before += steps + 1 - r;
    return before + i;
}

struct Critical {
    bool found = false;
    Vec2 uv = Vec2::Zero();
    double g = 0.0;
    double hessianDeterminant = 0.0;
};

Critical newtonCriticalPoint(const SmoothSurface& surface, const Camera& camera, Index face, Vec2 x,
                             int iterations) {
    const bool quad = surface.isQuad(face);
    constexpr double kDelta = 1e-5;
    const auto gradientAt = [&](const Vec2& y) {
        return orientationGradient(surface.evaluate({face, y.x(), y.y()}), camera);
    };
    Critical c;
    for (int it = 0; it < iterations; ++it) {
        const Vec2 grad = gradientAt(x);
        Eigen::Matrix2d h;
        for (int a = 0; a < 2; ++a) {
            Vec2 d = Vec2::Zero();
            d[a] = kDelta;
            h.col(a) = (gradientAt(x + d) - gradientAt(x - d)) / (2.0 * kDelta);
        }
        h = 0.5 * (h + h.transpose()).eval();
        const double det = h.determinant();
        if (!(std::abs(det) > 0.0))
            return c;
        const Vec2 step = h.inverse() * grad;
        x -= step;
        if (!insideFace(quad, x, 1e-9))
            return c;
        if (step.norm() < 1e-11) {
            c.found = true;
            c.uv = x;
            c.hessianDeterminant = det;
            c.g = orientation(surface.evaluate({face, x.x(), x.y()}), camera);
            return c;
        }
    }
    return c;
}

} // namespace

std::shared_ptr<const FaceLattice> sharedFaceLattice(const std::shared_ptr<const SmoothSurface>& s,
                                                     int steps) {
    static SharedResultCache<SmoothSurface, int, FaceLattice> cache(4);
    return cache.get(s, steps, [&] { return buildLattice(*s, steps); }).first;
}

InteriorSeeds findInteriorSeeds(const SmoothSurface& surface, const FaceLattice& lattice,
                                const Camera& camera, const InteriorSeedOptions& options) {
    const Index faces = surface.domain().faceCount();
    const int m = lattice.steps;
    struct FaceResult {
        long long candidates = 0;
        std::vector<Critical> critical;
        std::vector<InteriorSeed> seeds;
    };
    std::vector<FaceResult> results(static_cast<size_t>(faces));
    tbb::parallel_for(Index(0), faces, [&](Index f) {
        FaceResult& r = results[static_cast<size_t>(f)];
        const bool quad = surface.isQuad(f);
        const size_t base = lattice.offset[static_cast<size_t>(f)];
        const auto gAt = [&](long long node) {
            const size_t k = base + static_cast<size_t>(node);
            return facingFunction(camera, lattice.positions[k], lattice.normals[k]);
        };
        for (int j = 1; j < m; ++j)
            for (int i = 1; i < m; ++i) {
                const long long here = nodeIndex(quad, m, i, j);
                if (here < 0 || (!quad && i + j > m - 1))
                    continue;
                const double g0 = gAt(here);
                bool isMax = true, isMin = true;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const long long n = nodeIndex(quad, m, i + di, j + dj);
                        if ((di == 0 && dj == 0) || n < 0)
                            continue;
                        const double gn = gAt(n);
                        isMax = isMax && g0 > gn;
                        isMin = isMin && g0 < gn;
                    }
                if (!isMax && !isMin)
                    continue;
                ++r.candidates;
                const Critical c = newtonCriticalPoint(surface, camera, f,
                                                       lattice.uv[base + static_cast<size_t>(here)],
                                                       options.newtonIterations);
                if (!c.found)
                    continue;
                bool known = false;
                for (const Critical& other : r.critical)
                    known = known || (other.uv - c.uv).norm() < 1e-7;
                if (!known)
                    r.critical.push_back(c);
            }
        // Rays from each extremum to the first sign change of g.
        const double step = 0.5 / m;
        for (const Critical& c : r.critical) {
            if (!(c.hessianDeterminant > 0.0) || c.g == 0.0)
                continue;
            const bool front = c.g > 0.0;
            for (int k = 0; k < options.raysPerExtremum; ++k) {
                const double angle = 2.0 * std::numbers::pi * k / options.raysPerExtremum;
                const Vec2 dir(std::cos(angle), std::sin(angle));
                const auto gOnRay = [&](double s) {
                    const Vec2 y = c.uv + s * dir;
                    return orientation(surface.evaluateFirstOrder({f, y.x(), y.y()}), camera);
                };
                double lo = 0.0, hi = -1.0;
                for (double s = step;; s += step) {
                    if (!insideFace(quad, c.uv + s * dir)) {
                        const FaceExit exit = segmentExit(quad, c.uv + lo * dir, c.uv + s * dir);
                        s = lo + exit.s * (s - lo);
                        if ((gOnRay(s) > 0.0) != front)
                            hi = s;
                        break;
                    }
                    if ((gOnRay(s) > 0.0) != front) {
                        hi = s;
                        break;
                    }
                    lo = s;
                }
                if (hi < 0.0)
                    continue;
                for (int b = 0; b < 40; ++b) {
                    const double mid = 0.5 * (lo + hi);
                    ((gOnRay(mid) > 0.0) == front ? lo : hi) = mid;
                }
                const Vec2 y = c.uv + 0.5 * (lo + hi) * dir;
                CorrectorOptions corrector;
                corrector.gTolerance = options.gTolerance;
                const CorrectedPoint p = correctOntoContour(surface, camera, f, y, corrector);
                if (p.converged && insideFace(quad, p.uv))
                    r.seeds.push_back({{f, p.uv.x(), p.uv.y()}, {f, c.uv.x(), c.uv.y()}});
            }
        }
    });
    InteriorSeeds out;
    for (const FaceResult& r : results) {
        out.candidates += r.candidates;
        for (const Critical& c : r.critical) {
            ++out.criticalPoints;
            (c.hessianDeterminant > 0.0 ? out.extrema : out.saddles)++;
        }
        out.seeds.insert(out.seeds.end(), r.seeds.begin(), r.seeds.end());
    }
    return out;
}

} // namespace contour::traced
