#include "visibility/ViewGraphBuilder.h"

#include "core/Predicates.h"
#include "core/SmallLoopCrossings.h"
#include "visibility/ImageIntersections.h"
#include "visibility/LocalOcclusion.h"
#include "visibility/NearFaceTest.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour {

namespace {

// Where a node cuts a curve: segment `segment` at parameter `tau` in [0, 1)
// (3D, from point `segment` towards the next one). Vertex cuts have tau 0.
struct Cut {
    Index segment = 0;
    double tau = 0.0;
    Index node = kInvalidIndex;
    enum class Role { Vertex, Near, Far, Plain } role = Role::Plain;
    // Vertex: whether the curve has an edge before/after the point, and the
    // one-ring occluders of each (tutorial app. C.2).
    bool hasBefore = false, hasAfter = false;
    int occBefore = 0, occAfter = 0;
    // At a smooth cusp: the radial curvature of the branch before/after
    // (branchCurvature()).
    double kappaBefore = 0.0, kappaAfter = 0.0;
    // Far: the part of the far curve before the cut is the occluded one.
    bool occludedBefore = false;
    Index chainBefore = kInvalidIndex, chainAfter = kInvalidIndex;
};

bool cutLess(const Cut& a, const Cut& b) {
    return a.segment != b.segment ? a.segment < b.segment : a.tau < b.tau;
}

// A curve edge at a mesh vertex (tutorial §4.6 step 4: on-surface
// singularities are found by iterating over vertices).
struct Incidence {
    Index curve;
    Index point;   // the vertex's index in the curve
    Index segment; // the curve segment of this edge
    bool after;    // the edge follows the point in curve order
    Index other;   // the edge's other vertex
};

// Exterior/interior classification of a contour edge.
struct EdgeClass {
    bool known = false; // computed (classifyCurveEdges)
    bool concave = false;
    bool unreliable = false;
};

class Builder {
public:
    Builder(const ViewGraphInput& input, const Camera& camera, const ViewGraphOptions& options,
            ViewGraphBuildStats& stats)
        : mesh_(*input.mesh), curves_(*input.curves), secondFaces_(input.secondFaces),
          orientation_(*input.faceOrientation),
          facing_(input.facing ? input.facing : input.faceOrientation),
          cuspVertex_(input.cuspVertex), singularCusp_(input.singularCusp),
          radialCurvature_(input.radialCurvature), faceInconsistent_(input.faceInconsistent),
          camera_(camera), options_(options), stats_(stats), cuts_(curves_.size()) {
        if (options_.foldTest == CurtainFoldTest::SmoothCusps &&
            (!cuspVertex_ || !radialCurvature_ || !faceInconsistent_))
            throw std::invalid_argument(
                "buildViewGraph: smooth-cusp curtain folds need cusp, radial curvature and "
                "inconsistent-face fields");
    }

    ViewGraph build() {
        classifyCurveEdges();
        vertexNodes();
        curveCusps();
        boundaryJunctionsInFaces();
        surfaceIntersectionEnds();
        imageIntersectionNodes();
        curveEnds();
        makeChains();
        fillNodes();
        return std::move(graph_);
    }

private:
    const TriangleMesh& mesh_;
    const std::vector<Polyline>& curves_;
    const std::vector<std::vector<Index>>* secondFaces_;
    const std::vector<int>& orientation_;
    const std::vector<int>* facing_;
    const std::vector<std::uint8_t>* cuspVertex_;
    const std::vector<std::uint8_t>* singularCusp_;
    const std::vector<double>* radialCurvature_;
    const std::vector<std::uint8_t>* faceInconsistent_;
    const Camera& camera_;
    const ViewGraphOptions& options_;
    ViewGraphBuildStats& stats_;
    std::vector<std::vector<Cut>> cuts_;
    std::vector<EdgeClass> edgeClass_; // per mesh edge, see classifyCurveEdges
    ViewGraph graph_;

    Index segmentCount(Index c) const { return static_cast<Index>(curves_[c].segmentCount()); }
    const CurvePoint& point(Index c, Index k) const {
        const Polyline& line = curves_[c];
        return line.points[static_cast<size_t>(k) % line.points.size()];
    }
    // The point at parameter tau of segment s (exact at tau 0 and 1).
    Vec3 pointAt(Index c, Index s, double tau) const {
        const Vec3& a = point(c, s).position;
        if (tau == 0.0)
            return a;
        const Vec3& b = point(c, s + 1).position;
        if (tau == 1.0)
            return b;
        return a + tau * (b - a);
    }

    Index addNode(ViewNodeType type, const Vec3& position) {
        ViewNode node;
        node.type = type;
        node.position = position;
        node.image = camera_.project(position).pixel;
        graph_.nodes.push_back(std::move(node));
        return static_cast<Index>(graph_.nodes.size() - 1);
    }

    // Tutorial app. C (convexity) or Bénard 2014 footnote 3 (near face).
    EdgeClass computeClass(Index e) const {
        EdgeClass result;
        result.known = true;
        const Index h = mesh_.edgeHalfedge(e);
        const Index o = mesh_.opposite(h);
        if (o != kInvalidIndex) {
            const Vec3& a = mesh_.position(mesh_.from(h));
            const Vec3& b = mesh_.position(mesh_.to(h));
            const Vec3& p1 = mesh_.position(mesh_.to(TriangleMesh::next(h)));
            const Vec3& p2 = mesh_.position(mesh_.to(TriangleMesh::next(o)));
            if (options_.foldTest == CurtainFoldTest::Convexity) {
                // Edge ab with triangles abd and bae is concave iff
                // FRONTSIDE(a, b, d, e) > 0 (tutorial app. C).
                result.concave = frontSide(a, b, p1, p2) > 0;
            } else if (options_.foldTest == CurtainFoldTest::NearFace ||
                       options_.foldTest == CurtainFoldTest::SmoothCusps) {
                // Bénard 2014 §8.1: exterior iff the near face (footnote 3)
                // has a front-facing VBO.
                const NearFace near = nearFace(mesh_, camera_, e);
                result.concave = !(orientation_[near.face] > 0);
                result.unreliable = near.margin < options_.nearFaceEpsilon;
            }
        }
        return result;
    }
    EdgeClass classify(Index e) const {
        const EdgeClass& known = edgeClass_[static_cast<size_t>(e)];
        return known.known ? known : computeClass(e);
    }

