#include "ConsistentOverlayLayer.h"

#include "SnapshotToVtk.h"
#include "VtkStyle.h"
#include "pipeline/FieldNames.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>

namespace contour {

ConsistentOverlayLayer::ConsistentOverlayLayer() {
    using vtkStyle::setColor;
    for (Slot& s : slots_) {
        s.mapper->ScalarVisibilityOff();
        s.mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
        s.actor->SetMapper(s.mapper);
        s.actor->VisibilityOff();
        s.actor->PickableOff();
    }
    {
        vtkProperty* property = slot(SceneOverlay::InconsistentFaces).actor->GetProperty();
        setColor(property, sceneColors::kInconsistentOutline);
        property->SetLineWidth(static_cast<float>(sceneColors::kInconsistentOutlineWidth));
        property->LightingOff();
    }
    {
        // Standard radial 1 and other radial 0 map to table entries 1 and 0.
        radialColors_->SetNumberOfTableValues(2);
        radialColors_->SetTableRange(0.0, 1.0);
        radialColors_->Build();
        vtkStyle::setTableColor(radialColors_, 0, sceneColors::kRadialTint);
        vtkStyle::setTableColor(radialColors_, 1, sceneColors::kStandardRadialTint);
        Slot& tint = slot(SceneOverlay::RadialFaces);
        tint.mapper->SetLookupTable(radialColors_);
        tint.mapper->SetScalarModeToUseCellData();
        tint.mapper->SetColorModeToMapScalars();
        tint.mapper->UseLookupTableScalarRangeOn();
        tint.mapper->ScalarVisibilityOn();
        // In front of the mesh (pushed back by 2, 4), behind the lines.
        tint.mapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(0.0, 0.0);
        vtkProperty* property = tint.actor->GetProperty();
        property->SetOpacity(sceneColors::kRadialTintOpacity);
        property->SetAmbient(0.3);
        property->SetDiffuse(0.7);
        property->SetSpecular(0.0);
    }
    {
        Slot& edges = slot(SceneOverlay::RadialEdges);
        edges.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -60.0);
        vtkProperty* property = edges.actor->GetProperty();
        setColor(property, sceneColors::kRadialEdge);
        property->SetLineWidth(static_cast<float>(sceneColors::kRadialEdgeWidth));
        property->LightingOff();
    }
    {
        // Round dots pulled in front of the curves they lie on.
        Slot& contour = slot(SceneOverlay::ContourVertices);
        contour.mapper->SetRelativeCoincidentTopologyPointOffsetParameter(-120.0);
        vtkProperty* property = contour.actor->GetProperty();
        setColor(property, sceneColors::kContourVertex);
        property->SetPointSize(static_cast<float>(sceneColors::kContourVertexSize));
        property->RenderPointsAsSpheresOn();
        property->LightingOff();
    }
    {
        // Patch (1), macro-patch (2) and cut (3) edges, by cell label.
        patchEdgeColors_->SetNumberOfTableValues(3);
        patchEdgeColors_->SetTableRange(1.0, 3.0);
        patchEdgeColors_->Build();
        vtkStyle::setTableColor(patchEdgeColors_, 0, sceneColors::kPatchEdge);
        vtkStyle::setTableColor(patchEdgeColors_, 1, sceneColors::kMacroPatchEdge);
        vtkStyle::setTableColor(patchEdgeColors_, 2, sceneColors::kCutEdge);
        Slot& edges = slot(SceneOverlay::PatchEdges);
        edges.mapper->SetLookupTable(patchEdgeColors_);
        edges.mapper->SetScalarModeToUseCellData();
        edges.mapper->SetColorModeToMapScalars();
        edges.mapper->UseLookupTableScalarRangeOn();
        edges.mapper->ScalarVisibilityOn();
        edges.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-2.0, -40.0);
        vtkProperty* property = edges.actor->GetProperty();
        property->SetLineWidth(static_cast<float>(sceneColors::kPatchEdgeWidth));
        property->LightingOff();
    }
    {
        vtkProperty* property = slot(SceneOverlay::Cones).actor->GetProperty();
        setColor(property, sceneColors::kCone);
        property->SetPointSize(static_cast<float>(sceneColors::kConeSize));
        property->RenderPointsAsSpheresOn();
        property->LightingOff();
    }
    {
        // Large squares: a different glyph from the C vertices' dots.
        vtkProperty* property = slot(SceneOverlay::Cusps).actor->GetProperty();
        setColor(property, sceneColors::kCuspVertex);
        property->SetPointSize(static_cast<float>(sceneColors::kCuspVertexSize));
        property->LightingOff();
    }
}

