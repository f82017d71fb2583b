#include "contours/consistent/numerics/JointRootSearch.h"

#include <algorithm>
#include <cmath>

namespace contour::consistent {

bool mayChangeSign(double a, double b, double c) {
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
        return true;
    return changesSign(a, b, c);
}

bool changesSign(double a, double b, double c) {
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
        return false;
    const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
    return lo <= 0.0 && hi >= 0.0 && !(lo == 0.0 && hi == 0.0);
}

namespace {

struct Corner {
    Point2L point;
    Barycentric barycentric;
    std::array<double, 2> values;
};

using Tri = std::array<Corner, 3>;

long double distance(const Point2L& a, const Point2L& b) {
    return std::hypot(a[0] - b[0], a[1] - b[1]);
}

long double area(const Tri& t) {
    const long double ux = t[1].point[0] - t[0].point[0], uy = t[1].point[1] - t[0].point[1];
    const long double vx = t[2].point[0] - t[0].point[0], vy = t[2].point[1] - t[0].point[1];
    return std::abs(ux * vy - uy * vx) / 2.0L;
}

bool bothMayChange(const Tri& t) {
    for (int k = 0; k < 2; ++k)
        if (!mayChangeSign(t[0].values[k], t[1].values[k], t[2].values[k]))
            return false;
    return true;
}

bool bothChange(const Tri& t) {
    for (int k = 0; k < 2; ++k)
        if (!changesSign(t[0].values[k], t[1].values[k], t[2].values[k]))
            return false;
    return true;
}

} // namespace

JointRootResult findJointRoots(const std::array<Point2L, 3>& corners,
                               const std::array<std::array<double, 2>, 3>& cornerValues,
                               const JointFunctions& functions, const JointRootOptions& options) {
    JointRootResult out;
    const long double merge = options.mergeDistance >= 0.0L
                                  ? options.mergeDistance
                                  : 1e4L * std::sqrt(2.0L * options.minArea);
    Tri first;
    for (int i = 0; i < 3; ++i) {
        first[i].point = corners[i];
        first[i].barycentric = {0.0L, 0.0L, 0.0L};
        first[i].barycentric[i] = 1.0L;
        first[i].values = cornerValues[i];
    }
    if (!bothMayChange(first))
        return out;
    // Depth first, so that the stack stays at about two triangles per level.
    std::vector<Tri> stack{first};
    while (!stack.empty()) {
        const Tri t = stack.back();
        stack.pop_back();
        int longest = 0; // edge i runs from corner i to corner i + 1
        long double length = -1.0L;
        for (int i = 0; i < 3; ++i) {
            const long double l = distance(t[i].point, t[(i + 1) % 3].point);
            if (l > length) {
                length = l;
                longest = i;
            }
        }
        if (area(t) < options.minArea || length < options.minEdge) {
            if (!bothChange(t)) {
                ++out.rejectedUndefined;
                continue;
            }
            JointRoot r;
            for (int k = 0; k < 2; ++k)
                r.point[k] = (t[0].point[k] + t[1].point[k] + t[2].point[k]) / 3.0L;
            for (int k = 0; k < 3; ++k)
                r.barycentric[k] =
                    (t[0].barycentric[k] + t[1].barycentric[k] + t[2].barycentric[k]) / 3.0L;
            const bool known =
                std::any_of(out.roots.begin(), out.roots.end(),
                            [&](const JointRoot& x) { return distance(x.point, r.point) < merge; });
            if (!known)
                out.roots.push_back(r);
            continue;
        }
        if (out.evaluations >= options.maxEvaluations) {
            out.budgetExhausted = true;
            break;
        }
        const Corner& a = t[longest];
        const Corner& b = t[(longest + 1) % 3];
        const Corner& c = t[(longest + 2) % 3];
        Corner m;
        for (int k = 0; k < 2; ++k)
            m.point[k] = (a.point[k] + b.point[k]) / 2.0L;
        for (int k = 0; k < 3; ++k)
            m.barycentric[k] = (a.barycentric[k] + b.barycentric[k]) / 2.0L;
        m.values = functions(m.point, m.barycentric);
        ++out.evaluations;
        // Both halves keep the corners' order, hence the orientation.
        for (const Tri& child : {Tri{a, m, c}, Tri{m, b, c}})
            if (bothMayChange(child))
                stack.push_back(child);
    }
    return out;
}

} // namespace contour::consistent
