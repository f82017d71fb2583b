// Patch adjacency of the Powell-Sabin spline and the chaining of per-patch
// contour segments into loops (contours/powell_sabin/PatchAdjacency.h,
// ContourChains.h; Capouellez et al. 2023 §4.2). The adjacency is checked
// against the spline's own continuity (positions agree along every shared
// side, at every node). Chaining is checked on synthetic segments with known
// ends: the zero set of a function given per split-point node and linear on
// every patch, whose crossings of a shared side are the same from both sides
// by construction (across macro-patch sides, mesh edges and cut edges of a
// cube with 8 cones, through patch corners and cones), and on a fitted sphere
// with the segments of patchContours and, independently, with chords between
// the exact roots of tau . n on the patch sides.
#include "PowellSabinLayouts.h"
#include "contours/powell_sabin/ConeSelection.h"
#include "contours/powell_sabin/ConformalMap.h"
#include "contours/powell_sabin/ContourChains.h"
#include "contours/powell_sabin/PatchContour.h"
#include "contours/powell_sabin/ThinPlateFit.h"
#include "mesh/ProceduralShapes.h"

#include <Eigen/Geometry>
#include <QtTest>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

Vec3 unitBarycentric(int corner) {
    Vec3 b = Vec3::Zero();
    b[corner] = 1.0;
    return b;
}

Vec3 sidePoint(int side, double t) {
    Vec3 b = Vec3::Zero();
    b[side] = 1.0 - t;
    b[(side + 1) % 3] = t;
    return b;
}

// The unit square as two triangles, uv = xy: boundary, no cuts, no cones.
ConeLayout squareLayout() {
    ConeLayout l;
    const std::vector<Vec3> pos = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    const std::vector<Triangle> tris = {{0, 1, 2}, {0, 2, 3}};
    l.mesh = TriangleMesh(pos, tris);
    for (const Triangle& t : tris)
        l.cornerUv.push_back({pos[t[0]].head<2>(), pos[t[1]].head<2>(), pos[t[2]].head<2>()});
    l.cutEdge.assign(l.mesh.edgeCount(), 0);
    l.isCone.assign(l.mesh.vertexCount(), 0);
    return l;
}

// The cube of PowellSabinLayouts.h with its sides turned by random angles.
ConeLayout cubeLayout(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    std::array<double, 6> angles;
    for (double& a : angles)
        a = angle(rng);
    return testing::cubeLayout(n, angles);
}

struct Surface {
    ConeLayout layout;
    PowellSabinSpline spline;
    PatchAdjacency adjacency;
};

Surface fitted(ConeLayout layout) {
    Surface s;
    s.layout = std::move(layout);
    const ThinPlateFit fit(s.layout);
    s.spline = fit.fit(s.layout.mesh.positions());
    s.adjacency = PatchAdjacency(s.layout, s.spline);
    return s;
}

Vec3 nodePosition(const Surface& s, Index node) {
    const PatchCorner c = s.adjacency.patchesAt(node).front();
    return s.spline.position(c.patch, unitBarycentric(c.corner));
}

// A segment from a to b (uv of the patch) with one of three
// parameterizations, traversed either way: the chaining must not depend on
// them. kind 0: t in [0, 1]; 1: t in [-2, 3]; 2: rational, W = 1 + t.
ContourSegment segmentBetween(Index patch, Vec2 a, int sideA, Vec2 b, int sideB, int kind,
                              bool swap) {
    if (swap) {
        std::swap(a, b);
        std::swap(sideA, sideB);
    }
    ContourSegment s;
    s.patch = patch;
    s.kind = ConicKind::ParallelLines;
    s.startSide = sideA;
    s.endSide = sideB;
    Eigen::Matrix3d& c = s.curve.coefficients;
    c.setZero();
    if (kind == 0) {
        c.block<2, 1>(0, 0) = a;
        c.block<2, 1>(0, 1) = b - a;
        c(2, 0) = 1.0;
        s.t0 = 0.0;
        s.t1 = 1.0;
    } else if (kind == 1) {
        c.block<2, 1>(0, 0) = a + 0.4 * (b - a);
        c.block<2, 1>(0, 1) = 0.2 * (b - a);
        c(2, 0) = 1.0;
        s.t0 = -2.0;
        s.t1 = 3.0;
    } else {
        // (a (1 - t) + 2 b t) / (1 + t): a at t = 0, b at t = 1.
        c.block<2, 1>(0, 0) = a;
        c.block<2, 1>(0, 1) = 2.0 * b - a;
        c(2, 0) = 1.0;
        c(2, 1) = 1.0;
        s.t0 = 0.0;
        s.t1 = 1.0;
    }
    return s;
}

Vec2 curveAt(const ContourSegment& s, double t) {
    const Eigen::Vector3d v = s.curve.coefficients * Eigen::Vector3d(1.0, t, t * t);
    return Vec2(v.x(), v.y()) / v.z();
}

struct Marching {
    std::vector<ContourSegment> segments;
    int degenerate = 0; // patches whose zero set is not one segment between two points
    int fourCrossings = 0;
};

