#include "Selection.h"

#include "pipeline/FieldNames.h"
#include "pipeline/Snapshot.h"

#include <algorithm>

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
