// Vertex-normal patches (van Overveld & Wyvill). Section numbers refer to the
// paper's text as stored in ../shared/papers (its internal references
// "section 3.1/3.2/3.3" mean §2.4/§2.5/§2.6, notes B.10). No library provides
// these patches: the Bézier nets, their evaluation in Bernstein form and the
// chain rule to the domain face's (u, v) are written out here.
#include "surface/VertexNormalPatches.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace contour {

const char* toString(EdgeControlMethod method) {
    switch (method) {
    case EdgeControlMethod::MinimalCurvature:
        return "minimal-curvature";
    case EdgeControlMethod::MaximallyStretched:
        return "maximally-stretched";
    }
    return "unknown";
}

EdgeControlMethod edgeControlMethodFromName(const std::string& name) {
    if (name == "minimal-curvature")
        return EdgeControlMethod::MinimalCurvature;
    if (name == "maximally-stretched")
        return EdgeControlMethod::MaximallyStretched;
    throw std::invalid_argument("unknown edge control method \"" + name +
                                "\" (expected minimal-curvature or maximally-stretched)");
}

namespace vnp {

std::array<Vec3, 4> edgeCubic(const Vec3& p0, const Vec3& n0, const Vec3& p3, const Vec3& n3,
                              EdgeControlMethod method) {
    // §2.4. The constraints (1), (2) read n0·(p1 − p0) = 0 and
    // n3·(p2 − p3) = 0 (the text drops the parentheses, notes B.2). The 2x2
    // multiplier systems are written with n·n kept (1 for unit normals), so
    // that their determinants, 4 − cos²φ and 25 − 9 cos²φ for unit normals,
    // never vanish (§2.4: "This matrix is always non-singular").
    const Vec3 delta = p3 - p0;
    const double a = n0.dot(n0), b = n3.dot(n3), c = n0.dot(n3);
    const double ab = a * b; // one product, so that swapping the ends is exact
    std::array<Vec3, 4> out{p0, p0, p3, p3};
    if (method == EdgeControlMethod::MinimalCurvature) {
        // §2.4 "Minimal curvature", eqs. (6)-(9): minimise ∫|p''|² subject to
        // (1), (2). Stationarity gives p0 − 2p1 + p2 ∥ n0 and
        // p1 − 2p2 + p3 ∥ n3, i.e. (8) and (9):
        //   p1 = (2p0 + p3 − 2μ0 n0 − μ3 n3)/3, p2 = (2p3 + p0 − 2μ3 n3 − μ0 n0)/3,
        // and (1), (2) give the system
        //   2μ0 (n0·n0) + μ3 (n0·n3) = n0·(p3 − p0)
        //   μ0 (n3·n0) + 2μ3 (n3·n3) = −n3·(p3 − p0).
        const double d0 = n0.dot(delta), d3 = -n3.dot(delta);
        const double det = 4.0 * ab - c * c;
        const double mu0 = (2.0 * b * d0 - c * d3) / det;
        const double mu3 = (2.0 * a * d3 - c * d0) / det;
        const auto inner = [](const Vec3& near, const Vec3& far, const Vec3& nNear,
                              const Vec3& nFar, double muNear, double muFar) -> Vec3 {
            return (2.0 * near + far - 2.0 * muNear * nNear - muFar * nFar) / 3.0;
        };
        out[1] = inner(p0, p3, n0, n3, mu0, mu3);
        out[2] = inner(p3, p0, n3, n0, mu3, mu0);
    } else {
        // §2.4 "A maximally stretched configuration", eqs. (3)-(5): minimise
        // |3p1 − 2p0 − p2|² + |3p2 − 2p3 − p1|² subject to (1), (2):
        //   p1 = (p3 + 3p0)/4 − 5μ0 n0 − 3μ3 n3, p2 = (p0 + 3p3)/4 − 3μ0 n0 − 5μ3 n3,
        //   5μ0 (n0·n0) + 3μ3 (n0·n3) = n0·(p3 − p0)/4
        //   3μ0 (n3·n0) + 5μ3 (n3·n3) = n3·(p0 − p3)/4.
        const double e0 = n0.dot(delta) / 4.0, e3 = -n3.dot(delta) / 4.0;
        const double det = 25.0 * ab - 9.0 * c * c;
        const double mu0 = (5.0 * b * e0 - 3.0 * c * e3) / det;
        const double mu3 = (5.0 * a * e3 - 3.0 * c * e0) / det;
        const auto inner = [](const Vec3& near, const Vec3& far, const Vec3& nNear,
                              const Vec3& nFar, double muNear, double muFar) -> Vec3 {
            return (far + 3.0 * near) / 4.0 - 5.0 * muNear * nNear - 3.0 * muFar * nFar;
        };
        out[1] = inner(p0, p3, n0, n3, mu0, mu3);
        out[2] = inner(p3, p0, n3, n0, mu3, mu0);
    }
    return out;
}

std::array<Vec3, 5> cubicToQuadratics(const std::array<Vec3, 4>& p) {
    // §2.3 step 2, §2.5 and Fig. 2: the middle point is the cubic's
    // de Casteljau midpoint; q1 on p0p1 and q3 on p3p2 keep the end tangents
    // (notes B.3). The sums are grouped symmetrically so that the reversed
    // cubic gives the reversed points bit for bit (no cracks).
    const Vec3 q1 = (p[0] + 3.0 * p[1]) / 4.0;
    const Vec3 q3 = (3.0 * p[2] + p[3]) / 4.0;
    const Vec3 m = ((p[0] + p[3]) + 3.0 * (p[1] + p[2])) / 8.0;
    return {p[0], q1, m, q3, p[3]};
}

Vec3 quadraticMidpointNormal(const Vec3& p0, const Vec3& n0, const Vec3& p3, const Vec3& n3) {
    // §2.7: n(1/2) = (n0 + n3)/2 + n_m/4, n_m = −3 ((n0 + n3)·Δ)/(Δ·Δ) Δ.
    // The text's "(n_0 + n_3 · Δ)" is read as ((n0 + n3)·Δ), the only
    // dimensionally consistent grouping (notes B.6); the result is
    // normalised. Symmetric in the two ends.
    const Vec3 delta = p3 - p0;
    const Vec3 sum = n0 + n3;
    const double dd = delta.dot(delta);
    Vec3 n = 0.5 * sum;
    if (dd > 0.0)
        n += 0.25 * (-3.0 * sum.dot(delta) / dd) * delta;
    const double len = n.norm();
    if (len > 0.0)
        return n / len;
    const double s = sum.norm();
    return s > 0.0 ? Vec3(sum / s) : n0;
}

} // namespace vnp

