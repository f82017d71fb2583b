// The view graph of the fitted Powell-Sabin spline's contours
// (contours/powell_sabin/SplineViewGraph.h; Capouellez et al. 2023 §4.2) on
// splines built through the method's pipeline (cones, refinement, conformal
// map, layout, thin-plate fit to the perspective-transformed vertices).
// Checked against two oracles that share no code with the contour, cusp and
// ray modules: the QI of every chain's ray point by counting the sheets of a
// dense piecewise-linear sampling of every patch in front of it, and the
// number of contour loops and cusps from the sign changes of tau . n and of
// the radial curvature II(tau, tau) on a fine lattice of every patch.
#include "contours/powell_sabin/ConeSelection.h"
#include "contours/powell_sabin/ConformalMap.h"
#include "contours/powell_sabin/SplineViewGraph.h"
#include "contours/powell_sabin/ThinPlateFit.h"
#include "core/UnionFind.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <QtTest>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <unordered_map>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

// The mesh through the paper's pipeline; the fit is redone per view.
struct Setup {
    ConeLayout layout;
    std::unique_ptr<ThinPlateFit> fit;
};

Setup setupOf(const TriangleMesh& mesh) {
    const Cones cones = selectCones(mesh);
    const ConeRefinement refined = refineAroundCones(mesh, cones.vertices);
    const ConformalMap map = computeConformalMap(refined.mesh, refined.cones);
    Setup s;
    s.layout = layoutConformalMap(refined.mesh.positions(), map, refined.cones);
    s.fit = std::make_unique<ThinPlateFit>(s.layout);
    return s;
}

Camera cameraAt(const Vec3& eye, const Vec3& up) {
    Camera c;
    c.projection = Projection::Perspective;
    c.eye = eye;
    c.target = Vec3::Zero();
    c.up = up;
    c.fovYDegrees = 30.0;
    c.viewport = {800, 600};
    return c;
}

struct View {
    Camera camera;
    std::unique_ptr<ProjectiveTransform> transform;
    PowellSabinSpline spline;
    std::vector<ContourSegment> segments;
    ContourChaining chaining;
    SplineViewGraph result;
    double secondsFit = 0.0, secondsContours = 0.0;
};

View viewOf(const Setup& setup, const Camera& camera, const SplineViewGraphOptions& options = {}) {
    using Clock = std::chrono::steady_clock;
    View v;
    v.camera = camera;
    v.transform = std::make_unique<ProjectiveTransform>(camera);
    Clock::time_point t = Clock::now();
    std::vector<Vec3> targets;
    for (const Vec3& x : setup.layout.mesh.positions())
        targets.push_back(v.transform->apply(x));
    v.spline = setup.fit->fit(targets);
    v.secondsFit = std::chrono::duration<double>(Clock::now() - t).count();
    t = Clock::now();
    const PatchAdjacency adjacency(setup.layout, v.spline);
    const Vec3 tau(0, 0, 1);
    for (Index p = 0; p < static_cast<Index>(v.spline.patches.size()); ++p)
        for (const ContourSegment& s : patchContours(v.spline.patches[p], p, tau))
            v.segments.push_back(s);
    v.chaining = chainContours(v.segments, adjacency, v.spline);
    v.secondsContours = std::chrono::duration<double>(Clock::now() - t).count();
    v.result =
        buildSplineViewGraph(v.spline, v.segments, v.chaining, camera, *v.transform, options);
    return v;
}

Vec3 lattice(int i, int j, int n) {
    const double a = double(i) / n, b = double(j) / n;
    return Vec3(1.0 - a - b, a, b);
}

