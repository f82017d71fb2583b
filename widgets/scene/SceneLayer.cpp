#include "SceneLayer.h"

#include <algorithm>
#include <limits>
#include <vtkProp.h>
#include <vtkRenderer.h>

namespace contour {

void SceneLayer::addToRenderers(vtkRenderer* scene, vtkRenderer* overlay) const {
    for (const Prop& p : props())
        (p.overTheScene ? overlay : scene)->AddViewProp(p.prop);
}

void SceneLayer::removeFromRenderers(vtkRenderer* scene, vtkRenderer* overlay) const {
    for (const Prop& p : props())
        (p.overTheScene ? overlay : scene)->RemoveViewProp(p.prop);
}

void SceneLayer::setVisible(bool visible) {
    visible_ = visible;
    applyVisibility();
}

int SceneLayer::visibleActorCount() const {
    const std::vector<Prop> all = props();
    return static_cast<int>(std::count_if(all.begin(), all.end(),
                                          [](const Prop& p) { return p.prop->GetVisibility(); }));
}

std::array<double, 6> SceneLayer::visibleBounds() const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::array<double, 6> box{kInf, -kInf, kInf, -kInf, kInf, -kInf};
    for (const Prop& p : props()) {
        if (!p.prop->GetVisibility())
            continue;
        const double* b = p.prop->GetBounds(); // null for 2D actors
        if (!b || b[0] > b[1])
            continue;
        for (int axis = 0; axis < 3; ++axis) {
            box[2 * axis] = std::min(box[2 * axis], b[2 * axis]);
            box[2 * axis + 1] = std::max(box[2 * axis + 1], b[2 * axis + 1]);
        }
    }
    return box;
}

} // namespace contour
