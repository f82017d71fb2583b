#include "Selection.h"

#include "pipeline/FieldNames.h"
#include "pipeline/Snapshot.h"

#include <algorithm>
#include <limits>

namespace contour {

const char* toString(SelectionKind kind) {
    switch (kind) {
    case SelectionKind::None:
        return "nothing";
    case SelectionKind::Face:
        return "face";
    case SelectionKind::Vertex:
        return "vertex";
    case SelectionKind::Edge:
        return "edge";
    case SelectionKind::Chain:
        return "chain";
    }
    return "nothing";
}

QString Selection::describe() const {
    if (isEmpty())
        return QStringLiteral("nothing");
    return QStringLiteral("%1 %2").arg(QString::fromLatin1(toString(kind))).arg(id);
}

Selection pickWithinFace(const TriangleMesh& mesh, Index face, const std::array<Vec2, 3>& corners,
                         const Vec2& click, double vertexRadius, double edgeRadius) {
    double shortest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < 3; ++i)
        shortest = std::min(shortest, (corners[(i + 1) % 3] - corners[i]).norm());
    vertexRadius = std::min(vertexRadius, 0.3 * shortest);
    edgeRadius = std::min(edgeRadius, 0.15 * shortest);
    size_t nearestCorner = 0;
    for (size_t i = 1; i < 3; ++i)
        if ((corners[i] - click).norm() < (corners[nearestCorner] - click).norm())
            nearestCorner = i;
    if ((corners[nearestCorner] - click).norm() <= vertexRadius)
        return Selection::vertex(mesh.triangle(face)[nearestCorner]);
    int nearestEdge = -1;
    double edgeDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < 3; ++i) {
        const Vec2 a = corners[i];
        const Vec2 ab = corners[(i + 1) % 3] - a;
        const double s = ab.squaredNorm() > 0.0
                             ? std::clamp((click - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                             : 0.0;
        const double d = (a + s * ab - click).norm();
        if (d < edgeDistance) {
            edgeDistance = d;
            nearestEdge = static_cast<int>(i);
        }
    }
    if (nearestEdge >= 0 && edgeDistance <= edgeRadius)
        return Selection::edge(mesh.edge(TriangleMesh::halfedge(face, nearestEdge)));
    return Selection::face(face);
}

bool selectionExists(const Snapshot& snapshot, const Selection& selection) {
    if (selection.isEmpty() || selection.id < 0)
        return false;
    switch (selection.kind) {
    case SelectionKind::None:
        return false;
    case SelectionKind::Face:
        return snapshot.mesh && selection.id < snapshot.mesh->faceCount();
    case SelectionKind::Vertex:
        return snapshot.mesh && selection.id < snapshot.mesh->vertexCount();
    case SelectionKind::Edge:
        return snapshot.mesh && selection.id < snapshot.mesh->edgeCount();
    case SelectionKind::Chain:
        return snapshot.viewGraph &&
               selection.id < static_cast<Index>(snapshot.viewGraph->chains.size());
    }
    return false;
}

std::vector<Index> inconsistentFaces(const Snapshot& snapshot) {
    std::vector<Index> faces;
    const Field* field = snapshot.field(fields::kConsistent);
    if (!field || field->location != FieldLocation::Face || !field->labels() || !snapshot.mesh)
        return faces;
    const std::vector<int>& consistent = *field->labels();
    const Index n = std::min(snapshot.mesh->faceCount(), static_cast<Index>(consistent.size()));
    for (Index f = 0; f < n; ++f)
        if (consistent[static_cast<size_t>(f)] == 0)
            faces.push_back(f);
    return faces;
}

Index nextInconsistentFace(const Snapshot& snapshot, Index current) {
    const std::vector<Index> faces = inconsistentFaces(snapshot);
    if (faces.empty())
        return kInvalidIndex;
    if (current == kInvalidIndex)
        return faces.front();
    const auto next = std::upper_bound(faces.begin(), faces.end(), current);
    return next == faces.end() ? faces.front() : *next;
}

void SelectionModel::select(const Selection& selection) {
    const Selection next = selection.isEmpty() ? Selection() : selection;
    if (next == selection_)
        return;
    selection_ = next;
    emit changed(selection_);
}

} // namespace contour