// Oracle 1: the sheets of the spline in front of transformed point x, from
// a dense triangulation of every patch whose control points' box contains
// x's image (a patch lies in their convex hull). Hits within `margin` times
// the patch's size of x's depth are x's own sheet (the flat triangles miss
// the fold by about that much) and are not counted.
int oracleQi(const PowellSabinSpline& spline, const Vec3& x, int n, double margin) {
    int count = 0;
    for (Index p = 0; p < static_cast<Index>(spline.patches.size()); ++p) {
        const QuadraticBezier<Vec3>& patch = spline.patches[p];
        Eigen::AlignedBox3d box;
        for (const Vec3& c : patch.control)
            box.extend(c);
        if (x.x() < box.min().x() || x.x() > box.max().x() || x.y() < box.min().y() ||
            x.y() > box.max().y())
            continue;
        const double size = box.diagonal().norm();
        std::vector<Vec3> pts;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i + j <= n; ++i)
                pts.push_back(spline.position(p, lattice(i, j, n)));
        auto at = [&](int i, int j) {
            return pts[j * (n + 1) - j * (j - 1) / 2 + i];
        };
        auto test = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
            const Vec2 e1 = (b - a).head<2>(), e2 = (c - a).head<2>(), d = (x - a).head<2>();
            const double det = e1.x() * e2.y() - e1.y() * e2.x();
            if (det == 0.0)
                return;
            const double u = (d.x() * e2.y() - d.y() * e2.x()) / det;
            const double w = (e1.x() * d.y() - e1.y() * d.x()) / det;
            if (u < 0.0 || w < 0.0 || u + w > 1.0)
                return;
            const double z = a.z() + u * (b.z() - a.z()) + w * (c.z() - a.z());
            count += z < x.z() - margin * size;
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i + j < n; ++i) {
                test(at(i, j), at(i + 1, j), at(i, j + 1));
                if (i + j + 1 < n)
                    test(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
    }
    return count;
}

// Oracle 2: the zero set of tau . n^ by marching triangles on an n-lattice
// of every patch, its loops, and along each loop the sign changes of the
// radial curvature II(tau, tau) (zero at the contour's cusps), evaluated in
// the patch that holds each piece, so that a jump across a patch side counts
// as well (a boundary cusp).
struct LatticeContour {
    int loops = 0;
    int signChanges = 0;
    int brokenPieces = 0; // crossing points of degree != 2
};