    // The contour edges' classes (the only ones asked for: curtain folds
    // and concave chains), computed once each, in parallel.
    void classifyCurveEdges() {
        edgeClass_.assign(static_cast<size_t>(mesh_.edgeCount()), EdgeClass{});
        std::vector<Index> edges;
        std::vector<std::uint8_t> listed(static_cast<size_t>(mesh_.edgeCount()), 0);
        for (const Polyline& line : curves_) {
            if (line.source != SegmentSource::MeshEdge || line.type != CurveType::Contour)
                continue;
            for (Index e : line.segmentElement)
                if (e != kInvalidIndex && !listed[static_cast<size_t>(e)]) {
                    listed[static_cast<size_t>(e)] = 1;
                    edges.push_back(e);
                }
        }
        tbb::parallel_for(size_t(0), edges.size(), [&](size_t k) {
            edgeClass_[static_cast<size_t>(edges[k])] = computeClass(edges[k]);
        });
    }

    void addCut(Index c, Cut cut) { cuts_[c].push_back(cut); }

    // The radial curvature of curve c's branch leaving point k forwards
    // (after) or backwards: the sum over the next few curve vertices, up to
    // another cusp (the value at the cusp itself is about 0; a few vertices
    // away its sign is the branch's). NaN values are skipped; 0 when none.
    double branchCurvature(Index c, Index k, bool after) const {
        constexpr int kVertices = 3;
        const Polyline& line = curves_[c];
        const Index n = static_cast<Index>(line.points.size());
        double sum = 0.0;
        for (int j = 1; j <= kVertices; ++j) {
            Index i = after ? k + j : k - j;
            if (line.closed)
                i = ((i % n) + n) % n;
            else if (i < 0 || i >= n)
                break;
            const Index v = line.points[static_cast<size_t>(i)].vertex;
            if (v == kInvalidIndex || (*cuspVertex_)[static_cast<size_t>(v)])
                break;
            const double kappa = (*radialCurvature_)[static_cast<size_t>(v)];
            if (std::isfinite(kappa))
                sum += kappa;
        }
        return sum;
    }

    // Whether a face of v's one-ring is inconsistent (SmoothCusps).
    bool nextToInconsistentFace(Index v) const {
        for (Index f : vertexFaces(mesh_, v))
            if ((*faceInconsistent_)[static_cast<size_t>(f)] != 0)
                return true;
        return false;
    }

    // Curtain folds, boundary curtain folds, Y junctions, bifurcations and
    // open ends at mesh vertices (tutorial §4.3 items 2–5, §4.6 steps 3–4).
    void vertexNodes() {
        // The curve edges at each vertex, in curve order (a stable sort by
        // vertex of the list in curve order).
        struct At {
            Index vertex;
            Incidence incidence;
        };
        std::vector<At> at;
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            if (line.source != SegmentSource::MeshEdge ||
                line.type == CurveType::SurfaceIntersection)
                continue;
            const Index n = segmentCount(c);
            for (Index s = 0; s < n; ++s) {
                const Index va = point(c, s).vertex, vb = point(c, s + 1).vertex;
                if (va == kInvalidIndex || vb == kInvalidIndex)
                    continue;
                const Index pb = line.closed ? (s + 1) % n : s + 1;
                at.push_back({va, {c, s, s, true, vb}});
                at.push_back({vb, {c, pb, s, false, va}});
            }
        }
        std::stable_sort(at.begin(), at.end(),
                         [](const At& x, const At& y) { return x.vertex < y.vertex; });
        std::vector<size_t> groups;
        for (size_t k = 0; k < at.size(); ++k)
            if (k == 0 || at[k].vertex != at[k - 1].vertex)
                groups.push_back(k);
        groups.push_back(at.size());

        // Per vertex, independently (in parallel): the one-ring occluders of
        // each curve edge (tutorial app. C.2) and the node type.
        struct Decision {
            ViewNodeType type = ViewNodeType::CurveEnd;
            bool isNode = false;
            bool unreliable = false;
            bool localOnly = false;
            bool smoothCusp = false; // SmoothCusps: a cusp vertex
            bool singularCusp = false; // SmoothCusps: a cusp vertex at a singular point
            bool fallback = false;   // SmoothCusps: the near-face test next to inconsistency
            bool zigZag = false;     // SmoothCusps: a mesh-only fold, not made a node
        };
        std::vector<int> occ(at.size(), 0);
        std::vector<Decision> decisions(groups.size() - 1);
        tbb::parallel_for(size_t(0), decisions.size(), [&](size_t g) {
            const size_t first = groups[g], count = groups[g + 1] - first;
            const Index v = at[first].vertex;
            auto list = [&](size_t i) -> const Incidence& {
                return at[first + i].incidence;
            };
            int contours = 0, boundaries = 0;
            for (size_t i = 0; i < count; ++i)
                (curves_[list(i).curve].type == CurveType::Contour ? contours : boundaries)++;
            for (size_t i = 0; i < count; ++i)
                occ[first + i] = oneRingOccluders(mesh_, camera_, v, list(i).other);

            Decision& d = decisions[g];
            d.isNode = true;
            if (contours > 0 && boundaries > 0)
                d.type = ViewNodeType::ContourBoundaryJunction;
            else if (contours > 2 || boundaries > 2)
                d.type = ViewNodeType::Bifurcation;
            else if (count == 1)
                d.type = ViewNodeType::CurveEnd;
            else if (list(0).curve != list(1).curve)
                d.type = ViewNodeType::Bifurcation; // two curve ends meeting: keep them linked
            else if (contours == 2) {
                const EdgeClass e0 =
                    classify(curves_[list(0).curve].segmentElement[list(0).segment]);
                const EdgeClass e1 =
                    classify(curves_[list(1).curve].segmentElement[list(1).segment]);
                d.type = ViewNodeType::CurtainFold;
                // Tutorial §4.3 item 3 (convex meets concave), or the general
                // definition of item 4: one edge is occluded by the one-ring
                // and the other is not (on consistent meshes the generator
                // also runs over edges that are no fold of the mesh).
                const int o0 = occ[first], o1 = occ[first + 1];
                const bool meshFold = e0.concave != e1.concave || o0 != o1;
                if (options_.foldTest == CurtainFoldTest::SmoothCusps &&
                    (*cuspVertex_)[static_cast<size_t>(v)]) {
                    // A cusp at a singular point of the surface stays a
                    // node (the oracle counts it) but is no smooth fold:
                    // the one-ring test decides its side and step, which
                    // may be none.
                    d.isNode = true;
                    d.singularCusp = singularCusp_ && (*singularCusp_)[static_cast<size_t>(v)];
                    d.smoothCusp = !d.singularCusp;
                } else if (options_.foldTest == CurtainFoldTest::SmoothCusps &&
                           !nextToInconsistentFace(v)) {
                    d.isNode = false;
                    d.zigZag = meshFold;
                } else {
                    d.isNode = meshFold;
                    d.localOnly = e0.concave == e1.concave && o0 != o1;
                    d.unreliable = e0.unreliable || e1.unreliable;
                    d.fallback = meshFold && options_.foldTest == CurtainFoldTest::SmoothCusps;
                }
            } else {
                // Tutorial app. C.2: exactly one of the two boundary edges is
                // occluded by a face of the one-ring.
                d.type = ViewNodeType::BoundaryCurtainFold;
                d.isNode = (occ[first] > 0) != (occ[first + 1] > 0);
            }
        });

