// The dense oracle of the Powell-Sabin spline's contour (SplineGroundTruth.h).
#include "SplineGroundTruth.h"

#include "contours/powell_sabin/PowellSabinState.h"
#include "pipeline/ViewGraph.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

namespace contour::testing {

using namespace contour::powell_sabin;

PowellSabinSurface::PowellSabinSurface(std::shared_ptr<const ConeLayout> layout,
                                       std::shared_ptr<const PowellSabinSpline> spline)
    : layout_(std::move(layout)), spline_(std::move(spline)) {
    if (!layout_ || !spline_)
        throw std::invalid_argument("PowellSabinSurface: no layout or no spline");
    const TriangleMesh& mesh = layout_->mesh;
    if (spline_->faceCount() != mesh.faceCount() ||
        spline_->patches.size() != static_cast<size_t>(kPs12Patches) * mesh.faceCount() ||
        layout_->cornerUv.size() != static_cast<size_t>(mesh.faceCount()))
        throw std::invalid_argument("PowellSabinSurface: the spline does not match the layout");
    domain_.positions.assign(mesh.positions().begin(), mesh.positions().end());
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Triangle& t = mesh.triangle(f);
        domain_.addFace({t[0], t[1], t[2]});
    }
    buildAdjacency();
    std::vector<Preimage> coneCorner(static_cast<size_t>(mesh.vertexCount()));
    for (Index f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const Index v = mesh.triangle(f)[static_cast<size_t>(c)];
            const Vec2 local = cornerCoordinates(false, c);
            coneCorner[static_cast<size_t>(v)] = {f, local.x(), local.y()};
        }
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        if (static_cast<size_t>(v) < layout_->isCone.size() && layout_->isCone[v] &&
            coneCorner[static_cast<size_t>(v)].face != kInvalidIndex) {
            cones_.push_back(v);
            conePoints_.push_back(evaluatePosition(coneCorner[static_cast<size_t>(v)]));
        }
}

SurfaceKind PowellSabinSurface::kind() const {
    // The enum names the workbench's own surfaces; a triangle domain with
    // per-triangle polynomial patches is closest to the Loop surface's shape.
    return SurfaceKind::Loop;
}

std::string PowellSabinSurface::description() const {
    return "the fitted Powell-Sabin spline (12 quadratic Bezier patches per layout triangle), "
           "evaluated exactly";
}

Vec2 PowellSabinSurface::uvOf(const Preimage& p) const {
    const std::array<Vec2, 3>& uv = layout_->cornerUv[static_cast<size_t>(p.face)];
    return uv[0] + p.u * (uv[1] - uv[0]) + p.v * (uv[2] - uv[0]);
}

std::pair<Index, Vec3> PowellSabinSurface::locate(const Preimage& p) const {
    const Vec2 uv = uvOf(p);
    // The sub-triangle whose smallest barycentric coordinate is largest:
    // the one that contains the point, or the nearest for a point on a side
    // or a round-off outside the face.
    Index best = kInvalidIndex;
    Vec3 bestBarycentric = Vec3::Zero();
    double bestScore = -std::numeric_limits<double>::infinity();
    for (int l = 0; l < kPs12Patches; ++l) {
        const Index patch = kPs12Patches * p.face + l;
        const Vec3 b = barycentricOf(spline_->patches[static_cast<size_t>(patch)].domain, uv);
        const double score = b.minCoeff();
        if (score > bestScore) {
            bestScore = score;
            best = patch;
            bestBarycentric = b;
        }
    }
    return {best, bestBarycentric};
}

SurfacePoint PowellSabinSurface::evaluate(const Preimage& p) const {
    const auto [patch, barycentric] = locate(p);
    const QuadraticBezier<Vec3>& bezier = spline_->patches[static_cast<size_t>(patch)];
    SurfacePoint sp;
    sp.position = powell_sabin::evaluate(bezier, barycentric);
    Vec3 pu, pv, puu, puv, pvv;
    uvDerivatives(bezier, barycentric, pu, pv);
    uvSecondDerivatives(bezier, puu, puv, pvv);
    // Chain rule from the layout's uv to the face's local (u, v).
    const std::array<Vec2, 3>& uv = layout_->cornerUv[static_cast<size_t>(p.face)];
    const Vec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
    sp.du = e1.x() * pu + e1.y() * pv;
    sp.dv = e2.x() * pu + e2.y() * pv;
    sp.duu = e1.x() * e1.x() * puu + 2.0 * e1.x() * e1.y() * puv + e1.y() * e1.y() * pvv;
    sp.duv =
        e1.x() * e2.x() * puu + (e1.x() * e2.y() + e1.y() * e2.x()) * puv + e1.y() * e2.y() * pvv;
    sp.dvv = e2.x() * e2.x() * puu + 2.0 * e2.x() * e2.y() * puv + e2.y() * e2.y() * pvv;
    // The fit eliminates the gradient at a cone (§5.2), so the normal is
    // zero there; round-off in the Bezier differences must not give it a
    // direction.
    const bool corner =
        (p.u == 0.0 && p.v == 0.0) || (p.u == 1.0 && p.v == 0.0) || (p.u == 0.0 && p.v == 1.0);
    if (corner) {
        const int c = p.u == 1.0 ? 1 : (p.v == 1.0 ? 2 : 0);
        const Index v = layout_->mesh.triangle(p.face)[static_cast<size_t>(c)];
        if (layout_->isCone[static_cast<size_t>(v)]) {
            sp.du = Vec3::Zero();
            sp.dv = Vec3::Zero();
        }
    }
    return sp;
}

