#include "MeshColoringLayer.h"

#include "FieldLabels.h"
#include "SnapshotToVtk.h"
#include "VtkStyle.h"
#include "pipeline/FieldNames.h"

#include <QFileInfo>
#include <QString>
#include <algorithm>
#include <span>
#include <vtkCellData.h>
#include <vtkCoordinate.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkTextProperty.h>

namespace contour {

namespace {

// A system font with Greek letters for the scalar bar's title (κr), which
// VTK's embedded fonts may lack. Empty when there is none: the text then uses
// VTK's embedded Arial.
QString greekFontFile() {
    static const QString path = [] {
        for (const char* candidate :
             {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
              "/usr/share/fonts/TTF/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"})
            if (QFileInfo::exists(QString::fromLatin1(candidate)))
                return QString::fromLatin1(candidate);
        return QString();
    }();
    return path;
}

void setTextStyle(vtkTextProperty* text, int size) {
    const SceneColor& color = sceneColors::kScalarBarText;
    text->SetColor(color.r, color.g, color.b);
    text->SetFontSize(size);
    text->BoldOff();
    text->ItalicOff();
    text->ShadowOn();
    if (const QString font = greekFontFile(); !font.isEmpty()) {
        text->SetFontFamily(VTK_FONT_FILE);
        text->SetFontFile(font.toLocal8Bit().constData());
    }
}

// The scalar bar's box in normalized viewport coordinates: along the bottom,
// centred (a horizontal bar leaves room for a long title), at least
// kBarMarginPixels above the bottom edge so that the label of the NaN swatch,
// drawn below the bar, fits.
constexpr double kBarLeft = 0.18, kBarBottom = 0.03, kBarWidth = 0.64, kBarHeight = 0.14;
constexpr double kBarMarginPixels = 34.0;

double barBottom(int viewportHeight) {
    return std::max(kBarBottom, kBarMarginPixels / std::max(1, viewportHeight));
}

} // namespace

void MeshColoringLayer::applySurfaceLook(vtkProperty* property) {
    vtkStyle::setColor(property, sceneColors::kUnclassifiedFace);
    // No specular highlight: shading then only scales a face's colour, so its
    // hue tells front from back everywhere.
    property->SetAmbient(0.3);
    property->SetDiffuse(0.7);
    property->SetSpecular(0.0);
}

MeshColoringLayer::MeshColoringLayer()
    : colorField_(fields::kFacing), displayedField_(fields::kFacing) {
    using vtkStyle::setTableColor;
    // Facing -1, 0, +1 map to table entries 0, 1, 2.
    facingColors_->SetNumberOfTableValues(3);
    facingColors_->SetTableRange(-1.0, 1.0);
    facingColors_->Build();
    setTableColor(facingColors_, 0, sceneColors::kBackFace);
    setTableColor(facingColors_, 1, sceneColors::kEdgeOnFace);
    setTableColor(facingColors_, 2, sceneColors::kFrontFace);
    meshMapper_->SetLookupTable(facingColors_);
    meshMapper_->SetScalarModeToUseCellData();
    meshMapper_->SetColorModeToMapScalars();
    meshMapper_->UseLookupTableScalarRangeOn();
    meshMapper_->ScalarVisibilityOff();
    // Polygons pushed away from the viewer, so curves on the surface are not
    // z-fought.
    meshMapper_->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0);
    meshMapper_->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    meshActor_->SetMapper(meshMapper_);
    applySurfaceLook(meshActor_->GetProperty());
    meshActor_->VisibilityOff();

    // VBO -1, 0, +1 map to table entries 0, 1, 2: B, undefined, F.
    labelColors_->SetNumberOfTableValues(3);
    labelColors_->SetTableRange(-1.0, 1.0);
    labelColors_->Build();
    setTableColor(labelColors_, 0, sceneColors::kBackFace);
    setTableColor(labelColors_, 1, sceneColors::kUndefinedVbo);
    setTableColor(labelColors_, 2, sceneColors::kFrontFace);

    fillDivergingLookupTable(fieldColors_, 1.0);
    scalarBar_->SetLookupTable(fieldColors_);
    scalarBar_->SetOrientationToHorizontal();
    scalarBar_->SetNumberOfLabels(5); // -m, -m/2, 0, m/2, m
    scalarBar_->SetLabelFormat("%-#6.3g");
    scalarBar_->SetMaximumNumberOfColors(kDivergingTableSize);
    scalarBar_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    scalarBar_->GetPositionCoordinate()->SetValue(kBarLeft, kBarBottom);
    scalarBar_->GetPosition2Coordinate()->SetValue(kBarWidth, kBarHeight);
    scalarBar_->UnconstrainedFontSizeOn();
    scalarBar_->SetBarRatio(0.3);
    setTextStyle(scalarBar_->GetTitleTextProperty(), 16);
    setTextStyle(scalarBar_->GetLabelTextProperty(), 13);
    setTextStyle(scalarBar_->GetAnnotationTextProperty(), 13);
    scalarBar_->SetNanAnnotation("NaN");
    scalarBar_->DrawNanAnnotationOff();
    scalarBar_->PickableOff();
    scalarBar_->VisibilityOff();
}