        // The nodes, in vertex order.
        for (size_t g = 0; g + 1 < groups.size(); ++g) {
            const Decision& d = decisions[g];
            stats_.localOnlyFolds += d.localOnly;
            stats_.zigZagsIgnored += d.zigZag;
            stats_.fallbackFolds += d.fallback;
            stats_.smoothCuspFolds += d.smoothCusp;
            stats_.singularCuspFolds += d.singularCusp;
            if (!d.isNode)
                continue;
            const size_t first = groups[g], count = groups[g + 1] - first;
            const Index v = at[first].vertex;
            const Index node = addNode(d.type, mesh_.position(v));
            graph_.nodes[node].meshVertex = v;
            graph_.nodes[node].unreliable = d.unreliable;
            graph_.nodes[node].smoothCusp = d.smoothCusp;
            graph_.nodes[node].singularCusp = d.singularCusp;
            stats_.unreliableFolds += d.unreliable;
            // One cut per (curve, point); both edges of a curve through the
            // vertex share it.
            std::map<std::pair<Index, Index>, Cut> perPoint;
            for (size_t i = 0; i < count; ++i) {
                const Incidence& incidence = at[first + i].incidence;
                Cut& cut = perPoint[{incidence.curve, incidence.point}];
                cut.segment = incidence.point;
                cut.tau = 0.0;
                cut.node = node;
                cut.role = Cut::Role::Vertex;
                if (incidence.after) {
                    cut.hasAfter = true;
                    cut.occAfter = occ[first + i];
                    if (d.smoothCusp)
                        cut.kappaAfter = branchCurvature(incidence.curve, incidence.point, true);
                } else {
                    cut.hasBefore = true;
                    cut.occBefore = occ[first + i];
                    if (d.smoothCusp)
                        cut.kappaBefore = branchCurvature(incidence.curve, incidence.point, false);
                }
            }
            for (const auto& [key, cut] : perPoint)
                addCut(key.first, cut);
        }
    }