int PowellSabinSurface::coneRingAt(const Preimage& p, double fraction) const {
    const Triangle& t = layout_->mesh.triangle(p.face);
    const std::array<double, 3> weight{1.0 - p.u - p.v, p.u, p.v};
    for (int c = 0; c < 3; ++c) {
        if (!layout_->isCone[static_cast<size_t>(t[static_cast<size_t>(c)])] ||
            1.0 - weight[static_cast<size_t>(c)] > fraction)
            continue;
        const auto it = std::find(cones_.begin(), cones_.end(), t[static_cast<size_t>(c)]);
        return static_cast<int>(it - cones_.begin());
    }
    return -1;
}

BoundingBox PowellSabinSurface::boundingBox() const {
    BoundingBox box;
    for (const QuadraticBezier<Vec3>& patch : spline_->patches)
        for (const Vec3& c : patch.control)
            box.extend(c);
    return box;
}

Camera transformedCamera(const Camera& view, const BoundingBox& box) {
    Camera c;
    c.projection = Projection::Orthographic;
    c.viewport = view.viewport;
    // Transformed x, y of a perspective view are camera x/d, y/d (§3), whose
    // image half-height is tan(fov/2); an orthographic view is rigid.
    c.orthoHeight = view.isOrthographic()
                        ? view.orthoHeight
                        : 2.0 * std::tan(0.5 * view.fovYDegrees * 3.14159265358979323846 / 180.0);
    const double extent = std::max(1.0, box.diagonal());
    const double zMin = box.isEmpty() ? 0.0 : box.min.z();
    c.target = Vec3(0.0, 0.0, zMin + extent);
    c.eye = Vec3(0.0, 0.0, zMin - extent);
    c.up = Vec3(0.0, 1.0, 0.0);
    return c;
}

int components(int items, const std::vector<std::pair<int, int>>& joins) {
    std::vector<int> parent(static_cast<size_t>(items));
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&parent](int x) {
        while (parent[static_cast<size_t>(x)] != x) {
            parent[static_cast<size_t>(x)] =
                parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
            x = parent[static_cast<size_t>(x)];
        }
        return x;
    };
    int count = items;
    for (const auto& [a, b] : joins) {
        const int ra = find(a), rb = find(b);
        if (ra != rb) {
            parent[static_cast<size_t>(ra)] = rb;
            --count;
        }
    }
    return count;
}

namespace {

// Cusps of one loop after the zig-zag rule: sorted by image arc, clusters of
// neighbours closer than `pixels` count their parity.
int clusteredCusps(std::vector<double> arcs, double length, bool closed, double pixels) {
    if (arcs.empty() || pixels <= 0.0)
        return static_cast<int>(arcs.size());
    std::sort(arcs.begin(), arcs.end());
    const size_t n = arcs.size();
    std::vector<double> gaps(n); // gaps[i]: from cusp i to the next
    for (size_t i = 0; i + 1 < n; ++i)
        gaps[i] = arcs[i + 1] - arcs[i];
    gaps[n - 1] = closed ? length - arcs[n - 1] + arcs[0] : std::numeric_limits<double>::infinity();
    // Start after a wide gap, so that a cluster across a closed loop's
    // start stays whole.
    size_t first = 0;
    while (first < n && gaps[(first + n - 1) % n] < pixels)
        ++first;
    if (first == n)
        return static_cast<int>(n % 2);
    int count = 0, cluster = 0;
    for (size_t s = 0; s < n; ++s) {
        const size_t i = (first + s) % n;
        ++cluster;
        if (gaps[i] >= pixels) {
            count += cluster % 2;
            cluster = 0;
        }
    }
    return count + cluster % 2;
}

} // namespace