LatticeContour latticeContour(const PowellSabinSpline& spline, int n) {
    Eigen::AlignedBox3d all;
    for (const auto& patch : spline.patches)
        for (const Vec3& c : patch.control)
            all.extend(c);
    // Lattice points on shared patch sides agree up to round-off: a point
    // within q of a known one (looked up in the neighbouring cells) is it.
    const double q = 1e-8 * all.diagonal().norm();
    auto key = [&](const Vec3& x, int dx, int dy, int dz) {
        return std::array<long long, 3>{static_cast<long long>(std::floor(x.x() / q)) + dx,
                                        static_cast<long long>(std::floor(x.y() / q)) + dy,
                                        static_cast<long long>(std::floor(x.z() / q)) + dz};
    };
    std::map<std::array<long long, 3>, std::vector<std::pair<Vec3, int>>> cells;
    int vertices = 0;
    auto vid = [&](const Vec3& x) {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = cells.find(key(x, dx, dy, dz));
                    if (it == cells.end())
                        continue;
                    for (const auto& [y, id] : it->second)
                        if ((x - y).norm() <= q)
                            return id;
                }
        cells[key(x, 0, 0, 0)].push_back({x, vertices});
        return vertices++;
    };
    // Crossing points by lattice edge; pieces as (point, point, g, g).
    std::map<std::pair<int, int>, int> pointOf;
    struct Piece {
        int a, b;
        double ga, gb;
    };
    std::vector<Piece> pieces;
    const Vec3 tau(0, 0, 1);
    // |p_u| |p_v| below this (relative to the patches' typical size) is a cone.
    double typical = 0.0;
    for (Index p = 0; p < static_cast<Index>(spline.patches.size()); ++p) {
        Vec3 du, dv;
        spline.derivatives(p, Vec3::Constant(1.0 / 3.0), du, dv);
        typical += du.norm() * dv.norm() / static_cast<double>(spline.patches.size());
    }
    const double coneSize = 1e-12 * typical;
    for (Index p = 0; p < static_cast<Index>(spline.patches.size()); ++p) {
        const QuadraticBezier<Vec3>& patch = spline.patches[p];
        Vec3 duu, duv, dvv;
        uvSecondDerivatives(patch, duu, duv, dvv);
        struct Sample {
            int id;
            double f, g;
        };
        std::vector<Sample> s;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i + j <= n; ++i) {
                Vec3 b = lattice(i, j, n);
                Vec3 du, dv;
                spline.derivatives(p, b, du, dv);
                if (du.norm() * dv.norm() <= coneSize) {
                    // A cone: the sign of tau . n^ next to it, inside the
                    // patch (a cone off the contour is not an island).
                    b = 0.999 * b + Vec3::Constant(0.001 / 3.0);
                    spline.derivatives(p, b, du, dv);
                }
                const Vec3 nn = du.cross(dv);
                const double len = nn.norm();
                // At a cone both derivatives vanish (§5.2): only round-off
                // is left of the normal there, so it counts as zero.
                const double size = du.norm() * dv.norm();
                const Vec3 nh =
                    len > 1e-9 * size && size > coneSize ? Vec3(nn / len) : Vec3::Zero();
                const Vec3 tp = tau - tau.dot(nh) * nh;
                Eigen::Matrix<double, 3, 2> J;
                J << du, dv;
                const Vec2 w = J.colPivHouseholderQr().solve(tp);
                const Vec3 second =
                    w.x() * w.x() * duu + 2.0 * w.x() * w.y() * duv + w.y() * w.y() * dvv;
                s.push_back(
                    {vid(spline.position(p, lattice(i, j, n))), nh.dot(tau), nh.dot(second)});
            }
        auto at = [&](int i, int j) -> const Sample& {
            return s[static_cast<size_t>(j * (n + 1) - j * (j - 1) / 2 + i)];
        };
        auto tri = [&](const Sample& a, const Sample& b, const Sample& c) {
            std::array<const Sample*, 3> v = {&a, &b, &c};
            std::vector<std::pair<int, double>> cross;
            for (int e = 0; e < 3; ++e) {
                const Sample& x = *v[e];
                const Sample& y = *v[(e + 1) % 3];
                if ((x.f >= 0.0) == (y.f >= 0.0))
                    continue;
                const std::pair<int, int> edge = std::minmax(x.id, y.id);
                const int id =
                    pointOf.emplace(edge, static_cast<int>(pointOf.size())).first->second;
                const double lambda = x.f / (x.f - y.f);
                cross.push_back({id, x.g + lambda * (y.g - x.g)});
            }
            if (cross.size() == 2)
                pieces.push_back(
                    {cross[0].first, cross[1].first, cross[0].second, cross[1].second});
        };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i + j < n; ++i) {
                tri(at(i, j), at(i + 1, j), at(i, j + 1));
                if (i + j + 1 < n)
                    tri(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
    }
    LatticeContour out;
    const int points = static_cast<int>(pointOf.size());
    std::vector<std::vector<int>> incident(static_cast<size_t>(points));
    for (int k = 0; k < static_cast<int>(pieces.size()); ++k) {
        incident[pieces[k].a].push_back(k);
        incident[pieces[k].b].push_back(k);
    }
    for (const auto& inc : incident)
        out.brokenPieces += inc.size() != 2;

    std::vector<char> used(pieces.size(), 0);
    for (int start = 0; start < static_cast<int>(pieces.size()); ++start) {
        if (used[start])
            continue;
        ++out.loops;
        // Walk the loop: g values in order along it.
        std::vector<double> g;
        int piece = start, from = pieces[start].a;
        while (piece >= 0 && !used[piece]) {
            used[piece] = 1;
            const Piece& pc = pieces[piece];
            const bool forward = pc.a == from;
            g.push_back(forward ? pc.ga : pc.gb);
            g.push_back(forward ? pc.gb : pc.ga);
            const int to = forward ? pc.b : pc.a;
            int nextPiece = -1;
            for (int k : incident[to])
                if (!used[k])
                    nextPiece = k;
            from = to;
            piece = nextPiece;
        }
        for (size_t k = 0; k < g.size(); ++k)
            out.signChanges += (g[k] > 0.0) != (g[(k + 1) % g.size()] > 0.0);
    }
    return out;
}

