#pragma once
// One kind of data of the 3D view, in the manner of 3D Slicer's displayable
// managers: a layer owns its VTK actors, builds their data from a Snapshot
// (and its own display options) and can be put in a renderer, drawn and
// tested alone. SceneView3D composes the layers; none of them runs an
// algorithm, they only convert snapshot parts to VTK data (SnapshotToVtk.h).
#include "pipeline/Snapshot.h"

#include <array>
#include <vector>

class vtkProp;
class vtkRenderer;

namespace contour {

class SceneLayer {
public:
    virtual ~SceneLayer() = default;
    SceneLayer(const SceneLayer&) = delete;
    SceneLayer& operator=(const SceneLayer&) = delete;

    // An actor of the layer and where it goes: depth-tested with the surface
    // (the scene renderer) or drawn over everything (the overlay renderer).
    struct Prop {
        vtkProp* prop;
        bool overTheScene;
    };
    // Every actor of the layer, in drawing order.
    virtual std::vector<Prop> props() const = 0;

    // Adds the layer's actors to `scene` and `overlay` (the same renderer when
    // the layer is drawn alone), or removes them.
    void addToRenderers(vtkRenderer* scene, vtkRenderer* overlay) const;
    void removeFromRenderers(vtkRenderer* scene, vtkRenderer* overlay) const;

    // Builds the layer's VTK data from `snapshot` (an empty snapshot draws
    // nothing). Parts of the snapshot that did not change since the last call
    // are not converted again.
    virtual void update(const Snapshot& snapshot) = 0;

    // The layer as a whole on or off; when on, each actor shows what the
    // layer's data and options say.
    void setVisible(bool visible);
    bool isVisible() const { return visible_; }

    int actorCount() const { return static_cast<int>(props().size()); }
    int visibleActorCount() const;
    // The bounds (x min, x max, y min, y max, z min, z max) of the visible 3D
    // actors; min > max when none is visible.
    std::array<double, 6> visibleBounds() const;

protected:
    SceneLayer() = default;
    // Sets every actor's visibility from the layer's state and isVisible().
    virtual void applyVisibility() = 0;

private:
    bool visible_ = true;
};

} // namespace contour
