#include "contours/consistent/mesh/ConsistentMesh.h"

#include "core/Predicates.h"
#include "surface/SurfaceFields.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour::consistent {

VertexLabel labelFromG(double g) {
    return g > 0.0 ? VertexLabel::Front : g < 0.0 ? VertexLabel::Back : VertexLabel::Contour;
}

ConsistentMesh::ConsistentMesh(std::shared_ptr<const SmoothSurface> surface, const Camera& camera,
                               double chartTolerance)
    : surface_(std::move(surface)), camera_(camera), tolerance_(chartTolerance) {
    if (!surface_)
        throw std::invalid_argument("ConsistentMesh: no smooth surface");
}

// Bénard 2014 §4: a vertex's position is always f(u_i), its normal n(u_i).
MeshVertex ConsistentMesh::evaluate(const Preimage& p) const {
    return evaluated(p, surface_->evaluate(p));
}

MeshVertex ConsistentMesh::evaluated(const Preimage& p, const SurfacePoint& sp) const {
    MeshVertex v;
    v.preimage = p;
    v.position = sp.position;
    v.normal = sp.normal();
    v.g = orientation(sp, camera_);
    v.radialCurvature = radialCurvature(sp, camera_);
    v.label = labelFromG(v.g);
    return v;
}

MeshVertex ConsistentMesh::evaluateWithoutCurvature(const Preimage& p) const {
    // f, n and g need first derivatives only (the same bits as evaluate()).
    const SurfacePoint sp = surface_->evaluateFirstOrder(p);
    MeshVertex v;
    v.preimage = p;
    v.position = sp.position;
    v.normal = sp.normal();
    v.g = orientation(sp, camera_);
    v.radialCurvature = std::numeric_limits<double>::quiet_NaN();
    v.label = labelFromG(v.g);
    return v;
}

Index ConsistentMesh::addVertex(const MeshVertex& v) {
    preimageTable_.reset();
    vertices_.push_back(v);
    vertexFaces_.emplace_back();
    return vertexCount() - 1;
}

void ConsistentMesh::reserve(Index vertices, Index faces) {
    vertices_.reserve(vertices);
    vertexFaces_.reserve(vertices);
    faces_.reserve(faces);
    facePhase_.reserve(faces);
    ownHalfedges().reserve(3 * static_cast<size_t>(faces));
}

HalfedgeMap& ConsistentMesh::ownHalfedges() {
    if (sharedHalfedges_) {
        halfedgeFace_ = *sharedHalfedges_;
        sharedHalfedges_.reset();
    }
    return halfedgeFace_;
}

std::shared_ptr<const HalfedgeMap> ConsistentMesh::shareHalfedges() {
    if (!sharedHalfedges_)
        sharedHalfedges_ = std::make_shared<const HalfedgeMap>(std::move(halfedgeFace_));
    halfedgeFace_.clear();
    return sharedHalfedges_;
}

void ConsistentMesh::assignShared(std::vector<MeshVertex> vertices, std::vector<Triangle> faces,
                                  std::vector<int> facePhase,
                                  std::shared_ptr<const HalfedgeMap> halfedges) {
    if (!halfedges) {
        assign(std::move(vertices), std::move(faces), std::move(facePhase), nullptr);
        return;
    }
    // The copying overload with an empty table to copy, then the shared one.
    static const HalfedgeMap kEmpty;
    assign(std::move(vertices), std::move(faces), std::move(facePhase), &kEmpty);
    halfedgeFace_.clear();
    sharedHalfedges_ = std::move(halfedges);
}