// The chains as edges between their nodes: one cycle (a closed chain alone,
// or open chains through nodes of even degree, all connected).
bool isOneCycle(const ViewGraph& g) {
    if (g.chains.size() == 1 && g.chains[0].closed)
        return true;
    UnionFind uf(g.nodes.size());
    for (const ViewChain& c : g.chains) {
        if (c.closed)
            return false;
        uf.unite(c.startNode, c.endNode);
    }
    std::set<Index> roots;
    for (Index v = 0; v < static_cast<Index>(g.nodes.size()); ++v) {
        if (g.nodes[v].chains.size() % 2 != 0)
            return false;
        roots.insert(uf.find(v));
    }
    return roots.size() == 1;
}

// Structural invariants every graph must satisfy.
void checkStructure(const View& v) {
    const ViewGraph& g = v.result.graph;
    QCOMPARE(v.chaining.unmatchedEnds, Index(0));
    QCOMPARE(v.result.samples.size(), g.chains.size());
    for (Index c = 0; c < static_cast<Index>(g.chains.size()); ++c) {
        const ViewChain& chain = g.chains[c];
        QVERIFY(chain.points.size() >= 3);
        QCOMPARE(chain.image.size(), chain.points.size());
        QCOMPARE(chain.depth.size(), chain.points.size());
        QCOMPARE(chain.segmentElement.size(), chain.points.size() - 1);
        // A ray on every chain of a pixel or more (SplineViewGraphOptions::
        // minRayChainPixels); shorter ones may take their QI by propagation.
        QVERIFY(chain.qi >= 0);
        if (chain.decidedBy == VisibilityRule::RayTest) {
            QCOMPARE(chain.rayQi, chain.qi);
            QVERIFY(v.result.raySample[c] != kInvalidIndex);
        } else {
            QCOMPARE(chain.decidedBy, VisibilityRule::Propagation);
            QVERIFY(!chain.closed && chain.lengthPixels < 1.0);
            QVERIFY(chain.propagatedFrom != kInvalidIndex && chain.propagatedVia != kInvalidIndex);
            QCOMPARE(v.result.raySample[c], kInvalidIndex);
        }
        // Points are world points that project to the stored pixels, and
        // the spline point of the stored (segment, t).
        for (size_t i = 0; i < chain.points.size(); i += 7) {
            const ProjectedPoint p = v.camera.project(chain.points[i]);
            QVERIFY((p.pixel - chain.image[i]).norm() < 1e-6);
            QVERIFY(std::abs(p.depth - chain.depth[i]) < 1e-9);
            const SplineSampleRef& r = v.result.samples[c][i];
            const ContourSegment& seg = v.segments[r.segment];
            const Vec3 x = v.spline.position(
                seg.patch, barycentricOf(v.spline.patches[seg.patch].domain, seg.curve.at(r.t)));
            QVERIFY((v.transform->invert(x) - chain.points[i]).norm() < 1e-9);
        }
        if (chain.closed) {
            QVERIFY(chain.startNode == kInvalidIndex && chain.endNode == kInvalidIndex);
            QVERIFY((chain.image.front() - chain.image.back()).norm() < 1e-3);
        } else {
            QVERIFY(chain.startNode >= 0 && chain.endNode >= 0);
            QVERIFY((g.nodes[chain.startNode].image - chain.image.front()).norm() < 1e-3);
        }
    }
    // Chord error: the curve between two samples stays near the chord.
    const ViewChain& first = g.chains.front();
    for (size_t i = 0; i + 1 < first.points.size(); ++i) {
        const SplineSampleRef& a = v.result.samples[0][i];
        const SplineSampleRef& b = v.result.samples[0][i + 1];
        if (a.segment != b.segment)
            continue;
        const ContourSegment& seg = v.segments[a.segment];
        const Vec3 x =
            v.spline.position(seg.patch, barycentricOf(v.spline.patches[seg.patch].domain,
                                                       seg.curve.at(0.5 * (a.t + b.t))));
        const Vec2 m = v.camera.project(v.transform->invert(x)).pixel;
        const Vec2 pa = first.image[i], d = first.image[i + 1] - pa;
        const double lambda = std::clamp((m - pa).dot(d) / d.squaredNorm(), 0.0, 1.0);
        QVERIFY((m - pa - lambda * d).norm() <= 0.25 + 1e-9);
    }
    long long listed = 0;
    for (const ViewNode& n : g.nodes)
        listed += static_cast<long long>(n.chains.size());
    long long ends = 0;
    for (const ViewChain& c : g.chains)
        ends += c.closed ? 0 : 2;
    QCOMPARE(listed, ends);
}

} // namespace