std::vector<SceneLayer::Prop> MeshColoringLayer::props() const {
    return {{meshActor_, false}, {scalarBar_, false}};
}

void MeshColoringLayer::update(const Snapshot& snapshot) {
    if (snapshot.mesh != mesh_) {
        mesh_ = snapshot.mesh;
        meshData_ = mesh_ ? meshToPolyData(*mesh_) : nullptr;
        meshMapper_->SetInputData(meshData_ ? meshData_.Get()
                                            : vtkSmartPointer<vtkPolyData>::New().Get());
        shownFieldValues_.reset();
        shownArrayName_.clear();
        shownNormals_.reset();
    }
    snapshot_ = mesh_ ? snapshot : Snapshot();
    if (meshData_) {
        const auto normals = snapshot.fields.find(fields::kVertexNormal);
        const std::shared_ptr<const Field> normalField =
            normals == snapshot.fields.end() ? nullptr : normals->second;
        if (normalField != shownNormals_ || !normalField) {
            if (vtkSmartPointer<vtkDoubleArray> smooth = smoothSurfaceNormals(snapshot)) {
                meshData_->GetPointData()->SetNormals(smooth);
                shownNormals_ = normalField;
            } else {
                meshData_->GetPointData()->SetNormals(nullptr);
                shownNormals_.reset();
            }
        }
        if (vtkSmartPointer<vtkIntArray> facing = facingToCellArray(snapshot))
            meshData_->GetCellData()->SetScalars(facing);
        else
            meshData_->GetCellData()->RemoveArray(kVtkFacingArray);
    }
    updateColoring();
}

void MeshColoringLayer::setColorField(const std::string& field) {
    colorField_ = field.empty() ? std::string(fields::kFacing) : field;
    if (meshData_)
        updateColoring();
}

void MeshColoringLayer::removeShownArray() {
    if (meshData_ && !shownArrayName_.empty()) {
        meshData_->GetPointData()->RemoveArray(shownArrayName_.c_str());
        meshData_->GetCellData()->RemoveArray(shownArrayName_.c_str());
    }
    shownArrayName_.clear();
    shownFieldValues_.reset();
}

void MeshColoringLayer::updateColoring() {
    scalarFields_ = meshData_ ? scalarFieldNames(snapshot_) : std::vector<std::string>{};
    labelFields_ = meshData_ ? faceLabelFieldNames(snapshot_) : std::vector<std::string>{};
    const auto lists = [this](const std::vector<std::string>& names) {
        return std::find(names.begin(), names.end(), colorField_) != names.end();
    };
    showsScalar_ = meshData_ && lists(scalarFields_);
    showsLabels_ = meshData_ && !showsScalar_ && lists(labelFields_);
    displayedField_ = showsScalar_ || showsLabels_ ? colorField_ : std::string(fields::kFacing);

    if (showsScalar_) {
        const std::shared_ptr<const Field>& field = snapshot_.fields.at(displayedField_);
        if (field != shownFieldValues_) {
            removeShownArray();
            FieldLocation location = FieldLocation::Vertex;
            vtkSmartPointer<vtkDoubleArray> values =
                scalarFieldToArray(snapshot_, displayedField_, &location);
            if (location == FieldLocation::Face)
                meshData_->GetCellData()->AddArray(values);
            else
                meshData_->GetPointData()->AddArray(values);
            shownArrayName_ = displayedField_;
            shownFieldValues_ = field;
            scalarRange_ = symmetricRange(std::span<const double>(
                values->GetPointer(0), static_cast<size_t>(values->GetNumberOfTuples())));
            fillDivergingLookupTable(fieldColors_, scalarRange_.halfWidth);
        }
        if (field->location == FieldLocation::Face) {
            meshMapper_->SetScalarModeToUseCellFieldData();
            meshMapper_->InterpolateScalarsBeforeMappingOff();
        } else {
            // Interpolating the scalar (not the colour) across a triangle
            // keeps the map's colours exact inside it.
            meshMapper_->SetScalarModeToUsePointFieldData();
            meshMapper_->InterpolateScalarsBeforeMappingOn();
        }
        meshMapper_->SelectColorArray(displayedField_.c_str());
        meshMapper_->SetLookupTable(fieldColors_);
        meshMapper_->ScalarVisibilityOn();
        showsFacing_ = false;
        scalarBar_->SetTitle(fieldDisplayName(displayedField_).c_str());
        scalarBar_->SetDrawNanAnnotation(scalarRange_.nanCount > 0);
    } else if (showsLabels_) {
        const std::shared_ptr<const Field>& field = snapshot_.fields.at(displayedField_);
        if (field != shownFieldValues_) {
            removeShownArray();
            meshData_->GetCellData()->AddArray(faceLabelsToCellArray(snapshot_, displayedField_));
            shownArrayName_ = displayedField_;
            shownFieldValues_ = field;
        }
        meshMapper_->SetScalarModeToUseCellFieldData();
        meshMapper_->InterpolateScalarsBeforeMappingOff();
        meshMapper_->SelectColorArray(displayedField_.c_str());
        meshMapper_->SetLookupTable(labelColors_);
        meshMapper_->ScalarVisibilityOn();
        showsFacing_ = false;
    } else {
        removeShownArray();
        showsFacing_ = meshData_ && meshData_->GetCellData()->GetArray(kVtkFacingArray);
        meshMapper_->SetScalarModeToUseCellData();
        meshMapper_->InterpolateScalarsBeforeMappingOff();
        meshMapper_->SetLookupTable(facingColors_);
        meshMapper_->SetScalarVisibility(showsFacing_);
    }
    if (meshData_)
        meshData_->Modified();
    applyVisibility();
}