void ConsistentMesh::assign(std::vector<MeshVertex> vertices, std::vector<Triangle> faces,
                            std::vector<int> facePhase, const HalfedgeMap* halfedges) {
    preimageTable_.reset();
    vertices_ = std::move(vertices);
    faces_ = std::move(faces);
    facePhase_ = std::move(facePhase);
    orientationCache_.assign(faces_.size(), kOrientationUnknown);
    domainFaceCache_.assign(faces_.size(), kDomainFaceUnknown);
    std::vector<Index> valence(vertices_.size(), 0);
    for (const Triangle& t : faces_)
        for (Index w : t)
            ++valence[static_cast<size_t>(w)];
    vertexFaces_.assign(vertices_.size(), {});
    for (size_t v = 0; v < vertices_.size(); ++v)
        vertexFaces_[v].reserve(static_cast<size_t>(valence[v]));
    sharedHalfedges_.reset();
    if (halfedges) {
        halfedgeFace_ = *halfedges;
        for (Index f = 0; f < faceCount(); ++f)
            for (Index w : faces_[f])
                vertexFaces_[w].push_back(f);
    } else {
        halfedgeFace_.clear();
        halfedgeFace_.reserve(3 * faces_.size());
        for (Index f = 0; f < faceCount(); ++f)
            attachFace(f);
    }
}

Index ConsistentMesh::addFace(const Triangle& t, int phase) {
    faces_.push_back(t);
    facePhase_.push_back(phase);
    attachFace(faceCount() - 1);
    return faceCount() - 1;
}

void ConsistentMesh::attachFace(Index f) {
    forgetFace(f);
    const Triangle& t = faces_[f];
    for (int i = 0; i < 3; ++i) {
        if (!ownHalfedges().insert(key(t[i], t[(i + 1) % 3]), f))
            throw std::logic_error("ConsistentMesh: non-manifold or inconsistently oriented edge");
        vertexFaces_[t[i]].push_back(f);
    }
}

void ConsistentMesh::detachFace(Index f) {
    const Triangle& t = faces_[f];
    for (int i = 0; i < 3; ++i) {
        ownHalfedges().erase(key(t[i], t[(i + 1) % 3]), f);
        std::erase(vertexFaces_[t[i]], f);
    }
}

void ConsistentMesh::forgetFace(Index f) {
    const auto i = static_cast<size_t>(f);
    if (i < orientationCache_.size())
        orientationCache_[i] = kOrientationUnknown;
    if (i < domainFaceCache_.size())
        domainFaceCache_[i] = kDomainFaceUnknown;
}

void ConsistentMesh::forgetFacesOf(Index v) {
    for (Index f : vertexFaces_[v])
        forgetFace(f);
}

void ConsistentMesh::sizeFaceCaches() const {
    orientationCache_.resize(faces_.size(), kOrientationUnknown);
    domainFaceCache_.resize(faces_.size(), kDomainFaceUnknown);
}

ConsistentMesh::FaceCaches ConsistentMesh::faceCaches() const {
    sizeFaceCaches();
    return {tolerance_, orientationCache_, domainFaceCache_};
}

void ConsistentMesh::adoptFaceCaches(const FaceCaches& caches) {
    if (caches.chartTolerance != tolerance_ || caches.orientation.size() != faces_.size() ||
        caches.domainFace.size() != faces_.size())
        return;
    orientationCache_ = caches.orientation;
    domainFaceCache_ = caches.domainFace;
}

Index ConsistentMesh::faceOfHalfedge(Index a, Index b) const {
    return halfedgeTable().find(key(a, b));
}

std::vector<std::array<Index, 2>> ConsistentMesh::edges() const {
    std::vector<std::array<Index, 2>> out;
    for (const Triangle& t : faces_)
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            if (a < b || faceOfHalfedge(b, a) == kInvalidIndex)
                out.push_back({a, b});
        }
    return out;
}