OracleFigures oracleFigures(const GroundTruth& truth, const PowellSabinSurface& surface,
                            const Camera& camera, const OracleRules& rules) {
    const double smallLoopPixels = rules.zigZagPixels;
    OracleFigures out;
    out.samples = truth.samples;
    out.loops = static_cast<int>(truth.loops.size());
    const size_t cones = surface.cones().size();
    const double ring =
        std::min(0.5, static_cast<double>(rules.coneRingSteps) / std::max(1, truth.samples));
    // Per loop: the cones it passes, and whether it lies wholly in one ring
    // (the degenerate loop the lattice draws around a cone where tau . n
    // keeps one sign on a punctured neighbourhood: an isolated point of the
    // contour, not a curve).
    std::vector<char> kept(truth.loops.size(), 1);
    std::vector<std::vector<int>> pointCone(truth.loops.size());
    std::vector<std::pair<int, int>> joins;
    std::vector<int> firstLoopAtCone(cones, -1);
    std::vector<int> keptIndex(truth.loops.size(), -1);
    int keptCount = 0;
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        const GroundTruthLoop& loop = truth.loops[l];
        std::vector<int>& at = pointCone[l];
        for (const Preimage& p : loop.preimages)
            at.push_back(surface.coneRingAt(p, ring));
        const bool inOneRing =
            !at.empty() && at.front() >= 0 &&
            std::all_of(at.begin(), at.end(), [&](int k) { return k == at.front(); });
        if (inOneRing) {
            kept[l] = 0;
            ++out.coneOnlyLoops;
            continue;
        }
        keptIndex[l] = keptCount++;
    }
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        if (!kept[l])
            continue;
        for (const int k : pointCone[l]) {
            if (k < 0)
                continue;
            int& first = firstLoopAtCone[static_cast<size_t>(k)];
            if (first < 0)
                first = keptIndex[l];
            else if (first != keptIndex[l])
                joins.emplace_back(first, keptIndex[l]);
        }
    }
    out.keptLoops = keptCount;
    out.components = components(keptCount, joins);
    out.conePoints = static_cast<int>(std::count_if(firstLoopAtCone.begin(), firstLoopAtCone.end(),
                                                    [](int l) { return l >= 0; }));
    // Cusps per kept loop, at the image arc of their nearest loop point
    // (the oracle places them within one lattice segment).
    std::vector<std::vector<double>> cuspArcs(truth.loops.size());
    std::vector<std::vector<double>> arcs(truth.loops.size());
    std::vector<double> lengths(truth.loops.size(), 0.0);
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        const GroundTruthLoop& loop = truth.loops[l];
        double arc = 0.0;
        for (size_t i = 0; i < loop.points.size(); ++i) {
            if (i > 0)
                arc += (camera.project(loop.points[i]).pixel -
                        camera.project(loop.points[i - 1]).pixel)
                           .norm();
            arcs[l].push_back(arc);
        }
        if (loop.closed && loop.points.size() > 1)
            arc += (camera.project(loop.points.front()).pixel -
                    camera.project(loop.points.back()).pixel)
                       .norm();
        lengths[l] = arc;
    }
    for (const GroundTruthCusp& cusp : truth.cusps) {
        if (cusp.loop < 0 || !kept[static_cast<size_t>(cusp.loop)])
            continue;
        const GroundTruthLoop& loop = truth.loops[static_cast<size_t>(cusp.loop)];
        size_t nearest = 0;
        double best = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < loop.points.size(); ++i) {
            const double d = (loop.points[i] - cusp.position).squaredNorm();
            if (d < best) {
                best = d;
                nearest = i;
            }
        }
        // A loop through a cone turns there between the rays of its corner,
        // and the radial curvature may change sign across it: the method
        // has a cone node there (no QI is propagated through it, §4.2), not
        // a cusp.
        if (pointCone[static_cast<size_t>(cusp.loop)][nearest] >= 0) {
            ++out.coneCusps;
            continue;
        }
        ++out.rawCusps;
        cuspArcs[static_cast<size_t>(cusp.loop)].push_back(
            arcs[static_cast<size_t>(cusp.loop)][nearest]);
    }
    for (size_t l = 0; l < truth.loops.size(); ++l)
        out.cusps +=
            clusteredCusps(cuspArcs[l], lengths[l], truth.loops[l].closed, rules.zigZagPixels);
    // How well the lattice's crossings sit on the contour: |tau . n| with
    // the unit normal, away from the cones where the normal is undefined.
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        if (!kept[l])
            continue;
        const GroundTruthLoop& loop = truth.loops[l];
        for (size_t i = 0; i < loop.preimages.size(); ++i)
            if (pointCone[l][i] < 0)
                out.maxFacing = std::max(
                    out.maxFacing, std::abs(surface.evaluate(loop.preimages[i]).normal().z()));
    }
    // Crossings with the loops cut at the cone rings.
    GroundTruth whole, cut;
    for (size_t l = 0; l < truth.loops.size(); ++l) {
        if (!kept[l])
            continue;
        const GroundTruthLoop& loop = truth.loops[l];
        whole.loops.push_back(loop);
        const std::vector<int>& at = pointCone[l];
        const size_t n = loop.points.size();
        const auto firstOut = std::find_if(at.begin(), at.end(), [](int k) { return k >= 0; });
        if (firstOut == at.end()) {
            GroundTruthLoop piece;
            piece.closed = loop.closed;
            piece.points = loop.points;
            cut.loops.push_back(std::move(piece));
            continue;
        }
        // A closed loop is walked from a removed point so that the piece
        // across its start stays whole.
        const size_t start = loop.closed ? static_cast<size_t>(firstOut - at.begin()) : 0;
        GroundTruthLoop piece;
        const auto flush = [&]() {
            if (piece.points.size() >= 2)
                cut.loops.push_back(piece);
            piece.points.clear();
        };
        for (size_t s = 0; s <= n; ++s) {
            if (s == n && !loop.closed)
                break;
            const size_t i = (start + s) % n;
            if (at[i] >= 0)
                flush();
            else
                piece.points.push_back(loop.points[i]);
        }
        flush();
    }
    out.crossings = imageCrossings(cut, camera, smallLoopPixels);
    out.coneCrossings = imageCrossings(whole, camera, smallLoopPixels) - out.crossings;
    return out;
}

