#include "visibility/ImageIntersections.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_sweep_2.h>
#include <CGAL/Surface_sweep_2/Default_visitor.h>
#include <CGAL/Surface_sweep_2/Surface_sweep_2_utils.h>
#include <CGAL/box_intersection_d.h>
#include <algorithm>
#include <optional>
#include <set>

namespace contour {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Filter = CGAL::Exact_predicates_inexact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
// Each input segment carries its index; the sweep's subcurves carry the set
// of indices of the input segments they lie on (several where segments
// overlap).
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, Index>;
using Point = Traits::Point_2;
using Curve = Traits::Curve_2;

// The sweep's own events name the points where segments meet: CGAL's
// surface sweep (Bentley–Ottmann) handles each distinct point once, in xy
// order, and every subcurve ends at the event being handled when it is
// reported (add_subcurve) and starts at an event among its right curves.
// So the input segments through an event's point are the data of the
// subcurves reported while handling it and of its right curves; no map of
// exact points is needed afterwards (that map cost more than the sweep:
// about 1M exact point comparisons on a 118k-face consistent mesh).
class MeetingVisitor : public CGAL::Surface_sweep_2::Default_visitor<MeetingVisitor, Traits> {
public:
    using Base = CGAL::Surface_sweep_2::Default_visitor<MeetingVisitor, Traits>;
    using Event = Base::Event;
    using Subcurve = Base::Subcurve;
    using Status_line_iterator = Subcurve::Status_line_iterator;
    using Surface_sweep = CGAL::Surface_sweep_2::Surface_sweep_2<MeetingVisitor>;
    using Subcurve_xm = Traits::X_monotone_curve_2;

    // Called with the event's point and the sorted, distinct indices of the
    // input segments through it, when there are two or more.
    std::function<void(const Point&, const std::vector<Index>&)> onMeeting;
    // Pairs of input segments that share a subcurve (collinear overlaps).
    std::set<std::pair<Index, Index>> overlapping;

    template <typename CurveIterator> void sweep(CurveIterator begin, CurveIterator end) {
        std::vector<Subcurve_xm> curves;
        std::vector<Point> points;
        curves.reserve(static_cast<size_t>(std::distance(begin, end)));
        CGAL::Surface_sweep_2::make_x_monotone(begin, end, std::back_inserter(curves),
                                               std::back_inserter(points), this->traits());
        this->surface_sweep()->sweep(curves.begin(), curves.end(), points.begin(), points.end());
    }

    void add_subcurve(const Subcurve_xm& curve, Subcurve*) { addData(curve.data()); }

    bool after_handle_event(Event* event, Status_line_iterator, bool) {
        for (auto it = event->right_curves_begin(); it != event->right_curves_end(); ++it)
            addData((*it)->last_curve().data());
        std::sort(ids_.begin(), ids_.end());
        ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
        if (ids_.size() >= 2 && onMeeting)
            onMeeting(event->point(), ids_);
        ids_.clear();
        return true;
    }

private:
    std::vector<Index> ids_;

    template <typename Data> void addData(const Data& data) {
        const size_t first = ids_.size();
        ids_.insert(ids_.end(), data.begin(), data.end());
        if (ids_.size() - first < 2)
            return;
        std::vector<Index> shared(ids_.begin() + static_cast<std::ptrdiff_t>(first), ids_.end());
        std::sort(shared.begin(), shared.end());
        for (size_t i = 0; i < shared.size(); ++i)
            for (size_t j = i + 1; j < shared.size(); ++j)
                overlapping.emplace(shared[i], shared[j]);
    }
};

// Where two segments known to cross inside both (exactly) meet, in double:
// a + t (b − a) with t from the two cross products.
Vec2 crossingPoint(const ImageSegment& s, const ImageSegment& o) {
    const Vec2 d = s.b - s.a, e = o.b - o.a;
    const double denominator = d.x() * e.y() - d.y() * e.x();
    const Vec2 w = o.a - s.a;
    const double t = denominator != 0.0
                         ? std::clamp((w.x() * e.y() - w.y() * e.x()) / denominator, 0.0, 1.0)
                         : 0.0;
    return s.a + t * d;
}

} // namespace

