#include "contours/consistent/mesh/ConsistentMesh.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace contour::consistent {

ConsistentMesh::ConsistentMesh(std::shared_ptr<const SmoothSurface> surface, const Camera& camera,
                               double chartTolerance)
    : charts_(surface, chartTolerance), evaluator_(std::move(surface), camera) {}

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
    return {charts_.tolerance(), orientationCache_, domainFaceCache_};
}

void ConsistentMesh::adoptFaceCaches(const FaceCaches& caches) {
    if (caches.chartTolerance != charts_.tolerance() ||
        caches.orientation.size() != faces_.size() || caches.domainFace.size() != faces_.size())
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
                o = charts_.parameterOrientationIn(
                    {table->of(t[0]), table->of(t[1]), table->of(t[2])});
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
            p0.face == p1.face || !table
                ? charts_.interpolate(p0, p1, 0.5)
                : charts_.interpolateIn(table->of(t[0]), table->of(t[1]), 0.5);
        if (!mid) {
            domainFaceCache_[f] = kInvalidIndex;
            return;
        }
        std::optional<Preimage> centroid;
        if (mid->face == p2.face || !table) {
            centroid = charts_.interpolate(*mid, p2, 1.0 / 3.0);
        } else {
            const DomainCharts::Preimages rm = charts_.equivalents(*mid);
            centroid = charts_.interpolateIn(DomainCharts::span(rm), table->of(t[2]), 1.0 / 3.0);
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
        table.offsets[v + 1] = charts_.equivalents(vertices_[v].preimage).size();
    });
    for (size_t v = 0; v < nv; ++v)
        table.offsets[v + 1] += table.offsets[v];
    table.reps.resize(table.offsets[nv]);
    tbb::parallel_for(size_t(0), nv, [&](size_t v) {
        const DomainCharts::Preimages e = charts_.equivalents(vertices_[v].preimage);
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
    return charts_.parameterOrientation(
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