// Domain edge i runs from corner i to corner i+1 (SmoothSurface.h).
bool ConsistentMesh::onDomainEdge(const Preimage& p, int edge) const {
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

bool ConsistentMesh::onAnyDomainEdge(const Preimage& p) const {
    for (int e = 0; e < cornerCount(p.face); ++e)
        if (onDomainEdge(p, e))
            return true;
    return false;
}

bool ConsistentMesh::insideWithTolerance(const Preimage& p) const {
    const double t = tolerance_;
    if (surface_->isQuad(p.face))
        return p.u >= -t && p.u <= 1.0 + t && p.v >= -t && p.v <= 1.0 + t;
    return p.u >= -t && p.v >= -t && p.u + p.v <= 1.0 + t;
}

Preimage ConsistentMesh::clampIntoFace(Preimage p) const {
    p.u = std::clamp(p.u, 0.0, 1.0);
    p.v = std::clamp(p.v, 0.0, 1.0);
    if (!surface_->isQuad(p.face) && p.u + p.v > 1.0) {
        const double s = p.u + p.v;
        p.u /= s;
        p.v /= s;
    }
    return p;
}

// Appendix B: a point on a shared domain edge (or corner) has one preimage
// in each face around it; walking across the edges it lies on collects them
// all (the one-ring of a domain corner, or the two faces of an edge).
void ConsistentMesh::Preimages::push_back(const Preimage& p) {
    if (heap_.empty() && size_ < kInline) {
        inline_[static_cast<size_t>(size_++)] = p;
        return;
    }
    if (heap_.empty())
        heap_.assign(inline_.begin(), inline_.end());
    heap_.push_back(p);
    ++size_;
}

ConsistentMesh::Preimages ConsistentMesh::equivalents(const Preimage& p) const {
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

std::optional<Vec2> ConsistentMesh::inEdgeChart(PreimageSpan reps, Index face) const {
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

std::optional<Vec2> ConsistentMesh::inChart(PreimageSpan reps, Index face) const {
    if (const std::optional<Vec2> c = inEdgeChart(reps, face))
        return c;
    for (const Preimage& r : reps)
        if (const std::optional<Preimage> t = acrossRegularCorner(r, face))
            return Vec2(t->u, t->v);
    return std::nullopt;
}

std::optional<Preimage> ConsistentMesh::acrossRegularCorner(const Preimage& r, Index face) const {
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

std::optional<Preimage> ConsistentMesh::interpolate(const Preimage& a, const Preimage& b,
                                                    double t) const {
    // Same face: the first pair the search below tries (each list starts
    // with the preimage itself), without building the lists.
    if (a.face == b.face)
        return clampIntoFace({a.face, (1.0 - t) * a.u + t * b.u, (1.0 - t) * a.v + t * b.v});
    const Preimages ra = equivalents(a), rb = equivalents(b);
    return interpolateIn(span(ra), span(rb), t);
}

void ConsistentMesh::interpolate(const Preimage& a, const Preimage& b, std::span<const double> t,
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

std::optional<Preimage> ConsistentMesh::interpolateIn(PreimageSpan ra, PreimageSpan rb,
                                                      double t) const {
    // Both preimages in one face: plain interpolation.
    for (const Preimage& x : ra)
        for (const Preimage& y : rb)
            if (x.face == y.face)
                return clampIntoFace(
                    {x.face, (1.0 - t) * x.u + t * y.u, (1.0 - t) * x.v + t * y.v});
    // Edge-adjacent faces: express y in x's chart, interpolate there and map
    // the result into a face that contains it.
    for (const Preimage& x : ra)
        for (const Preimage& y : rb)
            for (int e = 0; e < cornerCount(y.face); ++e) {
                if (surface_->neighbor(y.face, e).face != x.face)
                    continue;
                const Preimage yx = surface_->transferAcrossEdge(y, e);
                const Preimage m{x.face, (1.0 - t) * x.u + t * yx.u, (1.0 - t) * x.v + t * yx.v};
                if (insideWithTolerance(m))
                    return clampIntoFace(m);
                for (int back = 0; back < cornerCount(x.face); ++back) {
                    if (surface_->neighbor(x.face, back).face != y.face)
                        continue;
                    const Preimage my = surface_->transferAcrossEdge(m, back);
                    if (insideWithTolerance(my))
                        return clampIntoFace(my);
                }
            }
    // Faces sharing a regular corner (setVertexRingCharts): the same in the
    // chart of that corner's one-ring.
    for (const Preimage& x : vertexRingCharts_ ? ra : PreimageSpan{})
        for (const Preimage& y : rb) {
            const std::optional<Preimage> yx = acrossRegularCorner(y, x.face);
            if (!yx)
                continue;
            const Preimage m{x.face, (1.0 - t) * x.u + t * yx->u, (1.0 - t) * x.v + t * yx->v};
            if (insideWithTolerance(m))
                return clampIntoFace(m);
            for (int back = 0; back < cornerCount(x.face); ++back) {
                if (surface_->neighbor(x.face, back).face == kInvalidIndex)
                    continue;
                const Preimage my = surface_->transferAcrossEdge(m, back);
                if (insideWithTolerance(my))
                    return clampIntoFace(my);
            }
            if (const std::optional<Preimage> my = acrossRegularCorner(m, y.face);
                my && insideWithTolerance(*my))
                return clampIntoFace(*my);
        }
    return std::nullopt; // no common chart: the caller cancels (appendix B)
}

template <typename Visit>
void ConsistentMesh::forEachChart(const std::array<Preimage, 3>& p, Visit visit) const {
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
void ConsistentMesh::forEachChart(const std::array<PreimageSpan, 3>& reps, Visit visit) const {
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
    // that holds all three.
    Preimages tried;
    for (const auto& candidates : reps)
        for (const Preimage& chart : candidates) {
            if (std::any_of(tried.begin(), tried.end(),
                            [&](const Preimage& x) { return x.face == chart.face; }))
                continue;
            tried.push_back(chart);
            std::array<Vec2, 3> c;
            bool all = true;
            for (int i = 0; i < 3 && all; ++i) {
                const std::optional<Vec2> x = inChart(reps[i], chart.face);
                all = x.has_value();
                if (all)
                    c[i] = *x;
            }
            if (all)
                visit(c);
        }
}

// The charts a mesh without setVertexRingCharts has: each pair in one face
// or in edge-adjacent faces (interpolate()'s first two cases), and the three
// in one face's chart extended across its edges.
bool ConsistentMesh::withinEdgeCharts(const std::array<Preimage, 3>& p) const {
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
ConsistentMesh::chartCoordinates(const std::array<Preimage, 3>& p) const {
    std::vector<std::array<Vec2, 3>> out;
    forEachChart(p, [&](const std::array<Vec2, 3>& c) { out.push_back(c); });
    return out;
}

// Near an extraordinary domain vertex the charts of different faces do not
// agree exactly, so the orientation is the worst over every common chart:
// independent of the corners' order, and a fold in any chart counts.
std::optional<int> ConsistentMesh::parameterOrientation(const std::array<Preimage, 3>& p) const {
    bool any = false;
    int worst = 1;
    forEachChart(p, [&](const std::array<Vec2, 3>& c) {
        any = true;
        worst = std::min(worst, orientation2d(c[0], c[1], c[2]));
    });
    if (!any)
        return std::nullopt;
    return worst;
}

// The vertex table pays when many faces are unknown (after the
// initialization); a few edited faces find their corners' preimages
// directly (the same preimages, so the same results).
std::shared_ptr<const ConsistentMesh::VertexPreimages>
ConsistentMesh::tableFor(size_t unknownFaces) const {
    std::shared_ptr<const VertexPreimages> table = currentVertexPreimages();
    if (!table && 4 * unknownFaces > faces_.size())
        table = vertexPreimages();
    return table;
}

std::vector<std::optional<int>> ConsistentMesh::parameterOrientations() const {
    sizeFaceCaches();
    const size_t nf = faces_.size();
    const auto unknown = static_cast<size_t>(
        std::count(orientationCache_.begin(), orientationCache_.end(), kOrientationUnknown));
    const std::shared_ptr<const VertexPreimages> table = tableFor(unknown);
    std::vector<std::optional<int>> out(nf);
    tbb::parallel_for(size_t(0), nf, [&](size_t f) {
        std::int8_t& cached = orientationCache_[f];
        if (cached == kOrientationUnknown) {
            const Triangle& t = faces_[f];
            std::optional<int> o;
            if (table) {
                const std::array<PreimageSpan, 3> r{table->of(t[0]), table->of(t[1]),
                                                    table->of(t[2])};
                bool any = false;
                int worst = 1;
                forEachChart(r, [&](const std::array<Vec2, 3>& c) {
                    any = true;
                    worst = std::min(worst, orientation2d(c[0], c[1], c[2]));
                });
                if (any)
                    o = worst;
            } else {
                o = parameterOrientation(static_cast<Index>(f));
            }
            cached = o ? static_cast<std::int8_t>(*o) : kOrientationNoChart;
        }
        if (cached != kOrientationNoChart)
            out[f] = cached;
    });
    return out;
}

std::vector<Index> ConsistentMesh::centroidDomainFaces() const {
    sizeFaceCaches();
    const auto unknown = static_cast<size_t>(
        std::count(domainFaceCache_.begin(), domainFaceCache_.end(), kDomainFaceUnknown));
    const std::shared_ptr<const VertexPreimages> table = tableFor(unknown);
    tbb::parallel_for(size_t(0), faces_.size(), [&](size_t f) {
        if (domainFaceCache_[f] != kDomainFaceUnknown)
            return;
        const Triangle& t = faces_[f];
        const Preimage &p0 = vertices_[t[0]].preimage, &p1 = vertices_[t[1]].preimage,
                       &p2 = vertices_[t[2]].preimage;
        // interpolate(p0, p1, 0.5), then a third of the way to p2 (the
        // table holds equivalents() of each corner: the same as
        // interpolate() without it).
        const std::optional<Preimage> mid =
            p0.face == p1.face || !table ? interpolate(p0, p1, 0.5)
                                         : interpolateIn(table->of(t[0]), table->of(t[1]), 0.5);
        if (!mid) {
            domainFaceCache_[f] = kInvalidIndex;
            return;
        }
        std::optional<Preimage> centroid;
        if (mid->face == p2.face || !table) {
            centroid = interpolate(*mid, p2, 1.0 / 3.0);
        } else {
            const Preimages rm = equivalents(*mid);
            centroid = interpolateIn(span(rm), table->of(t[2]), 1.0 / 3.0);
        }
        domainFaceCache_[f] = centroid ? centroid->face : kInvalidIndex;
    });
    return domainFaceCache_;
}

std::shared_ptr<const ConsistentMesh::VertexPreimages> ConsistentMesh::vertexPreimages() const {
    if (preimageTable_ && preimageTable_->offsets.size() == vertices_.size() + 1)
        return preimageTable_;
    const size_t nv = vertices_.size();
    auto built = std::make_shared<VertexPreimages>();
    VertexPreimages& table = *built;
    table.offsets.assign(nv + 1, 0);
    tbb::parallel_for(size_t(0), nv, [&](size_t v) {
        table.offsets[v + 1] = equivalents(vertices_[v].preimage).size();
    });
    for (size_t v = 0; v < nv; ++v)
        table.offsets[v + 1] += table.offsets[v];
    table.reps.resize(table.offsets[nv]);
    tbb::parallel_for(size_t(0), nv, [&](size_t v) {
        const Preimages e = equivalents(vertices_[v].preimage);
        std::copy(e.begin(), e.end(),
                  table.reps.begin() + static_cast<std::ptrdiff_t>(table.offsets[v]));
    });
    preimageTable_ = built;
    return preimageTable_;
}

std::shared_ptr<const ConsistentMesh::VertexPreimages>
ConsistentMesh::currentVertexPreimages() const {
    if (preimageTable_ && preimageTable_->offsets.size() == vertices_.size() + 1)
        return preimageTable_;
    return nullptr;
}

std::optional<int> ConsistentMesh::parameterOrientation(Index f) const {
    const Triangle& t = faces_[f];
    return parameterOrientation(
        {vertices_[t[0]].preimage, vertices_[t[1]].preimage, vertices_[t[2]].preimage});
}

Index ConsistentMesh::splitEdge(Index a, Index b, MeshVertex v, int phase) {
    v.phase = phase;
    edgeTags_.erase(undirectedKey(a, b));
    const Index m = addVertex(v);
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
        const Index f = faceOfHalfedge(x, y);
        if (f == kInvalidIndex)
            continue;
        Triangle t = faces_[f];
        while (t[0] != x)
            std::rotate(t.begin(), t.begin() + 1, t.end());
        const Index c = t[2];
        detachFace(f);
        faces_[f] = {x, m, c};
        facePhase_[f] = phase;
        attachFace(f);
        addFace({m, y, c}, phase);
    }
    return m;
}

Index ConsistentMesh::splitFace(Index f, MeshVertex v, int phase) {
    v.phase = phase;
    const Triangle t = faces_[f];
    const Index m = addVertex(v);
    detachFace(f);
    faces_[f] = {t[0], t[1], m};
    facePhase_[f] = phase;
    attachFace(f);
    addFace({t[1], t[2], m}, phase);
    addFace({t[2], t[0], m}, phase);
    return m;
}

void ConsistentMesh::setVertex(Index v, const MeshVertex& x, int phase) {
    // The preimage tables depend on preimages only (the normal wiggle keeps
    // them).
    const Preimage& old = vertices_[v].preimage;
    if (old.face != x.preimage.face || std::memcmp(&old.u, &x.preimage.u, sizeof old.u) != 0 ||
        std::memcmp(&old.v, &x.preimage.v, sizeof old.v) != 0) {
        preimageTable_.reset();
        forgetFacesOf(v);
    }
    vertices_[v] = x;
    if (phase >= 0) {
        vertices_[v].phase = phase;
        for (Index f : vertexFaces_[v])
            facePhase_[f] = phase;
    }
}

std::array<Index, 2> ConsistentMesh::oppositeVertices(Index a, Index b) const {
    std::array<Index, 2> out{kInvalidIndex, kInvalidIndex};
    for (int side = 0; side < 2; ++side) {
        const Index f = side == 0 ? faceOfHalfedge(a, b) : faceOfHalfedge(b, a);
        if (f == kInvalidIndex)
            continue;
        for (Index w : faces_[f])
            if (w != a && w != b)
                out[side] = w;
    }
    return out;
}

bool ConsistentMesh::flipEdge(Index a, Index b, int phase) {
    const Index f0 = faceOfHalfedge(a, b), f1 = faceOfHalfedge(b, a);
    if (f0 == kInvalidIndex || f1 == kInvalidIndex)
        return false;
    const auto [c, d] = oppositeVertices(a, b);
    if (c == d || faceOfHalfedge(c, d) != kInvalidIndex || faceOfHalfedge(d, c) != kInvalidIndex)
        return false;
    detachFace(f0);
    detachFace(f1);
    faces_[f0] = {a, d, c};
    faces_[f1] = {b, c, d};
    facePhase_[f0] = phase;
    facePhase_[f1] = phase;
    attachFace(f0);
    attachFace(f1);
    edgeTags_.erase(undirectedKey(a, b));
    return true;
}

std::vector<Index> ConsistentMesh::neighbours(Index v) const {
    std::vector<Index> out;
    for (Index f : vertexFaces_[v])
        for (Index w : faces_[f])
            if (w != v && std::find(out.begin(), out.end(), w) == out.end())
                out.push_back(w);
    return out;
}

bool ConsistentMesh::isBoundaryVertex(Index v) const {
    for (Index f : vertexFaces_[v]) {
        const Triangle& t = faces_[f];
        for (int i = 0; i < 3; ++i)
            if (t[i] == v && (faceOfHalfedge(t[(i + 1) % 3], v) == kInvalidIndex ||
                              faceOfHalfedge(v, t[(i + 2) % 3]) == kInvalidIndex))
                return true;
    }
    return false;
}

bool ConsistentMesh::removeValence3Vertex(Index v, int phase) {
    const std::vector<Index> around = vertexFaces_[v];
    if (around.size() != 3 || isBoundaryVertex(v))
        return false;
    // The fan v-a-b, v-b-x, v-x-a (counter-clockwise) becomes a-b-x, which
    // keeps the fan's orientation.
    Triangle first = faces_[around[0]];
    while (first[0] != v)
        std::rotate(first.begin(), first.begin() + 1, first.end());
    const Index a = first[1], b = first[2];
    Index third = kInvalidIndex;
    for (Index w : neighbours(v))
        if (w != a && w != b)
            third = w;
    if (third == kInvalidIndex)
        return false;
    for (Index f : around)
        detachFace(f);
    // Keep the face slots compact: reuse around[0], move the last faces into
    // the other two slots.
    std::vector<Index> slots(around.begin(), around.end());
    std::sort(slots.begin(), slots.end());
    faces_[slots[0]] = {a, b, third};
    facePhase_[slots[0]] = phase;
    attachFace(slots[0]);
    for (int k = 2; k >= 1; --k) {
        const Index slot = slots[k];
        const Index last = faceCount() - 1;
        if (slot != last) {
            detachFace(last);
            faces_[slot] = faces_[last];
            facePhase_[slot] = facePhase_[last];
            attachFace(slot);
        }
        faces_.pop_back();
        facePhase_.pop_back();
    }
    for (auto it = edgeTags_.begin(); it != edgeTags_.end();) {
        const auto [x, y] = edgeFromKey(it->first);
        it = x == v || y == v ? edgeTags_.erase(it) : std::next(it);
    }
    return true;
}

void ConsistentMesh::compact() {
    std::vector<Index> newIndex(vertices_.size(), kInvalidIndex);
    Index n = 0;
    for (Index v = 0; v < vertexCount(); ++v)
        if (!vertexFaces_[v].empty())
            newIndex[v] = n++;
    if (n == vertexCount())
        return;
    preimageTable_.reset();
    // Faces keep their slots and their corners' preimages: the face caches
    // stay valid across the renumbering.
    std::vector<std::int8_t> orientation = std::move(orientationCache_);
    std::vector<Index> domainFace = std::move(domainFaceCache_);
    std::vector<MeshVertex> vertices(n);
    for (Index v = 0; v < vertexCount(); ++v)
        if (newIndex[v] != kInvalidIndex)
            vertices[newIndex[v]] = vertices_[v];
    std::unordered_map<std::uint64_t, int> tags;
    for (const auto& [k, tag] : edgeTags_) {
        const auto [x, y] = edgeFromKey(k);
        if (newIndex[x] != kInvalidIndex && newIndex[y] != kInvalidIndex)
            tags[undirectedKey(newIndex[x], newIndex[y])] = tag;
    }
    vertices_ = std::move(vertices);
    edgeTags_ = std::move(tags);
    sharedHalfedges_.reset();
    halfedgeFace_.clear();
    // Sized once (not grown face by face): the same lists and table.
    halfedgeFace_.reserve(3 * faces_.size());
    std::vector<Index> valence(static_cast<size_t>(n), 0);
    for (Triangle& t : faces_)
        for (Index& w : t) {
            w = newIndex[w];
            ++valence[static_cast<size_t>(w)];
        }
    vertexFaces_.assign(n, {});
    for (size_t v = 0; v < static_cast<size_t>(n); ++v)
        vertexFaces_[v].reserve(static_cast<size_t>(valence[v]));
    for (Index f = 0; f < faceCount(); ++f)
        attachFace(f);
    orientationCache_ = std::move(orientation);
    domainFaceCache_ = std::move(domainFace);
}

int ConsistentMesh::edgeTag(Index a, Index b) const {
    const auto it = edgeTags_.find(undirectedKey(a, b));
    return it == edgeTags_.end() ? kNoTag : it->second;
}

void ConsistentMesh::setEdgeTag(Index a, Index b, int tag) {
    if (tag == kNoTag)
        edgeTags_.erase(undirectedKey(a, b));
    else
        edgeTags_[undirectedKey(a, b)] = tag;
}

void ConsistentMesh::shiftVertex(Index v, const Preimage& p, VertexLabel label, int phase) {
    preimageTable_.reset();
    forgetFacesOf(v);
    MeshVertex moved = evaluate(p);
    moved.label = label;
    moved.provenance = Provenance::Shifted;
    moved.phase = phase;
    vertices_[v] = moved;
    for (Index f : vertexFaces_[v])
        facePhase_[f] = phase;
}

std::shared_ptr<const TriangleMesh> ConsistentMesh::toTriangleMesh() const {
    std::vector<Vec3> positions(vertices_.size());
    for (size_t i = 0; i < vertices_.size(); ++i)
        positions[i] = vertices_[i].position;
    return std::make_shared<const TriangleMesh>(std::move(positions), faces_);
}

} // namespace contour::consistent
