#include "contours/consistent/mesh/VertexEvaluator.h"

#include "surface/SurfaceFields.h"

#include <limits>
#include <stdexcept>

namespace contour::consistent {

VertexEvaluator::VertexEvaluator(std::shared_ptr<const SmoothSurface> surface, const Camera& camera)
    : surface_(std::move(surface)), camera_(camera) {
    if (!surface_)
        throw std::invalid_argument("VertexEvaluator: no smooth surface");
}

MeshVertex VertexEvaluator::evaluate(const Preimage& p) const {
    return evaluated(p, surface_->evaluate(p));
}

MeshVertex VertexEvaluator::evaluated(const Preimage& p, const SurfacePoint& sp) const {
    MeshVertex v;
    v.preimage = p;
    v.position = sp.position;
    v.normal = sp.normal();
    v.g = orientation(sp, camera_);
    v.radialCurvature = radialCurvature(sp, camera_);
    v.label = labelFromG(v.g);
    return v;
}

MeshVertex VertexEvaluator::evaluateWithoutCurvature(const Preimage& p) const {
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

} // namespace contour::consistent
