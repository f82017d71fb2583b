#include "contours/consistent/mesh/DomainCharts.h"

#include "core/Predicates.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contour::consistent {

DomainCharts::DomainCharts(std::shared_ptr<const SmoothSurface> surface, double chartTolerance)
    : surface_(std::move(surface)), tolerance_(chartTolerance) {
    if (!surface_)
        throw std::invalid_argument("DomainCharts: no smooth surface");
    const PolygonMesh& domain = surface_->domain();
    facesAround_.assign(static_cast<size_t>(domain.vertexCount()), 0);
    for (Index f = 0; f < domain.faceCount(); ++f)
        for (const Index w : domain.face(f))
            ++facesAround_[static_cast<size_t>(w)];
}

// Domain edge i runs from corner i to corner i+1 (SmoothSurface.h).
bool DomainCharts::onDomainEdge(const Preimage& p, int edge) const {
    const double t = tolerance_;
    if (surface_->isQuad(p.face)) {
        switch (edge) {
        case 0:
            return std::abs(p.v) <= t;
        case 1:
            return std::abs(p.u - 1.0) <= t;
        case 2:
            return std::abs(p.v - 1.0) <= t;
        default:
            return std::abs(p.u) <= t;
        }
    }
    switch (edge) {
    case 0:
        return std::abs(p.v) <= t;
    case 1:
        return std::abs(p.u + p.v - 1.0) <= t;
    default:
        return std::abs(p.u) <= t;
    }
}

bool DomainCharts::onAnyDomainEdge(const Preimage& p) const {
    for (int e = 0; e < cornerCount(p.face); ++e)
        if (onDomainEdge(p, e))
            return true;
    return false;
}

bool DomainCharts::insideWithTolerance(const Preimage& p) const {
    const double t = tolerance_;
    if (surface_->isQuad(p.face))
        return p.u >= -t && p.u <= 1.0 + t && p.v >= -t && p.v <= 1.0 + t;
    return p.u >= -t && p.v >= -t && p.u + p.v <= 1.0 + t;
}

Preimage DomainCharts::clampIntoFace(Preimage p) const {
    p.u = std::clamp(p.u, 0.0, 1.0);
    p.v = std::clamp(p.v, 0.0, 1.0);
    if (!surface_->isQuad(p.face) && p.u + p.v > 1.0) {
        const double s = p.u + p.v;
        p.u /= s;
        p.v /= s;
    }
    return p;
}

void DomainCharts::Preimages::push_back(const Preimage& p) {
    if (heap_.empty() && size_ < kInline) {
        inline_[static_cast<size_t>(size_++)] = p;
        return;
    }
    if (heap_.empty())
        heap_.assign(inline_.begin(), inline_.end());
    heap_.push_back(p);
    ++size_;
}

// Appendix B: a point on a shared domain edge (or corner) has one preimage
// in each face around it; walking across the edges it lies on collects them
// all (the one-ring of a domain corner, or the two faces of an edge).
DomainCharts::Preimages DomainCharts::equivalents(const Preimage& p) const {
    Preimages out;
    out.push_back(p);
    for (size_t i = 0; i < out.size(); ++i) {
        const Preimage q = out[i];
        for (int e = 0; e < cornerCount(q.face); ++e) {
            if (!onDomainEdge(q, e))
                continue;
            const SmoothSurface::EdgeNeighbor nb = surface_->neighbor(q.face, e);
            if (nb.face == kInvalidIndex)
                continue;
            if (std::any_of(out.begin(), out.end(),
                            [&](const Preimage& r) { return r.face == nb.face; }))
                continue;
            out.push_back(clampIntoFace(surface_->transferAcrossEdge(q, e)));
        }
    }
    return out;
}

std::optional<Vec2> DomainCharts::inEdgeChart(PreimageSpan reps, Index face) const {
    for (const Preimage& r : reps)
        if (r.face == face)
            return Vec2(r.u, r.v);
    for (const Preimage& r : reps)
        for (int e = 0; e < cornerCount(r.face); ++e)
            if (surface_->neighbor(r.face, e).face == face) {
                const Preimage t = surface_->transferAcrossEdge(r, e);
                return Vec2(t.u, t.v);
            }
    return std::nullopt;
}

std::optional<Vec2> DomainCharts::inChart(PreimageSpan reps, Index face) const {
    if (const std::optional<Vec2> c = inEdgeChart(reps, face))
        return c;
    for (const Preimage& r : reps)
        if (const std::optional<Preimage> t = acrossRegularCorner(r, face))
            return Vec2(t->u, t->v);
    return std::nullopt;
}

