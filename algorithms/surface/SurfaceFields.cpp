#include "surface/SurfaceFields.h"

#include "camera/Facing.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Parameter coordinates (a, b) of a tangent vector t = a f_u + b f_v (the
// least-squares solution when t is not exactly tangent): I^-1 (f_u·t, f_v·t).
Vec2 parameterCoordinates(const SurfacePoint& p, const FundamentalForms& ff, const Vec3& t) {
    const double det = ff.firstDeterminant();
    const double a = p.du.dot(t), b = p.dv.dot(t);
    return Vec2(ff.G * a - ff.F * b, ff.E * b - ff.F * a) / det;
}

bool degenerate(const FundamentalForms& ff) {
    const double det = ff.firstDeterminant();
    return !(det > 0.0) || !std::isfinite(det);
}

template <typename F> std::vector<double> parallelMap(std::span<const SurfacePoint> points, F f) {
    std::vector<double> out(points.size());
    tbb::parallel_for(size_t(0), points.size(), [&](size_t i) { out[i] = f(points[i]); });
    return out;
}

} // namespace

FundamentalForms fundamentalForms(const SurfacePoint& p) {
    const Vec3 n = p.normal();
    FundamentalForms ff;
    ff.E = p.du.dot(p.du);
    ff.F = p.du.dot(p.dv);
    ff.G = p.dv.dot(p.dv);
    ff.L = p.duu.dot(n);
    ff.M = p.duv.dot(n);
    ff.N = p.dvv.dot(n);
    return ff;
}

ShapeOperator shapeOperator(const SurfacePoint& p) {
    const FundamentalForms ff = fundamentalForms(p);
    ShapeOperator s;
    s.n = p.normal();
    if (degenerate(ff) || s.n.isZero()) {
        s.s11 = s.s12 = s.s22 = kNaN;
        return s;
    }
    s.e1 = p.du.normalized();
    const Vec3 e2 = s.e2();
    // Parameter coordinates of e1 and e2; II on them.
    const Vec2 x1 = parameterCoordinates(p, ff, s.e1), x2 = parameterCoordinates(p, ff, e2);
    const auto second = [&](const Vec2& a, const Vec2& b) {
        return ff.L * a.x() * b.x() + ff.M * (a.x() * b.y() + a.y() * b.x()) + ff.N * a.y() * b.y();
    };
    s.s11 = second(x1, x1);
    s.s12 = second(x1, x2);
    s.s22 = second(x2, x2);
    return s;
}

Curvatures curvatures(const ShapeOperator& s) {
    if (!s.valid()) {
        const Vec3 nanVec = Vec3::Constant(kNaN);
        return {kNaN, kNaN, nanVec, nanVec, kNaN, kNaN};
    }
    Eigen::Matrix2d m;
    m << s.s11, s.s12, s.s12, s.s22;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen;
    eigen.computeDirect(m);
    Curvatures c;
    c.kMin = eigen.eigenvalues()(0);
    c.kMax = eigen.eigenvalues()(1);
    const Eigen::Vector2d v = eigen.eigenvectors().col(1);
    c.dirMax = (v(0) * s.e1 + v(1) * s.e2()).normalized();
    c.dirMin = s.n.cross(c.dirMax);
    c.gaussian = s.gaussian();
    c.mean = s.mean();
    return c;
}

Curvatures curvatures(const SurfacePoint& p) {
    return curvatures(shapeOperator(p));
}

double gaussianCurvature(const SurfacePoint& p) {
    const FundamentalForms ff = fundamentalForms(p);
    return degenerate(ff) ? kNaN : ff.secondDeterminant() / ff.firstDeterminant();
}

double meanCurvature(const SurfacePoint& p) {
    const FundamentalForms ff = fundamentalForms(p);
    return degenerate(ff)
               ? kNaN
               : (ff.E * ff.N - 2.0 * ff.F * ff.M + ff.G * ff.L) / (2.0 * ff.firstDeterminant());
}

double normalCurvature(const ShapeOperator& s, const Vec3& direction, double minSine) {
    if (!s.valid())
        return kNaN;
    const double a = direction.dot(s.e1), b = direction.dot(s.e2());
    const double w2 = a * a + b * b; // |w|^2, w = direction - (direction · n) n
    if (!(w2 > minSine * minSine * direction.squaredNorm()))
        return kNaN;
    return (s.s11 * a * a + 2.0 * s.s12 * a * b + s.s22 * b * b) / w2;
}

double normalCurvature(const SurfacePoint& p, const Vec3& direction, double minSine) {
    return normalCurvature(shapeOperator(p), direction, minSine);
}

double normalCurvature(const SurfacePoint& p, const Vec2& parameterDirection) {
    const FundamentalForms ff = fundamentalForms(p);
    if (degenerate(ff))
        return kNaN;
    const double first = ff.first(parameterDirection);
    return first > 0.0 ? ff.second(parameterDirection) / first : kNaN;
}

double orientation(const SurfacePoint& p, const Camera& camera) {
    return facingFunction(camera, p.position, p.normal());
}

void unitNormalDerivatives(const SurfacePoint& p, Vec3& dnu, Vec3& dnv) {
    const Vec3 big = p.du.cross(p.dv);
    const double len = big.norm();
    if (!(len > 0.0)) {
        dnu = dnv = Vec3::Zero();
        return;
    }
    const Vec3 n = big / len;
    const Vec3 bigU = p.duu.cross(p.dv) + p.du.cross(p.duv);
    const Vec3 bigV = p.duv.cross(p.dv) + p.du.cross(p.dvv);
    dnu = (bigU - bigU.dot(n) * n) / len;
    dnv = (bigV - bigV.dot(n) * n) / len;
}

Vec2 orientationGradient(const SurfacePoint& p, const Camera& camera) {
    Vec3 dnu, dnv;
    unitNormalDerivatives(p, dnu, dnv);
    // d/du [(c - f) · n] = -f_u · n + (c - f) · n_u, and f_u · n = 0; for an
    // orthographic camera c - f is constant and the same formula holds.
    const Vec3 v = camera.toCamera(p.position);
    return Vec2(v.dot(dnu), v.dot(dnv));
}

double radialCurvature(const ShapeOperator& s, const Vec3& position, const Camera& camera,
                       double minSine) {
    // w = v - (v · n) n: normalCurvature() projects onto the tangent plane.
    return normalCurvature(s, camera.toCamera(position), minSine);
}

double radialCurvature(const SurfacePoint& p, const Camera& camera, double minSine) {
    return radialCurvature(shapeOperator(p), p.position, camera, minSine);
}

std::vector<double> orientations(std::span<const SurfacePoint> points, const Camera& camera) {
    return parallelMap(points, [&](const SurfacePoint& p) { return orientation(p, camera); });
}

std::vector<double> radialCurvatures(std::span<const SurfacePoint> points, const Camera& camera) {
    return parallelMap(points, [&](const SurfacePoint& p) { return radialCurvature(p, camera); });
}

std::vector<double> gaussianCurvatures(std::span<const SurfacePoint> points) {
    return parallelMap(points, [](const SurfacePoint& p) { return gaussianCurvature(p); });
}

std::vector<double> meanCurvatures(std::span<const SurfacePoint> points) {
    return parallelMap(points, [](const SurfacePoint& p) { return meanCurvature(p); });
}

std::vector<ShapeOperator> shapeOperators(std::span<const SurfacePoint> points) {
    std::vector<ShapeOperator> out(points.size());
    tbb::parallel_for(size_t(0), points.size(),
                      [&](size_t i) { out[i] = shapeOperator(points[i]); });
    return out;
}

} // namespace contour
