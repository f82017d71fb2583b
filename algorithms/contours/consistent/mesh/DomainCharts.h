#pragma once
// The charts of a smooth surface's parameter domain in which preimages are
// interpolated (Bénard, Hertzmann & Kass 2014, appendix B). A point on a
// domain edge or corner has one preimage per domain face around it; two
// preimages are interpolated in a face that holds both, or, when they lie in
// edge-adjacent faces, in one face's chart extended across the shared edge
// (SmoothSurface::transferAcrossEdge), the result mapped back into a face
// that contains it. When no such chart exists the interpolation fails
// (nullopt) and the caller cancels the operation and counts it; nothing is
// guessed.
//
// Everything here depends on preimages only, never on a mesh's faces:
// ConsistentMesh keeps the loops over its faces and their caches.
#include "surface/SmoothSurface.h"

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace contour::consistent {

class DomainCharts {
public:
    // chartTolerance: how far (in domain parameters) a preimage may be from a
    // domain edge and still count as lying on it (so that it also has a
    // preimage in the neighbouring face), and how far outside a face an
    // interpolated preimage may land and still count as inside.
    DomainCharts(std::shared_ptr<const SmoothSurface> surface, double chartTolerance);

    const SmoothSurface& surface() const { return *surface_; }
    const std::shared_ptr<const SmoothSurface>& surfacePtr() const { return surface_; }
    double tolerance() const { return tolerance_; }

    // Appendix B also names the chart of a regular domain vertex's one-ring
    // (four quads, one per quadrant): with this on, two preimages in faces
    // that share only such a corner have a common chart too (the second
    // face's coordinates carried across two edges, both ways round the
    // corner agreeing). Off: a face and its edge neighbours only.
    void setVertexRingCharts(bool on) { vertexRingCharts_ = on; }
    bool vertexRingCharts() const { return vertexRingCharts_; }

    // A few preimages without a heap allocation in the common case (a domain
    // corner of valence <= kInline); the hot loops call equivalents() for
    // every interpolation and every face orientation.
    class Preimages {
    public:
        static constexpr int kInline = 12;
        void push_back(const Preimage& p);
        size_t size() const { return static_cast<size_t>(size_); }
        const Preimage& operator[](size_t i) const { return data()[i]; }
        const Preimage* begin() const { return data(); }
        const Preimage* end() const { return data() + size_; }

    private:
        const Preimage* data() const { return heap_.empty() ? inline_.data() : heap_.data(); }
        std::array<Preimage, kInline> inline_;
        std::vector<Preimage> heap_;
        int size_ = 0;
    };
    using PreimageSpan = std::span<const Preimage>;
    static PreimageSpan span(const Preimages& p) { return {p.begin(), p.size()}; }

    // Every preimage of the same surface point (one per domain face around a
    // domain edge or corner the point lies on), p first.
    Preimages equivalents(const Preimage& p) const;
    // Whether p lies on local edge `edge` of its face (edge i runs from
    // corner i to corner i+1), or on any of its edges, within the tolerance.
    bool onDomainEdge(const Preimage& p, int edge) const;
    bool onAnyDomainEdge(const Preimage& p) const;
    // Whether p lies inside its face, the tolerance outside included.
    bool insideWithTolerance(const Preimage& p) const;
    // p moved to the nearest point of its face (closed).
    Preimage clampIntoFace(Preimage p) const;

    // u(t) = (1 - t) u_a + t u_b in a common chart.
    std::optional<Preimage> interpolate(const Preimage& a, const Preimage& b, double t) const;
    // The same for several t (out[i] at t[i]): the charts of a and b are
    // found once.
    void interpolate(const Preimage& a, const Preimage& b, std::span<const double> t,
                     std::span<std::optional<Preimage>> out) const;
    // interpolate() given both preimages' equivalents().
    std::optional<Preimage> interpolateIn(PreimageSpan ra, PreimageSpan rb, double t) const;
    // The same in one common chart of the two (numbered 0, 1, ... in the
    // order interpolateIn() tries them, interpolationCharts() in all):
    // near a domain vertex of valence 3 the charts disagree on where the
    // straight segment runs.
    std::optional<Preimage> interpolateInChart(PreimageSpan ra, PreimageSpan rb, double t,
                                               int chart) const;
    int interpolationCharts(const Preimage& a, const Preimage& b) const;
    // interpolate(a, b, t) for t chosen one at a time (a bisection): a's and
    // b's equivalents() are found once, so at(t) is interpolate(a, b, t)
    // without that search (the same results).
    class Segment;
    Segment segment(const Preimage& a, const Preimage& b) const;
    // The segment in common chart `chart` only (interpolateInChart()).
    Segment segmentInChart(const Preimage& a, const Preimage& b, int chart) const;

    // A preimage (given by its equivalents()) in the chart of `face`: its
    // own face, an edge neighbour of one of its faces, or (with
    // setVertexRingCharts) a face sharing only a regular corner with one.
    std::optional<Vec2> inChart(PreimageSpan reps, Index face) const;
    // The same without the regular-corner charts.
    std::optional<Vec2> inEdgeChart(PreimageSpan reps, Index face) const;
    // r in the chart of `face` when the two faces share only a regular
    // corner (setVertexRingCharts), else nullopt.
    std::optional<Preimage> acrossRegularCorner(const Preimage& r, Index face) const;
    // Whether the chart of `face` extended across its edges reaches the
    // preimages (their equivalents()) through two edge neighbours that are
    // neighbours of each other (a domain vertex of valence 3), where the
    // chart is cut: forEachChart() offers such a chart only when no other
    // holds the three.
    bool cutBetweenNeighbours(const std::array<PreimageSpan, 3>& reps, Index face) const;

    // The three preimages' coordinates in every common chart: the domain
    // faces holding all three, or else the faces whose chart extended across
    // their edges holds all three (the corners' faces, and only when none
    // does, an edge neighbour of the first corner's faces that shares an
    // irregular domain vertex with a face of every corner); empty when there
    // is none.
    std::vector<std::array<Vec2, 3>> chartCoordinates(const std::array<Preimage, 3>& p) const;
    // Whether p[0] shares a face or edge-adjacent faces with p[1] and with
    // p[2], and the three lie in one face's chart extended across its edges:
    // the charts without setVertexRingCharts. A move that must not straddle
    // a regular corner asks this (contour insertion's snap rule).
    bool withinEdgeCharts(const std::array<Preimage, 3>& p) const;
    // Sign of the triangle's orientation in parameter space (+1
    // counter-clockwise, the domain's orientation; -1 a fold; 0 degenerate),
    // the worst over all common charts, or nullopt when the corners have no
    // common chart.
    std::optional<int> parameterOrientation(const std::array<Preimage, 3>& p) const;
    // The same given the corners' equivalents().
    std::optional<int> parameterOrientationIn(const std::array<PreimageSpan, 3>& reps) const;

private:
    std::shared_ptr<const SmoothSurface> surface_;
    double tolerance_;
    bool vertexRingCharts_ = false;
    std::vector<int> facesAround_; // per domain vertex, the domain faces around it

    int cornerCount(Index domainFace) const { return surface_->isQuad(domainFace) ? 4 : 3; }
    // Calls visit(coordinates) for every common chart of the three
    // preimages, in the order chartCoordinates() lists them; reps are their
    // equivalents().
    template <typename Visit>
    void forEachChart(const std::array<PreimageSpan, 3>& reps, Visit visit) const;
    template <typename Visit>
    void forEachChart(const std::array<Preimage, 3>& p, Visit visit) const;
    // The worst orientation over forEachChart(corners), nullopt without a
    // chart.
    template <typename Corners> std::optional<int> worstOrientation(const Corners& corners) const;
    // Calls visit(k, interpolation or nullopt) for the k-th common chart of
    // the two preimages (given by their equivalents()) until visit returns
    // true.
    template <typename Visit>
    void forEachInterpolation(PreimageSpan ra, PreimageSpan rb, double t, Visit visit) const;
};

class DomainCharts::Segment {
public:
    std::optional<Preimage> at(double t) const {
        if (chart_ >= 0)
            return c_->interpolateInChart(span(ra_), span(rb_), t, chart_);
        return a_.face == b_.face ? c_->interpolate(a_, b_, t)
                                  : c_->interpolateIn(span(ra_), span(rb_), t);
    }

private:
    friend class DomainCharts;
    Segment(const DomainCharts& c, const Preimage& a, const Preimage& b, int chart)
        : c_(&c), a_(a), b_(b), chart_(chart) {
        if (a.face != b.face || chart >= 0) {
            ra_ = c.equivalents(a);
            rb_ = c.equivalents(b);
        }
    }
    const DomainCharts* c_;
    Preimage a_, b_;
    int chart_;
    Preimages ra_, rb_;
};

inline DomainCharts::Segment DomainCharts::segment(const Preimage& a, const Preimage& b) const {
    return {*this, a, b, -1};
}

inline DomainCharts::Segment DomainCharts::segmentInChart(const Preimage& a, const Preimage& b,
                                                          int chart) const {
    return {*this, a, b, chart};
}

} // namespace contour::consistent