// Around a domain vertex of valence 3 a face's two edge neighbours are
// neighbours of each other, and the face's chart extended across both edges
// is cut along their shared edge: that edge appears twice, a quarter turn
// apart, so a point on it is held at two places and a triangle with corners
// in both neighbours is drawn across the cut, folded or not regardless of
// the surface. Such a chart is not one of the corners' common charts.
bool DomainCharts::cutBetweenNeighbours(const std::array<PreimageSpan, 3>& reps, Index face) const {
    std::array<Index, 12> via{};
    int count = 0;
    const auto isNeighbour = [&](Index a, Index b) {
        for (int e = 0; e < cornerCount(a); ++e)
            if (surface_->neighbor(a, e).face == b)
                return true;
        return false;
    };
    for (const PreimageSpan& r : reps) {
        if (std::any_of(r.begin(), r.end(), [&](const Preimage& x) { return x.face == face; }))
            continue;
        for (const Preimage& x : r)
            if (isNeighbour(x.face, face) &&
                std::find(via.begin(), via.begin() + count, x.face) == via.begin() + count &&
                count < static_cast<int>(via.size()))
                via[static_cast<size_t>(count++)] = x.face;
    }
    for (int i = 0; i < count; ++i)
        for (int j = i + 1; j < count; ++j)
            if (isNeighbour(via[static_cast<size_t>(i)], via[static_cast<size_t>(j)]))
                return true;
    return false;
}

std::optional<Preimage> DomainCharts::acrossRegularCorner(const Preimage& r, Index face) const {
    if (!vertexRingCharts_)
        return std::nullopt;
    // Around a regular corner exactly two paths of two edges lead from
    // r.face to the diagonal face, and they agree (the quadrant chart);
    // elsewhere there is one path, or they disagree: no chart.
    std::optional<Preimage> out;
    int paths = 0;
    for (int e = 0; e < cornerCount(r.face); ++e) {
        const SmoothSurface::EdgeNeighbor nb = surface_->neighbor(r.face, e);
        if (nb.face == kInvalidIndex || nb.face == face)
            continue;
        for (int e2 = 0; e2 < cornerCount(nb.face); ++e2) {
            if (surface_->neighbor(nb.face, e2).face != face)
                continue;
            const Preimage t = surface_->transferAcrossEdge(surface_->transferAcrossEdge(r, e), e2);
            if (out && (std::abs(out->u - t.u) > 1e-9 || std::abs(out->v - t.v) > 1e-9))
                return std::nullopt;
            out = t;
            ++paths;
        }
    }
    return paths == 2 ? out : std::nullopt;
}

std::optional<Preimage> DomainCharts::interpolate(const Preimage& a, const Preimage& b,
                                                  double t) const {
    // Same face: the first pair the search below tries (each list starts
    // with the preimage itself), without building the lists.
    if (a.face == b.face)
        return clampIntoFace({a.face, (1.0 - t) * a.u + t * b.u, (1.0 - t) * a.v + t * b.v});
    const Preimages ra = equivalents(a), rb = equivalents(b);
    return interpolateIn(span(ra), span(rb), t);
}

void DomainCharts::interpolate(const Preimage& a, const Preimage& b, std::span<const double> t,
                               std::span<std::optional<Preimage>> out) const {
    if (a.face == b.face) {
        for (size_t i = 0; i < t.size(); ++i)
            out[i] = interpolate(a, b, t[i]);
        return;
    }
    const Preimages ra = equivalents(a), rb = equivalents(b);
    for (size_t i = 0; i < t.size(); ++i)
        out[i] = interpolateIn(span(ra), span(rb), t[i]);
}

std::optional<Preimage> DomainCharts::interpolateIn(PreimageSpan ra, PreimageSpan rb,
                                                    double t) const {
    std::optional<Preimage> out;
    forEachInterpolation(ra, rb, t, [&](int, const std::optional<Preimage>& p) {
        out = p;
        return p.has_value();
    });
    return out; // nullopt: no common chart, the caller cancels (appendix B)
}

std::optional<Preimage> DomainCharts::interpolateInChart(PreimageSpan ra, PreimageSpan rb, double t,
                                                         int chart) const {
    std::optional<Preimage> out;
    forEachInterpolation(ra, rb, t, [&](int k, const std::optional<Preimage>& p) {
        if (k != chart)
            return false;
        out = p;
        return true;
    });
    return out;
}

int DomainCharts::interpolationCharts(const Preimage& a, const Preimage& b) const {
    const Preimages ra = equivalents(a), rb = equivalents(b);
    int count = 0;
    forEachInterpolation(span(ra), span(rb), 0.5, [&](int, const std::optional<Preimage>&) {
        ++count;
        return false;
    });
    return count;
}