std::vector<SceneLayer::Prop> ConsistentOverlayLayer::props() const {
    // What must be seen wherever it is (outlines, cusps) goes over the scene.
    return {{slot(SceneOverlay::InconsistentFaces).actor, true},
            {slot(SceneOverlay::RadialFaces).actor, false},
            {slot(SceneOverlay::RadialEdges).actor, false},
            {slot(SceneOverlay::ContourVertices).actor, false},
            {slot(SceneOverlay::Cusps).actor, true},
            {slot(SceneOverlay::PatchEdges).actor, false},
            {slot(SceneOverlay::Cones).actor, true}};
}

void ConsistentOverlayLayer::update(const Snapshot& snapshot) {
    std::array<vtkSmartPointer<vtkPolyData>, kSceneOverlayCount> converted{};
    const auto at = [&converted](SceneOverlay o) -> vtkSmartPointer<vtkPolyData>& {
        return converted[static_cast<size_t>(o)];
    };
    if (snapshot.mesh) {
        at(SceneOverlay::InconsistentFaces) = inconsistentFaceOutlines(snapshot);
        at(SceneOverlay::RadialFaces) = radialFacesToPolyData(snapshot);
        at(SceneOverlay::ContourVertices) = markedVerticesToPolyData(snapshot, fields::kLabel, 0);
        at(SceneOverlay::Cusps) = markedVerticesToPolyData(snapshot, fields::kCusp, 1);
        at(SceneOverlay::RadialEdges) = markedEdgesToPolyData(snapshot, fields::kRadialEdge);
        at(SceneOverlay::PatchEdges) = labelledEdgesToPolyData(snapshot, fields::kPatchEdge);
        at(SceneOverlay::Cones) = markedVerticesToPolyData(snapshot, fields::kCone, 1);
    }
    // The tint shares the mesh's points: shade it like the mesh.
    if (vtkPolyData* tint = at(SceneOverlay::RadialFaces))
        tint->GetPointData()->SetNormals(normals_);
    for (size_t i = 0; i < slots_.size(); ++i) {
        Slot& s = slots_[i];
        s.data = converted[i];
        s.mapper->SetInputData(s.data ? s.data.Get() : vtkSmartPointer<vtkPolyData>::New().Get());
    }
    applyVisibility();
}

void ConsistentOverlayLayer::setEnabled(SceneOverlay overlay, bool enabled) {
    slot(overlay).enabled = enabled;
    applyVisibility();
}

bool ConsistentOverlayLayer::isShown(SceneOverlay overlay) const {
    if (motionDrawing_ && overlay == SceneOverlay::RadialFaces)
        return false;
    return isVisible() && isEnabled(overlay) && isAvailable(overlay);
}

long long ConsistentOverlayLayer::elementCount(SceneOverlay overlay) const {
    vtkPolyData* poly = slot(overlay).data;
    if (!poly)
        return 0;
    return poly->GetNumberOfVerts() + poly->GetNumberOfLines() + poly->GetNumberOfPolys();
}

void ConsistentOverlayLayer::setMotionDrawing(bool on) {
    motionDrawing_ = on;
    applyVisibility();
}

void ConsistentOverlayLayer::applyVisibility() {
    for (int i = 0; i < kSceneOverlayCount; ++i)
        slots_[static_cast<size_t>(i)].actor->SetVisibility(isShown(static_cast<SceneOverlay>(i)));
}

} // namespace contour
