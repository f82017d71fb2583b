#include "SnapshotToVtk.h"

#include "pipeline/FieldNames.h"

#include <algorithm>
#include <set>
#include <span>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
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

// Polylines over points of their own, as flat cells.
struct PolylineCells {
    std::vector<Vec3> positions;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;

    // One polyline through `points` (each placed by `position`); a closed
    // one repeats its first point.
    template <class Points, class Position>
    void add(const Points& points, bool closed, Position position) {
        const vtkIdType first = static_cast<vtkIdType>(positions.size());
        for (const auto& p : points) {
            connectivity.push_back(static_cast<vtkIdType>(positions.size()));
            positions.push_back(position(p));
        }
        if (closed)
            connectivity.push_back(first);
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
    }

    vtkSmartPointer<vtkPolyData> polyData() const {
        auto poly = vtkSmartPointer<vtkPolyData>::New();
        poly->SetPoints(makePoints(positions));
        poly->SetLines(makeCells(offsets, connectivity));
        return poly;
    }
};

// One vertex cell per position, in order.
vtkSmartPointer<vtkPolyData> verticesToPolyData(std::span<const Vec3> positions) {
    std::vector<vtkIdType> offsets(positions.size() + 1);
    std::vector<vtkIdType> connectivity(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        connectivity[i] = static_cast<vtkIdType>(i);
        offsets[i + 1] = static_cast<vtkIdType>(i + 1);
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(positions));
    poly->SetVerts(makeCells(offsets, connectivity));
    return poly;
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

namespace {

// The integer field `name` on every vertex, face or edge of the mesh (by
// `location`), or null.
const std::vector<int>* meshLabels(const Snapshot& snapshot, const std::string& name,
                                   FieldLocation location) {
    const Field* field = snapshot.field(name);
    if (!field || field->location != location || !field->labels() || !snapshot.mesh)
        return nullptr;
    const TriangleMesh& mesh = *snapshot.mesh;
    const Index expected = location == FieldLocation::Vertex ? mesh.vertexCount()
                           : location == FieldLocation::Face ? mesh.faceCount()
                                                             : mesh.edgeCount();
    return static_cast<Index>(field->labels()->size()) == expected ? field->labels() : nullptr;
}

vtkSmartPointer<vtkIntArray> toIntArray(const std::vector<int>& labels, const char* name) {
    auto array = vtkSmartPointer<vtkIntArray>::New();
    array->SetName(name);
    array->SetNumberOfTuples(static_cast<vtkIdType>(labels.size()));
    std::copy(labels.begin(), labels.end(), array->GetPointer(0));
    return array;
}

} // namespace

vtkSmartPointer<vtkIntArray> facingToCellArray(const Snapshot& snapshot) {
    const std::vector<int>* labels = meshLabels(snapshot, fields::kFacing, FieldLocation::Face);
    return labels ? toIntArray(*labels, kVtkFacingArray) : nullptr;
}

std::vector<std::string> faceLabelFieldNames(const Snapshot& snapshot) {
    std::vector<std::string> names;
    if (meshLabels(snapshot, fields::kVbo, FieldLocation::Face))
        names.emplace_back(fields::kVbo);
    return names;
}

vtkSmartPointer<vtkIntArray> faceLabelsToCellArray(const Snapshot& snapshot,
                                                   const std::string& name) {
    const std::vector<int>* labels = meshLabels(snapshot, name, FieldLocation::Face);
    return labels ? toIntArray(*labels, name.c_str()) : nullptr;
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
    PolylineCells cells;
    auto types = vtkSmartPointer<vtkIntArray>::New();
    types->SetName(kVtkCurveTypeArray);
    for (const Polyline& curve : curves) {
        if (curve.points.size() < 2)
            continue;
        cells.add(curve.points, curve.closed, [](const CurvePoint& p) { return p.position; });
        types->InsertNextValue(static_cast<int>(curve.type));
    }
    auto poly = cells.polyData();
    poly->GetCellData()->AddArray(types);
    poly->GetCellData()->SetActiveScalars(kVtkCurveTypeArray);
    return poly;
}

vtkSmartPointer<vtkPolyData> cageToPolyData(const PolygonMesh& cage) {
    std::set<std::pair<Index, Index>> edges;
    for (Index f = 0; f < cage.faceCount(); ++f) {
        const std::span<const Index> polygon = cage.face(f);
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const Index a = polygon[i];
            const Index b = polygon[(i + 1) % polygon.size()];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    for (const auto& [a, b] : edges) {
        connectivity.push_back(a);
        connectivity.push_back(b);
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(cage.positions));
    poly->SetLines(makeCells(offsets, connectivity));
    return poly;
}

vtkSmartPointer<vtkPolyData> viewChainsToPolyData(const ViewGraph& graph, ChainState state) {
    PolylineCells cells;
    auto indices = vtkSmartPointer<vtkIntArray>::New();
    indices->SetName(kVtkChainIndexArray);
    auto qis = vtkSmartPointer<vtkIntArray>::New();
    qis->SetName(kVtkChainQiArray);
    for (size_t c = 0; c < graph.chains.size(); ++c) {
        const ViewChain& chain = graph.chains[c];
        if (chain.points.size() < 2 || chainState(chain) != state)
            continue;
        // A closed chain already repeats its first point.
        cells.add(chain.points, false, [](const Vec3& p) { return p; });
        indices->InsertNextValue(static_cast<int>(c));
        qis->InsertNextValue(chain.qi);
    }
    auto poly = cells.polyData();
    poly->GetCellData()->AddArray(indices);
    poly->GetCellData()->AddArray(qis);
    return poly;
}

vtkSmartPointer<vtkPolyData> groundTruthLoopsToPolyData(const GroundTruth& truth) {
    PolylineCells cells;
    for (const GroundTruthLoop& loop : truth.loops)
        if (loop.points.size() >= 2)
            cells.add(loop.points, loop.closed, [](const Vec3& p) { return p; });
    return cells.polyData();
}

vtkSmartPointer<vtkPolyData> groundTruthCuspsToPolyData(const GroundTruth& truth) {
    std::vector<Vec3> positions;
    for (const GroundTruthCusp& cusp : truth.cusps)
        positions.push_back(cusp.position);
    return verticesToPolyData(positions);
}

vtkSmartPointer<vtkPolyData> viewNodesToPolyData(const ViewGraph& graph, bool hidden) {
    std::vector<Vec3> positions;
    auto types = vtkSmartPointer<vtkIntArray>::New();
    types->SetName(kVtkNodeTypeArray);
    for (Index n = 0; n < static_cast<Index>(graph.nodes.size()); ++n) {
        if (nodeIsHidden(graph, n) != hidden)
            continue;
        positions.push_back(graph.nodes[n].position);
        types->InsertNextValue(static_cast<int>(graph.nodes[n].type));
    }
    auto poly = verticesToPolyData(positions);
    poly->GetPointData()->AddArray(types);
    return poly;
}

vtkSmartPointer<vtkPolyData> inconsistentFaceOutlines(const Snapshot& snapshot) {
    const std::vector<int>* consistent =
        meshLabels(snapshot, fields::kConsistent, FieldLocation::Face);
    if (!consistent)
        return nullptr;
    const TriangleMesh& mesh = *snapshot.mesh;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        if ((*consistent)[f] != 0)
            continue;
        const Triangle& t = mesh.triangle(f);
        connectivity.insert(connectivity.end(), {t[0], t[1], t[2], t[0]});
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(mesh.positions()));
    poly->SetLines(makeCells(offsets, connectivity));
    return poly;
}

vtkSmartPointer<vtkPolyData> radialFacesToPolyData(const Snapshot& snapshot) {
    const std::vector<int>* radial = meshLabels(snapshot, fields::kRadial, FieldLocation::Face);
    const std::vector<int>* standard =
        meshLabels(snapshot, fields::kStandardRadial, FieldLocation::Face);
    if (!radial && !standard)
        return nullptr;
    const TriangleMesh& mesh = *snapshot.mesh;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    auto kinds = vtkSmartPointer<vtkIntArray>::New();
    kinds->SetName(kVtkStandardRadialArray);
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const bool isStandard = standard && (*standard)[f] != 0;
        if (!isStandard && !(radial && (*radial)[f] != 0))
            continue;
        const Triangle& t = mesh.triangle(f);
        connectivity.insert(connectivity.end(), {t[0], t[1], t[2]});
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
        kinds->InsertNextValue(isStandard ? 1 : 0);
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(mesh.positions()));
    poly->SetPolys(makeCells(offsets, connectivity));
    poly->GetCellData()->SetScalars(kinds);
    return poly;
}

