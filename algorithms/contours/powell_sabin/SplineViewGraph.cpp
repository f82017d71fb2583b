#include "contours/powell_sabin/SplineViewGraph.h"

#include "visibility/ImageIntersections.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>

namespace contour::powell_sabin {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double cross2(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

void checkOptions(const SplineViewGraphOptions& o) {
    auto positive = [](double x) {
        return std::isfinite(x) && x > 0.0;
    };
    auto nonNegative = [](double x) {
        return std::isfinite(x) && x >= 0.0;
    };
    if (!positive(o.maxChordPixels))
        throw std::invalid_argument("buildSplineViewGraph: maxChordPixels must be positive");
    if (o.initialPiecesPerSegment < 1)
        throw std::invalid_argument("buildSplineViewGraph: initialPiecesPerSegment must be >= 1");
    if (o.maxBisectionDepth < 0 || o.maxBisectionDepth > 60)
        throw std::invalid_argument("buildSplineViewGraph: maxBisectionDepth must be in 0..60");
    if (!nonNegative(o.cuspOnSegmentTolerance))
        throw std::invalid_argument(
            "buildSplineViewGraph: cuspOnSegmentTolerance must be non-negative");
    if (!nonNegative(o.nodeMergeParameter) || o.nodeMergeParameter >= 0.5)
        throw std::invalid_argument("buildSplineViewGraph: nodeMergeParameter must be in [0, 0.5)");
    if (o.crossingNewtonSteps < 0)
        throw std::invalid_argument("buildSplineViewGraph: crossingNewtonSteps must be >= 0");
    if (!positive(o.crossingResidualPixels))
        throw std::invalid_argument(
            "buildSplineViewGraph: crossingResidualPixels must be positive");
    if (!positive(o.crossingSidePixels))
        throw std::invalid_argument("buildSplineViewGraph: crossingSidePixels must be positive");
    if (!nonNegative(o.coneCrossingPixels))
        throw std::invalid_argument(
            "buildSplineViewGraph: coneCrossingPixels must be non-negative");
    if (!nonNegative(o.minRayChainPixels))
        throw std::invalid_argument("buildSplineViewGraph: minRayChainPixels must be non-negative");
    if (!positive(o.gridCellsPerPatch))
        throw std::invalid_argument("buildSplineViewGraph: gridCellsPerPatch must be positive");
}

// A point of a chain of the chaining at chain parameter s: link floor(s)
// (the last link at s = L) at the fraction s - floor(s) of its traversal.
struct ChainPoint {
    Index segment = kInvalidIndex;
    Index patch = kInvalidIndex;
    double t = 0.0;
    Vec2 uv = Vec2::Zero();
    Vec3 barycentric = Vec3::Zero();
    Vec3 p = Vec3::Zero(); // transformed
    // d p / d s: the 3D tangent in the traversal direction (transformed).
    Vec3 tangent = Vec3::Zero();
    Vec2 domainDirection = Vec2::Zero(); // d r / d s
};

// A node's place on one polyline.
struct Station {
    double s = 0.0;
    Index node = kInvalidIndex;
};

struct Polyline {
    const ContourChain* chain = nullptr;
    bool closed = false;
    double length = 0.0; // number of links
    // Sorted by s; for a closed chain s in [0, L) and the chords wrap.
    std::vector<Station> stations;
    std::vector<Vec3> p; // transformed
    std::vector<Vec3> world;
    std::vector<Vec2> pixel;
    std::vector<double> cameraDepth;
    std::vector<SplineSampleRef> ref;
    std::vector<Index> chordPatch;
    Index chordCount() const {
        const Index n = static_cast<Index>(stations.size());
        return closed ? n : n - 1;
    }
    Index next(Index i) const { return closed && i + 1 == Index(stations.size()) ? 0 : i + 1; }
    double chordEndS(Index i) const {
        return closed && i + 1 == Index(stations.size()) ? length : stations[next(i)].s;
    }
};

class Builder {
public:
    Builder(const PowellSabinSpline& spline, std::span<const ContourSegment> segments,
            const ContourChaining& chaining, const Camera& camera,
            const ProjectiveTransform& transform, const SplineViewGraphOptions& options)
        : spline_(spline), segments_(segments), chaining_(chaining), camera_(camera),
          transform_(transform), o_(options) {}

    SplineViewGraph run();

private:
    ChainPoint evaluate(const ContourChain& chain, double s) const;
    // The point at fraction u of link k's traversal (u = 1: its end, which
    // evaluate(k + 1) would take from the next link).
    ChainPoint evaluateLink(const ContourChain& chain, Index k, double u) const;
    Index addNode(ViewNodeType type);
    void findCusps();
    void sample();
    void sampleLink(Index c, Index link, std::vector<Station>& out) const;
    void evaluateStations(Polyline& poly) const;
    void findCrossings();
    // Whether polyline cb changes sides of polyline ca where they meet, at
    // parameters sa and sb: both sides farther from ca than the crossing's
    // residual (pixels), so that round-off cannot make the sign.
    bool changesSides(Index ca, double sa, Index cb, double sb, double residual) const;
    void addEndNodes();
    void cutChains();
    void rayTests();
    void propagate(std::vector<Index>& queue);
    void checkRules();
    void conflict(Index chain, int propagated, Index from, Index via, const std::string& reason);

    const PowellSabinSpline& spline_;
    std::span<const ContourSegment> segments_;
    const ContourChaining& chaining_;
    const Camera& camera_;
    const ProjectiveTransform& transform_;
    const SplineViewGraphOptions& o_;
    const Vec3 tau_{0.0, 0.0, 1.0};

    SplineViewGraph out_;
    std::vector<Polyline> polys_;
    // Nodes waiting to be placed on each polyline (cusps, then crossings).
    std::vector<std::vector<Station>> pending_;
    // Cusps: the far branch follows the node in the traversal direction.
    std::map<Index, bool> farAfter_;
    std::vector<Vec3> rayOrigin_; // per view chain, world (zero without a ray)
    struct Crossing {
        Index node = kInvalidIndex;
        Index nearPoly = kInvalidIndex, farPoly = kInvalidIndex;
        double nearS = 0.0, farS = 0.0;
        bool occludedForward = false;
    };
    std::vector<Crossing> crossings_;
    // Per node: (polyline, station index) of each place it lies on.
    std::vector<std::vector<std::pair<Index, Index>>> places_;
    // Per polyline, per station: the view chains before and after it.
    std::vector<std::vector<Index>> before_, after_;
};

ChainPoint Builder::evaluate(const ContourChain& chain, double s) const {
    const Index links = static_cast<Index>(chain.links.size());
    const Index k = std::clamp(static_cast<Index>(std::floor(s)), Index(0), links - 1);
    return evaluateLink(chain, k, std::clamp(s - k, 0.0, 1.0));
}

ChainPoint Builder::evaluateLink(const ContourChain& chain, Index k, double u) const {
    const ChainLink& link = chain.links[k];
    const ContourSegment& seg = segments_[link.segment];
    ChainPoint c;
    c.segment = link.segment;
    c.patch = seg.patch;
    const double span = seg.t1 - seg.t0;
    c.t = link.reversed ? seg.t1 - u * span : seg.t0 + u * span;
    c.uv = seg.curve.at(c.t);
    const QuadraticBezier<Vec3>& patch = spline_.patches[seg.patch];
    c.barycentric = barycentricOf(patch.domain, c.uv);
    c.p = powell_sabin::evaluate(patch, c.barycentric);
    Vec3 du, dv;
    uvDerivatives(patch, c.barycentric, du, dv);
    c.domainDirection = seg.curve.derivative(c.t) * (link.reversed ? -span : span);
    c.tangent = du * c.domainDirection.x() + dv * c.domainDirection.y();
    return c;
}

Index Builder::addNode(ViewNodeType type) {
    ViewNode node;
    node.type = type;
    out_.graph.nodes.push_back(node);
    return static_cast<Index>(out_.graph.nodes.size() - 1);
}

// §4.2: interior cusps from PatchCusps (eq. 5-6) placed on their segment,
// and boundary cusps at the joins of links in different patches.
void Builder::findCusps() {
    // Where every segment lies in the chaining.
    struct Place {
        Index chain = kInvalidIndex;
        Index link = kInvalidIndex;
    };
    std::vector<Place> place(segments_.size());
    std::vector<std::vector<Index>> patchSegments(spline_.patches.size());
    for (Index i = 0; i < static_cast<Index>(segments_.size()); ++i) {
        const Index p = segments_[i].patch;
        if (p < 0 || p >= static_cast<Index>(spline_.patches.size()))
            throw std::invalid_argument("buildSplineViewGraph: segment " + std::to_string(i) +
                                        " has patch " + std::to_string(p) + " outside the spline");
        patchSegments[p].push_back(i);
    }
    for (Index c = 0; c < static_cast<Index>(chaining_.chains.size()); ++c) {
        const ContourChain& chain = chaining_.chains[c];
        if (chain.links.empty())
            throw std::invalid_argument("buildSplineViewGraph: chain " + std::to_string(c) +
                                        " has no links");
        for (Index k = 0; k < static_cast<Index>(chain.links.size()); ++k) {
            const Index seg = chain.links[k].segment;
            if (seg < 0 || seg >= static_cast<Index>(segments_.size()))
                throw std::invalid_argument("buildSplineViewGraph: chain " + std::to_string(c) +
                                            " names segment " + std::to_string(seg) +
                                            " outside the segments");
            place[seg] = {c, k};
        }
    }

    // A node at s on chain c, unless one is already within the merge distance
    // (cyclically on a loop).
    auto addStation = [&](Index c, double s, Index node) {
        const Polyline& poly = polys_[c];
        if (poly.closed && s >= poly.length)
            s -= poly.length;
        // A cusp at an open chain's end is at its cone or boundary point.
        if (!poly.closed &&
            (s <= o_.nodeMergeParameter || s >= poly.length - o_.nodeMergeParameter))
            return false;
        for (const Station& st : pending_[c]) {
            double d = std::abs(st.s - s);
            if (poly.closed)
                d = std::min(d, poly.length - d);
            if (d <= o_.nodeMergeParameter)
                return false;
        }
        pending_[c].push_back({s, node});
        return true;
    };

    // The closest point of every segment of the patch to a cusp: a coarse
    // scan, then golden-section refinement around the best sample.
    struct Located {
        Index segment = kInvalidIndex;
        double t = 0.0, distance = std::numeric_limits<double>::infinity();
    };
    const auto locate = [&](Index p, const PatchCusp& cusp) {
        Located best;
        for (Index si : patchSegments[p]) {
            const ContourSegment& seg = segments_[si];
            auto dist = [&](double t) {
                return (seg.curve.at(t) - cusp.uv).squaredNorm();
            };
            constexpr int kScan = 64;
            int bestJ = 0;
            double bd = std::numeric_limits<double>::infinity();
            for (int j = 0; j <= kScan; ++j) {
                const double d = dist(seg.t0 + (seg.t1 - seg.t0) * j / kScan);
                if (d < bd) {
                    bd = d;
                    bestJ = j;
                }
            }
            double a = seg.t0 + (seg.t1 - seg.t0) * std::max(0, bestJ - 1) / kScan;
            double b = seg.t0 + (seg.t1 - seg.t0) * std::min(kScan, bestJ + 1) / kScan;
            const double g = 0.5 * (std::sqrt(5.0) - 1.0);
            for (int it = 0; it < 80; ++it) {
                const double x1 = b - g * (b - a), x2 = a + g * (b - a);
                if (dist(x1) < dist(x2))
                    b = x2;
                else
                    a = x1;
            }
            const double t = 0.5 * (a + b);
            const double d = std::sqrt(dist(t));
            if (d < best.distance)
                best = {si, t, d};
        }
        return best;
    };
    // The patches' cusps and their places are independent of each other:
    // found in parallel, placed in order.
    std::vector<PatchCuspResult> cuspsOf(spline_.patches.size());
    std::vector<std::vector<Located>> locatedOf(spline_.patches.size());
    tbb::parallel_for(Index(0), static_cast<Index>(spline_.patches.size()), [&](Index p) {
        if (patchSegments[p].empty())
            return;
        cuspsOf[p] = patchCusps(spline_.patches[p], tau_, o_.cusp);
        for (const PatchCusp& cusp : cuspsOf[p].cusps)
            locatedOf[p].push_back(locate(p, cusp));
    });
    for (Index p = 0; p < static_cast<Index>(spline_.patches.size()); ++p) {
        if (patchSegments[p].empty())
            continue;
        const QuadraticBezier<Vec3>& patch = spline_.patches[p];
        const PatchCuspResult& found = cuspsOf[static_cast<size_t>(p)];
        out_.stats.degenerateCuspPatches += found.degenerate;
        double side = 0.0;
        for (int i = 0; i < 3; ++i)
            side = std::max(side, (patch.domain[(i + 1) % 3] - patch.domain[i]).norm());
        for (size_t k = 0; k < found.cusps.size(); ++k) {
            const PatchCusp& cusp = found.cusps[k];
            const Located& at = locatedOf[static_cast<size_t>(p)][k];
            const Index bestSeg = at.segment;
            const double bestT = at.t, bestD = at.distance;
            if (bestSeg == kInvalidIndex || bestD > o_.cuspOnSegmentTolerance * side) {
                ++out_.stats.unplacedCusps;
                continue;
            }
            const ContourSegment& seg = segments_[bestSeg];
            const Place where = place[bestSeg];
            if (where.chain == kInvalidIndex) {
                ++out_.stats.unplacedCusps;
                continue;
            }
            const ContourChain& chain = chaining_.chains[where.chain];
            const bool reversed = chain.links[where.link].reversed;
            const double u = (bestT - seg.t0) / (seg.t1 - seg.t0);
            const double s = where.link + (reversed ? 1.0 - u : u);
            const Index node = static_cast<Index>(out_.graph.nodes.size());
            if (!addStation(where.chain, s, node))
                continue; // the same cusp from the patch across a shared side
            addNode(ViewNodeType::CurtainFold);
            ViewNode& n = out_.graph.nodes[node];
            n.smoothCusp = true;
            n.qiStep = 1;
            // PatchCusps.h: QI + 1 along T iff tau . t > 0; the traversal
            // runs along T when its domain direction has a positive dot.
            const Vec2 direction = seg.curve.derivative(bestT) * (reversed ? -1.0 : 1.0);
            const bool alongT = direction.dot(cusp.domainTangent) > 0.0;
            farAfter_[node] = alongT == cusp.qiIncreasesAlongDomainTangent;
            ++out_.stats.interiorCusps;
        }
    }

    // §4.2 patch-boundary cusps: the two tangents of a join on either side
    // of the normal in the image.
    for (Index c = 0; c < static_cast<Index>(chaining_.chains.size()); ++c) {
        const ContourChain& chain = chaining_.chains[c];
        const Index links = static_cast<Index>(chain.links.size());
        for (Index k = chain.closed ? 0 : 1; k < links; ++k) {
            const Index prev = (k + links - 1) % links;
            const ContourSegment& a = segments_[chain.links[prev].segment];
            const ContourSegment& b = segments_[chain.links[k].segment];
            if (a.patch == b.patch)
                continue; // an interior join: the curve is smooth there
            const ChainPoint end = evaluateLink(chain, prev, 1.0);
            const ChainPoint start = evaluateLink(chain, k, 0.0);
            const Vec3 na = spline_.normal(end.patch, end.barycentric);
            const Vec3 nb = spline_.normal(start.patch, start.barycentric);
            if (na.norm() == 0.0 || nb.norm() == 0.0)
                continue; // a cone: chains end there
            const Vec3 n = na.normalized() + nb.normalized();
            if (!isBoundaryCusp(n, end.tangent, start.tangent, tau_, o_.cusp))
                continue;
            const Index node = static_cast<Index>(out_.graph.nodes.size());
            if (!addStation(c, static_cast<double>(k), node))
                continue;
            addNode(ViewNodeType::CurtainFold);
            ViewNode& vn = out_.graph.nodes[node];
            vn.smoothCusp = true;
            vn.qiStep = 1;
            // The far branch leaves the node away from the viewer (the limit
            // of the interior rule when both tangents tend to tau).
            const double zBefore = -end.tangent.normalized().dot(tau_);
            const double zAfter = start.tangent.normalized().dot(tau_);
            farAfter_[node] = zAfter > zBefore;
            vn.unreliable = (zBefore > 0.0) == (zAfter > 0.0);
            out_.stats.unreliableCusps += vn.unreliable;
            ++out_.stats.boundaryCusps;
        }
    }
}

// Uniform pieces of link k and its nodes, then bisection until every chord
// is within maxChordPixels of the curve at its parameter midpoint. Emits the
// stations in [k, k + 1); the chain's last point (s = L) is added by the
// caller for an open chain and is station 0 again for a loop.
void Builder::sampleLink(Index c, Index link, std::vector<Station>& out) const {
    const Polyline& poly = polys_[c];
    std::vector<Station> fixed;
    const int n = o_.initialPiecesPerSegment;
    for (int i = 0; i < n; ++i)
        fixed.push_back({link + static_cast<double>(i) / n, kInvalidIndex});
    for (const Station& st : pending_[c]) {
        if (st.s < link || st.s >= link + 1.0)
            continue;
        auto at =
            std::find_if(fixed.begin(), fixed.end(), [&](const Station& f) { return f.s == st.s; });
        if (at != fixed.end())
            at->node = st.node;
        else
            fixed.push_back(st);
    }
    std::sort(fixed.begin(), fixed.end(),
              [](const Station& a, const Station& b) { return a.s < b.s; });
    fixed.push_back({link + 1.0, kInvalidIndex});
    auto pixelAt = [&](double s) {
        return camera_.project(transform_.invert(evaluate(*poly.chain, s).p)).pixel;
    };
    std::vector<Vec2> pix;
    for (const Station& f : fixed)
        pix.push_back(pixelAt(f.s));
    struct Piece {
        double a, b;
        Vec2 pa, pb;
        int depth;
    };
    for (size_t i = 0; i + 1 < fixed.size(); ++i) {
        out.push_back(fixed[i]);
        // Depth first, first half on top: the points come out in order.
        std::vector<Piece> stack{{fixed[i].s, fixed[i + 1].s, pix[i], pix[i + 1], 0}};
        while (!stack.empty()) {
            const Piece piece = stack.back();
            stack.pop_back();
            const double m = 0.5 * (piece.a + piece.b);
            const Vec2 pm = pixelAt(m);
            const Vec2 d = piece.pb - piece.pa;
            const double len2 = d.squaredNorm();
            const double lambda =
                len2 > 0.0 ? std::clamp((pm - piece.pa).dot(d) / len2, 0.0, 1.0) : 0.0;
            const double error = (pm - (piece.pa + lambda * d)).norm();
            if (error > o_.maxChordPixels && piece.depth < o_.maxBisectionDepth) {
                stack.push_back({m, piece.b, pm, piece.pb, piece.depth + 1});
                stack.push_back({piece.a, m, piece.pa, pm, piece.depth + 1});
            } else if (piece.b != fixed[i + 1].s) {
                out.push_back({piece.b, kInvalidIndex});
            }
        }
    }
}

void Builder::evaluateStations(Polyline& poly) const {
    const size_t n = poly.stations.size();
    poly.p.resize(n);
    poly.world.resize(n);
    poly.pixel.resize(n);
    poly.cameraDepth.resize(n);
    poly.ref.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const ChainPoint c = evaluate(*poly.chain, poly.stations[i].s);
        poly.p[i] = c.p;
        poly.world[i] = transform_.invert(c.p);
        const ProjectedPoint pp = camera_.project(poly.world[i]);
        poly.pixel[i] = pp.pixel;
        poly.cameraDepth[i] = pp.depth;
        poly.ref[i] = {c.segment, c.t};
    }
    poly.chordPatch.resize(static_cast<size_t>(poly.chordCount()));
    for (Index i = 0; i < poly.chordCount(); ++i) {
        const Index links = static_cast<Index>(poly.chain->links.size());
        const Index k =
            std::clamp(static_cast<Index>(std::floor(poly.stations[i].s)), Index(0), links - 1);
        poly.chordPatch[i] = segments_[poly.chain->links[k].segment].patch;
    }
}

void Builder::sample() {
    // Each chain is sampled on its own.
    tbb::parallel_for(Index(0), static_cast<Index>(polys_.size()), [&](Index c) {
        Polyline& poly = polys_[c];
        std::vector<Station> st;
        for (Index k = 0; k < static_cast<Index>(poly.chain->links.size()); ++k)
            sampleLink(c, k, st);
        if (!poly.closed)
            st.push_back({poly.length, kInvalidIndex});
        poly.stations = std::move(st);
        evaluateStations(poly);
    });
}

// §4.2 image-space intersections, on the sampled chords (exact segment
// tests): the nearer curve at the crossing passes in front.
void Builder::findCrossings() {
    std::vector<ImageSegment> chords;
    std::vector<std::pair<Index, Index>> owner; // (polyline, chord)
    for (Index c = 0; c < static_cast<Index>(polys_.size()); ++c) {
        const Polyline& poly = polys_[c];
        for (Index i = 0; i < poly.chordCount(); ++i) {
            chords.push_back({poly.pixel[i], poly.pixel[poly.next(i)]});
            owner.push_back({c, i});
        }
    }
    // Nodes at the ends of a chord (several chains share cone nodes).
    auto endNodes = [&](Index chord) {
        const auto [c, i] = owner[chord];
        const Polyline& poly = polys_[c];
        return std::array<Index, 2>{poly.stations[i].node, poly.stations[poly.next(i)].node};
    };
    auto ignore = [&](Index a, Index b) {
        const auto [ca, ia] = owner[a];
        const auto [cb, ib] = owner[b];
        if (ca == cb) {
            const Polyline& poly = polys_[ca];
            if (poly.next(ia) == ib || poly.next(ib) == ia)
                return true;
        }
        // Chords from a common node meet only there (unless collinear).
        for (Index x : endNodes(a))
            for (Index y : endNodes(b))
                if (x != kInvalidIndex && x == y)
                    return true;
        return false;
    };
    const ImageIntersectionResult found = imageIntersections(chords, ignore);
    out_.stats.imageOverlaps = static_cast<Index>(found.overlaps.size());

    auto chordS = [&](Index chord, const Vec2& point) {
        const auto [c, i] = owner[chord];
        const Polyline& poly = polys_[c];
        const Vec2 a = poly.pixel[i], d = poly.pixel[poly.next(i)] - a;
        const double len2 = d.squaredNorm();
        const double lambda = len2 > 0.0 ? std::clamp((point - a).dot(d) / len2, 0.0, 1.0) : 0.0;
        const double s0 = poly.stations[i].s;
        return s0 + lambda * (poly.chordEndS(i) - s0);
    };
    auto chordRange = [&](Index chord) {
        const auto [c, i] = owner[chord];
        return std::pair<double, double>{polys_[c].stations[i].s, polys_[c].chordEndS(i)};
    };
    // Cone points in the image (chain ends at Bifurcation nodes).
    std::vector<Vec2> cones;
    for (const Polyline& poly : polys_)
        for (size_t e : {size_t(0), poly.stations.size() - 1})
            if (!poly.closed && poly.stations[e].node != kInvalidIndex &&
                out_.graph.nodes[poly.stations[e].node].type == ViewNodeType::Bifurcation)
                cones.push_back(poly.pixel[e]);
    std::vector<std::array<double, 4>> seen;   // (polyline, s, polyline, s) of each chord crossing
    std::vector<std::array<double, 4>> onBoth; // the same after Newton, on both curves
    const auto pixelOf = [&](const Vec3& p) {
        return camera_.project(transform_.invert(p)).pixel;
    };
    // One crossing of chords of polylines ca and cb near `point` (pixels),
    // at sa in [la, ha] and sb in [lb, hb].
    const auto candidate = [&](Index ca, double sa, double la, double ha, Index cb, double sb,
                               double lb, double hb, const Vec2& point) {
        // §4.2: the loops through a cone meet there at one surface point;
        // a crossing next to it is that meeting, not an occlusion.
        bool atCone = false;
        for (const Vec2& c : cones)
            atCone = atCone || (c - point).norm() <= o_.coneCrossingPixels;
        if (atCone) {
            ++out_.stats.coneCrossings;
            return;
        }
        Polyline& pa = polys_[ca];
        Polyline& pb = polys_[cb];
        // A crossing through a sample is reported by both chords there.
        auto wrapped = [](const Polyline& poly, double v) {
            return poly.closed && v >= poly.length ? v - poly.length : v;
        };
        const std::array<double, 4> key = {
            double(std::min(ca, cb)), ca <= cb ? wrapped(pa, sa) : wrapped(pb, sb),
            double(std::max(ca, cb)), ca <= cb ? wrapped(pb, sb) : wrapped(pa, sa)};
        bool duplicate = false;
        for (const std::array<double, 4>& old : seen)
            duplicate = duplicate ||
                        (old[0] == key[0] && old[2] == key[2] &&
                         std::abs(old[1] - key[1]) <= 1e-12 && std::abs(old[3] - key[3]) <= 1e-12);
        if (duplicate)
            return;
        seen.push_back(key);
        // The chords cross within the chord error of the curves: Newton on
        // p_a(s_a).xy = p_b(s_b).xy (transformed xy is an affine image of
        // the pixels) moves the node onto both curves, within the two chords
        // and their neighbours (the curves' crossing can lie just past a
        // chord's end).
        ChainPoint a, b;
        // Newton within the chords, or (widen) also their neighbours.
        const auto newton = [&](double& ta, double& tb, bool widen) {
            const double wa = widen ? ha - la : 0.0, wb = widen ? hb - lb : 0.0;
            const double loA = std::max(0.0, la - wa), hiA = std::min(pa.length, ha + wa);
            const double loB = std::max(0.0, lb - wb), hiB = std::min(pb.length, hb + wb);
            a = evaluate(*pa.chain, ta);
            b = evaluate(*pb.chain, tb);
            for (int it = 0; it < o_.crossingNewtonSteps; ++it) {
                Eigen::Matrix2d jac;
                jac << a.tangent.head<2>(), -b.tangent.head<2>();
                const Vec2 step = jac.fullPivLu().solve(Vec2(b.p.head<2>() - a.p.head<2>()));
                if (!step.allFinite())
                    break;
                const double na = ta + step.x(), nb = tb + step.y();
                if (na < loA || na > hiA || nb < loB || nb > hiB)
                    break;
                ta = na;
                tb = nb;
                a = evaluate(*pa.chain, ta);
                b = evaluate(*pb.chain, tb);
            }
            return (pixelOf(a.p) - pixelOf(b.p)).norm();
        };
        const double chordS0 = sa, chordT0 = sb;
        const double residual = newton(sa, sb, false);
        if (o_.crossingNewtonSteps > 0 && residual > o_.crossingResidualPixels) {
            // Two curves closer than the chord error can have chords that
            // cross where the curves do not (or cross elsewhere): the chords
            // are cut into finer chords of the exact curves, and a crossing
            // of those must take Newton onto both curves.
            constexpr int kPieces = 8;
            std::array<ImageSegment, 2 * kPieces> pieces;
            const auto at = [](double lo, double hi, int i) {
                return lo + (hi - lo) * i / kPieces;
            };
            for (int i = 0; i < kPieces; ++i) {
                pieces[i] = {pixelOf(evaluate(*pa.chain, at(la, ha, i)).p),
                             pixelOf(evaluate(*pa.chain, at(la, ha, i + 1)).p)};
                pieces[kPieces + i] = {pixelOf(evaluate(*pb.chain, at(lb, hb, i)).p),
                                       pixelOf(evaluate(*pb.chain, at(lb, hb, i + 1)).p)};
            }
            const ImageIntersectionResult finer = imageIntersections(pieces, [](Index i, Index j) {
                return (i < kPieces) == (j < kPieces); // pieces of one curve
            });
            bool onCurves = false;
            for (const ImageCrossing& y : finer.crossings) {
                const Index i = y.first, j = y.second - kPieces;
                const auto along = [&](const ImageSegment& piece) {
                    const Vec2 d = piece.b - piece.a;
                    const double len2 = d.squaredNorm();
                    return len2 > 0.0 ? std::clamp((y.point - piece.a).dot(d) / len2, 0.0, 1.0)
                                      : 0.0;
                };
                double ta =
                    at(la, ha, static_cast<int>(i)) + along(pieces[i]) * (ha - la) / kPieces;
                double tb =
                    at(lb, hb, static_cast<int>(j)) + along(pieces[y.second]) * (hb - lb) / kPieces;
                if (newton(ta, tb, false) <= o_.crossingResidualPixels) {
                    sa = ta;
                    sb = tb;
                    onCurves = true;
                    break;
                }
            }
            if (!onCurves) {
                double ta = chordS0, tb = chordT0;
                if (newton(ta, tb, true) <= o_.crossingResidualPixels) {
                    sa = ta;
                    sb = tb;
                    onCurves = true;
                }
            }
            if (!onCurves) {
                ++out_.stats.chordOnlyCrossings;
                return;
            }
        }
        // Two branches that touch without crossing pass the residual test:
        // where the contour runs along a patch side, a boundary cusp's two
        // branches run back along each other within 1e-9 px, and their
        // chords cross. §4.2's T-junction is a crossing of the image curves:
        // the far curve must change sides of the other one there.
        if (o_.crossingNewtonSteps > 0 &&
            !changesSides(ca, sa, cb, sb, (pixelOf(a.p) - pixelOf(b.p)).norm())) {
            ++out_.stats.touchingCrossings;
            return;
        }
        // The same crossing of the curves found from two pairs of chords.
        bool again = false;
        for (const std::array<double, 4>& old : onBoth)
            again = again ||
                    (old[0] == ca && old[2] == cb && std::abs(old[1] - sa) <= 1e-9 &&
                     std::abs(old[3] - sb) <= 1e-9) ||
                    (old[0] == cb && old[2] == ca && std::abs(old[1] - sb) <= 1e-9 &&
                     std::abs(old[3] - sa) <= 1e-9);
        if (again)
            return;
        onBoth.push_back({double(ca), sa, double(cb), sb});
        sa = wrapped(pa, sa);
        sb = wrapped(pb, sb);
        const bool aNear = a.p.z() < b.p.z();
        const ChainPoint& nearPt = aNear ? a : b;
        const ChainPoint& farPt = aNear ? b : a;

        // The side of the near contour the near surface folds to: along
        // the tangent-plane preimage w of tau, p(r + h w) = p + h tau +
        // h^2 / 2 D^2p[w, w] exactly on a quadratic patch.
        const QuadraticBezier<Vec3>& patch = spline_.patches[nearPt.patch];
        Vec3 du, dv, duu, duv, dvv;
        uvDerivatives(patch, nearPt.barycentric, du, dv);
        uvSecondDerivatives(patch, duu, duv, dvv);
        Eigen::Matrix<double, 3, 2> J;
        J << du, dv;
        const Vec2 w = J.colPivHouseholderQr().solve(tau_);
        const Vec3 fold = w.x() * w.x() * duu + 2.0 * w.x() * w.y() * duv + w.y() * w.y() * dvv;
        const Vec2 nearTangent = nearPt.tangent.head<2>();
        const Vec2 farTangent = farPt.tangent.head<2>();
        const double sideFold = cross2(nearTangent, fold.head<2>());
        const double sideFar = cross2(nearTangent, farTangent);

        const Index node = addNode(ViewNodeType::ImageIntersection);
        ViewNode& vn = out_.graph.nodes[node];
        vn.qiStep = 2; // §4.2: contour over contour
        vn.position = transform_.invert(farPt.p);
        vn.nearPoint = transform_.invert(nearPt.p);
        const double scale = nearTangent.norm() * fold.head<2>().norm();
        vn.unreliable = !(std::abs(sideFold) > 1e-9 * scale) || sideFar == 0.0;
        out_.stats.unreliableTJunctions += vn.unreliable;
        Crossing cr;
        cr.node = node;
        cr.nearPoly = aNear ? ca : cb;
        cr.farPoly = aNear ? cb : ca;
        cr.nearS = aNear ? sa : sb;
        cr.farS = aNear ? sb : sa;
        cr.occludedForward = (sideFold > 0.0) == (sideFar > 0.0);
        crossings_.push_back(cr);
        pending_[cr.nearPoly].push_back({cr.nearS, node});
        pending_[cr.farPoly].push_back({cr.farS, node});
        ++out_.stats.tJunctions;
    };
    for (const ImageCrossing& x : found.crossings) {
        if (ignore(x.first, x.second))
            continue;
        const auto [la, ha] = chordRange(x.first);
        const auto [lb, hb] = chordRange(x.second);
        candidate(owner[x.first].first, chordS(x.first, x.point), la, ha, owner[x.second].first,
                  chordS(x.second, x.point), lb, hb, x.point);
    }
    // Insert the crossing stations into the sampled polylines.
    for (Index c = 0; c < static_cast<Index>(polys_.size()); ++c) {
        Polyline& poly = polys_[c];
        bool changed = false;
        for (const Station& st : pending_[c]) {
            if (out_.graph.nodes[st.node].type != ViewNodeType::ImageIntersection)
                continue;
            auto at = std::lower_bound(poly.stations.begin(), poly.stations.end(), st.s,
                                       [](const Station& a, double s) { return a.s < s; });
            if (at != poly.stations.end() && at->s == st.s && at->node == kInvalidIndex)
                at->node = st.node;
            else
                poly.stations.insert(at, st);
            changed = true;
        }
        if (changed)
            evaluateStations(poly);
    }
}

bool Builder::changesSides(Index ca, double sa, Index cb, double sb, double residual) const {
    const Polyline& pa = polys_[ca];
    const Polyline& pb = polys_[cb];
    const auto pixelOf = [&](const Vec3& p) {
        return camera_.project(transform_.invert(p)).pixel;
    };
    // Half the room around s on a polyline: to its ends and its nearest node
    // (a cusp turns the curve back).
    const auto roomAround = [&](Index c, double s) {
        const Polyline& poly = polys_[c];
        double room = 0.5 * (poly.closed ? poly.length : std::min(s, poly.length - s));
        for (const Station& st : pending_[c]) {
            double d = std::abs(st.s - s);
            if (poly.closed)
                d = std::min(d, poly.length - d);
            room = std::min(room, 0.5 * d);
        }
        return room;
    };
    // Offsets along b: about sidePixels away in the image, within its room.
    const double room = roomAround(cb, sb);
    const ChainPoint at = evaluate(*pb.chain, sb);
    constexpr double kProbe = 1e-7;
    const double speed = (pixelOf(at.p + kProbe * at.tangent) - pixelOf(at.p)).norm() / kProbe;
    const double h = speed > 0.0 ? std::min(room, o_.crossingSidePixels / speed) : room;
    if (!(h > 0.0))
        return false;
    const auto wrap = [](const Polyline& poly, double s) {
        if (!poly.closed)
            return std::clamp(s, 0.0, poly.length);
        s = std::fmod(s, poly.length);
        return s < 0.0 ? s + poly.length : s;
    };
    // The side of q (pixels) of curve a, at q's closest point on a (Gauss-
    // Newton from sa in the image) within a's room around sa.
    const double roomA = roomAround(ca, sa);
    const auto sideOf = [&](const Vec2& q) {
        double off = 0.0;
        Vec2 x = Vec2::Zero(), d = Vec2::Zero();
        for (int it = 0; it < 2 * o_.crossingNewtonSteps + 1; ++it) {
            const ChainPoint c = evaluate(*pa.chain, wrap(pa, sa + off));
            x = pixelOf(c.p);
            d = (pixelOf(c.p + kProbe * c.tangent) - x) / kProbe;
            const double d2 = d.squaredNorm();
            if (!(d2 > 0.0))
                break;
            const double step = (q - x).dot(d) / d2;
            if (!std::isfinite(step) || step == 0.0)
                break;
            off = std::clamp(off + step, -roomA, roomA);
        }
        return cross2(d.normalized(), q - x);
    };
    const double before = sideOf(pixelOf(evaluate(*pb.chain, wrap(pb, sb - h)).p));
    const double after = sideOf(pixelOf(evaluate(*pb.chain, wrap(pb, sb + h)).p));
    const double floor = 8.0 * residual;
    return (before < -floor && after > floor) || (before > floor && after < -floor);
}

// Chain ends: cones (one node per cone point, shared by its chains), the
// surface boundary, unmatched ends.
void Builder::addEndNodes() {
    std::map<Index, Index> coneNode;
    for (Index c = 0; c < static_cast<Index>(polys_.size()); ++c) {
        Polyline& poly = polys_[c];
        if (poly.closed)
            continue;
        for (int e = 0; e < 2; ++e) {
            const ChainEnd& end = e == 0 ? poly.chain->front : poly.chain->back;
            Station& st = e == 0 ? poly.stations.front() : poly.stations.back();
            if (st.node != kInvalidIndex)
                throw std::logic_error("buildSplineViewGraph: a node at a chain end");
            Index node = kInvalidIndex;
            if (end.kind == ChainEndKind::Cone && end.node != kInvalidIndex) {
                auto [it, fresh] = coneNode.emplace(end.node, kInvalidIndex);
                if (fresh) {
                    it->second = addNode(ViewNodeType::Bifurcation);
                    ++out_.stats.conePoints;
                }
                node = it->second;
            } else if (end.kind == ChainEndKind::Boundary && o_.boundaryCurves) {
                node = addNode(ViewNodeType::ContourBoundaryJunction);
                ++out_.stats.boundaryEnds;
            } else {
                node = addNode(ViewNodeType::CurveEnd);
                if (end.kind == ChainEndKind::Boundary)
                    ++out_.stats.boundaryEnds;
                else
                    ++out_.stats.curveEnds;
            }
            st.node = node;
        }
    }
}

// Every chain between two consecutive nodes of a polyline becomes a view
// chain; a loop without a node is one closed chain.
void Builder::cutChains() {
    ViewGraph& g = out_.graph;
    places_.assign(g.nodes.size(), {});
    before_.assign(polys_.size(), {});
    after_.assign(polys_.size(), {});
    for (Index c = 0; c < static_cast<Index>(polys_.size()); ++c) {
        Polyline& poly = polys_[c];
        // Every chain needs an inner point for its ray: a midpoint between
        // two adjacent nodes.
        for (size_t i = 0; i < poly.stations.size(); ++i) {
            const size_t j = static_cast<size_t>(poly.next(static_cast<Index>(i)));
            if (j >= poly.stations.size() || (j == 0 && !poly.closed))
                continue;
            if (poly.stations[i].node != kInvalidIndex && poly.stations[j].node != kInvalidIndex &&
                (poly.stations.size() > 1)) {
                const double s0 = poly.stations[i].s;
                const double s1 = poly.chordEndS(static_cast<Index>(i));
                poly.stations.insert(poly.stations.begin() + static_cast<long>(i) + 1,
                                     {0.5 * (s0 + s1), kInvalidIndex});
                ++i;
            }
        }
        evaluateStations(poly);
        const Index n = static_cast<Index>(poly.stations.size());
        before_[c].assign(static_cast<size_t>(n), kInvalidIndex);
        after_[c].assign(static_cast<size_t>(n), kInvalidIndex);
        std::vector<Index> nodeStations;
        for (Index i = 0; i < n; ++i)
            if (poly.stations[i].node != kInvalidIndex)
                nodeStations.push_back(i);
        auto emit = [&](Index from, Index count, bool closedLoop) {
            ViewChain chain;
            chain.type = CurveType::Contour;
            chain.source = SegmentSource::Face;
            chain.curve = c;
            chain.closed = closedLoop;
            std::vector<SplineSampleRef> refs;
            for (Index k = 0; k < count; ++k) {
                const Index i = (from + k) % n;
                chain.points.push_back(poly.world[i]);
                chain.image.push_back(poly.pixel[i]);
                chain.depth.push_back(poly.cameraDepth[i]);
                refs.push_back(poly.ref[i]);
                if (k + 1 < count)
                    chain.segmentElement.push_back(poly.chordPatch[i]);
            }
            for (size_t k = 1; k < chain.image.size(); ++k)
                chain.lengthPixels += (chain.image[k] - chain.image[k - 1]).norm();
            const Index id = static_cast<Index>(g.chains.size());
            if (!closedLoop) {
                const Index first = from, last = (from + count - 1) % n;
                chain.startNode = poly.stations[first].node;
                chain.endNode = poly.stations[last].node;
                after_[c][first] = id;
                before_[c][last] = id;
                g.nodes[chain.startNode].chains.push_back(id);
                g.nodes[chain.endNode].chains.push_back(id);
            }
            g.chains.push_back(std::move(chain));
            out_.contourChain.push_back(c);
            out_.samples.push_back(std::move(refs));
        };
        if (poly.closed && nodeStations.empty()) {
            emit(0, n + 1, true);
        } else if (poly.closed) {
            for (size_t k = 0; k < nodeStations.size(); ++k) {
                const Index a = nodeStations[k];
                const Index b = nodeStations[(k + 1) % nodeStations.size()];
                const Index count = (b - a + n) % n + 1 + (b == a ? n : 0);
                emit(a, count, false);
            }
        } else {
            for (size_t k = 0; k + 1 < nodeStations.size(); ++k)
                emit(nodeStations[k], nodeStations[k + 1] - nodeStations[k] + 1, false);
        }
        for (Index i : nodeStations)
            places_[poly.stations[i].node].push_back({c, i});
    }
    // Node positions: the place on the first polyline through it.
    for (Index v = 0; v < static_cast<Index>(g.nodes.size()); ++v) {
        ViewNode& node = g.nodes[v];
        if (places_[v].empty())
            throw std::logic_error("buildSplineViewGraph: a node on no chain");
        const auto [c, i] = places_[v].front();
        if (node.type != ViewNodeType::ImageIntersection)
            node.position = polys_[c].world[i];
        node.image = camera_.project(node.position).pixel;
        if (node.type == ViewNodeType::CurtainFold) {
            const bool farAfter = farAfter_.at(v);
            const Index before = before_[c][i], after = after_[c][i];
            node.nearChains = {farAfter ? before : after, kInvalidIndex};
            node.farChains = {kInvalidIndex, farAfter ? after : before};
        }
    }
    for (const Crossing& x : crossings_) {
        ViewNode& node = g.nodes[x.node];
        Index nearBefore = kInvalidIndex, nearAfter = kInvalidIndex;
        Index farBefore = kInvalidIndex, farAfter = kInvalidIndex;
        for (const auto& [c, i] : places_[x.node]) {
            const double s = polys_[c].stations[i].s;
            if (c == x.nearPoly && s == x.nearS && nearBefore == kInvalidIndex &&
                nearAfter == kInvalidIndex) {
                nearBefore = before_[c][i];
                nearAfter = after_[c][i];
            } else if (c == x.farPoly && s == x.farS) {
                farBefore = before_[c][i];
                farAfter = after_[c][i];
            }
        }
        node.nearChains = {nearBefore, nearAfter};
        node.farChains = x.occludedForward ? std::array<Index, 2>{farBefore, farAfter}
                                           : std::array<Index, 2>{farAfter, farBefore};
    }
}

// One ray per chain (§4.2), through the sample nearest half its image
// length, against the patches of its grid cell.
void Builder::rayTests() {
    ViewGraph& g = out_.graph;
    const Index patchCount = static_cast<Index>(spline_.patches.size());
    // A uniform grid over the patches' image boxes, rebuilt per view (the
    // fit moves every patch), as flat arrays: with tens of thousands of
    // patches and a few hundred rays the build is the cost, not the rays.
    std::vector<Eigen::AlignedBox2d> boxes(spline_.patches.size());
    tbb::parallel_for(Index(0), patchCount, [&](Index p) {
        for (const Vec3& c : spline_.patches[p].control)
            boxes[p].extend(c.head<2>());
    });
    Eigen::AlignedBox2d all;
    for (const Eigen::AlignedBox2d& box : boxes)
        all.extend(box);
    const Vec2 size = all.isEmpty() ? Vec2(1, 1) : Vec2(all.sizes().cwiseMax(1e-300));
    const double cells = std::max(1.0, o_.gridCellsPerPatch * patchCount);
    const int nx =
        std::clamp(static_cast<int>(std::ceil(std::sqrt(cells * size.x() / size.y()))), 1, 4096);
    const int ny = std::clamp(static_cast<int>(std::ceil(cells / nx)), 1, 4096);
    auto cellOf = [&](const Vec2& x, int& i, int& j) {
        i = std::clamp(static_cast<int>(std::floor((x.x() - all.min().x()) / size.x() * nx)), 0,
                       nx - 1);
        j = std::clamp(static_cast<int>(std::floor((x.y() - all.min().y()) / size.y() * ny)), 0,
                       ny - 1);
    };
    // Cell c holds cellPatches[cellStart[c] .. cellStart[c + 1]).
    std::vector<Index> cellStart(static_cast<size_t>(nx) * ny + 1, 0);
    std::vector<std::array<int, 4>> span(spline_.patches.size());
    for (Index p = 0; p < patchCount; ++p) {
        std::array<int, 4>& r = span[static_cast<size_t>(p)];
        cellOf(boxes[p].min(), r[0], r[1]);
        cellOf(boxes[p].max(), r[2], r[3]);
        for (int j = r[1]; j <= r[3]; ++j)
            for (int i = r[0]; i <= r[2]; ++i)
                ++cellStart[static_cast<size_t>(j) * nx + i + 1];
    }
    for (size_t c = 1; c < cellStart.size(); ++c)
        cellStart[c] += cellStart[c - 1];
    std::vector<Index> cellPatches(static_cast<size_t>(cellStart.back()));
    std::vector<Index> fill(cellStart.begin(), cellStart.end() - 1);
    for (Index p = 0; p < patchCount; ++p) {
        const std::array<int, 4>& r = span[static_cast<size_t>(p)];
        for (int j = r[1]; j <= r[3]; ++j)
            for (int i = r[0]; i <= r[2]; ++i)
                cellPatches[static_cast<size_t>(fill[static_cast<size_t>(j) * nx + i]++)] = p;
    }
    out_.raySample.assign(g.chains.size(), kInvalidIndex);
    rayOrigin_.assign(g.chains.size(), Vec3::Zero());
    auto castRay = [&](Index c) {
        ViewChain& chain = g.chains[c];
        const std::vector<Vec2>& im = chain.image;
        const Index n = static_cast<Index>(im.size());
        // Inner points only, when there are any.
        Index best = n / 2;
        double run = 0.0, bestGap = std::numeric_limits<double>::infinity();
        for (Index i = 0; i < n; ++i) {
            if (i > 0)
                run += (im[i] - im[i - 1]).norm();
            if (n > 2 && (i == 0 || i == n - 1))
                continue;
            const double gap = std::abs(run - 0.5 * chain.lengthPixels);
            if (gap < bestGap) {
                bestGap = gap;
                best = i;
            }
        }
        const SplineSampleRef& ref = out_.samples[c][best];
        const ContourSegment& seg = segments_[ref.segment];
        const QuadraticBezier<Vec3>& patch = spline_.patches[seg.patch];
        const Vec3 p =
            powell_sabin::evaluate(patch, barycentricOf(patch.domain, seg.curve.at(ref.t)));
        int qi = 0;
        if (all.contains(p.head<2>())) {
            int i, j;
            cellOf(p.head<2>(), i, j);
            const size_t cell = static_cast<size_t>(j) * nx + i;
            for (Index k = cellStart[cell]; k < cellStart[cell + 1]; ++k)
                qi += hitsInFront(spline_.patches[cellPatches[static_cast<size_t>(k)]], tau_,
                                  p.head<2>(), p.z(), o_.ray);
        }
        chain.qi = qi;
        chain.rayQi = qi;
        chain.decidedBy = VisibilityRule::RayTest;
        out_.raySample[c] = best;
        rayOrigin_[c] = transform_.invert(p);
    };
    std::vector<Index> queue;
    for (Index c = 0; c < static_cast<Index>(g.chains.size()); ++c)
        if (g.chains[c].closed || g.chains[c].lengthPixels >= o_.minRayChainPixels)
            queue.push_back(c);
    // Each ray writes only its own chain's fields.
    tbb::parallel_for(size_t(0), queue.size(), [&](size_t k) { castRay(queue[k]); });
    g.rayTests += static_cast<long long>(queue.size());
    propagate(queue);
    // Components of short chains only: a ray on the longest chain left.
    std::vector<Index> order(g.chains.size());
    for (size_t c = 0; c < order.size(); ++c)
        order[c] = static_cast<Index>(c);
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
        return g.chains[a].lengthPixels > g.chains[b].lengthPixels;
    });
    for (Index c : order)
        if (g.chains[c].qi < 0) {
            castRay(c);
            ++g.rayTests;
            queue.assign(1, c);
            propagate(queue);
        }
    out_.stats.rays = g.rayTests;
}