template <typename Visit>
void DomainCharts::forEachInterpolation(PreimageSpan ra, PreimageSpan rb, double t,
                                        Visit visit) const {
    int k = 0;
    // Both preimages in one face: plain interpolation.
    for (const Preimage& x : ra)
        for (const Preimage& y : rb)
            if (x.face == y.face && visit(k++, clampIntoFace({x.face, (1.0 - t) * x.u + t * y.u,
                                                              (1.0 - t) * x.v + t * y.v})))
                return;
    // Edge-adjacent faces: express y in x's chart, interpolate there and map
    // the result into a face that contains it.
    const auto located = [&](const Preimage& m, Index other) -> std::optional<Preimage> {
        if (insideWithTolerance(m))
            return clampIntoFace(m);
        for (int back = 0; back < cornerCount(m.face); ++back) {
            const Index nb = surface_->neighbor(m.face, back).face;
            if (nb == kInvalidIndex || (other != kInvalidIndex && nb != other))
                continue;
            const Preimage my = surface_->transferAcrossEdge(m, back);
            if (insideWithTolerance(my))
                return clampIntoFace(my);
        }
        return std::nullopt;
    };
    for (const Preimage& x : ra)
        for (const Preimage& y : rb)
            for (int e = 0; e < cornerCount(y.face); ++e) {
                if (surface_->neighbor(y.face, e).face != x.face)
                    continue;
                const Preimage yx = surface_->transferAcrossEdge(y, e);
                const Preimage m{x.face, (1.0 - t) * x.u + t * yx.u, (1.0 - t) * x.v + t * yx.v};
                if (visit(k++, located(m, y.face)))
                    return;
            }
    // Faces sharing a regular corner (setVertexRingCharts): the same in the
    // chart of that corner's one-ring.
    for (const Preimage& x : vertexRingCharts_ ? ra : PreimageSpan{})
        for (const Preimage& y : rb) {
            const std::optional<Preimage> yx = acrossRegularCorner(y, x.face);
            if (!yx)
                continue;
            const Preimage m{x.face, (1.0 - t) * x.u + t * yx->u, (1.0 - t) * x.v + t * yx->v};
            std::optional<Preimage> at = located(m, kInvalidIndex);
            if (!at)
                if (const std::optional<Preimage> my = acrossRegularCorner(m, y.face);
                    my && insideWithTolerance(*my))
                    at = clampIntoFace(*my);
            if (visit(k++, at))
                return;
        }
}

template <typename Visit>
void DomainCharts::forEachChart(const std::array<Preimage, 3>& p, Visit visit) const {
    // Three preimages inside one face, on none of its edges: that face is
    // the only common chart (equivalents() would return each alone).
    if (p[0].face == p[1].face && p[1].face == p[2].face && !onAnyDomainEdge(p[0]) &&
        !onAnyDomainEdge(p[1]) && !onAnyDomainEdge(p[2])) {
        visit(
            std::array<Vec2, 3>{Vec2(p[0].u, p[0].v), Vec2(p[1].u, p[1].v), Vec2(p[2].u, p[2].v)});
        return;
    }
    const std::array<Preimages, 3> reps{equivalents(p[0]), equivalents(p[1]), equivalents(p[2])};
    forEachChart(std::array<PreimageSpan, 3>{span(reps[0]), span(reps[1]), span(reps[2])}, visit);
}