namespace {

using Cubic = std::array<Vec3, 4>;
using Quintuple = std::array<Vec3, 5>; // two C1 quadratics

std::uint64_t edgeKey(Index a, Index b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return lo << 32 | hi;
}

template <typename T, size_t N> std::array<T, N> reversed(std::array<T, N> a) {
    std::reverse(a.begin(), a.end());
    return a;
}

constexpr int kTriangleNet = 15; // quartic-degree triangular net, 5 per side
constexpr int kQuadNet = 25;     // 5 x 5

int tri(int j, int k) {
    return VertexNormalPatches::netIndex(j, k);
}

// §2.3 step 3, §2.5 (3-sided): the 15-point net from the 5-point sides
// (side e runs from corner e to corner e+1), plus one interior point per
// corner by the parallelogram rule of §2.6: p_i = p12 + p1 − p, where p12 and
// p1 are the net points next to the corner p on its two sides.
void triangleNet(const std::array<Quintuple, 3>& side, Vec3* net) {
    for (int t = 0; t <= 4; ++t) {
        net[tri(t, 0)] = side[0][t];     // (4−t, t, 0): corner 0 -> corner 1
        net[tri(4 - t, t)] = side[1][t]; // (0, 4−t, t): corner 1 -> corner 2
        net[tri(0, 4 - t)] = side[2][t]; // (t, 0, 4−t): corner 2 -> corner 0
    }
    net[tri(1, 1)] = net[tri(1, 0)] + net[tri(0, 1)] - net[tri(0, 0)]; // (2,1,1) at corner 0
    net[tri(2, 1)] = net[tri(3, 0)] + net[tri(3, 1)] - net[tri(4, 0)]; // (1,2,1) at corner 1
    net[tri(1, 2)] = net[tri(0, 3)] + net[tri(1, 3)] - net[tri(0, 4)]; // (1,1,2) at corner 2
}

// §2.5 (4-sided): the 4x4 net of the cubic sides (side e from corner e to
// corner e+1; P[i][j] at i + 4j, i along u, j along v), one interior point
// per corner by §2.6, then every row and every column of 4 replaced by 5
// (§2.3 step 2): a 5x5 net of 4 biquadratic patches.
void quadNet(const std::array<Cubic, 4>& side, Vec3* net) {
    Vec3 p[16];
    const auto at = [&p](int i, int j) -> Vec3& {
        return p[i + 4 * j];
    };
    for (int t = 0; t <= 3; ++t) {
        at(t, 0) = side[0][t];
        at(3, t) = side[1][t];
        at(3 - t, 3) = side[2][t];
        at(0, 3 - t) = side[3][t];
    }
    at(1, 1) = at(1, 0) + at(0, 1) - at(0, 0);
    at(2, 1) = at(2, 0) + at(3, 1) - at(3, 0);
    at(1, 2) = at(0, 2) + at(1, 3) - at(0, 3);
    at(2, 2) = at(3, 2) + at(2, 3) - at(3, 3);
    Vec3 rows[20]; // 5 x 4, index i + 5j
    for (int j = 0; j < 4; ++j) {
        const Quintuple q = vnp::cubicToQuadratics({at(0, j), at(1, j), at(2, j), at(3, j)});
        for (int i = 0; i < 5; ++i)
            rows[i + 5 * j] = q[i];
    }
    for (int i = 0; i < 5; ++i) {
        const Quintuple q =
            vnp::cubicToQuadratics({rows[i], rows[i + 5], rows[i + 10], rows[i + 15]});
        for (int j = 0; j < 5; ++j)
            net[i + 5 * j] = q[j];
    }
}

// A quadratic triangular Bézier patch in barycentric form
// B(s) = Σ_{a+b+c=2} 2!/(a!b!c!) s0^a s1^b s2^c P_abc = sᵀ M s with
// M_ii = P_{2e_i}, M_ij = P_{e_i+e_j}; s is affine in the face's (u, v),
// s = s0 + u su + v sv, so B_u = 2 suᵀ M s, B_uu = 2 suᵀ M su, and so on.
struct QuadraticTriangle {
    Vec3 m[3][3];
    double s0[3], su[3], sv[3];