class TestPsViewGraph : public QObject {
    Q_OBJECT
private slots:
    void convexShapesHaveOneVisibleLoop() {
        // Sphere and ellipsoid from random perspective views: one loop, all
        // visible, without cusps, T-junctions or conflicts.
        const std::array<TriangleMesh, 2> meshes = {
            makeSphere(1.0, 10).triangulate(),
            makeEllipsoid(Vec3(1.3, 1.0, 0.7), 14).triangulate()};
        std::mt19937 rng(7);
        std::normal_distribution<double> gauss;
        int viewsWithoutCones = 0, loopChecks = 0;
        for (size_t m = 0; m < meshes.size(); ++m) {
            const Setup setup = setupOf(meshes[m]);
            for (int k = 0; k < 6; ++k) {
                const Vec3 dir = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
                const Vec3 up = std::abs(dir.z()) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
                const View v = viewOf(setup, cameraAt(5.0 * dir, up));
                checkStructure(v);
                if (QTest::currentTestFailed())
                    return;
                const ViewGraph& g = v.result.graph;
                const SplineViewGraphStats& st = v.result.stats;
                QCOMPARE(st.interiorCusps + st.boundaryCusps, Index(0));
                QCOMPARE(st.tJunctions, Index(0));
                QCOMPARE(g.conflicts.size(), size_t(0));
                for (const ViewChain& c : g.chains)
                    QCOMPARE(c.qi, 0);
                QVERIFY(isOneCycle(g));
                QVERIFY(g.rayTests <= static_cast<long long>(g.chains.size()));
                if (st.conePoints == 0) {
                    ++viewsWithoutCones;
                    QCOMPARE(st.loops, Index(1));
                    // The lattice oracle (cones make its loop count ambiguous).
                    const LatticeContour oracle = latticeContour(v.spline, 8);
                    QCOMPARE(oracle.brokenPieces, 0);
                    QCOMPARE(oracle.loops, 1);
                    QCOMPARE(oracle.signChanges, 0);
                    ++loopChecks;
                }
            }
        }
        qInfo("convex shapes: %d of 12 views without cones, %d lattice checks", viewsWithoutCones,
              loopChecks);
    }