// The zero set of the function phi per node, linear on every patch. Side
// crossings are moved along the side by up to `jitter` (independently in the
// two patches of a side); a crossing at a corner is reported on either of
// the corner's two sides.
Marching marchNodeFunction(const Surface& s, const std::vector<double>& phi, unsigned seed,
                           double jitter = 0.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> shake(-jitter, jitter);
    std::uniform_int_distribution<int> coin(0, 1), kind(0, 2);
    Marching m;
    for (Index p = 0; p < s.adjacency.patchCount(); ++p) {
        const auto& d = s.spline.patches[p].domain;
        std::array<double, 3> f;
        for (int c = 0; c < 3; ++c)
            f[c] = phi[s.adjacency.cornerNode(p, c)];
        std::vector<std::pair<Vec2, int>> points;
        int zeros = 0;
        for (int c = 0; c < 3; ++c)
            zeros += f[c] == 0.0;
        for (int c = 0; c < 3; ++c) {
            const int n = (c + 1) % 3, o = (c + 2) % 3;
            if (f[c] * f[n] < 0.0) {
                const double t = f[c] / (f[c] - f[n]) + shake(rng);
                points.emplace_back(d[c] + t * (d[n] - d[c]), c);
            }
            if (f[c] == 0.0 && f[n] * f[o] < 0.0)
                points.emplace_back(d[c], coin(rng) ? c : o);
        }
        if (zeros > 1 || (zeros == 1 && points.size() == 1) || points.size() > 2 ||
            points.size() == 1) {
            ++m.degenerate;
            continue;
        }
        if (points.size() == 2)
            m.segments.push_back(segmentBetween(p, points[0].first, points[0].second,
                                                points[1].first, points[1].second, kind(rng),
                                                coin(rng) != 0));
    }
    return m;
}

std::vector<double> nodeFunction(const Surface& s, const std::function<double(const Vec3&)>& f) {
    std::vector<double> phi(s.adjacency.nodeCount());
    for (Index n = 0; n < s.adjacency.nodeCount(); ++n)
        phi[n] = f(nodePosition(s, n));
    return phi;
}

// The 3D point where a link enters (front) or leaves its segment.
Vec3 linkPoint(const Surface& s, std::span<const ContourSegment> segments, const ChainLink& l,
               bool exit) {
    const ContourSegment& seg = segments[l.segment];
    const double t = (exit != l.reversed) ? seg.t1 : seg.t0;
    const auto& d = s.spline.patches[seg.patch].domain;
    return s.spline.position(seg.patch, barycentricOf(d, curveAt(seg, t)));
}

// Every segment once; consecutive links meet in 3D (and a loop's last link
// meets its first).
void checkChains(const Surface& s, std::span<const ContourSegment> segments,
                 const ContourChaining& c, double tolerance) {
    std::vector<int> seen(segments.size(), 0);
    double worst = 0.0;
    for (const ContourChain& chain : c.chains) {
        QVERIFY(!chain.links.empty());
        for (std::size_t k = 0; k < chain.links.size(); ++k) {
            ++seen[chain.links[k].segment];
            if (k + 1 < chain.links.size() || chain.closed) {
                const ChainLink& next = chain.links[(k + 1) % chain.links.size()];
                worst = std::max(worst, (linkPoint(s, segments, chain.links[k], true) -
                                         linkPoint(s, segments, next, false))
                                            .norm());
            }
        }
    }
    for (int n : seen)
        QCOMPARE(n, 1);
    QVERIFY2(worst < tolerance, qPrintable(QString("gap %1").arg(worst)));
}

// How many joins of each kind of side the chains cross.
std::map<PatchSideKind, int>
crossedSides(const Surface& s, std::span<const ContourSegment> segments, const ContourChaining& c) {
    std::map<PatchSideKind, int> count;
    for (const ContourChain& chain : c.chains)
        for (std::size_t k = 0; k < chain.links.size(); ++k) {
            if (k + 1 == chain.links.size() && !chain.closed)
                break;
            const ContourSegment& seg = segments[chain.links[k].segment];
            const int side = chain.links[k].reversed ? seg.startSide : seg.endSide;
            if (side >= 0)
                ++count[s.adjacency.neighbour(seg.patch, side).kind];
        }
    return count;
}

// The sphere through the paper's pipeline (cones, refinement, conformal
// map, layout, thin-plate fit); the fit is redone per view.
struct SphereSetup {
    ConeLayout layout;
    std::unique_ptr<ThinPlateFit> fit;
};

SphereSetup sphereSetup() {
    const TriangleMesh mesh = makeSphere(1.0, 10).triangulate();
    const Cones cones = selectCones(mesh);
    const ConeRefinement refined = refineAroundCones(mesh, cones.vertices);
    const ConformalMap map = computeConformalMap(refined.mesh, refined.cones);
    SphereSetup s;
    s.layout = layoutConformalMap(refined.mesh.positions(), map, refined.cones);
    s.fit = std::make_unique<ThinPlateFit>(s.layout);
    return s;
}