    SurfacePoint evaluate(double u, double v) const {
        double s[3];
        for (int i = 0; i < 3; ++i)
            s[i] = s0[i] + u * su[i] + v * sv[i];
        SurfacePoint out;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const Vec3& mij = m[i][j];
                out.position += s[i] * s[j] * mij;
                out.du += 2.0 * su[i] * s[j] * mij;
                out.dv += 2.0 * sv[i] * s[j] * mij;
                out.duu += 2.0 * su[i] * su[j] * mij;
                out.duv += 2.0 * su[i] * sv[j] * mij;
                out.dvv += 2.0 * sv[i] * sv[j] * mij;
            }
        return out;
    }
};

// §2.5 (3-sided): the 15 points read as 4 quadratic triangular sub-patches of
// 6 points each, split at the side midpoints: the corner patches (net
// ordinates with i, j or k >= 2) and the inverted middle one (all <= 2). In
// barycentrics b = (1 − u − v, u, v) of the domain triangle, the corner-0
// patch has local barycentrics (2b0 − 1, 2b1, 2b2), and the middle patch
// (1 − 2b0, 1 − 2b1, 1 − 2b2) with ordinate (a,b,c) at net (2−a, 2−b, 2−c).
SurfacePoint evaluateTriangleNet(const Vec3* net, double u, double v) {
    const double b[3] = {1.0 - u - v, u, v};
    int region = 3; // middle
    for (int i = 0; i < 3; ++i)
        if (b[i] >= 0.5) {
            region = i;
            break;
        }
    QuadraticTriangle q{};
    // Local barycentrics as affine functions of (u, v); d(b0, b1, b2)/du =
    // (−1, 1, 0) and /dv = (−1, 0, 1).
    const double bu[3] = {-1.0, 1.0, 0.0}, bv[3] = {-1.0, 0.0, 1.0}, bc[3] = {1.0, 0.0, 0.0};
    // Corner patch r: s_i = 2 b_i − [i = r]; middle patch: s_i = 1 − 2 b_i.
    const double scale = region == 3 ? -2.0 : 2.0;
    for (int i = 0; i < 3; ++i) {
        q.s0[i] = region == 3 ? 1.0 - 2.0 * bc[i] : 2.0 * bc[i] - (i == region ? 1.0 : 0.0);
        q.su[i] = scale * bu[i];
        q.sv[i] = scale * bv[i];
    }
    // Net point of the sub-patch ordinate e (a multi-index summing to 2).
    const auto point = [&](int a, int bb, int c) -> const Vec3& {
        int o[3] = {a, bb, c};
        for (int i = 0; i < 3; ++i)
            o[i] = region == 3 ? 2 - o[i] : o[i] + (i == region ? 2 : 0);
        return net[tri(o[1], o[2])];
    };
    q.m[0][0] = point(2, 0, 0);
    q.m[1][1] = point(0, 2, 0);
    q.m[2][2] = point(0, 0, 2);
    q.m[0][1] = q.m[1][0] = point(1, 1, 0);
    q.m[0][2] = q.m[2][0] = point(1, 0, 1);
    q.m[1][2] = q.m[2][1] = point(0, 1, 1);
    return q.evaluate(u, v);
}