void MeshColoringLayer::applyVisibility() {
    meshActor_->SetVisibility(isVisible() && meshData_ && !standIn_);
    scalarBar_->SetVisibility(isVisible() && meshData_ && showsScalar_);
}

void MeshColoringLayer::setStandIn(bool standIn) {
    standIn_ = standIn;
    applyVisibility();
}

vtkDataArray* MeshColoringLayer::surfaceNormals() const {
    return meshData_ ? meshData_->GetPointData()->GetNormals() : nullptr;
}

long long MeshColoringLayer::faceCount() const {
    return meshData_ ? meshData_->GetNumberOfPolys() : 0;
}

std::array<double, 3> MeshColoringLayer::faceColor(Index face) const {
    std::array<double, 3> rgb{};
    meshActor_->GetProperty()->GetColor(rgb.data());
    if (!meshData_ || !mesh_ || face < 0 || face >= mesh_->faceCount() ||
        !meshMapper_->GetScalarVisibility())
        return rgb;
    // What the mapper colours a face by (updateColoring()): a cell array, or
    // a vertex field whose mean over the face stands for it.
    vtkDataArray* values = nullptr;
    bool perVertex = false;
    switch (meshMapper_->GetScalarMode()) {
    case VTK_SCALAR_MODE_USE_CELL_DATA:
        values = meshData_->GetCellData()->GetScalars();
        break;
    case VTK_SCALAR_MODE_USE_CELL_FIELD_DATA:
        values = meshData_->GetCellData()->GetArray(meshMapper_->GetArrayName());
        break;
    case VTK_SCALAR_MODE_USE_POINT_FIELD_DATA:
        values = meshData_->GetPointData()->GetArray(meshMapper_->GetArrayName());
        perVertex = true;
        break;
    default:
        break;
    }
    vtkScalarsToColors* table = meshMapper_->GetLookupTable();
    if (!values || !table)
        return rgb;
    double value = 0.0;
    if (perVertex) {
        const Triangle& t = mesh_->triangle(face);
        for (int i = 0; i < 3; ++i)
            value += values->GetComponent(t[i], 0) / 3.0;
    } else {
        value = values->GetComponent(face, 0);
    }
    const unsigned char* mapped = table->MapValue(value);
    for (int k = 0; k < 3; ++k)
        rgb[static_cast<size_t>(k)] = mapped[k] / 255.0;
    return rgb;
}

bool MeshColoringLayer::isScalarBarVisible() const {
    return scalarBar_->GetVisibility() != 0;
}

std::string MeshColoringLayer::scalarBarTitle() const {
    const char* title = scalarBar_->GetTitle();
    return title ? title : "";
}

void MeshColoringLayer::placeScalarBar(int viewportHeight) {
    scalarBar_->GetPositionCoordinate()->SetValue(kBarLeft, barBottom(viewportHeight));
}

QRect MeshColoringLayer::scalarBarRect(const QSize& size) const {
    if (!isScalarBarVisible())
        return {};
    const int left = static_cast<int>(kBarLeft * size.width());
    const int right = static_cast<int>((kBarLeft + kBarWidth) * size.width());
    const double y = barBottom(size.height());
    const int bottom = size.height() - static_cast<int>(y * size.height());
    const int top = size.height() - static_cast<int>((y + kBarHeight) * size.height());
    return QRect(QPoint(left, top), QPoint(right - 1, bottom - 1));
}

} // namespace contour