    // The mesh-edge curve segment on each edge (contours and boundaries).
    std::map<Index, std::pair<Index, Index>> edgeSegments() const {
        std::map<Index, std::pair<Index, Index>> result;
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            if (line.source != SegmentSource::MeshEdge)
                continue;
            for (Index s = 0; s < segmentCount(c); ++s)
                result[line.segmentElement[s]] = {c, s};
        }
        return result;
    }

    double tauOnSegment(Index c, Index s, const Vec3& p) const {
        const Vec3 a = point(c, s).position, b = point(c, s + 1).position;
        const double len2 = (b - a).squaredNorm();
        return len2 > 0.0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
    }

    // Interpolated contours end inside boundary edges (tutorial app. C.1: a
    // smooth curve meets a boundary iff it ends on the same mesh edge).
    void boundaryJunctionsInFaces() {
        std::map<Index, std::pair<Index, Index>> onEdge;
        for (const auto& [e, ref] : edgeSegments())
            if (curves_[ref.first].type == CurveType::Boundary)
                onEdge[e] = ref;
        if (onEdge.empty())
            return;
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            if (line.source != SegmentSource::Face || line.type != CurveType::Contour ||
                line.closed || line.points.size() < 2)
                continue;
            for (const bool atEnd : {false, true}) {
                const CurvePoint& p = atEnd ? line.points.back() : line.points.front();
                const auto found = onEdge.find(p.edge);
                if (p.edge == kInvalidIndex || found == onEdge.end())
                    continue;
                const Index node = addNode(ViewNodeType::ContourBoundaryJunction, p.position);
                Cut own;
                own.segment = atEnd ? segmentCount(c) : 0;
                own.node = node;
                addCut(c, own);
                const auto [bc, bs] = found->second;
                Cut onBoundary;
                onBoundary.segment = bs;
                onBoundary.tau = tauOnSegment(bc, bs, p.position);
                onBoundary.node = node;
                addCut(bc, onBoundary);
            }
        }
    }

    // Surface-intersection curves crossing a contour or boundary edge on the
    // surface (tutorial §4.3 item 2, Bénard 2014 §8.2: handled logically, by
    // the edge the intersection point lies on, not by the 2D sweep).
    void surfaceIntersectionEnds() {
        bool any = false;
        for (const Polyline& line : curves_)
            any |= line.type == CurveType::SurfaceIntersection;
        if (!any)
            return;
        const std::map<Index, std::pair<Index, Index>> onEdge = edgeSegments();
        const double tolerance = 1e-9 * std::max(mesh_.boundingBox().diagonal(), 1e-300);
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            if (line.type != CurveType::SurfaceIntersection)
                continue;
            const Index n = segmentCount(c);
            for (Index k = 0; k < static_cast<Index>(line.points.size()); ++k) {
                const CurvePoint& p = line.points[k];
                // The point lies on both sheets; it may sit on an edge of a
                // face of either (CurvePoint::edge names one of them), so
                // every edge of the faces of its two segments is a candidate.
                std::vector<Index> edges;
                if (p.edge != kInvalidIndex)
                    edges.push_back(p.edge);
                for (const Index s : {k - 1, k}) {
                    if (s < 0 && !line.closed)
                        continue;
                    if (s >= n)
                        continue;
                    const Index sm = (s + n) % n;
                    std::vector<Index> faces = {line.segmentElement[sm]};
                    if (secondFaces_ && c < static_cast<Index>(secondFaces_->size()) &&
                        sm < static_cast<Index>((*secondFaces_)[c].size()))
                        faces.push_back((*secondFaces_)[c][sm]);
                    for (Index f : faces)
                        if (f != kInvalidIndex)
                            for (int corner = 0; corner < 3; ++corner)
                                edges.push_back(mesh_.edge(TriangleMesh::halfedge(f, corner)));
                }
                std::sort(edges.begin(), edges.end());
                edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
                Index node = kInvalidIndex;
                for (Index e : edges) {
                    const auto found = onEdge.find(e);
                    if (found == onEdge.end())
                        continue;
                    const auto [oc, os] = found->second;
                    if (curves_[oc].type == CurveType::SurfaceIntersection)
                        continue;
                    const double tau = tauOnSegment(oc, os, p.position);
                    if (e != p.edge && (pointAt(oc, os, tau) - p.position).norm() > tolerance)
                        continue; // the curve crosses the face, not this edge
                    if (node == kInvalidIndex) {
                        node = addNode(ViewNodeType::SurfaceIntersectionEnd, p.position);
                        Cut own;
                        own.segment = k;
                        own.node = node;
                        addCut(c, own);
                    }
                    Cut other;
                    other.segment = os;
                    other.tau = tau;
                    other.node = node;
                    addCut(oc, other);
                }
            }
        }
    }

    // The mesh vertices a segment touches (app. C.1: segments that share one
    // meet logically, not as an image-space T-junction).
    std::vector<Index> segmentVertices(Index c, Index s) const {
        const Polyline& line = curves_[c];
        std::vector<Index> v;
        auto addFace = [&](Index f) {
            if (f == kInvalidIndex)
                return;
            for (Index x : mesh_.triangle(f))
                v.push_back(x);
        };
        if (line.source == SegmentSource::MeshEdge) {
            const Index h = mesh_.edgeHalfedge(line.segmentElement[s]);
            v = {mesh_.from(h), mesh_.to(h)};
        } else {
            addFace(line.segmentElement[s]);
            if (secondFaces_ && c < static_cast<Index>(secondFaces_->size()) &&
                s < static_cast<Index>((*secondFaces_)[c].size()))
                addFace((*secondFaces_)[c][s]);
        }
        std::sort(v.begin(), v.end());
        return v;
    }

    // A curve segment, or (curve = kInvalidIndex) a mesh fold edge that is
    // not on any curve but occludes like one (see ViewGraphOptions).
    struct Ref {
        Index curve, segment; // for a fold edge: kInvalidIndex, the edge
    };
    // An image crossing where the far curve is split (tutorial §4.6 step 5).
    struct Junction {
        Ref nearRef, farRef;
        double tau[2] = {0.0, 0.0}; // near, far
        Vec3 at[2];                 // near, far
        Vec2 image = Vec2::Zero();
        CurveType nearType = CurveType::Contour;
        bool startOccluded = false;
    };
    Vec3 refPoint(const Ref& r, int end) const {
        if (r.curve != kInvalidIndex)
            return point(r.curve, r.segment + end).position;
        const Index h = mesh_.edgeHalfedge(r.segment);
        return mesh_.position(end == 0 ? mesh_.from(h) : mesh_.to(h));
    }
    SegmentSource refSource(const Ref& r) const {
        return r.curve == kInvalidIndex ? SegmentSource::MeshEdge : curves_[r.curve].source;
    }
    Index refElement(const Ref& r) const {
        return r.curve == kInvalidIndex ? r.segment : curves_[r.curve].segmentElement[r.segment];
    }
    CurveType refType(const Ref& r) const {
        return r.curve == kInvalidIndex ? CurveType::Contour : curves_[r.curve].type;
    }
    std::vector<Index> refVertices(const Ref& r) const {
        if (r.curve != kInvalidIndex)
            return segmentVertices(r.curve, r.segment);
        const Index h = mesh_.edgeHalfedge(r.segment);
        std::vector<Index> v = {mesh_.from(h), mesh_.to(h)};
        std::sort(v.begin(), v.end());
        return v;
    }
    // The faces a surface-intersection segment lies on (empty otherwise).
    std::vector<Index> intersectionFaces(const Ref& r) const {
        std::vector<Index> faces;
        if (r.curve == kInvalidIndex || curves_[r.curve].type != CurveType::SurfaceIntersection)
            return faces;
        faces.push_back(curves_[r.curve].segmentElement[r.segment]);
        if (secondFaces_ && r.curve < static_cast<Index>(secondFaces_->size()) &&
            r.segment < static_cast<Index>((*secondFaces_)[r.curve].size()))
            faces.push_back((*secondFaces_)[r.curve][r.segment]);
        return faces;
    }
    // Segments of curves off the mesh meet where they share a point: only
    // neighbours along one curve (the last and first of a closed one).
    bool consecutiveOnCurve(const Ref& a, const Ref& b) const {
        if (a.curve != b.curve)
            return false;
        const Index n = segmentCount(a.curve);
        const Index d = std::abs(a.segment - b.segment);
        return d <= 1 || (curves_[a.curve].closed && d == n - 1);
    }

    // App. C.1: two segments that meet on the surface, found by pointers
    // rather than in the image. Mesh-edge and interpolated segments meet
    // when they share a mesh vertex. A surface-intersection segment lies
    // inside its two faces: it meets the edges of those faces (handled as
    // surface-intersection ends) and the segments inside them; a curve
    // through one of their corners can still pass in front of it.
    bool logicallyMeet(const Ref& a, const Ref& b) const {
        if (a.curve != kInvalidIndex && b.curve != kInvalidIndex &&
            (curves_[a.curve].offMesh || curves_[b.curve].offMesh))
            return consecutiveOnCurve(a, b);
        const std::vector<Index> fa = intersectionFaces(a), fb = intersectionFaces(b);
        if (fa.empty() && fb.empty()) {
            const std::vector<Index> v0 = refVertices(a), v1 = refVertices(b);
            std::vector<Index> shared;
            std::set_intersection(v0.begin(), v0.end(), v1.begin(), v1.end(),
                                  std::back_inserter(shared));
            return !shared.empty();
        }
        const Ref& other = fa.empty() ? a : b;
        const std::vector<Index>& faces = fa.empty() ? fb : fa;
        if (refSource(other) == SegmentSource::MeshEdge) {
            const Index e = refElement(other);
            for (Index f : faces)
                for (int corner = 0; corner < 3; ++corner)
                    if (mesh_.edge(TriangleMesh::halfedge(f, corner)) == e)
                        return true;
            return false;
        }
        std::vector<Index> otherFaces = intersectionFaces(other);
        if (otherFaces.empty())
            otherFaces.push_back(refElement(other));
        for (Index f : faces)
            if (std::find(otherFaces.begin(), otherFaces.end(), f) != otherFaces.end())
                return true;
        return false;
    }

    // Whether mesh edge e is a fold of the mesh as seen from the camera (its
    // faces face opposite ways): only folds and boundaries occlude what
    // passes behind them (tutorial §4.3 item 1).
    bool isMeshFold(Index e) const {
        const Index h = mesh_.edgeHalfedge(e);
        const Index o = mesh_.opposite(h);
        if (o == kInvalidIndex)
            return false;
        const std::vector<int>& facing = *facing_;
        return (facing[TriangleMesh::face(h)] > 0) != (facing[TriangleMesh::face(o)] > 0);
    }

    // A vertex of a face next to near segment ab, on the side its surface
    // continues behind (app. C.2, "which side of the far segment is
    // occluded": SAMESIDE(a, b, cam, d, f)).
    Vec3 occludingApex(const Ref& r, const Vec3& a, const Vec3& b) {
        std::vector<Vec3> candidates;
        if (refSource(r) == SegmentSource::MeshEdge) {
            const Index h = mesh_.edgeHalfedge(refElement(r));
            candidates.push_back(mesh_.position(mesh_.to(TriangleMesh::next(h))));
            const Index o = mesh_.opposite(h);
            if (o != kInvalidIndex)
                candidates.push_back(mesh_.position(mesh_.to(TriangleMesh::next(o))));
        } else {
            // An interpolated contour crosses its face: no face lies on one
            // side only. Approximation: the vertex farthest from the plane.
            for (Index x : mesh_.triangle(refElement(r)))
                candidates.push_back(mesh_.position(x));
        }
        if (candidates.size() == 2 && (cameraPlaneSide(camera_, a, b, candidates[0]) > 0) ==
                                          (cameraPlaneSide(camera_, a, b, candidates[1]) > 0))
            return candidates[0];
        if (candidates.size() == 2)
            ++stats_.ambiguousOccludedSide;
        // The farthest from the plane (a, b, camera), by angle.
        const Vec3 n =
            (b - a).cross(camera_.isOrthographic() ? camera_.toCamera(a) : Vec3(camera_.eye - a));
        double best = -1.0;
        Vec3 chosen = candidates.front();
        for (const Vec3& x : candidates) {
            const double d = std::abs(n.dot(x - a)) / std::max((x - a).norm(), 1e-300);
            if (d > best) {
                best = d;
                chosen = x;
            }
        }
        return chosen;
    }

    // Tutorial §4.6 step 5, Bénard 2014 §8.2: image-space intersections
    // with CGAL's sweep line; the far curve is split and the node records
    // which side is occluded; the near curve is split too.
    void imageIntersectionNodes() {
        std::vector<Ref> refs;
        std::vector<ImageSegment> segments;
        std::vector<std::uint8_t> onCurve(mesh_.edgeCount(), 0);
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c)
            for (Index s = 0; s < segmentCount(c); ++s) {
                refs.push_back({c, s});
                if (curves_[c].source == SegmentSource::MeshEdge)
                    onCurve[curves_[c].segmentElement[s]] = 1;
            }
        if (options_.meshFoldOccluders)
            for (Index e = 0; e < mesh_.edgeCount(); ++e)
                if (!onCurve[e] && isMeshFold(e)) {
                    refs.push_back({kInvalidIndex, e});
                    ++stats_.foldOccluderEdges;
                }
        for (const Ref& r : refs)
            segments.push_back(
                {camera_.project(refPoint(r, 0)).pixel, camera_.project(refPoint(r, 1)).pixel});
        stats_.segments = static_cast<long long>(segments.size());
        const auto start = std::chrono::steady_clock::now();
        // Pairs that meet logically (app. C.1) or that are both fold edges
        // off the curves need no sweep.
        auto ignore = [&](Index i, Index j) {
            const Ref& a = refs[i];
            const Ref& b = refs[j];
            if (a.curve == kInvalidIndex && b.curve == kInvalidIndex)
                return true;
            if (refSource(a) == SegmentSource::MeshEdge &&
                refSource(b) == SegmentSource::MeshEdge &&
                refType(a) != CurveType::SurfaceIntersection &&
                refType(b) != CurveType::SurfaceIntersection) {
                const Index ha = mesh_.edgeHalfedge(refElement(a));
                const Index hb = mesh_.edgeHalfedge(refElement(b));
                const Index a0 = mesh_.from(ha), a1 = mesh_.to(ha);
                const Index b0 = mesh_.from(hb), b1 = mesh_.to(hb);
                return a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1;
            }
            return logicallyMeet(a, b);
        };
        const ImageIntersectionResult found = imageIntersections(segments, ignore);
        stats_.sweptSegments = found.sweptSegments;
        stats_.sweepSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats_.overlaps = static_cast<long long>(found.overlaps.size());
        stats_.degenerateSegments = found.degenerateSegments;
        stats_.imageCrossings = static_cast<long long>(found.crossings.size());

        // The crossings that split a curve, gathered first: those bounding a
        // sub-pixel loop of two drawn curves are flagged below.
        std::vector<Junction> junctions;
        for (const ImageCrossing& crossing : found.crossings) {
            const Ref r[2] = {refs[crossing.first], refs[crossing.second]};
            if (r[0].curve == kInvalidIndex && r[1].curve == kInvalidIndex)
                continue; // two fold edges off the curves: nothing to split
            if (logicallyMeet(r[0], r[1])) {
                ++stats_.logicalCrossings;
                continue;
            }
            if (!crossing.interiorFirst || !crossing.interiorSecond) {
                ++stats_.endpointTouches;
                continue;
            }
            // The 3D point of each segment under the crossing (perspective:
            // 1/depth is linear in the image).
            double tau[2], depth[2];
            Vec3 at[2];
            for (int i = 0; i < 2; ++i) {
                const Index id = i == 0 ? crossing.first : crossing.second;
                const ImageSegment& seg = segments[id];
                const Vec2 ab = seg.b - seg.a;
                const double lambda =
                    std::clamp((crossing.point - seg.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
                const Vec3 A = refPoint(r[i], 0), B = refPoint(r[i], 1);
                double t = lambda;
                if (!camera_.isOrthographic()) {
                    const double za = camera_.project(A).depth, zb = camera_.project(B).depth;
                    t = lambda * za / (lambda * za + (1.0 - lambda) * zb);
                }
                tau[i] = std::clamp(t, 0.0, 1.0);
                at[i] = A + tau[i] * (B - A);
                depth[i] = camera_.project(at[i]).depth;
            }
            if (depth[0] == depth[1]) {
                ++stats_.equalDepthCrossings;
                continue;
            }
            const int nearI = depth[0] < depth[1] ? 0 : 1, farI = 1 - nearI;
            Junction j;
            j.nearRef = r[nearI];
            j.farRef = r[farI];
            if (j.farRef.curve == kInvalidIndex)
                continue; // a fold edge off the curves behind a curve
            j.nearType = refType(j.nearRef);
            if (j.nearType == CurveType::SurfaceIntersection) {
                ++stats_.nonIndicatingNear; // not visibility-indicating (§4.4)
                continue;
            }
            // A contour-generator edge that is no fold of the mesh (consistent
            // contours next to inconsistent faces) hides nothing behind it.
            if (j.nearType == CurveType::Contour &&
                refSource(j.nearRef) == SegmentSource::MeshEdge &&
                !isMeshFold(refElement(j.nearRef))) {
                ++stats_.nonFoldNear;
                continue;
            }
            const Vec3 a = refPoint(j.nearRef, 0), b = refPoint(j.nearRef, 1);
            const Vec3 f = occludingApex(j.nearRef, a, b);
            const Vec3 d = refPoint(j.farRef, 0);
            j.startOccluded =
                (cameraPlaneSide(camera_, a, b, d) > 0) == (cameraPlaneSide(camera_, a, b, f) > 0);
            j.tau[0] = tau[nearI];
            j.tau[1] = tau[farI];
            j.at[0] = at[nearI];
            j.at[1] = at[farI];
            j.image = crossing.point;
            junctions.push_back(j);
        }
        const std::vector<std::uint8_t> small = smallLoopJunctions(junctions, refs, segments);

        for (size_t k = 0; k < junctions.size(); ++k) {
            const Junction& j = junctions[k];
            // A fold edge off the curves is no drawn curve: its crossing is
            // typed apart from the T-junctions of the drawn curves.
            const Index node =
                addNode(j.nearRef.curve != kInvalidIndex ? ViewNodeType::ImageIntersection
                                                         : ViewNodeType::HiddenFoldCrossing,
                        j.at[1]);
            graph_.nodes[node].image = j.image;
            graph_.nodes[node].nearPoint = j.at[0];
            graph_.nodes[node].smallLoop = small[k] != 0;
            stats_.smallLoopCrossings += small[k];
            // Tutorial §4.7: +2 behind a contour (two sheets meet at the
            // fold), +1 behind a boundary (one sheet).
            graph_.nodes[node].qiStep = j.nearType == CurveType::Contour ? 2 : 1;
            if (j.nearRef.curve != kInvalidIndex) {
                Cut nearCut;
                nearCut.segment = j.nearRef.segment;
                nearCut.tau = j.tau[0];
                nearCut.node = node;
                nearCut.role = Cut::Role::Near;
                addCut(j.nearRef.curve, nearCut);
            }
            Cut farCut;
            farCut.segment = j.farRef.segment;
            farCut.tau = j.tau[1];
            farCut.node = node;
            farCut.role = Cut::Role::Far;
            farCut.occludedBefore = j.startOccluded;
            addCut(j.farRef.curve, farCut);
        }
    }

    // The T-junctions of two drawn curves that bound a loop with less than
    // options_.smallLoopPixels of image arc on each side
    // (core/SmallLoopCrossings.h): the polylines' zig-zags next to cusps,
    // where the smooth contour does not cross. They stay nodes with their QI
    // steps (the polylines do cross there, and rays see the polylines'
    // mesh), flagged so that they are not counted as the surface's.
    // `refs` and `segments` are the sweep's input: every curve's segments
    // in order, already projected.
    std::vector<std::uint8_t> smallLoopJunctions(const std::vector<Junction>& junctions,
                                                 const std::vector<Ref>& refs,
                                                 const std::vector<ImageSegment>& segments) const {
        std::vector<std::uint8_t> out(junctions.size(), 0);
        if (!(options_.smallLoopPixels > 0.0))
            return out;
        // Image arc length at each curve's vertices.
        std::vector<std::vector<double>> arcs(curves_.size(), std::vector<double>{0.0});
        for (size_t k = 0; k < refs.size(); ++k)
            if (refs[k].curve != kInvalidIndex) {
                std::vector<double>& a = arcs[static_cast<size_t>(refs[k].curve)];
                a.push_back(a.back() + (segments[k].b - segments[k].a).norm());
            }
        std::vector<CurveArc> lengths(curves_.size());
        for (size_t c = 0; c < curves_.size(); ++c)
            lengths[c] = {arcs[c].back(), curves_[c].closed};
        const auto arcAt = [&](const Ref& r, double tau) {
            const std::vector<double>& a = arcs[static_cast<size_t>(r.curve)];
            const size_t s = static_cast<size_t>(r.segment);
            return a[s] + tau * (a[s + 1] - a[s]);
        };
        std::vector<size_t> index; // drawn-curve junctions among all
        std::vector<CurveCrossing> along;
        for (size_t k = 0; k < junctions.size(); ++k) {
            const Junction& j = junctions[k];
            if (j.nearRef.curve == kInvalidIndex)
                continue;
            index.push_back(k);
            along.push_back({j.nearRef.curve, arcAt(j.nearRef, j.tau[0]), j.farRef.curve,
                             arcAt(j.farRef, j.tau[1])});
        }
        const std::vector<std::uint8_t> flagged =
            smallLoopCrossings(along, lengths, options_.smallLoopPixels);
        for (size_t u = 0; u < index.size(); ++u)
            out[index[u]] = flagged[u];
        return out;
    }

    // Cusps the curves carry themselves (Polyline::cusps, traced contours):
    // curtain folds of the smooth surface, their far side the branch of the
    // larger radial curvature, one sheet (fillNodes).
    void curveCusps() {
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            const Index n = segmentCount(c);
            for (const CurveCusp& cusp : line.cusps) {
                if (cusp.segment < 0 || cusp.segment >= n)
                    continue;
                Cut cut;
                cut.segment = cusp.segment;
                cut.tau = cusp.tau;
                // A cusp at a point of the polyline: cut there (tau 0).
                if (cut.tau >= 1.0) {
                    cut.segment = (cut.segment + 1) % (line.closed ? n : n + 1);
                    cut.tau = 0.0;
                }
                cut.node = addNode(ViewNodeType::CurtainFold, pointAt(c, cut.segment, cut.tau));
                graph_.nodes[cut.node].smoothCusp = true;
                ++stats_.smoothCuspFolds;
                cut.role = Cut::Role::Vertex;
                cut.hasBefore = line.closed || cut.segment > 0 || cut.tau > 0.0;
                cut.hasAfter = line.closed || cut.segment < n;
                cut.kappaBefore = cusp.kappaBefore;
                cut.kappaAfter = cusp.kappaAfter;
                addCut(c, cut);
            }
        }
    }

    // Open curves must start and end at a node.
    void curveEnds() {
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            if (line.closed || line.points.size() < 2)
                continue;
            const Index n = segmentCount(c);
            for (const Index s : {Index(0), n}) {
                const bool present =
                    std::any_of(cuts_[c].begin(), cuts_[c].end(),
                                [&](const Cut& x) { return x.segment == s && x.tau == 0.0; });
                if (present)
                    continue;
                Cut cut;
                cut.segment = s;
                cut.node = addNode(ViewNodeType::CurveEnd, point(c, s).position);
                addCut(c, cut);
            }
        }
    }

    Index makeChain(Index c, Index s0, double t0, Index s1, double t1) {
        const Polyline& line = curves_[c];
        const Index n = segmentCount(c);
        ViewChain chain;
        chain.type = line.type;
        chain.curve = c;
        chain.source = line.source;
        // A cut at a vertex ends the chain on the previous segment.
        if (t1 == 0.0 && s1 > s0) {
            --s1;
            t1 = 1.0;
        }
        const bool secondFaces = secondFaces_ && c < static_cast<Index>(secondFaces_->size()) &&
                                 !(*secondFaces_)[c].empty();
        chain.points.push_back(pointAt(c, s0 % n, t0));
        for (Index s = s0;; ++s) {
            const Index sm = s % n;
            chain.points.push_back(s == s1 ? pointAt(c, sm, t1) : point(c, s + 1).position);
            chain.segmentElement.push_back(line.segmentElement[sm]);
            chain.segmentSecondFace.push_back(secondFaces ? (*secondFaces_)[c][sm] : kInvalidIndex);
            if (s == s1)
                break;
        }
        finishChain(chain);
        graph_.chains.push_back(std::move(chain));
        return static_cast<Index>(graph_.chains.size() - 1);
    }

    void finishChain(ViewChain& chain) {
        for (const Vec3& p : chain.points) {
            const ProjectedPoint q = camera_.project(p);
            chain.image.push_back(q.pixel);
            chain.depth.push_back(q.depth);
        }
        for (size_t i = 1; i < chain.image.size(); ++i)
            chain.lengthPixels += (chain.image[i] - chain.image[i - 1]).norm();
        chain.segmentRayQi.assign(chain.segmentCount(), -1);
        chain.segmentAmbiguous.assign(chain.segmentCount(), 0);
        if (chain.type == CurveType::Contour && chain.source == SegmentSource::MeshEdge &&
            options_.foldTest != CurtainFoldTest::None) {
            int concave = 0;
            for (Index e : chain.segmentElement)
                concave += classify(e).concave;
            chain.concave = 2 * concave > static_cast<int>(chain.segmentElement.size());
            if (concave != 0 && concave != static_cast<int>(chain.segmentElement.size()))
                ++stats_.mixedConvexityChains;
            // Tutorial theorem B.0.1: a concave contour is never visible.
            if (chain.concave && options_.foldTest == CurtainFoldTest::Convexity &&
                options_.concaveLowerBound)
                chain.qiLowerBound = 1;
        }
    }

    // Tutorial §4.6 / Bénard 2014 §8.3: the curves cut at their nodes.
    void makeChains() {
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            const Polyline& line = curves_[c];
            const Index n = segmentCount(c);
            if (n == 0)
                continue;
            std::vector<Cut>& cuts = cuts_[c];
            std::stable_sort(cuts.begin(), cuts.end(), cutLess);
            if (cuts.empty()) {
                // A closed curve with no node: one closed chain.
                ViewChain chain;
                chain.type = line.type;
                chain.curve = c;
                chain.source = line.source;
                chain.closed = true;
                const bool second = secondFaces_ && c < static_cast<Index>(secondFaces_->size()) &&
                                    !(*secondFaces_)[c].empty();
                for (Index s = 0; s <= n; ++s)
                    chain.points.push_back(point(c, s).position);
                for (Index s = 0; s < n; ++s) {
                    chain.segmentElement.push_back(line.segmentElement[s]);
                    chain.segmentSecondFace.push_back(second ? (*secondFaces_)[c][s]
                                                             : kInvalidIndex);
                }
                finishChain(chain);
                graph_.chains.push_back(std::move(chain));
                continue;
            }
            const size_t k = cuts.size();
            const size_t pieces = line.closed ? k : k - 1;
            for (size_t i = 0; i < pieces; ++i) {
                Cut& a = cuts[i];
                Cut& b = cuts[(i + 1) % k];
                Index s1 = b.segment;
                if (i + 1 == k) // wraps round a closed curve
                    s1 += n;
                const Index chain = makeChain(c, a.segment, a.tau, s1, b.tau);
                graph_.chains[chain].startNode = a.node;
                graph_.chains[chain].endNode = b.node;
                a.chainAfter = chain;
                b.chainBefore = chain;
            }
        }
    }

    void fillNodes() {
        // Curtain folds need the concavity of the chains on either side.
        // Per node, parallel to node.chains for vertex cuts: the branches'
        // radial curvature (smooth cusps only).
        std::vector<std::vector<double>> branchKappa(graph_.nodes.size());
        for (Index c = 0; c < static_cast<Index>(curves_.size()); ++c) {
            for (const Cut& cut : cuts_[c]) {
                ViewNode& node = graph_.nodes[cut.node];
                switch (cut.role) {
                case Cut::Role::Vertex:
                    if (cut.hasBefore && cut.chainBefore != kInvalidIndex) {
                        node.chains.push_back(cut.chainBefore);
                        node.localOccluders.push_back(cut.occBefore);
                        branchKappa[cut.node].push_back(cut.kappaBefore);
                    }
                    if (cut.hasAfter && cut.chainAfter != kInvalidIndex) {
                        node.chains.push_back(cut.chainAfter);
                        node.localOccluders.push_back(cut.occAfter);
                        branchKappa[cut.node].push_back(cut.kappaAfter);
                    }
                    break;
                case Cut::Role::Near:
                    node.nearChains = {cut.chainBefore, cut.chainAfter};
                    for (Index x : {cut.chainBefore, cut.chainAfter})
                        if (x != kInvalidIndex)
                            node.chains.push_back(x);
                    break;
                case Cut::Role::Far:
                    node.farChains = cut.occludedBefore
                                         ? std::array<Index, 2>{cut.chainAfter, cut.chainBefore}
                                         : std::array<Index, 2>{cut.chainBefore, cut.chainAfter};
                    for (Index x : {cut.chainBefore, cut.chainAfter})
                        if (x != kInvalidIndex)
                            node.chains.push_back(x);
                    break;
                case Cut::Role::Plain:
                    for (Index x : {cut.chainBefore, cut.chainAfter})
                        if (x != kInvalidIndex) {
                            node.chains.push_back(x);
                            // Y junctions inside a boundary edge: no face
                            // occludes any of the curves locally.
                            if (node.type == ViewNodeType::ContourBoundaryJunction)
                                node.localOccluders.push_back(0);
                        }
                    break;
                }
            }
        }
        for (size_t i = 0; i < graph_.nodes.size(); ++i) {
            ViewNode& node = graph_.nodes[i];
            if (node.type != ViewNodeType::CurtainFold &&
                node.type != ViewNodeType::BoundaryCurtainFold)
                continue;
            if (node.chains.size() != 2)
                continue;
            // Tutorial §4.7: the far chain is the one the vertex's one-ring
            // occludes (app. C.2 local overlap test). Usually the far chain is
            // the concave (interior) one, but a convex edge can be the
            // occluded one too (the rays agree with the local counts, not
            // with convexity, on grazing tori). At a cusp of the surface the
            // same local fact decides, not the sign of κr: on a torus the
            // exterior branch of a cusp next to the hole is the deeper one.
            // Ties fall back to convexity (mesh folds) or to the interior
            // branch, κr > 0 with the outward-normal sign of SurfaceFields.h
            // (cusps).
            const int o0 = node.localOccluders[0], o1 = node.localOccluders[1];
            int farSide = o1 > o0 ? 1 : 0;
            if (o0 == o1 && node.smoothCusp) {
                ++stats_.cuspFoldsSidedByCurvature;
                farSide = branchKappa[i][1] > branchKappa[i][0] ? 1 : 0;
            } else if (o0 == o1 && node.type == ViewNodeType::CurtainFold) {
                farSide = graph_.chains[node.chains[1]].concave ? 1 : 0;
            }
            const int nearSide = 1 - farSide;
            node.nearChains = {node.chains[nearSide], kInvalidIndex};
            node.farChains = {kInvalidIndex, node.chains[farSide]};
            if (node.smoothCusp) {
                // One sheet, as on a smooth surface; a loop with this one
                // node (its other cusp was not found) cannot step into
                // itself.
                node.qiStep = node.chains[0] != node.chains[1] ? 1 : 0;
                stats_.foldsWithoutStep += node.qiStep == 0;
                continue;
            }
            // The step is the number of one-ring faces over the far chain.
            node.qiStep = node.localOccluders[farSide] - node.localOccluders[nearSide];
            if (node.qiStep < 1)
                ++stats_.foldsWithoutStep;
            if (node.type == ViewNodeType::CurtainFold &&
                !graph_.chains[node.chains[farSide]].concave)
                ++stats_.convexFarFolds;
        }
    }
};

} // namespace

