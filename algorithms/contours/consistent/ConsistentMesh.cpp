#include "contours/consistent/ConsistentMesh.h"

#include "geometry/Predicates.h"
#include "surface/SurfaceFields.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

// Notes §1.3: a vertex's position is always f(u_i), its normal n(u_i).
MeshVertex ConsistentMesh::evaluate(const Preimage& p) const {
    const SurfacePoint sp = surface_->evaluate(p);
    MeshVertex v;
    v.preimage = p;
    v.position = sp.position;
    v.normal = sp.normal();
    v.g = orientation(sp, camera_);
    v.radialCurvature = radialCurvature(sp, camera_);
    v.label = labelFromG(v.g);
    return v;
}

Index ConsistentMesh::addVertex(const MeshVertex& v) {
    vertices_.push_back(v);
    vertexFaces_.emplace_back();
    return vertexCount() - 1;
}

Index ConsistentMesh::addFace(const Triangle& t, int phase) {
    faces_.push_back(t);
    facePhase_.push_back(phase);
    attachFace(faceCount() - 1);
    return faceCount() - 1;
}

void ConsistentMesh::attachFace(Index f) {
    const Triangle& t = faces_[f];
    for (int i = 0; i < 3; ++i) {
        const auto [it, inserted] = halfedgeFace_.emplace(key(t[i], t[(i + 1) % 3]), f);
        if (!inserted)
            throw std::logic_error("ConsistentMesh: non-manifold or inconsistently oriented edge");
        vertexFaces_[t[i]].push_back(f);
    }
}

void ConsistentMesh::detachFace(Index f) {
    const Triangle& t = faces_[f];
    for (int i = 0; i < 3; ++i) {
        const auto it = halfedgeFace_.find(key(t[i], t[(i + 1) % 3]));
        if (it != halfedgeFace_.end() && it->second == f)
            halfedgeFace_.erase(it);
        std::erase(vertexFaces_[t[i]], f);
    }
}

Index ConsistentMesh::faceOfHalfedge(Index a, Index b) const {
    const auto it = halfedgeFace_.find(key(a, b));
    return it == halfedgeFace_.end() ? kInvalidIndex : it->second;
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
std::vector<Preimage> ConsistentMesh::equivalents(const Preimage& p) const {
    std::vector<Preimage> out{p};
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

std::optional<Vec2> ConsistentMesh::inChart(const std::vector<Preimage>& reps, Index face) const {
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

std::optional<Preimage> ConsistentMesh::interpolate(const Preimage& a, const Preimage& b,
                                                    double t) const {
    const std::vector<Preimage> ra = equivalents(a), rb = equivalents(b);
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
    return std::nullopt; // no common chart: the caller cancels (appendix B)
}

std::vector<std::array<Vec2, 3>>
ConsistentMesh::chartCoordinates(const std::array<Preimage, 3>& p) const {
    const std::array<std::vector<Preimage>, 3> reps{equivalents(p[0]), equivalents(p[1]),
                                                    equivalents(p[2])};
    std::vector<std::array<Vec2, 3>> out;
    // Every domain face holding all three preimages is a faithful chart.
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
        if (found == 3)
            out.push_back(c);
    }
    if (!out.empty())
        return out;
    // Otherwise every face's chart extended across its edges (appendix B)
    // that holds all three.
    std::vector<Index> tried;
    for (const auto& candidates : reps)
        for (const Preimage& chart : candidates) {
            if (std::find(tried.begin(), tried.end(), chart.face) != tried.end())
                continue;
            tried.push_back(chart.face);
            std::array<Vec2, 3> c;
            bool all = true;
            for (int i = 0; i < 3 && all; ++i) {
                const std::optional<Vec2> x = inChart(reps[i], chart.face);
                all = x.has_value();
                if (all)
                    c[i] = *x;
            }
            if (all)
                out.push_back(c);
        }
    return out;
}

// Near an extraordinary domain vertex the charts of different faces do not
// agree exactly, so the orientation is the worst over every common chart:
// independent of the corners' order, and a fold in any chart counts.
std::optional<int> ConsistentMesh::parameterOrientation(const std::array<Preimage, 3>& p) const {
    const auto charts = chartCoordinates(p);
    if (charts.empty())
        return std::nullopt;
    int worst = 1;
    for (const auto& c : charts)
        worst = std::min(worst, orientation2d(c[0], c[1], c[2]));
    return worst;
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
    vertexFaces_.assign(n, {});
    halfedgeFace_.clear();
    for (Triangle& t : faces_)
        for (Index& w : t)
            w = newIndex[w];
    for (Index f = 0; f < faceCount(); ++f)
        attachFace(f);
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