// §2.5 (4-sided): the 5x5 net as 4 biquadratic tensor-product Bézier
// patches; sub-patch (a, b) covers [a/2, (a+1)/2] x [b/2, (b+1)/2] with local
// s = 2u − a, t = 2v − b, so d/du = 2 d/ds and d/dv = 2 d/dt.
SurfacePoint evaluateQuadNet(const Vec3* net, double u, double v) {
    const int a = u < 0.5 ? 0 : 1, b = v < 0.5 ? 0 : 1;
    const double s = 2.0 * u - a, t = 2.0 * v - b;
    const double bs[3] = {(1 - s) * (1 - s), 2 * s * (1 - s), s * s};
    const double ds[3] = {-2 * (1 - s), 2 - 4 * s, 2 * s};
    const double dds[3] = {2, -4, 2};
    const double bt[3] = {(1 - t) * (1 - t), 2 * t * (1 - t), t * t};
    const double dt[3] = {-2 * (1 - t), 2 - 4 * t, 2 * t};
    const double ddt[3] = {2, -4, 2};
    SurfacePoint out;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const Vec3& q = net[(2 * a + i) + 5 * (2 * b + j)];
            out.position += bs[i] * bt[j] * q;
            out.du += 2.0 * ds[i] * bt[j] * q;
            out.dv += 2.0 * bs[i] * dt[j] * q;
            out.duu += 4.0 * dds[i] * bt[j] * q;
            out.duv += 4.0 * ds[i] * dt[j] * q;
            out.dvv += 4.0 * bs[i] * ddt[j] * q;
        }
    return out;
}

// Newell normal of a polygon (length = twice its area when planar); taken
// about the centroid for accuracy far from the origin.
Vec3 newellNormal(const PolygonMesh& mesh, std::span<const Index> f) {
    Vec3 c = Vec3::Zero();
    for (Index v : f)
        c += mesh.positions[v];
    c /= static_cast<double>(f.size());
    Vec3 n = Vec3::Zero();
    for (size_t i = 0; i < f.size(); ++i)
        n += (mesh.positions[f[i]] - c).cross(mesh.positions[f[(i + 1) % f.size()]] - c);
    return n;
}

} // namespace

std::unique_ptr<VertexNormalPatches>
VertexNormalPatches::create(const PolygonMesh& cage, const VertexNormalPatchOptions& o) {
    if (!std::isfinite(o.apexLambda))
        throw std::invalid_argument("vertex-normal patches: apex lambda must be finite");
    if (!(o.boundaryMaxTiltDegrees >= 0.0 && o.boundaryMaxTiltDegrees <= 90.0))
        throw std::invalid_argument(
            "vertex-normal patches: boundary max tilt must be between 0 and 90 degrees");
    std::unique_ptr<VertexNormalPatches> s(new VertexNormalPatches());
    s->options_ = o;
    s->build(cage);
    return s;
}

