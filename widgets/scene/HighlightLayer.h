#pragma once
// The linked selection (Selection.h) drawn over everything in
// sceneColors::kSelection: a face's outline, a vertex's dot, an edge, or a
// view-graph chain. Nothing is drawn when the selection does not exist in the
// snapshot (another phase's mesh, no view graph).
#include "SceneLayer.h"
#include "Selection.h"

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

class vtkPolyData;

namespace contour {

class HighlightLayer : public SceneLayer {
public:
    HighlightLayer();

    std::vector<Prop> props() const override;
    void update(const Snapshot& snapshot) override;

    void setSelection(const Selection& selection);
    const Selection& selection() const { return selection_; }
    // The highlight's VTK data (null when nothing is drawn).
    vtkPolyData* highlightData() const { return data_; }

protected:
    void applyVisibility() override;

private:
    void rebuild();

    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
    vtkSmartPointer<vtkPolyData> data_;
    Selection selection_;
    Snapshot snapshot_;
};

} // namespace contour