    void torusFromGrazingViews() {
        // The torus seen at a grazing angle: the inner contour has cusps
        // and passes behind the outer one.
        const Setup setup = setupOf(makeTorus(2.0, 0.7, 16).triangulate());
        int totalCusps = 0, totalT = 0, chainsChecked = 0, chainsSkipped = 0,
            oracleDisagreements = 0;
        for (double elevation : {10.0, 15.0, 20.0}) {
            const double a = elevation * M_PI / 180.0, az = 0.3 + elevation / 40.0;
            const Vec3 dir(std::cos(a) * std::cos(az), std::cos(a) * std::sin(az), std::sin(a));
            const View v = viewOf(setup, cameraAt(9.0 * dir, Vec3(0, 0, 1)));
            checkStructure(v);
            if (QTest::currentTestFailed())
                return;
            const ViewGraph& g = v.result.graph;
            const SplineViewGraphStats& st = v.result.stats;
            const Index cusps = st.interiorCusps + st.boundaryCusps;
            QVERIFY(cusps > 0);
            QVERIFY(st.tJunctions > 0);
            if (cusps % 2 != 0 || !g.conflicts.empty()) {
                for (Index n = 0; n < static_cast<Index>(g.nodes.size()); ++n) {
                    const ViewNode& node = g.nodes[n];
                    const Vec3 x = v.transform->apply(node.position);
                    qWarning("node %d %s near %d,%d far %d,%d unreliable %d img %.1f %.1f at "
                             "(%.5f %.5f %.5f)",
                             int(n), toString(node.type), int(node.nearChains[0]),
                             int(node.nearChains[1]), int(node.farChains[0]),
                             int(node.farChains[1]), int(node.unreliable), node.image.x(),
                             node.image.y(), x.x(), x.y(), x.z());
                }
                for (Index c = 0; c < static_cast<Index>(g.chains.size()); ++c)
                    qWarning("chain %d: %d -> %d qi %d len %.1f curve %d", int(c),
                             int(g.chains[c].startNode), int(g.chains[c].endNode), g.chains[c].qi,
                             g.chains[c].lengthPixels, int(g.chains[c].curve));
                for (const VisibilityConflict& x : g.conflicts)
                    qWarning("conflict chain %d: %s", int(x.chain), x.reason.c_str());
                qWarning("unplaced %d degenerate %d", int(st.unplacedCusps),
                         int(st.degenerateCuspPatches));
            }
            QCOMPARE(cusps % 2, Index(0));
            QCOMPARE(st.conePoints, Index(0));
            totalCusps += cusps;
            totalT += st.tJunctions;
            for (Index n = 0; n < static_cast<Index>(g.nodes.size()); ++n) {
                const ViewNode& node = g.nodes[n];
                if (node.type == ViewNodeType::CurtainFold) {
                    QVERIFY(node.smoothCusp);
                    QCOMPARE(node.qiStep, 1);
                    QCOMPARE(g.chains[node.farChains[1]].qi - g.chains[node.nearChains[0]].qi, 1);
                } else if (node.type == ViewNodeType::ImageIntersection) {
                    QCOMPARE(node.qiStep, 2);
                    QCOMPARE(node.chains.size(), size_t(4));
                    QCOMPARE(g.chains[node.farChains[1]].qi - g.chains[node.farChains[0]].qi, 2);
                    QCOMPARE(g.chains[node.nearChains[0]].qi, g.chains[node.nearChains[1]].qi);
                }
            }
            QCOMPARE(g.conflicts.size(), size_t(0));
            // Every chain's QI against the dense depth oracle at its ray point,
            // except where the point is within a few pixels of a node: the
            // flat triangles cannot resolve the sub-pixel chains between a
            // cusp and a T-junction (the tip of an inner cusp just behind the
            // outer silhouette).
            for (Index c = 0; c < static_cast<Index>(g.chains.size()); ++c) {
                if (v.result.raySample[c] == kInvalidIndex) {
                    ++chainsSkipped; // a sub-pixel chain, propagated
                    continue;
                }
                const Vec2 at = g.chains[c].image[v.result.raySample[c]];
                double nearest = std::numeric_limits<double>::infinity();
                for (const ViewNode& node : g.nodes)
                    nearest = std::min(nearest, (node.image - at).norm());
                if (nearest < 3.0) {
                    ++chainsSkipped;
                    continue;
                }
                const SplineSampleRef& r = v.result.samples[c][v.result.raySample[c]];
                const ContourSegment& seg = v.segments[r.segment];
                const Vec3 x =
                    v.spline.position(seg.patch, barycentricOf(v.spline.patches[seg.patch].domain,
                                                               seg.curve.at(r.t)));
                const int oracle = oracleQi(v.spline, x, 24, 0.02);
                if (oracle != g.chains[c].qi) {
                    ++oracleDisagreements;
                    qWarning("elevation %g chain %d: ray QI %d, oracle %d, length %.1f px",
                             elevation, int(c), g.chains[c].qi, oracle, g.chains[c].lengthPixels);
                }
                ++chainsChecked;
            }
            // Loops and cusps against the lattice oracle.
            const LatticeContour oracle = latticeContour(v.spline, 8);
            QCOMPARE(oracle.brokenPieces, 0);
            QCOMPARE(static_cast<Index>(oracle.loops), v.chaining.closedLoops);
            QCOMPARE(static_cast<Index>(oracle.signChanges), cusps);
            qInfo("torus at %g deg: %d chains, %d loops, cusps %d + %d (lattice %d), %d "
                  "T-junctions, %lld rays, %.1f ms",
                  elevation, int(st.chains), int(v.chaining.closedLoops), int(st.interiorCusps),
                  int(st.boundaryCusps), oracle.signChanges, int(st.tJunctions), st.rays,
                  1e3 * st.secondsTotal);
        }
        QCOMPARE(oracleDisagreements, 0);
        QVERIFY(chainsChecked >= 10);
        qInfo("torus: %d cusps, %d T-junctions, %d chains against the depth oracle (%d within 3 "
              "px of a node skipped)",
              totalCusps, totalT, chainsChecked, chainsSkipped);
    }

