#include "contours/consistent/edits/LocalEdit.h"

#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/TriangleQuality.h"

#include <algorithm>
#include <limits>

namespace contour::consistent {

bool betterScore(const LocalScore& a, const LocalScore& b) {
    if (a.inconsistent != b.inconsistent)
        return a.inconsistent < b.inconsistent;
    return a.minQuality > b.minQuality;
}

void LocalEdit::clear() {
    faces_.clear();
    moved_.clear();
    added_.clear();
}

void LocalEdit::addFaces(const std::vector<Index>& meshFaces) {
    for (Index f : meshFaces)
        faces_.push_back(m_.face(f));
}

void LocalEdit::moveVertex(Index v, const MeshVertex& x) {
    for (auto& [w, record] : moved_)
        if (w == v) {
            record = x;
            return;
        }
    moved_.emplace_back(v, x);
}

Index LocalEdit::addVertex(const MeshVertex& x) {
    added_.push_back(x);
    return m_.vertexCount() + static_cast<Index>(added_.size()) - 1;
}

const MeshVertex& LocalEdit::vertex(Index v) const {
    if (v >= m_.vertexCount())
        return added_[v - m_.vertexCount()];
    for (const auto& [w, record] : moved_)
        if (w == v)
            return record;
    return m_.vertex(v);
}

Vbo LocalEdit::vbo(const Triangle& t) const {
    return vertexBasedOrientation(vertex(t[0]).label, vertex(t[1]).label, vertex(t[2]).label);
}

bool LocalEdit::consistent(const Triangle& t) const {
    const Facing facing = triangleFacing(m_.camera(), vertex(t[0]).position, vertex(t[1]).position,
                                         vertex(t[2]).position);
    return isConsistent(vbo(t), facing);
}

LocalScore LocalEdit::score() const {
    return {inconsistent(), minQuality()};
}

int LocalEdit::inconsistent() const {
    int n = 0;
    for (const Triangle& t : faces_)
        n += !consistent(t);
    return n;
}

double LocalEdit::minQuality() const {
    double q = std::numeric_limits<double>::infinity();
    for (const Triangle& t : faces_)
        q = std::min(q, bankSmithQuality(vertex(t[0]).position, vertex(t[1]).position,
                                         vertex(t[2]).position));
    return q;
}

bool LocalEdit::turnedOver(const Triangle& t) const {
    const MeshVertex &a = vertex(t[0]), &b = vertex(t[1]), &c = vertex(t[2]);
    const Vec3 n = (b.position - a.position).cross(c.position - a.position);
    for (const MeshVertex* x : {&a, &b, &c})
        if (!(n.dot(x->normal) > 0.0))
            return true;
    return false;
}

int LocalEdit::turnedOver() const {
    int n = 0;
    for (const Triangle& t : faces_)
        n += turnedOver(t);
    return n;
}

bool LocalEdit::labelsValid() const {
    for (const Triangle& t : faces_) {
        const Vbo here = vbo(t);
        if (here == Vbo::Undefined)
            return false;
        for (int i = 0; i < 3; ++i) {
            const Index a = t[i], b = t[(i + 1) % 3];
            const VertexLabel la = vertex(a).label, lb = vertex(b).label;
            if (la != VertexLabel::Contour || lb != VertexLabel::Contour)
                continue;
            // The face across a-b: in the edit, or else the mesh's (the
            // edit replaces a disc of faces, so that one is unchanged).
            std::optional<Triangle> across;
            for (const Triangle& u : faces_)
                for (int j = 0; j < 3; ++j)
                    if (u[j] == b && u[(j + 1) % 3] == a)
                        across = u;
            if (!across && a < m_.vertexCount() && b < m_.vertexCount()) {
                const Index f = m_.faceOfHalfedge(b, a);
                if (f != kInvalidIndex)
                    across = m_.face(f);
            }
            if (across && isDegenerateEdge(la, lb, here, vbo(*across)))
                return false;
        }
    }
    return true;
}

bool LocalEdit::parameterValid() const {
    for (const Triangle& t : faces_) {
        const std::optional<int> o = m_.parameterOrientation(
            {vertex(t[0]).preimage, vertex(t[1]).preimage, vertex(t[2]).preimage});
        if (!o || *o <= 0)
            return false;
    }
    return true;
}

bool LocalEdit::shiftable(Index v) const {
    const MeshVertex& x = vertex(v);
    if (x.label == VertexLabel::Contour || x.cusp)
        return false;
    int crossings = 0;
    std::vector<Index> ringContour;
    for (const Triangle& t : faces_) {
        const auto it = std::find(t.begin(), t.end(), v);
        if (it == t.end())
            continue;
        const int i = static_cast<int>(it - t.begin());
        const Index t1 = t[(i + 1) % 3], t2 = t[(i + 2) % 3];
        const VertexLabel l1 = vertex(t1).label, l2 = vertex(t2).label;
        // Rule 3: zero crossings on the outer boundary edge t1-t2.
        crossings += static_cast<int>(l1) * static_cast<int>(l2) < 0;
        for (Index w : {t1, t2}) {
            if (vertex(w).label == VertexLabel::Contour &&
                std::find(ringContour.begin(), ringContour.end(), w) == ringContour.end())
                ringContour.push_back(w);
            // Rule 4: interpolation to every neighbour still possible.
            if (!m_.interpolate(x.preimage, vertex(w).preimage, 0.5))
                return false;
        }
    }
    return crossings + static_cast<int>(ringContour.size()) <= 2;
}

std::vector<Index> inconsistentFaces(const ConsistentMesh& m) {
    std::vector<Index> out;
    for (Index f = 0; f < m.faceCount(); ++f)
        if (!faceIsConsistent(m, f))
            out.push_back(f);
    return out;
}

std::vector<Index> verticesOf(const ConsistentMesh& m, const std::vector<Index>& faces) {
    std::vector<Index> out;
    out.reserve(3 * faces.size());
    for (Index f : faces)
        out.insert(out.end(), m.face(f).begin(), m.face(f).end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

bool lockedCusp(const ConsistentMesh& m, Index w, bool cuspEdits) {
    return w != kInvalidIndex && m.vertex(w).cusp && (!cuspEdits || !onRadialEdge(m, w));
}

} // namespace contour::consistent
