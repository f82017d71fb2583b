#include "contours/consistent/edits/RingRetriangulation.h"

#include <algorithm>
#include <stdexcept>

namespace contour::consistent {

RingRetriangulation::RingRetriangulation(const ConsistentMesh& m, const std::vector<Index>& patch)
    : m_(m), nextFace_(m.faceCount()), nextVertex_(m.vertexCount()) {
    for (Index f : patch)
        faces_[f] = m.face(f);
}

Index RingRetriangulation::faceOfHalfedge(Index a, Index b) const {
    for (const auto& [f, t] : faces_)
        for (int i = 0; i < 3; ++i)
            if (t[i] == a && t[(i + 1) % 3] == b)
                return f;
    // Outside the patch the mesh is unchanged; inside it the copy decides.
    if (a >= m_.vertexCount() || b >= m_.vertexCount())
        return kInvalidIndex;
    const Index g = m_.faceOfHalfedge(a, b);
    return g != kInvalidIndex && !local(g) ? g : kInvalidIndex;
}

const std::vector<Index>& RingRetriangulation::vertexFaces(Index v) {
    auto it = vertexFaces_.find(v);
    if (it == vertexFaces_.end()) {
        std::vector<Index> start;
        if (v < m_.vertexCount())
            start = m_.vertexFaces(v);
        it = vertexFaces_.emplace(v, std::move(start)).first;
    }
    return it->second;
}

// As ConsistentMesh::detachFace / attachFace keep a vertex's faces: erased
// where they were, appended when attached.
void RingRetriangulation::detach(Index f) {
    for (Index w : faces_.at(f)) {
        vertexFaces(w);
        std::erase(vertexFaces_[w], f);
    }
}
void RingRetriangulation::attach(Index f) {
    for (Index w : faces_.at(f)) {
        vertexFaces(w);
        vertexFaces_[w].push_back(f);
    }
}

std::optional<Index> RingRetriangulation::splitFace(Index f) {
    if (merged_ || !local(f))
        return std::nullopt;
    const Triangle t = faces_[f];
    const Index x = nextVertex_++;
    vertexFaces_[x] = {};
    detach(f);
    faces_[f] = {t[0], t[1], x};
    attach(f);
    for (const Triangle& n : {Triangle{t[1], t[2], x}, Triangle{t[2], t[0], x}}) {
        faces_[nextFace_] = n;
        attach(nextFace_++);
    }
    edits_.push_back({Edit::Split, f, x});
    return x;
}

bool RingRetriangulation::flipEdge(Index a, Index b) {
    const Index f0 = faceOfHalfedge(a, b), f1 = faceOfHalfedge(b, a);
    if (merged_ || f0 == kInvalidIndex || f1 == kInvalidIndex || !local(f0) || !local(f1))
        return false;
    Index c = kInvalidIndex, d = kInvalidIndex;
    for (Index w : faces_[f0])
        if (w != a && w != b)
            c = w;
    for (Index w : faces_[f1])
        if (w != a && w != b)
            d = w;
    if (c == d || faceOfHalfedge(c, d) != kInvalidIndex || faceOfHalfedge(d, c) != kInvalidIndex)
        return false;
    detach(f0);
    detach(f1);
    faces_[f0] = {a, d, c};
    faces_[f1] = {b, c, d};
    attach(f0);
    attach(f1);
    edits_.push_back({Edit::Flip, a, b});
    return true;
}

bool RingRetriangulation::removeValence3Vertex(Index v) {
    const std::vector<Index> around = vertexFaces(v);
    if (merged_ || around.size() != 3)
        return false;
    for (Index f : around) {
        if (!local(f))
            return false;
        const Triangle t = rotatedTo(faces_[f], v);
        if (faceOfHalfedge(t[1], v) == kInvalidIndex || faceOfHalfedge(v, t[2]) == kInvalidIndex)
            return false;
    }
    const Triangle first = rotatedTo(faces_[around[0]], v);
    Index third = kInvalidIndex;
    for (Index f : around)
        for (Index w : faces_[f])
            if (w != v && w != first[1] && w != first[2])
                third = w;
    if (third == kInvalidIndex)
        return false;
    // The mesh then moves its last faces into the freed slots: no edit may
    // follow, and the copy only keeps the triangles.
    for (Index f : around) {
        detach(f);
        faces_.erase(f);
    }
    faces_[*std::min_element(around.begin(), around.end())] = {first[1], first[2], third};
    merged_ = true;
    edits_.push_back({Edit::Merge, v, kInvalidIndex});
    return true;
}

bool RingRetriangulation::cutEars(Index v, std::vector<Index> ring, std::vector<Triangle> faces,
                                  const std::vector<Index>& fan) {
    const auto has = [&](Index a, Index b, Index c) {
        for (size_t n = 0; n < faces.size(); ++n) {
            const Triangle& t = faces[n];
            for (int r = 0; r < 3; ++r)
                if (t[r] == a && t[(r + 1) % 3] == b && t[(r + 2) % 3] == c)
                    return static_cast<int>(n);
        }
        return -1;
    };
    // Every polygon triangulation has an ear; the fan corners stay.
    while (ring.size() > std::max<size_t>(fan.size(), 3)) {
        const int k = static_cast<int>(ring.size());
        bool flipped = false;
        for (int i = 0; i < k && !flipped; ++i) {
            const Index prev = ring[(i + k - 1) % k], w = ring[i], next = ring[(i + 1) % k];
            if (std::find(fan.begin(), fan.end(), w) != fan.end())
                continue;
            const int n = has(prev, w, next);
            if (n < 0)
                continue;
            if (!flipEdge(v, w))
                return false;
            faces.erase(faces.begin() + n);
            ring.erase(ring.begin() + i);
            flipped = true;
        }
        if (!flipped)
            return false;
    }
    return true;
}

std::vector<Triangle> RingRetriangulation::patchFaces() const {
    std::vector<Triangle> out;
    for (const auto& [f, t] : faces_)
        out.push_back(t);
    return out;
}

bool RingRetriangulation::endsIn(const std::vector<Triangle>& target) const {
    const auto canonical = [](Triangle t) {
        return rotatedTo(t, *std::min_element(t.begin(), t.end()));
    };
    std::vector<Triangle> now = patchFaces(), want = target;
    for (Triangle& t : now)
        t = canonical(t);
    for (Triangle& t : want)
        t = canonical(t);
    std::sort(now.begin(), now.end());
    std::sort(want.begin(), want.end());
    return now == want;
}

void RingRetriangulation::apply(ConsistentMesh& m, const MeshVertex* split, int phase) const {
    for (const Edit& e : edits_) {
        bool done = false;
        switch (e.kind) {
        case Edit::Split:
            done = split && m.splitFace(e.a, *split, phase) == e.b;
            break;
        case Edit::Flip:
            done = m.flipEdge(e.a, e.b, phase);
            break;
        case Edit::Merge:
            done = m.removeValence3Vertex(e.a, phase);
            break;
        }
        if (!done)
            throw std::logic_error("ring re-triangulation: the mesh refused a planned edit");
    }
}

std::vector<Index> simpleCycle(const std::vector<std::pair<Index, Index>>& edges) {
    std::vector<Index> ring;
    if (edges.size() < 3)
        return ring;
    Index w = edges.front().first;
    for (size_t k = 0; k < edges.size(); ++k) {
        ring.push_back(w);
        const auto it =
            std::find_if(edges.begin(), edges.end(),
                         [w](const std::pair<Index, Index>& e) { return e.first == w; });
        if (it == edges.end())
            return {};
        w = it->second;
    }
    if (w != ring.front())
        return {};
    std::vector<Index> sorted = ring;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
        return {};
    return ring;
}

std::vector<Index> outline(const ConsistentMesh& m, const std::vector<Index>& faces) {
    std::vector<std::pair<Index, Index>> half;
    for (Index f : faces) {
        const Triangle t = m.face(f);
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            const Index g = m.faceOfHalfedge(b, a);
            if (g == kInvalidIndex || std::find(faces.begin(), faces.end(), g) == faces.end())
                half.emplace_back(a, b);
        }
    }
    return simpleCycle(half);
}

} // namespace contour::consistent