// §4.2 propagation from the chains in `queue` to the chains without a QI,
// through T-junctions and cusps whose far side is known (not through cone
// points nor uncertain boundary cusps).
void Builder::propagate(std::vector<Index>& queue) {
    ViewGraph& g = out_.graph;
    auto give = [&](Index to, int qi, Index from, Index via) {
        if (to == kInvalidIndex || g.chains[to].qi >= 0 || qi < 0)
            return;
        ViewChain& chain = g.chains[to];
        chain.qi = qi;
        chain.decidedBy = VisibilityRule::Propagation;
        chain.propagatedFrom = from;
        chain.propagatedVia = via;
        ++out_.stats.propagatedChains;
        queue.push_back(to);
    };
    for (size_t k = 0; k < queue.size(); ++k) {
        const Index c = queue[k];
        const int qi = g.chains[c].qi;
        for (Index v : {g.chains[c].startNode, g.chains[c].endNode}) {
            if (v == kInvalidIndex)
                continue;
            const ViewNode& node = g.nodes[v];
            if (node.type == ViewNodeType::CurtainFold && !node.unreliable) {
                if (node.nearChains[0] == c)
                    give(node.farChains[1], qi + node.qiStep, c, v);
                else if (node.farChains[1] == c)
                    give(node.nearChains[0], qi - node.qiStep, c, v);
            } else if (node.type == ViewNodeType::ImageIntersection) {
                const auto [n0, n1] = node.nearChains;
                const auto [f0, f1] = node.farChains;
                if (c == n0 || c == n1)
                    give(c == n0 ? n1 : n0, qi, c, v);
                else if (c == f0)
                    give(f1, qi + node.qiStep, c, v);
                else if (c == f1)
                    give(f0, qi - node.qiStep, c, v);
            }
        }
    }
}

