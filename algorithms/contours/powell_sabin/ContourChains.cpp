// Chaining of the per-patch contour segments across patch sides and corners
// (Capouellez et al. 2023 §4.2, "View graph construction").
//
// Every segment end gets a place: on a patch side at a parameter, at a patch
// corner (a split-point node), or inside its patch. Ends on a shared side are
// matched with the neighbour's ends by the parameter along the side; ends at
// a corner node with the other ends at that node, by their 3D tangents (the
// contour generator of a C1 surface passes smoothly through a regular point);
// ends inside a patch by their uv. Matching is greedy by increasing gap, so
// the closest pairs win. Cones end chains.
#include "contours/powell_sabin/ContourChains.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace contour::powell_sabin {
namespace {

// r(t) and r'(t) of a rational quadratic, evaluated here so that chaining
// depends only on the contract of PatchContour.h.
void evaluateCurve(const RationalQuadratic& c, double t, Vec2& point, Vec2& derivative) {
    const Eigen::Vector3d powers(1.0, t, t * t);
    const Eigen::Vector3d dpowers(0.0, 1.0, 2.0 * t);
    const Eigen::Vector3d value = c.coefficients * powers;
    const Eigen::Vector3d slope = c.coefficients * dpowers;
    const double w = value.z();
    point = Vec2(value.x(), value.y()) / w;
    derivative =
        (Vec2(slope.x(), slope.y()) * w - Vec2(value.x(), value.y()) * slope.z()) / (w * w);
}

enum class Place { Side, Corner, Interior, BoundarySide };

struct End {
    Index segment = kInvalidIndex;
    bool atT1 = false;
    Index patch = kInvalidIndex;
    int side = -1;
    double t = 0.0; // along `side`
    Vec2 uv = Vec2::Zero();
    Vec3 tangent = Vec3::Zero(); // outgoing unit 3D tangent (into the segment)
    Place place = Place::Interior;
    Index node = kInvalidIndex; // for Corner
    Index partner = -1;         // the matched end
    ChainEnd terminus;          // when the end closes no join
};

std::string describe(const End& e, const PatchAdjacency& adjacency) {
    std::ostringstream s;
    s.precision(17);
    s << "segment " << e.segment << " (patch " << e.patch << ") end at t" << (e.atT1 ? 1 : 0);
    switch (e.place) {
    case Place::Side:
    case Place::BoundarySide: {
        const PatchSideNeighbour& n = adjacency.neighbour(e.patch, e.side);
        s << " on side " << e.side << " (" << toString(n.kind) << ") at parameter " << e.t;
        if (n.patch != kInvalidIndex)
            s << ", nothing on side " << n.side << " of patch " << n.patch << " near "
              << n.map(e.t);
        break;
    }
    case Place::Corner:
        s << " at the " << toString(adjacency.nodeKind(e.node)) << " node " << e.node
          << " (no partner among the ends there)";
        break;
    case Place::Interior:
        s << " inside the patch at uv (" << e.uv.x() << ", " << e.uv.y()
          << "), no other end of the patch there";
        break;
    }
    return s.str();
}

double longestSide(const std::array<Vec2, 3>& d) {
    return std::max({(d[1] - d[0]).norm(), (d[2] - d[1]).norm(), (d[0] - d[2]).norm()});
}

} // namespace

const char* toString(ChainEndKind kind) {
    switch (kind) {
    case ChainEndKind::Cone:
        return "cone";
    case ChainEndKind::Boundary:
        return "boundary";
    case ChainEndKind::Unmatched:
        return "unmatched";
    }
    return "?";
}

