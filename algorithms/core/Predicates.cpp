#include "core/Predicates.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace contour {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;

Kernel::Point_3 point(const Vec3& p) {
    return {p.x(), p.y(), p.z()};
}

int toInt(CGAL::Sign s) {
    return s == CGAL::POSITIVE ? 1 : s == CGAL::NEGATIVE ? -1 : 0;
}
} // namespace

int frontSide(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    // CGAL::orientation(p, q, r, s) is the sign of det[q-p, r-p, s-p].
    return toInt(CGAL::orientation(point(a), point(b), point(c), point(d)));
}

int frontSideOfDirection(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& direction) {
    // No library offers orient3d against a point at infinity, so: a static
    // floating-point filter (Shewchuk-style bound on the 3x3 determinant of
    // the differences), and CGAL's exact kernel when the filter cannot decide.
    const Vec3 u = b - a, v = c - a;
    const double det = u.cross(v).dot(direction);
    const Vec3 au = u.cwiseAbs(), av = v.cwiseAbs(), ad = direction.cwiseAbs();
    const double permanent = (au.y() * av.z() + au.z() * av.y()) * ad.x() +
                             (au.z() * av.x() + au.x() * av.z()) * ad.y() +
                             (au.x() * av.y() + au.y() * av.x()) * ad.z();
    // Differences and products each add relative error; 1e-14 bounds the total
    // generously for doubles (unit roundoff 1.1e-16, about a dozen operations).
    const double bound = 1e-14 * permanent;
    if (det > bound)
        return 1;
    if (det < -bound)
        return -1;
    using EP = ExactKernel::Point_3;
    using EV = ExactKernel::Vector_3;
    const EP ea(a.x(), a.y(), a.z()), eb(b.x(), b.y(), b.z()), ec(c.x(), c.y(), c.z());
    const EV ed(direction.x(), direction.y(), direction.z());
    return toInt(CGAL::orientation(eb - ea, ec - ea, ed));
}

int orientation2d(const Vec2& a, const Vec2& b, const Vec2& c) {
    return toInt(CGAL::orientation(Kernel::Point_2(a.x(), a.y()), Kernel::Point_2(b.x(), b.y()),
                                   Kernel::Point_2(c.x(), c.y())));
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
    return CGAL::collinear(point(a), point(b), point(c));
}

} // namespace contour
