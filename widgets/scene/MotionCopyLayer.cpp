#include "MotionCopyLayer.h"

#include "MeshColoringLayer.h"
#include "SceneColors.h"
#include "pipeline/FieldNames.h"

#include <algorithm>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>

namespace contour {

MotionCopyLayer::MotionCopyLayer() {
    // The mesh's lighting and a polygon offset, colours per triangle (direct
    // RGB).
    mapper_->SetScalarModeToUseCellData();
    mapper_->SetColorModeToDirectScalars();
    mapper_->ScalarVisibilityOn();
    mapper_->SetRelativeCoincidentTopologyPolygonOffsetParameters(8.0, 100.0);
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    actor_->SetMapper(mapper_);
    MeshColoringLayer::applySurfaceLook(actor_->GetProperty());
    actor_->VisibilityOff();
    actor_->PickableOff();
}

std::vector<SceneLayer::Prop> MotionCopyLayer::props() const {
    return {{actor_, false}};
}

void MotionCopyLayer::update(const Snapshot& snapshot) {
    snapshot_ = snapshot;
    if (copiedMesh_ && copiedMesh_ != snapshot.mesh)
        clearCopy();
    applyVisibility();
}

void MotionCopyLayer::setCopy(MotionMesh copy, std::shared_ptr<const TriangleMesh> mesh) {
    if (!mesh || mesh != snapshot_.mesh || !copy.data)
        return;
    copy_ = std::move(copy);
    copiedMesh_ = std::move(mesh);
    mapper_->SetInputData(copy_.data);
    applyVisibility();
}

void MotionCopyLayer::clearCopy() {
    copy_ = {};
    copiedMesh_.reset();
    mapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    applyVisibility();
}

bool MotionCopyLayer::isReady() const {
    return snapshot_.mesh && copy_.data && copiedMesh_ == snapshot_.mesh;
}

long long MotionCopyLayer::faceCount() const {
    return isReady() ? copy_.data->GetNumberOfPolys() : 0;
}

double MotionCopyLayer::buildSeconds() const {
    return isReady() ? copy_.seconds : 0.0;
}

void MotionCopyLayer::setShown(bool shown) {
    shown_ = shown;
    applyVisibility();
}

bool MotionCopyLayer::isShown() const {
    return actor_->GetVisibility() != 0;
}

void MotionCopyLayer::applyVisibility() {
    actor_->SetVisibility(isVisible() && shown_ && isReady());
}

void MotionCopyLayer::recolour(const MeshColoringLayer& coloring, bool radialTint) {
    if (!isReady())
        return;
    vtkPolyData* copy = copy_.data;
    const TriangleMesh& mesh = *snapshot_.mesh;
    const std::vector<Index>& source = copy_.sourceFaces;
    const auto count = static_cast<vtkIdType>(source.size());
    // Shaded like the mesh: smooth when the mesh has the surface's normals.
    copy->GetPointData()->SetNormals(coloring.hasSmoothShading() ? copy_.normals.Get() : nullptr);

    // The translucent radial tint folded into the colours: the same blend,
    // one opaque triangle.
    const auto faceLabels = [this, &mesh](const char* name) -> const std::vector<int>* {
        const Field* field = snapshot_.field(name);
        if (!field || field->location != FieldLocation::Face || !field->labels() ||
            static_cast<Index>(field->labels()->size()) != mesh.faceCount())
            return nullptr;
        return field->labels();
    };
    const std::vector<int>* radial = radialTint ? faceLabels(fields::kRadial) : nullptr;
    const std::vector<int>* standard = radialTint ? faceLabels(fields::kStandardRadial) : nullptr;
    const double opacity = sceneColors::kRadialTintOpacity;

    auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
    colors->SetName("motion_colors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(count);
    unsigned char* out = colors->GetPointer(0);
    for (vtkIdType c = 0; c < count; ++c) {
        const Index f = source[static_cast<size_t>(c)];
        std::array<double, 3> rgb = coloring.faceColor(f);
        const bool isStandard = standard && (*standard)[static_cast<size_t>(f)] != 0;
        if (isStandard || (radial && (*radial)[static_cast<size_t>(f)] != 0)) {
            const SceneColor& t =
                isStandard ? sceneColors::kStandardRadialTint : sceneColors::kRadialTint;
            const std::array<double, 3> tintRgb{t.r, t.g, t.b};
            for (size_t k = 0; k < 3; ++k)
                rgb[k] = (1.0 - opacity) * rgb[k] + opacity * tintRgb[k];
        }
        for (size_t k = 0; k < 3; ++k)
            *out++ = static_cast<unsigned char>(std::clamp(rgb[k], 0.0, 1.0) * 255.0 + 0.5);
    }
    copy->GetCellData()->SetScalars(colors);
    copy->Modified();
}

} // namespace contour