void Builder::conflict(Index chain, int propagated, Index from, Index via,
                       const std::string& reason) {
    ViewGraph& g = out_.graph;
    ViewChain& c = g.chains[chain];
    c.conflict = true;
    VisibilityConflict x;
    x.chain = chain;
    x.propagatedQi = propagated;
    x.rayQi = c.rayQi;
    x.reason = reason;
    x.fromChain = from;
    x.viaNode = via;
    x.rayOrigin = rayOrigin_[chain];
    g.conflicts.push_back(std::move(x));
}

// The propagation rules of §4.2, checked against the rays (never applied).
void Builder::checkRules() {
    ViewGraph& g = out_.graph;
    for (Index v = 0; v < static_cast<Index>(g.nodes.size()); ++v) {
        const ViewNode& node = g.nodes[v];
        if (node.type == ViewNodeType::CurtainFold) {
            const Index nearC = node.nearChains[0], farC = node.farChains[1];
            if (nearC == kInvalidIndex || farC == kInvalidIndex)
                continue;
            const int nearQi = g.chains[nearC].qi, farQi = g.chains[farC].qi;
            // A boundary cusp whose two branches both leave towards (or both
            // away from) the viewer: its 3D contour kinks in depth as well,
            // and §4.2 gives no rule there (no propagation through boundary
            // cusps); each branch keeps its own ray, and nothing is checked.
            if (node.unreliable) {
                out_.stats.uncheckedCuspSteps += std::abs(farQi - nearQi) != node.qiStep;
                continue;
            }
            const int expected = nearQi + node.qiStep;
            if (farQi != expected)
                conflict(farC, expected, nearC, v, "cusp: far branch != near branch + 1");
        } else if (node.type == ViewNodeType::ImageIntersection) {
            const auto [n0, n1] = node.nearChains;
            if (n0 != kInvalidIndex && n1 != kInvalidIndex && g.chains[n0].qi != g.chains[n1].qi)
                conflict(n1, g.chains[n0].qi, n0, v, "T-junction: near curve changes QI");
            const auto [f0, f1] = node.farChains;
            if (f0 != kInvalidIndex && f1 != kInvalidIndex) {
                const int expected = g.chains[f0].qi + node.qiStep;
                if (g.chains[f1].qi != expected)
                    conflict(f1, expected, f0, v, "T-junction: occluded far piece != far + 2");
            }
        }
    }
    out_.stats.conflicts = static_cast<Index>(g.conflicts.size());
}

