#include "SnapshotToVtk.h"

#include "pipeline/FieldNames.h"

#include <algorithm>
#include <span>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace contour {

namespace {

vtkSmartPointer<vtkPoints> makePoints(std::span<const Vec3> positions) {
    vtkNew<vtkDoubleArray> coordinates;
    coordinates->SetNumberOfComponents(3);
    coordinates->SetNumberOfTuples(static_cast<vtkIdType>(positions.size()));
    double* out = coordinates->GetPointer(0);
    for (const Vec3& p : positions) {
        *out++ = p.x();
        *out++ = p.y();
        *out++ = p.z();
    }
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetData(coordinates);
    return points;
}

// A cell array from flat offsets (size cells + 1) and connectivity.
vtkSmartPointer<vtkCellArray> makeCells(const std::vector<vtkIdType>& offsets,
                                        const std::vector<vtkIdType>& connectivity) {
    vtkNew<vtkIdTypeArray> offsetArray;
    offsetArray->SetNumberOfTuples(static_cast<vtkIdType>(offsets.size()));
    std::copy(offsets.begin(), offsets.end(), offsetArray->GetPointer(0));
    vtkNew<vtkIdTypeArray> connectivityArray;
    connectivityArray->SetNumberOfTuples(static_cast<vtkIdType>(connectivity.size()));
    std::copy(connectivity.begin(), connectivity.end(), connectivityArray->GetPointer(0));
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    cells->SetData(offsetArray, connectivityArray);
    return cells;
}

} // namespace

vtkSmartPointer<vtkPolyData> meshToPolyData(const TriangleMesh& mesh) {
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(mesh.positions()));
    const Index faces = mesh.faceCount();
    std::vector<vtkIdType> offsets(static_cast<size_t>(faces) + 1);
    std::vector<vtkIdType> connectivity(3 * static_cast<size_t>(faces));
    for (Index f = 0; f < faces; ++f) {
        offsets[f] = 3 * static_cast<vtkIdType>(f);
        const Triangle& t = mesh.triangle(f);
        for (int i = 0; i < 3; ++i)
            connectivity[3 * static_cast<size_t>(f) + i] = t[i];
    }
    offsets[faces] = 3 * static_cast<vtkIdType>(faces);
    poly->SetPolys(makeCells(offsets, connectivity));
    return poly;
}

vtkSmartPointer<vtkIntArray> facingToCellArray(const Snapshot& snapshot) {
    const Field* field = snapshot.field(fields::kFacing);
    if (!field || field->location != FieldLocation::Face || !field->labels() || !snapshot.mesh ||
        static_cast<Index>(field->labels()->size()) != snapshot.mesh->faceCount())
        return nullptr;
    const std::vector<int>& labels = *field->labels();
    auto array = vtkSmartPointer<vtkIntArray>::New();
    array->SetName(kVtkFacingArray);
    array->SetNumberOfTuples(static_cast<vtkIdType>(labels.size()));
    std::copy(labels.begin(), labels.end(), array->GetPointer(0));
    return array;
}

namespace {

// The field as scalars on the mesh's vertices or faces, or null.
const std::vector<double>* meshScalars(const Snapshot& snapshot, const Field& field) {
    const std::vector<double>* values = field.scalars();
    if (!values || !snapshot.mesh)
        return nullptr;
    const auto size = static_cast<Index>(values->size());
    if (field.location == FieldLocation::Vertex && size == snapshot.mesh->vertexCount())
        return values;
    if (field.location == FieldLocation::Face && size == snapshot.mesh->faceCount())
        return values;
    return nullptr;
}

} // namespace

std::vector<std::string> scalarFieldNames(const Snapshot& snapshot) {
    static const std::vector<std::string> known{fields::kG, fields::kRadialCurvature,
                                                fields::kGaussianCurvature, fields::kMeanCurvature};
    std::vector<std::string> names;
    for (const std::string& name : known)
        if (const Field* field = snapshot.field(name); field && meshScalars(snapshot, *field))
            names.push_back(name);
    // std::map: the others come in name order.
    for (const auto& [name, field] : snapshot.fields)
        if (field && meshScalars(snapshot, *field) &&
            std::find(known.begin(), known.end(), name) == known.end())
            names.push_back(name);
    return names;
}

