#pragma once
// Layouts with a known flat metric for the Powell-Sabin suites: the cube
// with its corners as cones and every edge a cut, and flat tori of a grid.
#include "contours/powell_sabin/ConeLayout.h"

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace contour::testing {

using powell_sabin::ConeLayout;

inline Eigen::Matrix2d rotation(double angle) {
    Eigen::Matrix2d r;
    r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return r;
}

// The cube [-1,1]^3 with an n x n grid per side. Every side is laid out as
// its own square, rotated by a per-side angle and moved apart: the cube's
// edges are cut edges, its 8 corners cones of angle 3 pi / 2.
inline ConeLayout cubeLayout(int n, const std::array<double, 6>& angles) {
    struct Side {
        Vec3 o, a, b;
    };
    // a x b points outwards, so (a, b) counter-clockwise seen from outside.
    const std::array<Side, 6> sides = {{{Vec3(1, -1, -1), Vec3(0, 2, 0), Vec3(0, 0, 2)},
                                        {Vec3(-1, 1, -1), Vec3(0, -2, 0), Vec3(0, 0, 2)},
                                        {Vec3(1, 1, -1), Vec3(-2, 0, 0), Vec3(0, 0, 2)},
                                        {Vec3(-1, -1, -1), Vec3(2, 0, 0), Vec3(0, 0, 2)},
                                        {Vec3(-1, -1, 1), Vec3(2, 0, 0), Vec3(0, 2, 0)},
                                        {Vec3(-1, 1, -1), Vec3(2, 0, 0), Vec3(0, -2, 0)}}};
    std::map<std::array<long, 3>, Index> ids;
    std::vector<Vec3> pos;
    std::vector<Triangle> tris;
    std::vector<std::array<Vec2, 3>> uvs;
    std::vector<int> sideOf;
    for (int s = 0; s < 6; ++s) {
        const Eigen::Matrix2d r = rotation(angles[s]);
        const Vec2 shift(5.0 * s, 1.0 - 0.5 * s);
        std::vector<Index> grid;
        std::vector<Vec2> uv;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const Vec3 x =
                    sides[s].o + (double(i) / n) * sides[s].a + (double(j) / n) * sides[s].b;
                const std::array<long, 3> key = {std::lround(x.x() * 1e6), std::lround(x.y() * 1e6),
                                                 std::lround(x.z() * 1e6)};
                auto [it, fresh] = ids.emplace(key, Index(pos.size()));
                if (fresh)
                    pos.push_back(x);
                grid.push_back(it->second);
                uv.push_back(r * Vec2(2.0 * i / n, 2.0 * j / n) + shift);
            }
        auto at = [n](int i, int j) {
            return j * (n + 1) + i;
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const std::array<int, 4> c = {at(i, j), at(i + 1, j), at(i + 1, j + 1),
                                              at(i, j + 1)};
                for (const std::array<int, 3>& t :
                     {std::array<int, 3>{c[0], c[1], c[2]}, std::array<int, 3>{c[0], c[2], c[3]}}) {
                    tris.push_back({grid[t[0]], grid[t[1]], grid[t[2]]});
                    uvs.push_back({uv[t[0]], uv[t[1]], uv[t[2]]});
                    sideOf.push_back(s);
                }
            }
    }
    ConeLayout l;
    l.mesh = TriangleMesh(pos, tris);
    l.cornerUv = uvs;
    l.cutEdge.assign(l.mesh.edgeCount(), 0);
    for (Index e = 0; e < l.mesh.edgeCount(); ++e) {
        const Index h = l.mesh.edgeHalfedge(e);
        l.cutEdge[e] =
            sideOf[TriangleMesh::face(h)] != sideOf[TriangleMesh::face(l.mesh.opposite(h))];
    }
    l.isCone.assign(l.mesh.vertexCount(), 0);
    for (Index v = 0; v < l.mesh.vertexCount(); ++v)
        l.isCone[v] = (l.mesh.position(v).cwiseAbs() - Vec3::Ones()).norm() < 1e-12;
    return l;
}

// A layout of `tris` with corner uv `uvs`, cut where the two faces of an
// edge give its ends different uv, no cones.
inline ConeLayout layoutWithCuts(std::vector<Vec3> pos, std::vector<Triangle> tris,
                                 std::vector<std::array<Vec2, 3>> uvs) {
    ConeLayout l;
    l.mesh = TriangleMesh(std::move(pos), std::move(tris));
    l.cornerUv = std::move(uvs);
    l.cutEdge.assign(l.mesh.edgeCount(), 0);
    for (Index e = 0; e < l.mesh.edgeCount(); ++e) {
        const Index h = l.mesh.edgeHalfedge(e);
        const Index o = l.mesh.opposite(h);
        if (o == kInvalidIndex)
            continue;
        l.cutEdge[e] = (l.cornerUv[TriangleMesh::face(h)][h % 3] -
                        l.cornerUv[TriangleMesh::face(o)][TriangleMesh::next(o) % 3])
                           .norm() > 1e-12;
    }
    l.isCone.assign(l.mesh.vertexCount(), 0);
    return l;
}

// An n x m grid torus with the flat metric of the rectangle [0, n] x [0,
// m aspect], cut along the loops i = 0 and j = 0, its vertex (i, j) at
// embed(2 pi i / n, 2 pi j / m).
inline ConeLayout flatTorusLayout(int n, int m, double aspect,
                                  const std::function<Vec3(double, double)>& embed) {
    std::vector<Vec3> pos;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i)
            pos.push_back(embed(2.0 * M_PI * i / n, 2.0 * M_PI * j / m));
    auto id = [n, m](int i, int j) {
        return Index((j % m) * n + (i % n));
    };
    std::vector<Triangle> tris;
    std::vector<std::array<Vec2, 3>> uvs;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            auto uv = [aspect](int a, int b) {
                return Vec2(a, aspect * b);
            };
            tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            uvs.push_back({uv(i, j), uv(i + 1, j), uv(i + 1, j + 1)});
            tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            uvs.push_back({uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)});
        }
    return layoutWithCuts(pos, tris, uvs);
}

} // namespace contour::testing