ImageIntersectionResult imageIntersections(std::span<const ImageSegment> segments,
                                           const std::function<bool(Index, Index)>& ignorePair) {
    ImageIntersectionResult result;
    // Which segments may take part in a wanted crossing: their boxes
    // overlap (closed boxes: touching counts) one of a pair not ignored.
    std::vector<std::uint8_t> candidate(segments.size(), ignorePair ? 0 : 1);
    if (ignorePair) {
        using Box =
            CGAL::Box_intersection_d::Box_with_info_d<double, 2, Index,
                                                      CGAL::Box_intersection_d::ID_EXPLICIT>;
        std::vector<Box> boxes;
        boxes.reserve(segments.size());
        for (size_t i = 0; i < segments.size(); ++i) {
            const Vec2 lo = segments[i].a.cwiseMin(segments[i].b);
            const Vec2 hi = segments[i].a.cwiseMax(segments[i].b);
            boxes.emplace_back(CGAL::Bbox_2(lo.x(), lo.y(), hi.x(), hi.y()), static_cast<Index>(i));
        }
        // Of two segments whose boxes overlap, only those that really meet
        // (closed segments, exact predicates on the input doubles) can give
        // a wanted crossing; on consistent meshes most box overlaps are
        // neighbouring segments of one curve, which meet at a shared vertex
        // and are ignored, or do not meet at all.
        std::vector<Filter::Segment_2> exact(segments.size());
        for (size_t i = 0; i < segments.size(); ++i)
            exact[i] = {{segments[i].a.x(), segments[i].a.y()},
                        {segments[i].b.x(), segments[i].b.y()}};
        CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
            const Index i = a.info(), j = b.info();
            if (candidate[i] && candidate[j])
                return;
            if (exact[i].is_degenerate() || exact[j].is_degenerate() ||
                !CGAL::do_intersect(exact[i], exact[j]))
                return;
            if (!ignorePair(i, j))
                candidate[i] = candidate[j] = 1;
        });
    }
    std::vector<Curve> curves;
    std::vector<std::pair<Point, Point>> ends(segments.size());
    curves.reserve(segments.size());
    for (size_t i = 0; i < segments.size(); ++i) {
        const Point a(segments[i].a.x(), segments[i].a.y());
        const Point b(segments[i].b.x(), segments[i].b.y());
        ends[i] = {a, b};
        if (a == b) {
            ++result.degenerateSegments;
            continue;
        }
        if (candidate[i])
            curves.emplace_back(SegmentTraits::Curve_2(a, b), static_cast<Index>(i));
    }
    result.sweptSegments = static_cast<long long>(curves.size());
    // Crossings at each meeting point, in the sweep's xy order; pairs that
    // overlap along a piece are reported as overlaps instead.
    std::vector<std::pair<Point, std::vector<Index>>> meetings;
    Traits traits;
    MeetingVisitor visitor;
    visitor.onMeeting = [&](const Point& p, const std::vector<Index>& ids) {
        meetings.emplace_back(p, ids);
    };
    MeetingVisitor::Surface_sweep sweep(&traits, &visitor);
    visitor.sweep(curves.begin(), curves.end());
    result.overlaps.assign(visitor.overlapping.begin(), visitor.overlapping.end());

    std::vector<std::uint8_t> interior;
    for (const auto& [point, ids] : meetings) {
        interior.assign(ids.size(), 0);
        // The point's position: exact input coordinates at a segment's end;
        // otherwise two segments' crossing computed in double (a few ulps; an
        // exact evaluation then rounding cost ~11 µs per point with GMP,
        // more than the sweep). Only the topology (who meets whom, at an end
        // or inside) is decided exactly; the builder uses the point for
        // parameters along the segments and the node's pixel.
        std::optional<Vec2> rounded;
        for (size_t i = 0; i < ids.size(); ++i) {
            const bool atFirst = point == ends[ids[i]].first;
            const bool atSecond = !atFirst && point == ends[ids[i]].second;
            interior[i] = !atFirst && !atSecond;
            if (!rounded && !interior[i])
                rounded = atFirst ? segments[ids[i]].a : segments[ids[i]].b;
        }
        if (!rounded)
            rounded = crossingPoint(segments[ids[0]], segments[ids[1]]);
        for (size_t i = 0; i < ids.size(); ++i) {
            for (size_t j = i + 1; j < ids.size(); ++j) {
                if (visitor.overlapping.count({ids[i], ids[j]}))
                    continue;
                ImageCrossing crossing;
                crossing.first = ids[i];
                crossing.second = ids[j];
                crossing.point = *rounded;
                crossing.interiorFirst = interior[i] != 0;
                crossing.interiorSecond = interior[j] != 0;
                result.crossings.push_back(crossing);
            }
        }
    }
    return result;
}

} // namespace contour