SplineViewGraph Builder::run() {
    const Clock::time_point start = Clock::now();
    checkOptions(o_);
    polys_.resize(chaining_.chains.size());
    pending_.assign(chaining_.chains.size(), {});
    for (size_t c = 0; c < chaining_.chains.size(); ++c) {
        polys_[c].chain = &chaining_.chains[c];
        polys_[c].closed = chaining_.chains[c].closed;
        polys_[c].length = static_cast<double>(chaining_.chains[c].links.size());
    }
    out_.stats.contourChains = static_cast<Index>(chaining_.chains.size());

    Clock::time_point t = Clock::now();
    findCusps();
    out_.stats.secondsCusps = secondsSince(t);
    t = Clock::now();
    sample();
    out_.stats.secondsSampling = secondsSince(t);
    addEndNodes();
    t = Clock::now();
    findCrossings();
    out_.stats.secondsIntersections = secondsSince(t);
    t = Clock::now();
    cutChains();
    out_.stats.secondsChains = secondsSince(t);
    t = Clock::now();
    rayTests();
    out_.stats.secondsRays = secondsSince(t);
    t = Clock::now();
    checkRules();
    out_.stats.secondsChecks = secondsSince(t);

    out_.stats.chains = static_cast<Index>(out_.graph.chains.size());
    for (const ViewChain& c : out_.graph.chains) {
        out_.stats.loops += c.closed;
        out_.stats.samples += static_cast<long long>(c.points.size());
    }
    out_.stats.secondsTotal = secondsSince(start);
    return std::move(out_);
}

} // namespace

SplineViewGraph buildSplineViewGraph(const PowellSabinSpline& spline,
                                     std::span<const ContourSegment> segments,
                                     const ContourChaining& chaining, const Camera& camera,
                                     const ProjectiveTransform& transform,
                                     const SplineViewGraphOptions& options) {
    Builder builder(spline, segments, chaining, camera, transform, options);
    return builder.run();
}

} // namespace contour::powell_sabin