// Roots in (0, 1) of c0 + c1 t + c2 t^2.
std::vector<double> unitRoots(double c0, double c1, double c2) {
    std::vector<double> r;
    const double scale = std::max({std::abs(c0), std::abs(c1), std::abs(c2)});
    if (scale == 0.0)
        return r;
    if (std::abs(c2) <= 1e-14 * scale) {
        if (c1 != 0.0)
            r.push_back(-c0 / c1);
    } else {
        const double disc = c1 * c1 - 4.0 * c2 * c0;
        if (disc < 0.0)
            return r;
        const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
        r.push_back(q / c2);
        if (q != 0.0)
            r.push_back(c0 / q);
    }
    std::vector<double> inside;
    for (double t : r)
        if (t > 0.0 && t < 1.0)
            inside.push_back(t);
    return inside;
}

// Independent per-patch extraction for a real spline: tau . n is quadratic
// along every patch side, so its roots there are exact; the segment of a
// patch with two roots is the chord between them. In a cone patch tau . n is
// a quadratic form centred at the cone (§5.2: zero gradients there), so the
// contour is lines from the cone to the roots on the opposite side.
Marching sideRootSegments(const Surface& s, const Vec3& tau, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coin(0, 1), kind(0, 2);
    Marching m;
    for (Index p = 0; p < s.adjacency.patchCount(); ++p) {
        const auto& d = s.spline.patches[p].domain;
        auto roots = [&](int side) {
            std::array<double, 3> q;
            for (int k = 0; k < 3; ++k)
                q[k] = tau.dot(s.spline.normal(p, sidePoint(side, 0.5 * k)));
            return unitRoots(q[0], -3.0 * q[0] + 4.0 * q[1] - q[2],
                             2.0 * q[0] - 4.0 * q[1] + 2.0 * q[2]);
        };
        auto at = [&](int side, double t) {
            return Vec2(d[side] + t * (d[(side + 1) % 3] - d[side]));
        };
        if (s.adjacency.isConeCorner(p, 0)) {
            for (double t : roots(1))
                m.segments.push_back(segmentBetween(p, d[0], coin(rng) ? 0 : 2, at(1, t), 1,
                                                    kind(rng), coin(rng) != 0));
            continue;
        }
        // Crossings in boundary order (side, then t).
        std::vector<std::pair<Vec2, int>> points;
        for (int side = 0; side < 3; ++side) {
            std::vector<double> r = roots(side);
            std::sort(r.begin(), r.end());
            for (double t : r)
                points.emplace_back(at(side, t), side);
        }
        auto add = [&](std::size_t i, std::size_t j) {
            m.segments.push_back(segmentBetween(p, points[i].first, points[i].second,
                                                points[j].first, points[j].second, kind(rng),
                                                coin(rng) != 0));
        };
        if (points.size() == 2) {
            add(0, 1);
        } else if (points.size() == 4) {
            // Two arcs that do not cross: (0 1)(2 3) or (1 2)(3 0). The
            // crossing of the diagonals lies between the two arcs, where tau.n
            // has the sign of the boundary between the arcs' ends.
            auto f = [&](const Vec2& x) {
                return tau.dot(s.spline.normal(p, barycentricOf(d, x)));
            };
            const Vec2 a0 = points[0].first, a1 = points[1].first, a2 = points[2].first,
                       a3 = points[3].first;
            Eigen::Matrix2d lhs;
            lhs.col(0) = a2 - a0;
            lhs.col(1) = a1 - a3;
            const Vec2 st = lhs.colPivHouseholderQr().solve(a1 - a0);
            const Vec2 centre = a0 + st.x() * (a2 - a0);
            // A boundary point between crossings 1 and 2.
            const Vec2 between = points[1].second == points[2].second
                                     ? Vec2(0.5 * (a1 + a2))
                                     : Vec2(d[(points[1].second + 1) % 3]);
            const bool firstPairing = f(centre) * f(between) > 0.0;
            if (firstPairing) {
                add(0, 1);
                add(2, 3);
            } else {
                add(1, 2);
                add(3, 0);
            }
            ++m.fourCrossings;
        } else if (!points.empty()) {
            ++m.degenerate;
            qInfo("patch %d: %d side roots", int(p), int(points.size()));
        }
    }
    return m;
}

// The chains of a sphere's contour: no errors, joins within the padding, the
// chains meet in 3D; either one closed loop or chains from cone to cone that
// form one connected cycle (every cone of even degree).
void checkSphereChains(const Surface& s, std::span<const ContourSegment> segments,
                       const ContourChaining& c) {
    QVERIFY2(c.unmatchedEnds == 0, c.firstUnmatched.c_str());
    QCOMPARE(c.looseJoins, Index(0));
    QCOMPARE(c.boundaryEnds, Index(0));
    checkChains(s, segments, c, 1e-8);
    if (c.openChains == 0) {
        QCOMPARE(c.closedLoops, Index(1));
        return;
    }
    QCOMPARE(c.closedLoops, Index(0));
    std::map<Index, int> degree;
    std::map<Index, Index> parent;
    std::function<Index(Index)> find = [&](Index x) {
        return parent[x] == x ? x : parent[x] = find(parent[x]);
    };
    for (const ContourChain& chain : c.chains) {
        QCOMPARE(chain.front.kind, ChainEndKind::Cone);
        QCOMPARE(chain.back.kind, ChainEndKind::Cone);
        for (Index n : {chain.front.node, chain.back.node}) {
            ++degree[n];
            parent.emplace(n, n);
        }
        parent[find(chain.front.node)] = find(chain.back.node);
    }
    std::set<Index> roots;
    for (const auto& [n, deg] : degree) {
        QCOMPARE(deg % 2, 0);
        roots.insert(find(n));
    }
    QCOMPARE(roots.size(), std::size_t(1));
}

} // namespace

