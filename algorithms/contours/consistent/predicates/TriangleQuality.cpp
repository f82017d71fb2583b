#include "contours/consistent/predicates/TriangleQuality.h"

#include <cmath>

namespace contour::consistent {

double bankSmithQuality(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double lengths = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    if (!(lengths > 0.0))
        return 0.0;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    return 4.0 * std::sqrt(3.0) * area / lengths;
}

} // namespace contour::consistent