std::string VertexNormalPatches::description() const {
    return std::string(
               "Vertex-normal patches (van Overveld & Wyvill), edge control points by the ") +
           toString(options_.edgeMethod) +
           " method: quadratic Bezier sub-patches per polygon, evaluated exactly; continuous "
           "(C0) across cage edges, tangent planes normal to the vertex normals at cage "
           "vertices, not tangent-continuous along edges in general.";
}

void VertexNormalPatches::build(const PolygonMesh& cage) {
    const Index nv = cage.vertexCount(), nf = cage.faceCount();
    if (nf <= 0)
        throw std::invalid_argument("vertex-normal patches: the cage has no faces");
    for (const Vec3& p : cage.positions)
        if (!p.allFinite())
            throw std::invalid_argument(
                "vertex-normal patches: the cage has a non-finite position");
    for (Index f = 0; f < nf; ++f) {
        const auto face = cage.face(f);
        if (face.size() < 3)
            throw std::invalid_argument("vertex-normal patches: face " + std::to_string(f) +
                                        " has fewer than 3 corners");
        for (Index v : face)
            if (v < 0 || v >= nv)
                throw std::invalid_argument("vertex-normal patches: face " + std::to_string(f) +
                                            " has a corner index out of range");
    }
    cageVertexCount_ = nv;

    // Vertex normals: the area-weighted average of the Newell normals of the
    // polygons around each vertex, normalised (the "normal vector averaging"
    // the paper assumes, §2 and §2.8).
    std::vector<Vec3> sum(static_cast<size_t>(nv), Vec3::Zero());
    std::vector<char> used(static_cast<size_t>(nv), 0);
    for (Index f = 0; f < nf; ++f) {
        const auto face = cage.face(f);
        const Vec3 n = newellNormal(cage, face);
        for (Index v : face) {
            sum[v] += n;
            used[v] = 1;
        }
    }
    normals_.assign(static_cast<size_t>(nv), Vec3::Zero());
    for (Index v = 0; v < nv; ++v) {
        const double len = sum[v].norm();
        if (used[v] && !(len > 0.0))
            throw std::invalid_argument("vertex-normal patches: vertex " + std::to_string(v) +
                                        " has a zero averaged normal (degenerate polygons)");
        if (used[v])
            normals_[v] = sum[v] / len;
    }

    // §2.8: a vertex on the border of an open mesh gets its normal projected
    // into the plane through its two border edges (the vase of colour plates
    // 3-4). Border edges are the directed cage edges without a twin.
    if (options_.boundaryNormalsInBorderPlane) {
        std::unordered_map<std::uint64_t, int> directed; // a << 32 | b -> count
        const auto key = [](Index a, Index b) {
            return static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint64_t>(b);
        };
        for (Index f = 0; f < nf; ++f) {
            const auto face = cage.face(f);
            for (size_t i = 0; i < face.size(); ++i)
                ++directed[key(face[i], face[(i + 1) % face.size()])];
        }
        std::vector<Index> borderNext(static_cast<size_t>(nv), kInvalidIndex);
        std::vector<Index> borderPrev(static_cast<size_t>(nv), kInvalidIndex);
        std::vector<int> borderCount(static_cast<size_t>(nv), 0);
        for (Index f = 0; f < nf; ++f) {
            const auto face = cage.face(f);
            for (size_t i = 0; i < face.size(); ++i) {
                const Index a = face[i], b = face[(i + 1) % face.size()];
                if (directed.count(key(b, a)))
                    continue;
                borderNext[a] = b;
                borderPrev[b] = a;
                ++borderCount[a];
            }
        }
        const double maxSin = std::sin(options_.boundaryMaxTiltDegrees * std::numbers::pi / 180.0);
        for (Index v = 0; v < nv; ++v) {
            // One border edge out and one in: a manifold border vertex.
            if (borderCount[v] != 1 || borderNext[v] == kInvalidIndex ||
                borderPrev[v] == kInvalidIndex)
                continue;
            const Vec3& p = cage.positions[v];
            const Vec3 in = p - cage.positions[borderPrev[v]];
            const Vec3 out = cage.positions[borderNext[v]] - p;
            const Vec3 w = in.cross(out);
            const double wl = w.norm();
            if (!(wl > 1e-12 * in.norm() * out.norm()))
                continue; // collinear border edges: no plane
            const Vec3 wn = w / wl;
            const Vec3& n = normals_[v];
            const double tilt = std::abs(n.dot(wn)); // sine of the angle out of the plane
            if (tilt > maxSin)
                continue;
            const Vec3 projected = n - n.dot(wn) * wn;
            const double pl = projected.norm();
            if (pl > 0.0)
                normals_[v] = projected / pl;
        }
    }

    // §2.4: two control points per cage edge from that edge's two vertices
    // and normals only, computed once from the lower to the higher vertex
    // index, so both polygons on the edge use the same curve (C0, §2.1.1).
    edgeCubics_.clear();
    const auto cubicOf = [&](Index a, Index b) -> Cubic {
        const std::uint64_t k = edgeKey(a, b);
        auto it = edgeCubics_.find(k);
        if (it == edgeCubics_.end()) {
            const Index lo = std::min(a, b), hi = std::max(a, b);
            it =
                edgeCubics_
                    .emplace(k, vnp::edgeCubic(cage.positions[lo], normals_[lo], cage.positions[hi],
                                               normals_[hi], options_.edgeMethod))
                    .first;
        }
        return a < b ? it->second : reversed(it->second);
    };

    domain_ = PolygonMesh();
    domain_.positions = cage.positions;
    faces_.clear();
    net_.clear();
    std::vector<std::pair<Index, Index>> apexFans; // (first domain face, count) per apex
    for (Index f = 0; f < nf; ++f) {
        const auto face = cage.face(f);
        const int n = static_cast<int>(face.size());
        std::vector<Cubic> side(static_cast<size_t>(n));
        for (int k = 0; k < n; ++k)
            side[k] = cubicOf(face[k], face[(k + 1) % n]);
        const auto addFace = [&](std::initializer_list<Index> corners, int netSize) {
            domain_.addFace(corners);
            faces_.push_back({f, static_cast<Index>(net_.size())});
            net_.resize(net_.size() + static_cast<size_t>(netSize));
            return net_.data() + faces_.back().netOffset;
        };
        if (n == 3) {
            Vec3* net = addFace({face[0], face[1], face[2]}, kTriangleNet);
            triangleNet({vnp::cubicToQuadratics(side[0]), vnp::cubicToQuadratics(side[1]),
                         vnp::cubicToQuadratics(side[2])},
                        net);
        } else if (n == 4) {
            Vec3* net = addFace({face[0], face[1], face[2], face[3]}, kQuadNet);
            quadNet({side[0], side[1], side[2], side[3]}, net);
        } else {
            // §2.5, n > 4: one interior point per corner by §2.6 from the
            // cubic side points next to it (4n points in all), then the apex
            // λ a_c + (1 − λ) a_i.
            std::vector<Vec3> interior(static_cast<size_t>(n));
            Vec3 ac = Vec3::Zero(), ai = Vec3::Zero();
            for (int k = 0; k < n; ++k) {
                const Vec3& c = cage.positions[face[k]];
                interior[k] = side[k][1] + side[(k + n - 1) % n][2] - c;
                ac += c;
                ai += interior[k];
            }
            ac /= n;
            ai /= n;
            const double lambda = options_.apexLambda;
            const Vec3 apex = lambda * ac + (1.0 - lambda) * ai;
            const Index apexIndex = domain_.vertexCount();
            domain_.positions.push_back(apex);
            // §2.5: the quadratic corner -> interior -> apex curves,
            // degree-elevated to cubics ("spokes", corner to apex).
            std::vector<Cubic> spoke(static_cast<size_t>(n));
            for (int k = 0; k < n; ++k) {
                const Vec3& c = cage.positions[face[k]];
                spoke[k] = {c, (c + 2.0 * interior[k]) / 3.0, (2.0 * interior[k] + apex) / 3.0,
                            apex};
            }
            // §2.5: n triangles (corner k, corner k+1, apex), each with the
            // 9 border points of a cubic triangle, dealt with as a 3-sided
            // polygon (5 points per side, interior points by §2.6).
            apexFans.emplace_back(static_cast<Index>(faces_.size()), n);
            for (int k = 0; k < n; ++k) {
                const int k1 = (k + 1) % n;
                Vec3* net = addFace({face[k], face[k1], apexIndex}, kTriangleNet);
                triangleNet({vnp::cubicToQuadratics(side[k]), vnp::cubicToQuadratics(spoke[k1]),
                             reversed(vnp::cubicToQuadratics(spoke[k]))},
                            net);
            }
        }
    }
    buildAdjacency();

    // Apex normals (used by refine()): the paper gives none. The fan's
    // patches do not share a tangent plane at the apex in general (§2.5,
    // footnote 5), so we take the normalised mean of their normals there.
    for (const auto& [first, count] : apexFans) {
        Vec3 n = Vec3::Zero();
        for (Index t = first; t < first + count; ++t)
            n += evaluate(Preimage{t, 0.0, 1.0}).normal();
        const double len = n.norm();
        normals_.push_back(len > 0.0 ? Vec3(n / len) : Vec3::UnitZ());
    }
}