class TestPsContourChains : public QObject {
    Q_OBJECT
private slots:
    void adjacencyOfTwoTriangles() {
        const Surface s = fitted(squareLayout());
        const PatchAdjacency& a = s.adjacency;
        QCOMPARE(a.patchCount(), Index(24));
        QCOMPARE(a.nodeCount(), Index(4 + 5 + 8));
        std::map<PatchSideKind, int> kinds;
        for (Index p = 0; p < a.patchCount(); ++p)
            for (int side = 0; side < 3; ++side) {
                const PatchSideNeighbour& n = a.neighbour(p, side);
                ++kinds[n.kind];
                if (n.kind == PatchSideKind::Boundary) {
                    QCOMPARE(n.patch, kInvalidIndex);
                    continue;
                }
                const PatchSideNeighbour& back = a.neighbour(n.patch, n.side);
                QCOMPARE(back.patch, p);
                QCOMPARE(back.side, side);
                QCOMPARE(back.kind, n.kind);
                QCOMPARE(n.kind == PatchSideKind::MacroPatch, p / 12 == n.patch / 12);
                // One uv frame: the same uv point and the same 3D point.
                for (double t : {0.0, 0.3, 1.0}) {
                    const auto& d = s.spline.patches[p].domain;
                    const auto& e = s.spline.patches[n.patch].domain;
                    const Vec2 x = d[side] + t * (d[(side + 1) % 3] - d[side]);
                    const double u = n.map(t);
                    const Vec2 y = e[n.side] + u * (e[(n.side + 1) % 3] - e[n.side]);
                    QVERIFY((x - y).norm() < 1e-14);
                    QVERIFY((s.spline.position(p, sidePoint(side, t)) -
                             s.spline.position(n.patch, sidePoint(n.side, u)))
                                .norm() < 1e-12);
                }
            }
        QCOMPARE(kinds[PatchSideKind::Boundary], 8);
        QCOMPARE(kinds[PatchSideKind::MeshEdge], 4);
        QCOMPARE(kinds[PatchSideKind::CutEdge], 0);
        QCOMPARE(kinds[PatchSideKind::MacroPatch], 60);
        // Patches around the nodes: 2 per face at a vertex, 4 per face at an
        // edge midpoint and a median point, 6 at a centroid.
        int boundaryNodes = 0;
        for (Index node = 0; node < a.nodeCount(); ++node) {
            boundaryNodes += a.isBoundaryNode(node);
            QVERIFY(!a.isConeNode(node));
            const auto around = a.patchesAt(node);
            const Index element = a.nodeElement(node);
            switch (a.nodeKind(node)) {
            case PatchNodeKind::Vertex:
                QCOMPARE(Index(around.size()), element == 0 || element == 2 ? Index(4) : Index(2));
                break;
            case PatchNodeKind::EdgeMidpoint:
                QCOMPARE(Index(around.size()),
                         s.layout.mesh.isBoundaryEdge(element) ? Index(4) : Index(8));
                break;
            case PatchNodeKind::MedianPoint:
                QCOMPARE(Index(around.size()), Index(4));
                break;
            case PatchNodeKind::Centroid:
                QCOMPARE(Index(around.size()), Index(6));
                break;
            }
            for (const PatchCorner& c : around) {
                QCOMPARE(a.cornerNode(c.patch, c.corner), node);
                QVERIFY((s.spline.patches[c.patch].domain[c.corner] -
                         s.spline.patches[around[0].patch].domain[around[0].corner])
                            .norm() < 1e-14);
            }
        }
        QCOMPARE(boundaryNodes, 8);
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, a.neighbour(24, 0));
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, a.neighbour(0, 3));
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, a.cornerNode(-1, 0));
        PowellSabinSpline wrong = s.spline;
        wrong.patches.pop_back();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, PatchAdjacency(s.layout, wrong));
    }

    void adjacencyOfCube() {
        // Positions agree along every shared side and at every node, across
        // cut edges whose two uv frames differ.
        const Surface s = fitted(cubeLayout(2, 7));
        const PatchAdjacency& a = s.adjacency;
        std::map<PatchSideKind, int> kinds;
        int cutFramesDiffer = 0;
        double worst = 0.0;
        for (Index p = 0; p < a.patchCount(); ++p)
            for (int side = 0; side < 3; ++side) {
                const PatchSideNeighbour& n = a.neighbour(p, side);
                ++kinds[n.kind];
                QVERIFY(n.patch != kInvalidIndex);
                QCOMPARE(a.neighbour(n.patch, n.side).patch, p);
                QCOMPARE(a.cornerNode(p, side), a.cornerNode(n.patch, (n.side + 1) % 3));
                QCOMPARE(a.cornerNode(p, (side + 1) % 3), a.cornerNode(n.patch, n.side));
                for (double t : {0.13, 0.5, 0.71})
                    worst =
                        std::max(worst, (s.spline.position(p, sidePoint(side, t)) -
                                         s.spline.position(n.patch, sidePoint(n.side, n.map(t))))
                                            .norm());
                if (n.kind == PatchSideKind::CutEdge) {
                    const auto& d = s.spline.patches[p].domain;
                    const auto& e = s.spline.patches[n.patch].domain;
                    cutFramesDiffer += (d[side] - e[(n.side + 1) % 3]).norm() > 1e-3;
                }
            }
        QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
        // 12 cube edges of 2 mesh edges, 2 faces, 2 halves each.
        QCOMPARE(kinds[PatchSideKind::CutEdge], 96);
        QCOMPARE(kinds[PatchSideKind::Boundary], 0);
        QVERIFY(kinds[PatchSideKind::MeshEdge] > 0);
        QVERIFY(cutFramesDiffer > 0);
        int cones = 0;
        double nodeWorst = 0.0;
        for (Index node = 0; node < a.nodeCount(); ++node) {
            cones += a.isConeNode(node);
            QVERIFY(!a.isBoundaryNode(node));
            const Vec3 x = nodePosition(s, node);
            for (const PatchCorner& c : a.patchesAt(node))
                nodeWorst = std::max(
                    nodeWorst, (s.spline.position(c.patch, unitBarycentric(c.corner)) - x).norm());
        }
        QCOMPARE(cones, 8);
        QVERIFY2(nodeWorst < 1e-12, qPrintable(QString::number(nodeWorst)));
        // Cone corners are the spline's cone patches, and only corner 0 of
        // patches 2i, 2i + 1 can be one.
        for (Index p = 0; p < a.patchCount(); ++p) {
            const bool touches =
                a.isConeCorner(p, 0) || a.isConeCorner(p, 1) || a.isConeCorner(p, 2);
            QCOMPARE(touches, s.spline.conePatch[p] != 0);
            QVERIFY(!a.isConeCorner(p, 1) && !a.isConeCorner(p, 2));
            if (a.isConeCorner(p, 0))
                QVERIFY(p % 12 < 6);
        }
    }

    void loopAcrossCutEdges() {
        const Surface s = fitted(cubeLayout(2, 3));
        const auto phi = nodeFunction(
            s, [](const Vec3& x) { return x.z() - 0.3 + 0.05 * x.x() + 0.02 * x.y(); });
        for (unsigned seed : {1u, 2u, 3u}) {
            const Marching m = marchNodeFunction(s, phi, seed, 2e-10);
            QCOMPARE(m.degenerate, 0);
            const ContourChaining c = chainContours(m.segments, s.adjacency, s.spline);
            QCOMPARE(c.unmatchedEnds, Index(0));
            QCOMPARE(c.closedLoops, Index(1));
            QCOMPARE(c.openChains, Index(0));
            QCOMPARE(Index(c.chains.size()), Index(1));
            QCOMPARE(c.looseJoins, Index(0));
            QCOMPARE(c.sideJoins, Index(m.segments.size()));
            QVERIFY(c.maxJoinGap <= 4e-10);
            checkChains(s, m.segments, c, 1e-8);
            const auto crossed = crossedSides(s, m.segments, c);
            // Around the four vertical cube edges, twice each (2 x 2 grid).
            QCOMPARE(crossed.at(PatchSideKind::CutEdge), 4);
            QVERIFY(crossed.at(PatchSideKind::MeshEdge) > 0);
            QVERIFY(crossed.at(PatchSideKind::MacroPatch) > 0);
        }
    }

    void loopThroughPatchCorners() {
        // A plane through one node of every kind: the contour passes through
        // the patch corner and the chain continues in another patch there.
        const Surface s = fitted(cubeLayout(2, 5));
        const PatchAdjacency& a = s.adjacency;
        std::map<std::string, Index> picks;
        for (Index node = 0; node < a.nodeCount(); ++node) {
            if (a.isConeNode(node))
                continue;
            std::string key = toString(a.nodeKind(node));
            if (a.nodeKind(node) == PatchNodeKind::EdgeMidpoint)
                key += s.layout.cutEdge[a.nodeElement(node)] ? " (cut)" : " (uncut)";
            picks.emplace(key, node);
        }
        QCOMPARE(picks.size(), std::size_t(5));
        std::mt19937 rng(11);
        std::normal_distribution<double> g;
        for (const auto& [key, node] : picks) {
            const Vec3 x0 = nodePosition(s, node);
            const Vec3 normal = Vec3(g(rng), g(rng), g(rng)).normalized();
            auto phi = nodeFunction(s, [&](const Vec3& x) { return normal.dot(x - x0); });
            phi[node] = 0.0;
            for (unsigned seed : {1u, 2u}) {
                const Marching m = marchNodeFunction(s, phi, seed);
                QCOMPARE(m.degenerate, 0);
                const ContourChaining c = chainContours(m.segments, s.adjacency, s.spline);
                QVERIFY2(c.unmatchedEnds == 0,
                         qPrintable(QString::fromStdString(key + ": " + c.firstUnmatched)));
                QCOMPARE(c.closedLoops, Index(1));
                QCOMPARE(c.openChains, Index(0));
                QVERIFY2(c.cornerJoins >= 1, key.c_str());
                QVERIFY(c.maxCornerTangentCosine < 0.0);
                checkChains(s, m.segments, c, 1e-8);
            }
        }
    }

    void cornerEndsOffByMoreThanThePadding() {
        // An end near a corner but beyond the padding still joins there
        // (counted as loose), and a side join beyond the padding too.
        const Surface s = fitted(cubeLayout(2, 5));
        const Index node = 5 + s.layout.mesh.vertexCount(); // an edge midpoint
        const Vec3 x0 = nodePosition(s, node);
        auto phi = nodeFunction(
            s, [&](const Vec3& x) { return Vec3(0.3, -0.8, 0.5).normalized().dot(x - x0); });
        phi[node] = 0.0;
        Marching m = marchNodeFunction(s, phi, 4);
        QCOMPARE(m.degenerate, 0);
        int moved = 0;
        for (ContourSegment& seg : m.segments) {
            if (moved > 0)
                break;
            const auto& d = s.spline.patches[seg.patch].domain;
            for (int end = 0; end < 2 && moved == 0; ++end) {
                const Vec2 x = curveAt(seg, end == 0 ? seg.t0 : seg.t1);
                const int side = end == 0 ? seg.startSide : seg.endSide;
                for (int c = 0; c < 3 && moved == 0; ++c) {
                    if ((x - d[c]).norm() >= 1e-12)
                        continue;
                    // Move the corner end 5e-8 along its side (from corner c).
                    const int toward = side == c ? (side + 1) % 3 : side;
                    const Vec2 p = d[c] + 5e-8 * (d[toward] - d[c]);
                    const Vec2 other = curveAt(seg, end == 0 ? seg.t1 : seg.t0);
                    const int otherSide = end == 0 ? seg.endSide : seg.startSide;
                    seg = segmentBetween(seg.patch, p, side, other, otherSide, 0, false);
                    ++moved;
                }
            }
        }
        QCOMPARE(moved, 1);
        const ContourChaining c = chainContours(m.segments, s.adjacency, s.spline);
        QCOMPARE(c.unmatchedEnds, Index(0));
        QCOMPARE(c.closedLoops, Index(1));
        QVERIFY(c.cornerJoins >= 1);
        checkChains(s, m.segments, c, 1e-6);
        // With the loose tolerance at the padding, that end is an error.
        ContourChainOptions strict;
        strict.looseTolerance = strict.padding;
        const ContourChaining e = chainContours(m.segments, s.adjacency, s.spline, strict);
        QVERIFY(e.unmatchedEnds >= 1);
        QVERIFY(!e.firstUnmatched.empty());
    }

    void unmatchedEndsAreReported() {
        const Surface s = fitted(cubeLayout(2, 3));
        const auto phi = nodeFunction(
            s, [](const Vec3& x) { return x.z() - 0.3 + 0.05 * x.x() + 0.02 * x.y(); });
        const Marching m = marchNodeFunction(s, phi, 9);
        // A missing segment: the chain is open at two unmatched ends.
        std::vector<ContourSegment> missing = m.segments;
        missing.erase(missing.begin() + 3);
        const ContourChaining c = chainContours(missing, s.adjacency, s.spline);
        QCOMPARE(c.unmatchedEnds, Index(2));
        QVERIFY(c.firstUnmatched.find("nothing on side") != std::string::npos);
        QCOMPARE(c.closedLoops, Index(0));
        QCOMPARE(c.openChains, Index(1));
        QCOMPARE(c.chains[0].front.kind, ChainEndKind::Unmatched);
        QCOMPARE(c.chains[0].back.kind, ChainEndKind::Unmatched);
        QCOMPARE(c.coneEnds + c.boundaryEnds, Index(0));
        checkChains(s, missing, c, 1e-8);
        // An end moved along its side by 1e-8: joined, counted as loose; by
        // 1e-4: two unmatched ends.
        for (double shift : {1e-8, 1e-4}) {
            std::vector<ContourSegment> moved = m.segments;
            ContourSegment& seg = moved[5];
            QVERIFY(seg.startSide >= 0);
            const auto& d = s.spline.patches[seg.patch].domain;
            const int side = seg.startSide;
            const double t = sideParameter(d, side, curveAt(seg, seg.t0)) + shift;
            seg = segmentBetween(seg.patch, d[side] + t * (d[(side + 1) % 3] - d[side]), side,
                                 curveAt(seg, seg.t1), seg.endSide, 0, false);
            const ContourChaining r = chainContours(moved, s.adjacency, s.spline);
            if (shift < 1e-6) {
                QCOMPARE(r.unmatchedEnds, Index(0));
                QCOMPARE(r.looseJoins, Index(1));
                QCOMPARE(r.closedLoops, Index(1));
                QVERIFY(std::abs(r.maxJoinGap - shift) < 1e-12);
            } else {
                QCOMPARE(r.unmatchedEnds, Index(2));
                QCOMPARE(r.openChains, Index(1));
            }
        }
    }

    void ellipseHalvesInsideAPatch() {
        // A closed contour inside one patch comes as two halves whose ends
        // are inside the domain; next to the cube's loop.
        const Surface s = fitted(cubeLayout(2, 3));
        const auto phi = nodeFunction(
            s, [](const Vec3& x) { return x.z() - 0.3 + 0.05 * x.x() + 0.02 * x.y(); });
        std::vector<ContourSegment> segments = marchNodeFunction(s, phi, 2).segments;
        const Index patch = 77;
        const auto& d = s.spline.patches[patch].domain;
        const Vec2 centre = (d[0] + d[1] + d[2]) / 3.0;
        const double k = 0.05 * (d[1] - d[0]).norm();
        for (int half = 0; half < 2; ++half) {
            // z(t) = +-k [(1 - t^2), 2t] / (1 + t^2), t in [-1, 1].
            const double sign = half == 0 ? 1.0 : -1.0;
            ContourSegment e;
            e.patch = patch;
            e.kind = ConicKind::Ellipse;
            e.curve.coefficients << centre.x() + sign * k, 2.0 * 0.0, centre.x() - sign * k,
                centre.y(), sign * 2.0 * k, centre.y(), 1.0, 0.0, 1.0;
            e.t0 = -1.0;
            e.t1 = 1.0;
            segments.push_back(e);
        }
        const ContourChaining c = chainContours(segments, s.adjacency, s.spline);
        QCOMPARE(c.unmatchedEnds, Index(0));
        QCOMPARE(c.closedLoops, Index(2));
        QCOMPARE(c.interiorJoins, Index(2));
        checkChains(s, segments, c, 1e-8);
        bool found = false;
        for (const ContourChain& chain : c.chains)
            if (chain.links.size() == 2 && chain.links[0].segment + 2 == Index(segments.size()))
                found = true;
        QVERIFY(found);
    }

    void conesEndChains() {
        const Surface s = fitted(cubeLayout(3, 5));
        const PatchAdjacency& a = s.adjacency;
        Index cone = kInvalidIndex;
        for (Index v = 0; v < s.layout.mesh.vertexCount(); ++v)
            if ((s.layout.mesh.position(v) - Vec3(1, 1, 1)).norm() < 1e-12)
                cone = v;
        QVERIFY(a.isConeNode(cone));
        const Vec3 x0 = nodePosition(s, cone);
        // One plane through the cone: one chain from the cone back to it.
        {
            auto phi = nodeFunction(s, [&](const Vec3& x) { return Vec3(1, -1, 0.3).dot(x - x0); });
            phi[cone] = 0.0;
            const Marching m = marchNodeFunction(s, phi, 3);
            QCOMPARE(m.degenerate, 0);
            const ContourChaining c = chainContours(m.segments, a, s.spline);
            QCOMPARE(c.unmatchedEnds, Index(0));
            QCOMPARE(c.closedLoops, Index(0));
            QCOMPARE(c.openChains, Index(1));
            QCOMPARE(c.coneEnds, Index(2));
            QCOMPARE(c.chains[0].front.node, cone);
            QCOMPARE(c.chains[0].back.node, cone);
            checkChains(s, m.segments, c, 1e-8);
        }
        // Two planes through the cone that meet the cube only there: two
        // loops that share the cone point, four chain ends at it.
        {
            // Both contain the line through the corner along (1, -2, 1),
            // which meets the cube only there.
            auto plane = [&](const Vec3& normal) {
                return [normal, x0](const Vec3& x) {
                    return normal.dot(x - x0);
                };
            };
            const auto p1 = plane(Vec3(2, -1, -4)), p2 = plane(Vec3(2, 0.7, -0.6));
            auto phi = nodeFunction(s, [&](const Vec3& x) { return p1(x) * p2(x); });
            phi[cone] = 0.0;
            const Marching m = marchNodeFunction(s, phi, 8);
            QCOMPARE(m.degenerate, 0);
            const ContourChaining c = chainContours(m.segments, a, s.spline);
            QVERIFY2(c.unmatchedEnds == 0, c.firstUnmatched.c_str());
            QCOMPARE(c.closedLoops, Index(0));
            QCOMPARE(c.openChains, Index(2));
            QCOMPARE(c.coneEnds, Index(4));
            for (const ContourChain& chain : c.chains) {
                QCOMPARE(chain.front.kind, ChainEndKind::Cone);
                QCOMPARE(chain.front.node, cone);
                QCOMPARE(chain.back.node, cone);
            }
            checkChains(s, m.segments, c, 1e-8);
        }
    }

    void boundaryEndsChains() {
        const Surface s = fitted(squareLayout());
        auto phi = nodeFunction(s, [](const Vec3& x) { return x.x() - 0.37 + 0.1 * x.y(); });
        const Marching m = marchNodeFunction(s, phi, 1);
        QCOMPARE(m.degenerate, 0);
        const ContourChaining c = chainContours(m.segments, s.adjacency, s.spline);
        QCOMPARE(c.unmatchedEnds, Index(0));
        QCOMPARE(c.openChains, Index(1));
        QCOMPARE(c.boundaryEnds, Index(2));
        QCOMPARE(c.chains[0].front.kind, ChainEndKind::Boundary);
        QVERIFY(c.chains[0].front.side >= 0);
        checkChains(s, m.segments, c, 1e-12);
        // Through a boundary vertex: the chain ends there.
        phi = nodeFunction(s, [](const Vec3& x) { return x.x() - x.y() * 0.8; });
        phi[0] = 0.0;
        const Marching v = marchNodeFunction(s, phi, 2);
        const ContourChaining b = chainContours(v.segments, s.adjacency, s.spline);
        QCOMPARE(b.unmatchedEnds, Index(0));
        QCOMPARE(b.openChains, Index(1));
        QCOMPARE(b.boundaryEnds, Index(2));
        const bool atVertex = b.chains[0].front.node == 0 || b.chains[0].back.node == 0;
        QVERIFY(atVertex);
    }

    void badInputThrows() {
        const Surface s = fitted(squareLayout());
        ContourSegment seg = segmentBetween(3, Vec2(0.1, 0.01), 0, Vec2(0.1, 0.02), 1, 0, false);
        auto chain = [&](const ContourSegment& x, const ContourChainOptions& o = {}) {
            const std::vector<ContourSegment> v = {x};
            return chainContours(v, s.adjacency, s.spline, o);
        };
        ContourSegment bad = seg;
        bad.patch = 24;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chain(bad));
        bad = seg;
        bad.t1 = bad.t0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chain(bad));
        bad = seg;
        bad.endSide = 3;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chain(bad));
        bad = seg;
        bad.curve.coefficients(2, 0) = 0.0; // W(t0) = 0
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chain(bad));
        ContourChainOptions o;
        o.padding = 1e-3;
        o.looseTolerance = 1e-6;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chain(seg, o));
        const Surface cube = fitted(cubeLayout(1, 1));
        const std::vector<ContourSegment> v = {seg};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, chainContours(v, cube.adjacency, s.spline));
        // No segments: no chains.
        const ContourChaining none = chainContours({}, s.adjacency, s.spline);
        QVERIFY(none.chains.empty());
    }

    void sphereContourIsOneLoop() {
        // The fitted sphere under random orthographic views, with the
        // segments of patchContours and those of the independent side-root
        // extraction: one closed loop, or, when the contour runs through
        // cones (there tau . n is a form centred at the cone, §5.2, and the
        // contour is lines through it when the form is indefinite), open
        // chains from cone to cone that close up into one cycle through them.
        const SphereSetup setup = sphereSetup();
        std::mt19937 rng(2024);
        std::normal_distribution<double> g;
        constexpr int kViews = 40;
        int viewsWithoutCones = 0, fourCrossings = 0, patchSegments = 0, sameTopology = 0;
        Index cornerJoins = 0;
        double maxGap = 0.0, maxCosine = -2.0;
        std::map<Index, int> coneEndHistogram;
        for (int view = 0; view < kViews; ++view) {
            const Eigen::Quaterniond q =
                Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
            std::vector<Vec3> targets;
            for (const Vec3& x : setup.layout.mesh.positions())
                targets.push_back(q * x);
            Surface s;
            s.layout = setup.layout;
            s.spline = setup.fit->fit(targets);
            s.adjacency = PatchAdjacency(s.layout, s.spline);
            const Vec3 tau(0, 0, 1);

            const Marching m = sideRootSegments(s, tau, unsigned(view));
            QCOMPARE(m.degenerate, 0);
            fourCrossings += m.fourCrossings;
            QVERIFY(m.segments.size() > 20);
            const ContourChaining own = chainContours(m.segments, s.adjacency, s.spline);
            checkSphereChains(s, m.segments, own);
            if (QTest::currentTestFailed())
                return;

            std::vector<ContourSegment> segments;
            for (Index p = 0; p < s.adjacency.patchCount(); ++p)
                for (const ContourSegment& seg : patchContours(s.spline.patches[p], p, tau))
                    segments.push_back(seg);
            patchSegments += static_cast<int>(segments.size());
            const ContourChaining c = chainContours(segments, s.adjacency, s.spline);
            checkSphereChains(s, segments, c);
            if (QTest::currentTestFailed()) {
                qWarning("view %d, patchContours segments", view);
                return;
            }
            sameTopology += c.closedLoops == own.closedLoops && c.openChains == own.openChains &&
                            c.coneEnds == own.coneEnds;
            viewsWithoutCones += c.openChains == 0;
            cornerJoins += c.cornerJoins;
            maxGap = std::max(maxGap, c.maxJoinGap);
            maxCosine = std::max(maxCosine, c.maxCornerTangentCosine);
            ++coneEndHistogram[c.coneEnds];
        }
        QString histogram;
        for (const auto& [ends, views] : coneEndHistogram)
            histogram += QString(" %1 cones: %2 views;").arg(ends / 2).arg(views);
        qInfo("%d views; contour through k cones (chain ends / 2):%s patches crossed twice "
              "(side roots): %d; patchContours segments: %d, largest join gap %.3g, corner "
              "joins %d (largest tangent cosine %.3g); same topology from both: %d",
              kViews, qPrintable(histogram), fourCrossings, patchSegments, maxGap, int(cornerJoins),
              maxCosine, sameTopology);
        QCOMPARE(sameTopology, kViews);
        QVERIFY(viewsWithoutCones > 0);
    }
};

QTEST_GUILESS_MAIN(TestPsContourChains)
#include "test_ps_contour_chains.moc"