template <typename Visit>
void DomainCharts::forEachChart(const std::array<PreimageSpan, 3>& reps, Visit visit) const {
    // Every domain face holding all three preimages is a faithful chart.
    bool any = false;
    for (const Preimage& chart : reps[0]) {
        std::array<Vec2, 3> c;
        int found = 0;
        for (int i = 0; i < 3; ++i)
            for (const Preimage& r : reps[i])
                if (r.face == chart.face) {
                    c[i] = Vec2(r.u, r.v);
                    ++found;
                    break;
                }
        if (found == 3) {
            visit(c);
            any = true;
        }
    }
    if (any)
        return;
    // Otherwise every face's chart extended across its edges (appendix B)
    // that holds all three and is not cut between them; only when every
    // such chart is cut (corners in all three faces around a domain vertex
    // of valence 3, where no chart is faithful) the cut ones.
    Preimages tried;
    const auto tryChart = [&](Index face, bool cut) {
        if (std::any_of(tried.begin(), tried.end(),
                        [&](const Preimage& x) { return x.face == face; }))
            return false;
        tried.push_back({face, 0.0, 0.0});
        if (cutBetweenNeighbours(reps, face) != cut)
            return false;
        std::array<Vec2, 3> c;
        for (int i = 0; i < 3; ++i) {
            const std::optional<Vec2> x = inChart(reps[i], face);
            if (!x)
                return false;
            c[i] = *x;
        }
        visit(c);
        return true;
    };
    const auto extended = [&](bool cut) {
        bool visited = false;
        tried = Preimages{};
        for (const auto& candidates : reps)
            for (const Preimage& chart : candidates)
                visited |= tryChart(chart.face, cut);
        return visited;
    };
    if (extended(false) || extended(true))
        return;
    // Nor any: the chart of a face none of the corners lies in, extended
    // across its edges (appendix B asks for a common chart, not one of the
    // corners' own), when that face and a face of every corner share an
    // irregular domain vertex (not four faces around it): two corners in
    // faces that share only that vertex, the third in a face next to both,
    // all in its one-ring. Around a regular vertex the one-ring charts
    // (setVertexRingCharts) decide; triangles spread over more than one
    // vertex's ring keep having no chart.
    const PolygonMesh& domain = surface_->domain();
    const auto aroundOneVertex = [&](Index face) {
        for (const Index w : domain.face(face)) {
            if (facesAround_[static_cast<size_t>(w)] == 4)
                continue;
            const auto touches = [&](const PreimageSpan& r) {
                return std::any_of(r.begin(), r.end(), [&](const Preimage& x) {
                    const auto corners = domain.face(x.face);
                    return std::find(corners.begin(), corners.end(), w) != corners.end();
                });
            };
            if (std::all_of(reps.begin(), reps.end(), touches))
                return true;
        }
        return false;
    };
    const auto neighbours = [&](bool cut) {
        // The corners' own faces are no candidates here (tried above).
        tried = Preimages{};
        for (const auto& candidates : reps)
            for (const Preimage& chart : candidates)
                tried.push_back(chart);
        bool visited = false;
        for (const Preimage& r : reps[0])
            for (int e = 0; e < cornerCount(r.face); ++e)
                if (const Index nb = surface_->neighbor(r.face, e).face;
                    nb != kInvalidIndex && aroundOneVertex(nb))
                    visited |= tryChart(nb, cut);
        return visited;
    };
    if (!neighbours(false))
        neighbours(true);
}

// The charts a mesh without setVertexRingCharts has: each pair in one face
// or in edge-adjacent faces (interpolate()'s first two cases), and the three
// in one face's chart extended across its edges.
bool DomainCharts::withinEdgeCharts(const std::array<Preimage, 3>& p) const {
    const std::array<Preimages, 3> reps{equivalents(p[0]), equivalents(p[1]), equivalents(p[2])};
    const auto pairShares = [&](const Preimages& ra, const Preimages& rb) {
        for (const Preimage& x : ra)
            for (const Preimage& y : rb) {
                if (x.face == y.face)
                    return true;
                for (int e = 0; e < cornerCount(y.face); ++e)
                    if (surface_->neighbor(y.face, e).face == x.face)
                        return true;
            }
        return false;
    };
    if (!pairShares(reps[0], reps[1]) || !pairShares(reps[0], reps[2]))
        return false;
    for (const auto& candidates : reps)
        for (const Preimage& chart : candidates) {
            bool all = true;
            for (int i = 0; i < 3 && all; ++i)
                all = inEdgeChart(span(reps[i]), chart.face).has_value();
            if (all)
                return true;
        }
    return false;
}

std::vector<std::array<Vec2, 3>>
DomainCharts::chartCoordinates(const std::array<Preimage, 3>& p) const {
    std::vector<std::array<Vec2, 3>> out;
    forEachChart(p, [&](const std::array<Vec2, 3>& c) { out.push_back(c); });
    return out;
}

// Near an extraordinary domain vertex the charts of different faces do not
// agree exactly, so the orientation is the worst over every common chart:
// independent of the corners' order, and a fold in any chart counts.
template <typename Corners>
std::optional<int> DomainCharts::worstOrientation(const Corners& corners) const {
    bool any = false;
    int worst = 1;
    forEachChart(corners, [&](const std::array<Vec2, 3>& c) {
        any = true;
        worst = std::min(worst, orientation2d(c[0], c[1], c[2]));
    });
    if (!any)
        return std::nullopt;
    return worst;
}

std::optional<int> DomainCharts::parameterOrientation(const std::array<Preimage, 3>& p) const {
    return worstOrientation(p);
}

std::optional<int>
DomainCharts::parameterOrientationIn(const std::array<PreimageSpan, 3>& reps) const {
    return worstOrientation(reps);
}

} // namespace contour::consistent
