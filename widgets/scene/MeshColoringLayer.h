#pragma once
// The working mesh of a snapshot, coloured by facing (sceneColors::kFrontFace
// / kBackFace, kUnclassifiedFace before the facing phase), by a face label
// field (the consistent method's VBO, Bénard 2014 Definition 1: F and B in
// the facing colours, undefined in kUndefinedVbo) or by a signed scalar field
// (g, radial, Gaussian or mean curvature) on the diverging map
// (DivergingColorMap.h) with its scalar bar. A tessellated smooth surface is
// shaded with its exact normals, a plain triangle mesh with flat faces.
#include "DivergingColorMap.h"
#include "SceneLayer.h"

#include <QRect>
#include <QSize>
#include <memory>
#include <string>
#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>

class vtkDataArray;
class vtkPolyData;
class vtkProperty;

namespace contour {

class MeshColoringLayer : public SceneLayer {
public:
    MeshColoringLayer();

    std::vector<Prop> props() const override;
    // Converts the mesh geometry only when the snapshot's mesh changes.
    void update(const Snapshot& snapshot) override;

    // What to colour the mesh by: fields::kFacing, a face label field
    // (faceLabelFieldNames) or a scalar field (scalarFieldNames). The choice
    // is kept across snapshots; a snapshot without that field is shown by
    // facing (displayedColorField()) until one has it again.
    void setColorField(const std::string& field);
    const std::string& colorField() const { return colorField_; }
    const std::string& displayedColorField() const { return displayedField_; }
    const std::vector<std::string>& labelFields() const { return labelFields_; }
    const std::vector<std::string>& scalarFields() const { return scalarFields_; }
    bool showsFacing() const { return showsFacing_; }
    bool showsFaceLabels() const { return showsLabels_; }
    bool showsScalarField() const { return showsScalar_; }
    const SymmetricRange& scalarRange() const { return scalarRange_; }

    bool isScalarBarVisible() const;
    std::string scalarBarTitle() const;
    // Keeps the bar's labels inside a viewport `viewportHeight` pixels high.
    void placeScalarBar(int viewportHeight);
    // The scalar bar's box in a viewport of `deviceSize` pixels, top-left
    // origin; empty when the bar is hidden.
    QRect scalarBarRect(const QSize& deviceSize) const;

    // The mesh's VTK data (null without a mesh), its smooth-shading normals
    // (null for flat faces) and the actor that draws it (for picking).
    vtkPolyData* meshData() const { return meshData_; }
    vtkDataArray* surfaceNormals() const;
    bool hasSmoothShading() const { return static_cast<bool>(shownNormals_); }
    vtkActor* meshActor() const { return meshActor_; }
    long long faceCount() const;

    // The colour the mesh gives face `face` before lighting (RGB in [0, 1]):
    // its facing or label colour, or the map's colour of the scalar field (a
    // vertex field by the mean over the face's corners).
    std::array<double, 3> faceColor(Index face) const;

    // While another layer stands in for the mesh (MotionCopyLayer) the mesh
    // actor is hidden; the scalar bar stays.
    void setStandIn(bool standIn);
    // The surface look (plain colour and lighting) any stand-in copies.
    static void applySurfaceLook(vtkProperty* property);

protected:
    void applyVisibility() override;

private:
    void updateColoring();
    void removeShownArray();

    vtkNew<vtkPolyDataMapper> meshMapper_;
    vtkNew<vtkActor> meshActor_;
    vtkNew<vtkLookupTable> facingColors_;
    vtkNew<vtkLookupTable> labelColors_;
    vtkNew<vtkLookupTable> fieldColors_;
    vtkNew<vtkScalarBarActor> scalarBar_;

    Snapshot snapshot_;
    std::shared_ptr<const TriangleMesh> mesh_;
    vtkSmartPointer<vtkPolyData> meshData_;
    std::string colorField_;
    std::string displayedField_;
    std::vector<std::string> scalarFields_;
    std::vector<std::string> labelFields_;
    // The field whose values are in meshData_ (to skip converting it again).
    std::shared_ptr<const Field> shownFieldValues_;
    std::string shownArrayName_;
    // The smooth surface's normals in meshData_, if any.
    std::shared_ptr<const Field> shownNormals_;
    SymmetricRange scalarRange_;
    bool showsFacing_ = false;
    bool showsLabels_ = false;
    bool showsScalar_ = false;
    bool standIn_ = false;
};

} // namespace contour