    void tJunctionsAreCrossingsOfTheCurves() {
        // Two branches closer than the chord tolerance can have chords that
        // cross where the curves do not: such crossings are left out
        // (counted), and every T-junction lies on both curves. On spot's 26
        // views, accepting every chord crossing that Newton does not bring
        // onto both curves still puts none off the curves: there the far
        // curve does not change sides of the near one, and the crossing is
        // left out as a touching meeting.
        const TriangleMesh spot =
            readMesh(std::string(CONTOUR_SOURCE_DIR) + "/samples/spot_control_mesh.obj")
                .triangulate();
        const Setup setup = setupOf(spot);
        SplineViewGraphOptions everyChordCrossing;
        everyChordCrossing.crossingResidualPixels = 1e9;
        long long chordOnly = 0, offTheCurves = 0, tJunctions = 0, touching = 0;
        const auto apart = [](const Camera& c, const ViewNode& n) {
            return (c.project(n.position).pixel - c.project(n.nearPoint).pixel).norm();
        };
        for (const Camera& camera : Camera::views26(spot.boundingBox(), Viewport{800, 600})) {
            const View exact = viewOf(setup, camera);
            chordOnly += exact.result.stats.chordOnlyCrossings;
            for (const ViewNode& n : exact.result.graph.nodes)
                if (n.type == ViewNodeType::ImageIntersection) {
                    ++tJunctions;
                    QVERIFY2(apart(camera, n) <= 1e-5,
                             qPrintable(QString::number(apart(camera, n))));
                }
            const View loose = viewOf(setup, camera, everyChordCrossing);
            QCOMPARE(loose.result.stats.chordOnlyCrossings, Index(0));
            touching += loose.result.stats.touchingCrossings;
            for (const ViewNode& n : loose.result.graph.nodes)
                offTheCurves +=
                    n.type == ViewNodeType::ImageIntersection && apart(camera, n) > 1e-5;
        }
        qInfo("spot, 26 views: %lld T-junctions, %lld chord crossings left out; with every "
              "chord crossing past Newton, %lld T-junctions off the curves and %lld touching "
              "meetings left out",
              tJunctions, chordOnly, offTheCurves, touching);
        QVERIFY(chordOnly > 0);
        QCOMPARE(offTheCurves, 0LL);
        QVERIFY(touching > 0);
    }

