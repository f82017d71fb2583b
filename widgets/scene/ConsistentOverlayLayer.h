#pragma once
// What the 3D view draws over the mesh from the consistent method's fields
// (Bénard 2014), each a toggle: the outlines of inconsistent faces
// (fields::kConsistent == 0, Definition 2, drawn over everything),
// translucent tints of radial and standard radial triangles (Definition 5,
// §6.3), the contour (C) vertices (fields::kLabel == 0, §6.2), the cusps
// (fields::kCusp, larger squares, drawn over everything) and the radial
// edges (fields::kRadialEdge); for the Powell-Sabin spline (Capouellez et
// al. 2023 §5) the patch boundaries (fields::kPatchEdge: patch, macro-patch
// and cut edges in three colours) and the cones (fields::kCone). An overlay
// is drawn when it is enabled and the snapshot has its fields.
#include "SceneLayer.h"

#include <array>
#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

class vtkDataArray;
class vtkPolyData;

namespace contour {

enum class SceneOverlay {
    InconsistentFaces,
    RadialFaces,
    ContourVertices,
    Cusps,
    RadialEdges,
    PatchEdges,
    Cones
};
inline constexpr int kSceneOverlayCount = 7;

class ConsistentOverlayLayer : public SceneLayer {
public:
    ConsistentOverlayLayer();

    std::vector<Prop> props() const override;
    void update(const Snapshot& snapshot) override;

    // The point normals the radial tint is shaded with (the mesh's own, so
    // the tint shades like the surface under it; null: flat). Applied by the
    // next update().
    void setSurfaceNormals(vtkDataArray* normals) { normals_ = normals; }

    // The choice is kept across snapshots (all enabled at first).
    void setEnabled(SceneOverlay overlay, bool enabled);
    bool isEnabled(SceneOverlay overlay) const { return slot(overlay).enabled; }
    // The snapshot has the overlay's fields.
    bool isAvailable(SceneOverlay overlay) const { return static_cast<bool>(slot(overlay).data); }
    bool isShown(SceneOverlay overlay) const;
    // Elements in the overlay's VTK data (outlined faces, tinted faces, C
    // vertices, cusps, radial edges); 0 when it is not available.
    long long elementCount(SceneOverlay overlay) const;
    // The overlay's VTK data, or null when it is not available.
    vtkPolyData* data(SceneOverlay overlay) const { return slot(overlay).data; }

    // While the camera moves the translucent tint is not drawn (a stand-in
    // folds it into its colours).
    void setMotionDrawing(bool on);

protected:
    void applyVisibility() override;

private:
    struct Slot {
        vtkNew<vtkPolyDataMapper> mapper;
        vtkNew<vtkActor> actor;
        vtkSmartPointer<vtkPolyData> data; // null when not available
        bool enabled = true;
    };
    Slot& slot(SceneOverlay overlay) { return slots_[static_cast<size_t>(overlay)]; }
    const Slot& slot(SceneOverlay overlay) const { return slots_[static_cast<size_t>(overlay)]; }

    std::array<Slot, kSceneOverlayCount> slots_;
    vtkNew<vtkLookupTable> radialColors_;
    vtkNew<vtkLookupTable> patchEdgeColors_;
    vtkSmartPointer<vtkDataArray> normals_;
    bool motionDrawing_ = false;
};

} // namespace contour
