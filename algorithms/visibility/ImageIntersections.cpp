#include "visibility/ImageIntersections.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_sweep_2_algorithms.h>
#include <CGAL/box_intersection_d.h>
#include <algorithm>
#include <map>

namespace contour {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
// Each input segment carries its index; the sweep's subcurves carry the set
// of indices of the input segments they lie on (several where segments
// overlap).
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, Index>;
using Point = Traits::Point_2;
using Curve = Traits::Curve_2;
using Subcurve = Traits::X_monotone_curve_2;

struct PointLess {
    bool operator()(const Point& p, const Point& q) const {
        return CGAL::compare_xy(p, q) == CGAL::SMALLER;
    }
};

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
        CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
            if (candidate[a.info()] && candidate[b.info()])
                return;
            if (!ignorePair(a.info(), b.info()))
                candidate[a.info()] = candidate[b.info()] = 1;
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
    std::vector<Subcurve> subcurves;
    Traits traits;
    CGAL::compute_subcurves(curves.begin(), curves.end(), std::back_inserter(subcurves),
                            /*mult_overlaps=*/false, traits);

    // Every endpoint of a subcurve is an input endpoint or an intersection;
    // the input segments through it are the ones whose subcurves end there.
    std::map<Point, std::vector<Index>, PointLess> through;
    std::map<std::pair<Index, Index>, bool> overlapping;
    for (const Subcurve& sub : subcurves) {
        std::vector<Index> ids(sub.data().begin(), sub.data().end());
        std::sort(ids.begin(), ids.end());
        for (size_t i = 0; i < ids.size(); ++i)
            for (size_t j = i + 1; j < ids.size(); ++j)
                overlapping[{ids[i], ids[j]}] = true;
        for (const Point& p : {sub.source(), sub.target()}) {
            std::vector<Index>& list = through[p];
            list.insert(list.end(), ids.begin(), ids.end());
        }
    }
    for (const auto& [pair, unused] : overlapping)
        result.overlaps.push_back(pair);

    for (auto& [point, ids] : through) {
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        if (ids.size() < 2)
            continue;
        const Vec2 rounded(CGAL::to_double(point.x()), CGAL::to_double(point.y()));
        for (size_t i = 0; i < ids.size(); ++i) {
            for (size_t j = i + 1; j < ids.size(); ++j) {
                if (overlapping.count({ids[i], ids[j]}))
                    continue;
                ImageCrossing crossing;
                crossing.first = ids[i];
                crossing.second = ids[j];
                crossing.point = rounded;
                crossing.interiorFirst =
                    point != ends[ids[i]].first && point != ends[ids[i]].second;
                crossing.interiorSecond =
                    point != ends[ids[j]].first && point != ends[ids[j]].second;
                result.crossings.push_back(crossing);
            }
        }
    }
    return result;
}

} // namespace contour
