#pragma once
// The snapshot's view graph (Snapshot::viewGraph): visible chains thick and
// bright, hidden ones thinner and darker (depth-tested like the surface, so
// orbit to see them), chains simplified away faint and optional, each
// coloured by QI or by chain; the nodes as round dots coloured by type
// (ViewGraphStyle.h): those on a visible chain drawn over everything, those
// only on hidden chains depth-tested with the hidden chains.
#include "SceneLayer.h"
#include "ViewGraphStyle.h"

#include <array>
#include <memory>
#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

class vtkPolyData;

namespace contour {

class ViewGraphLayer : public SceneLayer {
public:
    ViewGraphLayer();

    std::vector<Prop> props() const override;
    // Converts the view graph only when the snapshot's graph changes.
    void update(const Snapshot& snapshot) override;

    bool hasViewGraph() const { return static_cast<bool>(graph_); }
    // Display choices, kept across snapshots.
    void setShowHiddenCurves(bool show);
    bool showsHiddenCurves() const { return showHidden_; }
    void setShowSimplifiedCurves(bool show);
    bool showsSimplifiedCurves() const { return showSimplified_; }
    void setShowNodes(bool show);
    bool showsNodes() const { return showNodes_; }
    void setChainColoring(ChainColoring coloring);
    ChainColoring chainColoring() const { return coloring_; }
    // Visible chains coloured by QI in sceneColors::kContourOverField (over a
    // scalar field, whose map has red in it) instead of kContour3D.
    void setOverScalarField(bool over);

    // Chains in `state` drawn now (0 when that kind is off or there is no
    // view graph), node dots drawn now (both kinds), and their VTK data (null
    // without a view graph): the nodes on a visible chain, or with `hidden`
    // those whose chains are all hidden.
    long long chainsShown(ChainState state) const;
    long long nodesShown() const;
    vtkPolyData* chainData(ChainState state) const;
    vtkPolyData* nodeData(bool hidden) const;

protected:
    void applyVisibility() override;

private:
    void recolour();

    struct Part {
        vtkNew<vtkPolyDataMapper> mapper;
        vtkNew<vtkActor> actor;
        vtkSmartPointer<vtkPolyData> data; // null without a view graph
    };
    static constexpr int kChainStateCount = 3;
    std::array<Part, kChainStateCount> chains_; // ChainState order
    std::array<Part, 2> nodes_;                 // [0] on a visible chain, [1] hidden
    std::shared_ptr<const ViewGraph> graph_;
    bool showHidden_ = true;
    bool showSimplified_ = false;
    bool showNodes_ = true;
    bool overScalarField_ = false;
    ChainColoring coloring_ = ChainColoring::ByQi;
};

} // namespace contour
