#pragma once
// Bénard 2014 §8.1, footnote 3: which of a contour edge's two faces is
// nearer the camera. v is the unit vector from the edge's midpoint to the
// camera; w1, w2 are v projected into each face and turned towards that
// face's opposite vertex; face 1 is near if v·w1 > v·w2. The margin
// |v·(w1 − w2)| says how reliable the answer is (the paper's threshold is a
// parameter, near-face-epsilon).
#include "camera/Camera.h"
#include "mesh/TriangleMesh.h"

namespace contour {

struct NearFace {
    Index face = kInvalidIndex; // kInvalidIndex for a boundary edge
    double margin = 0.0;        // |v·(w1 − w2)|, in [0, 2]
};

NearFace nearFace(const TriangleMesh& mesh, const Camera& camera, Index edge);

} // namespace contour
