#pragma once
// The decimated copy of a large mesh (MotionMesh.h) drawn instead of the
// mesh while the camera moves, each triangle in the colour of the face it
// stands for (facing, VBO or the scalar field, MeshColoringLayer::faceColor)
// with the radial tint folded in, since the translucent tint is not drawn
// while moving. The copy is built elsewhere (on a worker thread) and handed
// to setCopy(); a copy of another mesh than the snapshot's is dropped.
#include "MotionMesh.h"
#include "SceneLayer.h"

#include <memory>
#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>

namespace contour {

class MeshColoringLayer;

class MotionCopyLayer : public SceneLayer {
public:
    MotionCopyLayer();

    std::vector<Prop> props() const override;
    // Drops the copy when the snapshot's mesh is not the one it stands for.
    void update(const Snapshot& snapshot) override;

    // The copy of `mesh` (ignored unless it is the current snapshot's mesh).
    void setCopy(MotionMesh copy, std::shared_ptr<const TriangleMesh> mesh);
    void clearCopy();
    // True when the copy of the current snapshot's mesh is there.
    bool isReady() const;
    // The mesh the copy stands for (null when none).
    const std::shared_ptr<const TriangleMesh>& copiedMesh() const { return copiedMesh_; }
    long long faceCount() const;
    double buildSeconds() const;
    vtkPolyData* copyData() const { return copy_.data; }

    // Gives every triangle its source face's colour under `coloring`, with
    // the snapshot's radial tint (sceneColors::kRadialTint and
    // kStandardRadialTint at kRadialTintOpacity) when `radialTint`.
    void recolour(const MeshColoringLayer& coloring, bool radialTint);

    // Drawn when asked for and ready.
    void setShown(bool shown);
    bool isShown() const;

protected:
    void applyVisibility() override;

private:
    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
    MotionMesh copy_;
    std::shared_ptr<const TriangleMesh> copiedMesh_;
    Snapshot snapshot_;
    bool shown_ = false;
};

} // namespace contour