vtkSmartPointer<vtkPolyData> markedVerticesToPolyData(const Snapshot& snapshot,
                                                      const std::string& field, int value) {
    const std::vector<int>* labels = meshLabels(snapshot, field, FieldLocation::Vertex);
    if (!labels)
        return nullptr;
    std::vector<Vec3> positions;
    for (Index v = 0; v < snapshot.mesh->vertexCount(); ++v)
        if ((*labels)[v] == value)
            positions.push_back(snapshot.mesh->position(v));
    std::vector<vtkIdType> offsets(positions.size() + 1);
    std::vector<vtkIdType> connectivity(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        offsets[i + 1] = static_cast<vtkIdType>(i + 1);
        connectivity[i] = static_cast<vtkIdType>(i);
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(positions));
    poly->SetVerts(makeCells(offsets, connectivity));
    return poly;
}

vtkSmartPointer<vtkPolyData> markedEdgesToPolyData(const Snapshot& snapshot,
                                                   const std::string& field) {
    const std::vector<int>* labels = meshLabels(snapshot, field, FieldLocation::Edge);
    if (!labels)
        return nullptr;
    const TriangleMesh& mesh = *snapshot.mesh;
    std::vector<vtkIdType> offsets{0};
    std::vector<vtkIdType> connectivity;
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if ((*labels)[e] == 0)
            continue;
        const Index h = mesh.edgeHalfedge(e);
        connectivity.insert(connectivity.end(), {mesh.from(h), mesh.to(h)});
        offsets.push_back(static_cast<vtkIdType>(connectivity.size()));
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(makePoints(mesh.positions()));
    poly->SetLines(makeCells(offsets, connectivity));
    return poly;
}

vtkSmartPointer<vtkPolyData> labelledEdgesToPolyData(const Snapshot& snapshot,
                                                     const std::string& field) {
    vtkSmartPointer<vtkPolyData> poly = markedEdgesToPolyData(snapshot, field);
    if (!poly)
        return nullptr;
    const std::vector<int>& labels = *meshLabels(snapshot, field, FieldLocation::Edge);
    auto scalars = vtkSmartPointer<vtkIntArray>::New();
    scalars->SetName(field.c_str());
    for (int label : labels)
        if (label != 0)
            scalars->InsertNextValue(label);
    poly->GetCellData()->SetScalars(scalars);
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
