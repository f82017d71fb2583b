#include "contours/consistent/predicates/Shiftability.h"

#include <algorithm>
#include <set>

namespace contour::consistent {

bool shiftKeepsParameterOrientation(const ConsistentMesh& m, Index v, const Preimage& p) {
    for (Index f : m.vertexFaces(v)) {
        const Triangle t = rotatedTo(m.face(f), v);
        for (Index w : {t[1], t[2]})
            if (!m.interpolate(p, m.vertex(w).preimage, 0.5))
                return false;
        const std::optional<int> o =
            m.parameterOrientation({p, m.vertex(t[1]).preimage, m.vertex(t[2]).preimage});
        if (!o || *o <= 0)
            return false;
    }
    return true;
}

bool shiftable(const ConsistentMesh& m, Index v, const Preimage& p, VertexLabel newLabel) {
    if (m.vertex(v).label == VertexLabel::Contour || m.vertex(v).cusp)
        return false;
    int crossings = 0;
    std::set<Index> ringContour;
    for (Index f : m.vertexFaces(v)) {
        const Triangle t = rotatedTo(m.face(f), v);
        const VertexLabel l1 = m.vertex(t[1]).label, l2 = m.vertex(t[2]).label;
        // Rule 2: no CCC triangle.
        if (newLabel == VertexLabel::Contour && l1 == VertexLabel::Contour &&
            l2 == VertexLabel::Contour)
            return false;
        // docs/dev/invariants.md item 4 (Definition 3): no degenerate CC edge, ever. Once
        // v is C, edge v-t1 with t1 C is degenerate when the vertices
        // opposite it on both sides carry the same label (an isolated F or B
        // vertex inside a tiny loop would otherwise be snapped flat).
        if (newLabel == VertexLabel::Contour && l1 == VertexLabel::Contour) {
            const Index g = m.faceOfHalfedge(t[1], v);
            if (g != kInvalidIndex) {
                const Triangle& o = m.face(g);
                for (Index b : o)
                    if (b != v && b != t[1] && m.vertex(b).label == l2)
                        return false;
            }
        }
        // Rule 3: zero crossings on the outer boundary edge t1-t2.
        crossings += static_cast<int>(l1) * static_cast<int>(l2) < 0;
        for (Index w : {t[1], t[2]})
            if (m.vertex(w).label == VertexLabel::Contour)
                ringContour.insert(w);
    }
    if (crossings + static_cast<int>(ringContour.size()) > 2)
        return false;
    // Rules 4 and 1: interpolation still possible, no fold.
    return shiftKeepsParameterOrientation(m, v, p);
}

} // namespace contour::consistent