vtkSmartPointer<vtkDoubleArray>
scalarFieldToArray(const Snapshot& snapshot, const std::string& name, FieldLocation* location) {
    const Field* field = snapshot.field(name);
    const std::vector<double>* values = field ? meshScalars(snapshot, *field) : nullptr;
    if (!values)
        return nullptr;
    auto array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfTuples(static_cast<vtkIdType>(values->size()));
    std::copy(values->begin(), values->end(), array->GetPointer(0));
    if (location)
        *location = field->location;
    return array;
}

vtkSmartPointer<vtkDoubleArray> smoothSurfaceNormals(const Snapshot& snapshot) {
    const Field* normals = snapshot.field(fields::kVertexNormal);
    const Field* preimages = snapshot.field(fields::kPreimageFace);
    if (!snapshot.mesh || !normals || !preimages || !normals->vectors() ||
        normals->location != FieldLocation::Vertex ||
        preimages->location != FieldLocation::Vertex ||
        static_cast<Index>(normals->vectors()->size()) != snapshot.mesh->vertexCount())
        return nullptr;
    const std::vector<Vec3>& values = *normals->vectors();
    auto array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName("Normals");
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    double* out = array->GetPointer(0);
    for (const Vec3& n : values) {
        *out++ = n.x();
        *out++ = n.y();
        *out++ = n.z();
    }
    return array;
}

vtkSmartPointer<vtkPolyData> curvesToPolyData(const std::vector<Polyline>& curves) {
    std::vector<Vec3> positions;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    auto types = vtkSmartPointer<vtkIntArray>::New();
    types->SetName(kVtkCurveTypeArray);
    for (const Polyline& curve : curves) {
        if (curve.points.size() < 2)
            continue;
        const vtkIdType first = static_cast<vtkIdType>(positions.size());
        for (const CurvePoint& p : curve.points) {
            connectivity.push_back(static_cast<vtkIdType>(positions.size()));
            positions.push_back(p.position);
        }
        if (curve.closed)
            connectivity.push_back(first);
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
        types->InsertNextValue(static_cast<int>(curve.type));
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(positions));
    poly->SetLines(makeCells(offsets, connectivity));
    poly->GetCellData()->AddArray(types);
    poly->GetCellData()->SetActiveScalars(kVtkCurveTypeArray);
    return poly;
}

vtkSmartPointer<vtkPolyData> frustumToPolyData(const Camera& camera, double depth) {
    std::vector<Vec3> positions;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    const auto addLine = [&](std::initializer_list<vtkIdType> ids) {
        connectivity.insert(connectivity.end(), ids);
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
    };
    const std::vector<Vec3> far = camera.frustumCorners(depth);
    if (camera.isOrthographic()) {
        const std::vector<Vec3> near = camera.frustumCorners(0.0);
        positions.insert(positions.end(), near.begin(), near.end()); // 0..3
        positions.insert(positions.end(), far.begin(), far.end());   // 4..7
        addLine({0, 1, 2, 3, 0});
        addLine({4, 5, 6, 7, 4});
        for (vtkIdType i = 0; i < 4; ++i)
            addLine({i, i + 4});
    } else {
        positions.push_back(camera.eye);                           // 0
        positions.insert(positions.end(), far.begin(), far.end()); // 1..4
        addLine({1, 2, 3, 4, 1});
        for (vtkIdType i = 1; i <= 4; ++i)
            addLine({0, i});
        // A tick on the top edge so "up" reads at a glance.
        const Vec3 top = 0.5 * (far[0] + far[1]);
        const Vec3 lift = 0.08 * (far[0] - far[3]);
        positions.push_back(top + lift); // 5
        addLine({1, 5, 2});
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(positions));
    poly->SetLines(makeCells(offsets, connectivity));
    return poly;
}

} // namespace contour