ViewGraph buildViewGraph(const ViewGraphInput& input, const Camera& camera,
                         const ViewGraphOptions& options, ViewGraphBuildStats* stats) {
    if (!input.mesh || !input.curves || !input.faceOrientation)
        throw std::invalid_argument("buildViewGraph: mesh, curves and face orientation needed");
    ViewGraphBuildStats local;
    Builder builder(input, camera, options, stats ? *stats : local);
    return builder.build();
}

std::vector<Index> segmentFaces(const TriangleMesh& mesh, const ViewChain& chain, size_t segment) {
    std::vector<Index> faces;
    const Index element =
        segment < chain.segmentElement.size() ? chain.segmentElement[segment] : kInvalidIndex;
    if (element == kInvalidIndex)
        return faces;
    if (chain.source == SegmentSource::MeshEdge) {
        const Index h = mesh.edgeHalfedge(element);
        faces.push_back(TriangleMesh::face(h));
        if (mesh.opposite(h) != kInvalidIndex)
            faces.push_back(TriangleMesh::face(mesh.opposite(h)));
    } else {
        faces.push_back(element);
        if (segment < chain.segmentSecondFace.size() &&
            chain.segmentSecondFace[segment] != kInvalidIndex)
            faces.push_back(chain.segmentSecondFace[segment]);
    }
    return faces;
}

} // namespace contour