MethodFigures methodFigures(const Snapshot& snapshot) {
    if (!snapshot.viewGraph)
        throw std::invalid_argument("methodFigures: the snapshot has no view graph");
    const ViewGraph& g = *snapshot.viewGraph;
    MethodFigures out;
    std::map<Index, int> chainIndex;
    for (const ViewChain& chain : g.chains)
        if (chain.type == CurveType::Contour && chain.curve != kInvalidIndex)
            chainIndex.emplace(chain.curve, static_cast<int>(chainIndex.size()));
    out.chains = static_cast<int>(chainIndex.size());
    std::vector<std::pair<int, int>> joins;
    for (const ViewNode& node : g.nodes) {
        switch (node.type) {
        case ViewNodeType::Bifurcation: {
            ++out.conePoints;
            int first = -1;
            for (const Index c : node.chains) {
                if (c == kInvalidIndex ||
                    g.chains[static_cast<size_t>(c)].type != CurveType::Contour)
                    continue;
                const auto it = chainIndex.find(g.chains[static_cast<size_t>(c)].curve);
                if (it == chainIndex.end())
                    continue;
                if (first < 0)
                    first = it->second;
                else
                    joins.emplace_back(first, it->second);
            }
            break;
        }
        case ViewNodeType::CurtainFold:
            out.cusps += node.smoothCusp;
            break;
        case ViewNodeType::ImageIntersection:
            ++out.tJunctions;
            break;
        default:
            break;
        }
    }
    out.components = components(out.chains, joins);
    out.conflicts = static_cast<int>(g.conflicts.size());
    return out;
}

SplineViewComparison compareWithOracle(const Snapshot& last, const Camera& view, int samples,
                                       const OracleRules& rules) {
    const PowellSabinState* state = powellSabinState(last);
    if (!state || !state->layout || !state->spline)
        throw std::invalid_argument("compareWithOracle: not a powell-sabin snapshot with a spline");
    if (samples < 2)
        throw std::invalid_argument("compareWithOracle: samples must be at least 2");
    const auto start = std::chrono::steady_clock::now();
    const auto surface = std::make_shared<const PowellSabinSurface>(state->layout, state->spline);
    const Camera camera = transformedCamera(view, surface->boundingBox());
    SplineViewComparison out;
    out.method = methodFigures(last);
    const DenseGroundTruth fine(surface, {samples, 4});
    out.fine = oracleFigures(fine.compute(camera), *surface, camera, rules);
    const DenseGroundTruth coarse(surface, {samples / 2, 4});
    out.coarse = oracleFigures(coarse.compute(camera), *surface, camera, rules);
    out.oracleSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace contour::testing