std::span<const Vec3> VertexNormalPatches::controlNet(Index domainFace) const {
    const FaceInfo& info = faces_.at(static_cast<size_t>(domainFace));
    return {net_.data() + info.netOffset,
            static_cast<size_t>(isQuad(domainFace) ? kQuadNet : kTriangleNet)};
}

std::array<Vec3, 4> VertexNormalPatches::cageEdgeCubic(Index a, Index b) const {
    const auto it = edgeCubics_.find(edgeKey(a, b));
    if (it == edgeCubics_.end())
        throw std::out_of_range("cageEdgeCubic: (" + std::to_string(a) + ", " + std::to_string(b) +
                                ") is not a cage edge");
    return a < b ? it->second : reversed(it->second);
}

SurfacePoint VertexNormalPatches::evaluate(const Preimage& p) const {
    if (p.face < 0 || p.face >= static_cast<Index>(faces_.size()))
        throw std::out_of_range("VertexNormalPatches::evaluate: face " + std::to_string(p.face) +
                                " out of range");
    const Vec3* net = net_.data() + faces_[p.face].netOffset;
    return isQuad(p.face) ? evaluateQuadNet(net, p.u, p.v) : evaluateTriangleNet(net, p.u, p.v);
}

RefinedMesh VertexNormalPatches::refine(int levels) const {
    if (levels < 0)
        throw std::invalid_argument("refine: levels must be >= 0, got " + std::to_string(levels));
    constexpr long long kMaxTriangles = 100'000'000;
    long long count = 0;
    for (Index f = 0; f < domain_.faceCount(); ++f)
        count += isQuad(f) ? (levels == 0 ? 2 : 8) : (levels == 0 ? 1 : 4);
    for (int l = 1; l < levels; ++l) {
        count *= 4;
        if (count > kMaxTriangles)
            break;
    }
    if (count > kMaxTriangles)
        throw std::invalid_argument("refine: " + std::to_string(levels) +
                                    " levels would give more than 100 million triangles");

    std::vector<Vec3> positions = domain_.positions;
    std::vector<Vec3> normals = normals_;
    std::vector<Triangle> triangles;
    std::vector<Index> source;
    if (levels == 0) {
        for (Index f = 0; f < domain_.faceCount(); ++f) {
            const auto c = domain_.face(f);
            triangles.push_back({c[0], c[1], c[2]});
            source.push_back(faces_[f].cageFace);
            if (c.size() == 4) {
                triangles.push_back({c[0], c[2], c[3]});
                source.push_back(faces_[f].cageFace);
            }
        }
        return {TriangleMesh(std::move(positions), std::move(triangles), std::move(source)),
                std::move(normals)};
    }

    // First pass (§2.5): the corners of the quadratic sub-patches, i.e. the
    // domain vertices, the side midpoints m and the centres of quads; new
    // normals by quadratic normal interpolation (§2.7) along each side.
    std::unordered_map<std::uint64_t, Index> mid;
    const auto sideMid = [&](Index a, Index b, const Vec3& position) -> Index {
        const auto [it, inserted] = mid.try_emplace(edgeKey(a, b), Index(0));
        if (inserted) {
            it->second = static_cast<Index>(positions.size());
            const Index lo = std::min(a, b), hi = std::max(a, b);
            positions.push_back(position);
            normals.push_back(vnp::quadraticMidpointNormal(positions[lo], normals[lo],
                                                           positions[hi], normals[hi]));
        }
        return it->second;
    };
    for (Index f = 0; f < domain_.faceCount(); ++f) {
        const auto c = domain_.face(f);
        const std::span<const Vec3> net = controlNet(f);
        const Index src = faces_[f].cageFace;
        if (c.size() == 3) {
            const Index m0 = sideMid(c[0], c[1], net[tri(2, 0)]);
            const Index m1 = sideMid(c[1], c[2], net[tri(2, 2)]);
            const Index m2 = sideMid(c[2], c[0], net[tri(0, 2)]);
            for (const Triangle& t : {Triangle{c[0], m0, m2}, Triangle{m0, c[1], m1},
                                      Triangle{m2, m1, c[2]}, Triangle{m0, m1, m2}}) {
                triangles.push_back(t);
                source.push_back(src);
            }
        } else {
            const Index m[4] = {sideMid(c[0], c[1], net[2]), sideMid(c[1], c[2], net[14]),
                                sideMid(c[2], c[3], net[22]), sideMid(c[3], c[0], net[10])};
            // The quad's centre: §2.7 along both mid-lines, averaged (the
            // paper gives no rule for it).
            const Index z = static_cast<Index>(positions.size());
            positions.push_back(net[12]);
            const Vec3 n = vnp::quadraticMidpointNormal(positions[m[0]], normals[m[0]],
                                                        positions[m[2]], normals[m[2]]) +
                           vnp::quadraticMidpointNormal(positions[m[1]], normals[m[1]],
                                                        positions[m[3]], normals[m[3]]);
            normals.push_back(n.norm() > 0.0 ? Vec3(n.normalized()) : normals[m[0]]);
            // Each biquadratic sub-patch as two triangles split along the
            // diagonal from the cage corner to the centre: 8 in all.
            for (int k = 0; k < 4; ++k) {
                triangles.push_back({c[k], m[k], z});
                triangles.push_back({c[k], z, m[(k + 3) % 4]});
                source.insert(source.end(), 2, src);
            }
        }
    }

    // Later passes (§2.5 applied again, §2.7 "quadratic subdivision regime"):
    // each triangle with its vertex normals is a 3-sided input polygon; its
    // output vertices are the side midpoints m of the §2.4 cubics, with
    // averaged normals.
    for (int level = 2; level <= levels; ++level) {
        mid.clear();
        std::vector<Triangle> next;
        std::vector<Index> nextSource;
        next.reserve(triangles.size() * 4);
        nextSource.reserve(triangles.size() * 4);
        const auto edgeMid = [&](Index a, Index b) -> Index {
            const auto [it, inserted] = mid.try_emplace(edgeKey(a, b), Index(0));
            if (inserted) {
                it->second = static_cast<Index>(positions.size());
                const Index lo = std::min(a, b), hi = std::max(a, b);
                const Cubic cubic = vnp::edgeCubic(positions[lo], normals[lo], positions[hi],
                                                   normals[hi], options_.edgeMethod);
                const Vec3 avg = normals[lo] + normals[hi];
                positions.push_back(vnp::cubicToQuadratics(cubic)[2]);
                normals.push_back(avg.norm() > 0.0 ? Vec3(avg.normalized()) : normals[lo]);
            }
            return it->second;
        };
        for (size_t t = 0; t < triangles.size(); ++t) {
            const Triangle c = triangles[t];
            const Index m0 = edgeMid(c[0], c[1]), m1 = edgeMid(c[1], c[2]),
                        m2 = edgeMid(c[2], c[0]);
            for (const Triangle& s : {Triangle{c[0], m0, m2}, Triangle{m0, c[1], m1},
                                      Triangle{m2, m1, c[2]}, Triangle{m0, m1, m2}}) {
                next.push_back(s);
                nextSource.push_back(source[t]);
            }
        }
        triangles = std::move(next);
        source = std::move(nextSource);
    }
    return {TriangleMesh(std::move(positions), std::move(triangles), std::move(source)),
            std::move(normals)};
}

} // namespace contour
