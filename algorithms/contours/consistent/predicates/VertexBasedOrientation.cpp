#include "contours/consistent/predicates/VertexBasedOrientation.h"

namespace contour::consistent {

// Definition 1: the VBO follows the non-C labels; it is
// undefined when both F and B occur or when all three vertices are C.
Vbo vertexBasedOrientation(VertexLabel a, VertexLabel b, VertexLabel c) {
    int front = 0, back = 0;
    for (VertexLabel l : {a, b, c}) {
        front += l == VertexLabel::Front;
        back += l == VertexLabel::Back;
    }
    if ((front > 0 && back > 0) || front + back == 0)
        return Vbo::Undefined;
    return front > 0 ? Vbo::Front : Vbo::Back;
}

// Definition 2.
bool isConsistent(Vbo vbo, Facing facing) {
    return (vbo == Vbo::Front && facing == Facing::Front) ||
           (vbo == Vbo::Back && facing == Facing::Back);
}

// Definition 3.
bool isDegenerateEdge(VertexLabel a, VertexLabel b, Vbo left, Vbo right) {
    return a == VertexLabel::Contour && b == VertexLabel::Contour && left != Vbo::Undefined &&
           left == right;
}

} // namespace contour::consistent
