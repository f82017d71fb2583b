#pragma once
// The per-vertex values of the consistent method's mesh at a preimage u
// (Bénard, Hertzmann & Kass 2014 §4, §6): position f(u), unit limit normal
// n(u), g(u) = (c - f) · n (eq. 1, c the camera), the radial curvature κr
// and the label sign(g). A vertex's position is always f(u_i), its normal
// n(u_i) (§4), so every vertex record of the mesh comes from here.
#include "camera/Camera.h"
#include "contours/consistent/mesh/MeshVertex.h"
#include "surface/SmoothSurface.h"

#include <memory>

namespace contour::consistent {

class VertexEvaluator {
public:
    VertexEvaluator(std::shared_ptr<const SmoothSurface> surface, const Camera& camera);

    const SmoothSurface& surface() const { return *surface_; }
    const Camera& camera() const { return camera_; }

    // Evaluates f, n, g and the radial curvature at p; the label is sign(g).
    MeshVertex evaluate(const Preimage& p) const;
    // evaluate(p) given sp = surface().evaluate(p), already computed (the
    // initialization's tessellation evaluated every vertex).
    MeshVertex evaluated(const Preimage& p, const SurfacePoint& sp) const;
    // The same without the radial curvature (NaN): what the label and the
    // facing of a candidate need. Every other field has evaluate()'s exact
    // value, so evaluate() of a chosen candidate gives the same record.
    MeshVertex evaluateWithoutCurvature(const Preimage& p) const;

private:
    std::shared_ptr<const SmoothSurface> surface_;
    Camera camera_;
};

} // namespace contour::consistent