    void badOptionsThrow() {
        const Setup setup = setupOf(makeSphere(1.0, 10).triangulate());
        SplineViewGraphOptions o;
        o.maxChordPixels = 0.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 viewOf(setup, cameraAt(Vec3(0, 0, 5), Vec3(0, 1, 0)), o));
        o = {};
        o.crossingResidualPixels = 0.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 viewOf(setup, cameraAt(Vec3(0, 0, 5), Vec3(0, 1, 0)), o));
        o = {};
        o.minRayChainPixels = -1.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 viewOf(setup, cameraAt(Vec3(0, 0, 5), Vec3(0, 1, 0)), o));
        o = {};
        o.initialPiecesPerSegment = 0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 viewOf(setup, cameraAt(Vec3(0, 0, 5), Vec3(0, 1, 0)), o));
        // A chaining naming a segment that does not exist.
        View v = viewOf(setup, cameraAt(Vec3(0, 0, 5), Vec3(0, 1, 0)));
        v.chaining.chains.front().links.front().segment = static_cast<Index>(v.segments.size());
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            buildSplineViewGraph(v.spline, v.segments, v.chaining, v.camera, *v.transform));
    }

    void timing() {
        // Per-view cost (reported, not asserted): fit, contours and chains,
        // then the view graph's steps.
        struct Model {
            const char* name;
            TriangleMesh mesh;
        };
        std::vector<Model> models;
        models.push_back({"sphere", makeSphere(1.0, 10).triangulate()});
        models.push_back({"torus", makeTorus(2.0, 0.7, 16).triangulate()});
        models.push_back(
            {"spot", readMesh(std::string(CONTOUR_SOURCE_DIR) + "/samples/spot_control_mesh.obj")
                         .triangulate()});
        for (const Model& m : models) {
            const Setup setup = setupOf(m.mesh);
            Eigen::AlignedBox3d box;
            for (const Vec3& x : setup.layout.mesh.positions())
                box.extend(x);
            const Vec3 centre = box.center();
            const double radius = 0.5 * box.diagonal().norm();
            for (const Vec3& d : {Vec3(0.3, -1.0, 0.4), Vec3(1.0, 0.5, 0.15)}) {
                Camera c = cameraAt(centre + 3.5 * radius * d.normalized(), Vec3(0, 0, 1));
                c.target = centre;
                const View v = viewOf(setup, c);
                const SplineViewGraphStats& s = v.result.stats;
                QCOMPARE(v.chaining.unmatchedEnds, Index(0));
                for (const VisibilityConflict& x : v.result.graph.conflicts) {
                    const ViewNode& node = v.result.graph.nodes[x.viaNode];
                    double toCone = std::numeric_limits<double>::infinity();
                    for (const ViewNode& other : v.result.graph.nodes)
                        if (other.type == ViewNodeType::Bifurcation)
                            toCone = std::min(toCone, (other.image - node.image).norm());
                    qInfo("  conflict node %.2f px from a cone point", toCone);
                    qInfo("  %s conflict: chain %d (%.1f px) ray QI %d, expected %d from chain %d "
                          "(%.1f px) via %s%s: %s",
                          m.name, int(x.chain), v.result.graph.chains[x.chain].lengthPixels,
                          x.rayQi, x.propagatedQi, int(x.fromChain),
                          v.result.graph.chains[x.fromChain].lengthPixels, toString(node.type),
                          node.unreliable ? " (unreliable)" : "", x.reason.c_str());
                }
                qInfo("%s (%zu patches): fit %.1f ms, contours+chains %.1f ms, view graph %.1f ms "
                      "(cusps %.1f, sampling %.1f, crossings %.1f, chains %.1f, rays %.1f); %d "
                      "chains, %d samples, cusps %d+%d, %d T (%d at a cone left out), %d cones, "
                      "%lld rays, %d conflicts",
                      m.name, v.spline.patches.size(), 1e3 * v.secondsFit, 1e3 * v.secondsContours,
                      1e3 * s.secondsTotal, 1e3 * s.secondsCusps, 1e3 * s.secondsSampling,
                      1e3 * s.secondsIntersections, 1e3 * s.secondsChains, 1e3 * s.secondsRays,
                      int(s.chains), int(s.samples), int(s.interiorCusps), int(s.boundaryCusps),
                      int(s.tJunctions), int(s.coneCrossings), int(s.conePoints), s.rays,
                      int(s.conflicts));
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestPsViewGraph)
#include "test_ps_view_graph.moc"
