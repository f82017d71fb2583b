#include "contours/powell_sabin/SplineTessellation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <unordered_map>

namespace contour::powell_sabin {

namespace {

// The 12-split's points have face-barycentric coordinates in multiples of
// 1/12 (corners, edge midpoints, the centroid, and the midpoints of the
// midpoint segments on the medians); a k-lattice on a sub-triangle is then
// on multiples of 1/(12 k), which identifies each point exactly.
constexpr int kSplitDenominator = 12;

struct PointKey {
    int kind; // 0 vertex, 1 edge, 2 face interior
    Index element;
    int a, b;
    bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
    size_t operator()(const PointKey& k) const {
        size_t h = std::hash<long long>{}((static_cast<long long>(k.kind) << 32) ^ k.element);
        h ^= std::hash<long long>{}((static_cast<long long>(k.a) << 20) ^ k.b) + 0x9e3779b9 +
             (h << 6) + (h >> 2);
        return h;
    }
};

} // namespace

Index tessellationTriangle(Index patch, const Vec3& b, int k) {
    const double x = std::clamp(b[1], 0.0, 1.0) * k, y = std::clamp(b[2], 0.0, 1.0) * k;
    int j = std::min(static_cast<int>(y), k - 1);
    int i = std::min(static_cast<int>(x), k - 1 - j);
    const bool down = (x - i) + (y - j) > 1.0 && i + j + 1 < k;
    Index index = 0;
    for (int r = 0; r < j; ++r)
        index += 2 * (k - r) - 1;
    return patch * k * k + index + 2 * i + (down ? 1 : 0);
}

namespace {

// A point of the spline and its unit normal (zero at a cone), mapped by
// toWorld.
void evaluateVertex(const QuadraticBezier<Vec3>& patch, const Vec3& bary,
                    const SplineToWorld& toWorld, Vec3& point, Vec3& normal) {
    Vec3 du, dv;
    uvDerivatives(patch, bary, du, dv);
    point = evaluate(patch, bary);
    if (toWorld.jacobian) {
        const Eigen::Matrix3d jac = toWorld.jacobian(point);
        du = jac * du;
        dv = jac * dv;
    }
    if (toWorld.point)
        point = toWorld.point(point);
    const Vec3 n = du.cross(dv);
    normal = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero();
}

} // namespace

TessellationPoints evaluateTessellationPoints(const SplineTessellation& previous,
                                              const PowellSabinSpline& spline,
                                              const SplineToWorld& toWorld) {
    const Index n = previous.mesh.vertexCount();
    if (static_cast<Index>(previous.vertexPatch.size()) != n)
        throw std::invalid_argument("evaluateTessellationPoints: the tessellation has no "
                                    "evaluation sites");
    for (Index p : previous.vertexPatch)
        if (p < 0 || p >= static_cast<Index>(spline.patches.size()))
            throw std::invalid_argument("evaluateTessellationPoints: the spline has other patches");
    TessellationPoints out;
    out.positions.resize(static_cast<size_t>(n));
    out.normals.resize(static_cast<size_t>(n));
    tbb::parallel_for(Index(0), n, [&](Index v) {
        evaluateVertex(spline.patches[previous.vertexPatch[v]], previous.vertexPatchBarycentric[v],
                       toWorld, out.positions[v], out.normals[v]);
    });
    return out;
}

SplineTessellation tessellateSpline(const PowellSabinSpline& spline, const ConeLayout& layout,
                                    int level, const SplineToWorld& toWorld) {
    if (level < 1)
        throw std::invalid_argument("tessellateSpline: level must be at least 1");
    const TriangleMesh& mesh = layout.mesh;
    if (spline.faceCount() != mesh.faceCount())
        throw std::invalid_argument("tessellateSpline: the spline and the layout differ");
    const int k = level;
    const int denominator = kSplitDenominator * k;
    SplineTessellation out;
    std::vector<Vec3> positions;
    std::unordered_map<PointKey, Index, PointKeyHash> index;
    std::vector<Triangle> triangles;
    // Per triangle side of the output: the label of the boundary it lies on.
    std::map<std::pair<Index, Index>, int> sideLabel;

    const auto keyOf = [&](Index f, const std::array<int, 3>& n) -> PointKey {
        int zeros = 0;
        for (int c = 0; c < 3; ++c)
            zeros += n[c] == 0;
        if (zeros == 2)
            for (int c = 0; c < 3; ++c)
                if (n[c] == denominator)
                    return {0, mesh.triangle(f)[c], 0, 0};
        if (zeros == 1)
            for (int s = 0; s < 3; ++s)
                if (n[(s + 2) % 3] == 0) {
                    // On side s (corner s -> s + 1), at n[s] / denominator from s + 1.
                    const Index h = TriangleMesh::halfedge(f, s);
                    const Index e = mesh.edge(h);
                    const int fromWeight = n[s];
                    const int t = h == mesh.edgeHalfedge(e) ? fromWeight : denominator - fromWeight;
                    return {1, e, t, 0};
                }
        return {2, f, n[0], n[1]};
    };

    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const std::array<Vec2, 3>& faceUv = layout.cornerUv[f];
        for (int l = 0; l < kPs12Patches; ++l) {
            const Index p = kPs12Patches * f + l;
            const QuadraticBezier<Vec3>& patch = spline.patches[p];
            // Sub-triangle corners in face-barycentric lattice units.
            std::array<std::array<int, 3>, 3> corner{};
            for (int c = 0; c < 3; ++c) {
                const Vec3 b = barycentricOf(faceUv, patch.domain[c]);
                for (int i = 0; i < 3; ++i)
                    corner[c][i] = static_cast<int>(std::lround(b[i] * kSplitDenominator)) * k;
            }
            // Lattice point (i, j) of the patch: weights (k - i - j, i, j) on its corners.
            std::vector<Index> local((k + 1) * (k + 2) / 2);
            std::vector<Vec3> localBary(local.size());
            const auto at = [k](int i, int j) {
                return j * (k + 1) - j * (j - 1) / 2 + i;
            };
            for (int j = 0; j <= k; ++j)
                for (int i = 0; i + j <= k; ++i) {
                    std::array<int, 3> n{};
                    for (int c = 0; c < 3; ++c)
                        n[c] =
                            ((k - i - j) * corner[0][c] + i * corner[1][c] + j * corner[2][c]) / k;
                    const PointKey key = keyOf(f, n);
                    auto [it, inserted] =
                        index.try_emplace(key, static_cast<Index>(positions.size()));
                    if (inserted) {
                        const Vec3 bary(double(k - i - j) / k, double(i) / k, double(j) / k);
                        Vec3 point, normal;
                        evaluateVertex(patch, bary, toWorld, point, normal);
                        positions.push_back(point);
                        out.normals.push_back(normal);
                        out.vertexPatch.push_back(p);
                        out.vertexPatchBarycentric.push_back(bary);
                        out.barycentric.push_back(Vec3(n[0], n[1], n[2]) / denominator);
                        out.vertexMacroPatch.push_back(f);
                    }
                    local[at(i, j)] = it->second;
                    localBary[at(i, j)] = Vec3(n[0], n[1], n[2]) / denominator;
                }
            const auto addTriangle = [&](int a, int b, int c) {
                triangles.push_back({local[a], local[b], local[c]});
                out.cornerBarycentric.push_back({localBary[a], localBary[b], localBary[c]});
                out.patch.push_back(static_cast<int>(p));
                out.macroPatch.push_back(static_cast<int>(f));
            };
            for (int j = 0; j < k; ++j)
                for (int i = 0; i + j < k; ++i) {
                    addTriangle(at(i, j), at(i + 1, j), at(i, j + 1));
                    if (i + j + 1 < k)
                        addTriangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                }
            // The patch's three sides: a macro-patch side when both of its
            // ends lie on one side of the face.
            for (int s = 0; s < 3; ++s) {
                const std::array<int, 3>& a = corner[s];
                const std::array<int, 3>& b = corner[(s + 1) % 3];
                int label = 1;
                for (int c = 0; c < 3; ++c)
                    if (a[c] == 0 && b[c] == 0) {
                        // Side (c + 1) of the face, opposite corner c.
                        const Index e = mesh.edge(TriangleMesh::halfedge(f, (c + 1) % 3));
                        label = layout.cutEdge[e] ? 3 : 2;
                    }
                for (int t = 0; t < k; ++t) {
                    const auto lattice = [&](int q) {
                        // Point q of side s, from corner s to corner s + 1.
                        switch (s) {
                        case 0:
                            return local[at(q, 0)];
                        case 1:
                            return local[at(k - q, q)];
                        default:
                            return local[at(0, k - q)];
                        }
                    };
                    Index u = lattice(t), v = lattice(t + 1);
                    if (u > v)
                        std::swap(u, v);
                    int& existing = sideLabel[{u, v}];
                    existing = std::max(existing, label);
                }
            }
        }
    }
    out.mesh = TriangleMesh(std::move(positions), std::move(triangles));
    out.patchEdge.assign(out.mesh.edgeCount(), 0);
    for (Index e = 0; e < out.mesh.edgeCount(); ++e) {
        const Index h = out.mesh.edgeHalfedge(e);
        Index u = out.mesh.from(h), v = out.mesh.to(h);
        if (u > v)
            std::swap(u, v);
        const auto it = sideLabel.find({u, v});
        if (it != sideLabel.end())
            out.patchEdge[e] = it->second;
    }
    return out;
}

} // namespace contour::powell_sabin