ContourChaining chainContours(std::span<const ContourSegment> segments,
                              const PatchAdjacency& adjacency, const PowellSabinSpline& spline,
                              const ContourChainOptions& options) {
    if (!(options.padding >= 0.0 && options.padding <= options.looseTolerance &&
          options.looseTolerance < 0.5))
        throw std::invalid_argument("chainContours: the options need 0 <= padding (" +
                                    std::to_string(options.padding) + ") <= looseTolerance (" +
                                    std::to_string(options.looseTolerance) + ") < 0.5");
    if (static_cast<std::size_t>(adjacency.patchCount()) != spline.patches.size())
        throw std::invalid_argument(
            "chainContours: the adjacency has " + std::to_string(adjacency.patchCount()) +
            " patches, the spline " + std::to_string(spline.patches.size()));

    // Places of all ends: 2i at t0, 2i+1 at t1 of segment i.
    std::vector<End> ends(2 * segments.size());
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const ContourSegment& seg = segments[i];
        const std::string name = "chainContours: segment " + std::to_string(i);
        if (seg.patch < 0 || seg.patch >= adjacency.patchCount())
            throw std::invalid_argument(name + " has patch " + std::to_string(seg.patch) +
                                        ", not in [0, " + std::to_string(adjacency.patchCount()) +
                                        ")");
        if (!(std::isfinite(seg.t0) && std::isfinite(seg.t1) && seg.t0 < seg.t1))
            throw std::invalid_argument(name + " has the interval [" + std::to_string(seg.t0) +
                                        ", " + std::to_string(seg.t1) +
                                        "], not finite with t0 < t1");
        if (seg.startSide < -1 || seg.startSide > 2 || seg.endSide < -1 || seg.endSide > 2)
            throw std::invalid_argument(name + " has sides " + std::to_string(seg.startSide) +
                                        ", " + std::to_string(seg.endSide) + ", not in -1..2");
        const QuadraticBezier<Vec3>& patch = spline.patches[static_cast<std::size_t>(seg.patch)];
        for (int k = 0; k < 2; ++k) {
            End& e = ends[2 * i + k];
            e.segment = static_cast<Index>(i);
            e.atT1 = k == 1;
            e.patch = seg.patch;
            e.side = k == 0 ? seg.startSide : seg.endSide;
            Vec2 d;
            evaluateCurve(seg.curve, k == 0 ? seg.t0 : seg.t1, e.uv, d);
            if (!(std::isfinite(e.uv.x()) && std::isfinite(e.uv.y()) && std::isfinite(d.x()) &&
                  std::isfinite(d.y())))
                throw std::invalid_argument(name + ": its curve is not finite at t" +
                                            std::to_string(k));
            // Outgoing: into the segment from this end.
            if (k == 1)
                d = -d;
            Vec3 du, dv;
            uvDerivatives(patch, barycentricOf(patch.domain, e.uv), du, dv);
            const Vec3 tangent = du * d.x() + dv * d.y();
            if (tangent.norm() > 0.0)
                e.tangent = tangent.normalized();

            if (e.side >= 0) {
                e.t = sideParameter(patch.domain, e.side, e.uv);
                if (e.t <= options.padding) {
                    e.place = Place::Corner;
                    e.node = adjacency.cornerNode(e.patch, e.side);
                } else if (e.t >= 1.0 - options.padding) {
                    e.place = Place::Corner;
                    e.node = adjacency.cornerNode(e.patch, (e.side + 1) % 3);
                } else {
                    e.place = adjacency.neighbour(e.patch, e.side).patch == kInvalidIndex
                                  ? Place::BoundarySide
                                  : Place::Side;
                }
            } else {
                const Vec3 b = barycentricOf(patch.domain, e.uv);
                int corner = 0;
                b.maxCoeff(&corner);
                if (b[corner] >= 1.0 - options.padding) {
                    e.place = Place::Corner;
                    e.node = adjacency.cornerNode(e.patch, corner);
                } else {
                    e.place = Place::Interior;
                }
            }
        }
    }

    ContourChaining result;
    auto join = [&](Index a, Index b) {
        ends[a].partner = b;
        ends[b].partner = a;
    };
    // Candidates (gap, tie-break, a, b), accepted greedily by increasing gap.
    using Candidate = std::tuple<double, int, Index, Index>;
    // The score is a gap (side and interior joins) or a tangent cosine
    // (corner joins).
    auto acceptGreedy = [&](std::vector<Candidate>& candidates, Index& counter, bool isGap) {
        std::sort(candidates.begin(), candidates.end());
        for (const auto& [score, tie, a, b] : candidates) {
            (void)tie;
            if (ends[a].partner >= 0 || ends[b].partner >= 0)
                continue;
            join(a, b);
            ++counter;
            if (isGap) {
                result.maxJoinGap = std::max(result.maxJoinGap, score);
                if (score > options.padding)
                    ++result.looseJoins;
            } else {
                result.maxCornerTangentCosine = std::max(result.maxCornerTangentCosine, score);
            }
        }
    };

    // Sides: ends grouped by the shared side, keyed by its lower (patch,
    // side), with the parameter in that side's direction.
    {
        std::map<Index, std::vector<std::pair<double, Index>>> bySide;
        for (Index e = 0; e < static_cast<Index>(ends.size()); ++e) {
            const End& end = ends[e];
            if (end.place != Place::Side)
                continue;
            const PatchSideNeighbour& n = adjacency.neighbour(end.patch, end.side);
            const Index own = 3 * end.patch + end.side, other = 3 * n.patch + n.side;
            if (own <= other)
                bySide[own].emplace_back(end.t, e);
            else
                bySide[other].emplace_back(n.map(end.t), e);
        }
        std::vector<Candidate> candidates;
        for (auto& [key, list] : bySide) {
            (void)key;
            std::sort(list.begin(), list.end());
            for (std::size_t i = 0; i < list.size(); ++i)
                for (std::size_t j = i + 1;
                     j < list.size() && list[j].first - list[i].first <= options.looseTolerance;
                     ++j) {
                    const End& a = ends[list[i].second];
                    const End& b = ends[list[j].second];
                    if (a.segment == b.segment)
                        continue; // a segment cannot continue into itself at one point
                    // Prefer the neighbour's end over one of the same patch.
                    candidates.emplace_back(list[j].first - list[i].first,
                                            a.patch == b.patch ? 1 : 0, list[i].second,
                                            list[j].second);
                }
        }
        acceptGreedy(candidates, result.sideJoins, true);
    }

    // Side ends left over near a side's end: the partner is at the corner
    // (or across it); they join the corner's ends.
    for (End& e : ends) {
        if (e.partner >= 0 || (e.place != Place::Side && e.place != Place::BoundarySide))
            continue;
        if (e.t <= options.looseTolerance) {
            e.place = Place::Corner;
            e.node = adjacency.cornerNode(e.patch, e.side);
        } else if (e.t >= 1.0 - options.looseTolerance) {
            e.place = Place::Corner;
            e.node = adjacency.cornerNode(e.patch, (e.side + 1) % 3);
        }
    }

    // Corners.
    {
        std::map<Index, std::vector<Index>> byNode;
        for (Index e = 0; e < static_cast<Index>(ends.size()); ++e)
            if (ends[e].place == Place::Corner)
                byNode[ends[e].node].push_back(e);
        for (auto& [node, list] : byNode) {
            if (adjacency.isConeNode(node)) {
                for (Index e : list)
                    ends[e].terminus = {ChainEndKind::Cone, node, ends[e].patch, -1};
                continue;
            }
            std::vector<Candidate> candidates;
            for (std::size_t i = 0; i < list.size(); ++i)
                for (std::size_t j = i + 1; j < list.size(); ++j) {
                    const double cosine = ends[list[i]].tangent.dot(ends[list[j]].tangent);
                    // Two ends at a regular point are one contour passing
                    // through; with more, only opposite tangents pair up.
                    if (list.size() == 2 || cosine < 0.0)
                        candidates.emplace_back(cosine, 0, list[i], list[j]);
                }
            acceptGreedy(candidates, result.cornerJoins, false);
            if (adjacency.isBoundaryNode(node))
                for (Index e : list)
                    if (ends[e].partner < 0)
                        ends[e].terminus = {ChainEndKind::Boundary, node, ends[e].patch, -1};
        }
    }

    // Inside patches: the ends of ellipse halves.
    {
        std::map<Index, std::vector<Index>> byPatch;
        for (Index e = 0; e < static_cast<Index>(ends.size()); ++e)
            if (ends[e].place == Place::Interior)
                byPatch[ends[e].patch].push_back(e);
        std::vector<Candidate> candidates;
        for (auto& [patch, list] : byPatch) {
            const double scale =
                longestSide(spline.patches[static_cast<std::size_t>(patch)].domain);
            for (std::size_t i = 0; i < list.size(); ++i)
                for (std::size_t j = i + 1; j < list.size(); ++j) {
                    const double gap = (ends[list[i]].uv - ends[list[j]].uv).norm() / scale;
                    if (gap <= options.looseTolerance)
                        candidates.emplace_back(gap, 0, list[i], list[j]);
                }
        }
        acceptGreedy(candidates, result.interiorJoins, true);
    }

    // Termini: boundary sides; everything else without a partner is an error.
    for (End& e : ends) {
        if (e.partner >= 0 || e.terminus.kind != ChainEndKind::Unmatched)
            continue;
        if (e.place == Place::BoundarySide) {
            e.terminus = {ChainEndKind::Boundary, kInvalidIndex, e.patch, e.side};
            continue;
        }
        e.terminus = {ChainEndKind::Unmatched, e.place == Place::Corner ? e.node : kInvalidIndex,
                      e.patch, e.place == Place::Side ? e.side : -1};
        if (result.unmatchedEnds++ == 0)
            result.firstUnmatched = describe(e, adjacency);
    }

    // Walk: open chains from their termini first, then the loops.
    std::vector<char> used(segments.size(), 0);
    auto walk = [&](Index entry, ContourChain& chain) {
        // `entry` is the end through which the chain enters a segment.
        Index current = entry;
        for (;;) {
            const Index segment = current / 2;
            if (used[segment])
                throw std::logic_error("chainContours: segment " + std::to_string(segment) +
                                       " reached twice");
            used[segment] = 1;
            chain.links.push_back({segment, (current & 1) != 0});
            const Index exit = current ^ 1;
            const Index next = ends[exit].partner;
            if (next < 0) {
                chain.back = ends[exit].terminus;
                return;
            }
            if (next == entry) {
                chain.closed = true;
                return;
            }
            current = next;
        }
    };
    for (Index e = 0; e < static_cast<Index>(ends.size()); ++e) {
        if (ends[e].partner >= 0 || used[e / 2])
            continue;
        ContourChain chain;
        chain.front = ends[e].terminus;
        walk(e, chain);
        result.chains.push_back(std::move(chain));
    }
    for (Index s = 0; s < static_cast<Index>(segments.size()); ++s) {
        if (used[s])
            continue;
        ContourChain chain;
        walk(2 * s, chain);
        if (!chain.closed)
            throw std::logic_error("chainContours: a chain without termini did not close");
        result.chains.push_back(std::move(chain));
    }

    for (const ContourChain& c : result.chains) {
        if (c.closed) {
            ++result.closedLoops;
            continue;
        }
        ++result.openChains;
        for (const ChainEnd* end : {&c.front, &c.back}) {
            if (end->kind == ChainEndKind::Cone)
                ++result.coneEnds;
            else if (end->kind == ChainEndKind::Boundary)
                ++result.boundaryEnds;
        }
    }
    return result;
}

} // namespace contour::powell_sabin
