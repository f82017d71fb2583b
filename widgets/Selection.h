#pragma once
// Linked selection: what the user selected in the current
// snapshot, shared by the 3D view, the 2D view and the inspector. An element
// is named by its index in the snapshot: a face or vertex of Snapshot::mesh,
// an edge of the mesh (TriangleMesh edge order, the order of edge fields), or
// a chain of Snapshot::viewGraph. Indices are what the phases publish, so a
// selection "survives" a step when the index still exists (phases that split,
// flip or compact the mesh may give it another element: the inspector always
// shows what the index names now).
#include "core/Types.h"
#include "mesh/TriangleMesh.h"

#include <QObject>
#include <QString>
#include <array>
#include <vector>

namespace contour {

struct Snapshot;

enum class SelectionKind { None, Face, Vertex, Edge, Chain };
const char* toString(SelectionKind kind);

struct Selection {
    SelectionKind kind = SelectionKind::None;
    Index id = kInvalidIndex;

    static Selection face(Index f) { return {SelectionKind::Face, f}; }
    static Selection vertex(Index v) { return {SelectionKind::Vertex, v}; }
    static Selection edge(Index e) { return {SelectionKind::Edge, e}; }
    static Selection chain(Index c) { return {SelectionKind::Chain, c}; }

    bool isEmpty() const { return kind == SelectionKind::None || id == kInvalidIndex; }
    bool operator==(const Selection&) const = default;
    // "face 12", "chain 3", "nothing".
    QString describe() const;
};

// What a click on face `face` of `mesh` picks, given the face's corners and
// the click in the same pixels (either view's): the nearest corner's vertex
// within `vertexRadius`, else the nearest side's edge within `edgeRadius`,
// else the face. On small faces the radii shrink (to 0.3 and 0.15 of the
// shortest side), so that the face's middle stays the face.
Selection pickWithinFace(const TriangleMesh& mesh, Index face, const std::array<Vec2, 3>& corners,
                         const Vec2& click, double vertexRadius, double edgeRadius);

// Whether the snapshot has the element the selection names.
bool selectionExists(const Snapshot& snapshot, const Selection& selection);

// The faces whose fields::kConsistent is 0 (Bénard 2014, Definition 2), in
// index order; empty when the snapshot has no such field.
std::vector<Index> inconsistentFaces(const Snapshot& snapshot);

// The first inconsistent face after `current` in index order, wrapping
// around (the first one when `current` is kInvalidIndex); kInvalidIndex when
// there is none.
Index nextInconsistentFace(const Snapshot& snapshot, Index current);

// The selection itself; views and the inspector listen to changed().
class SelectionModel : public QObject {
    Q_OBJECT

public:
    explicit SelectionModel(QObject* parent = nullptr) : QObject(parent) {}

    const Selection& selection() const { return selection_; }
    // Emits changed() when the selection differs from the current one.
    void select(const Selection& selection);
    void clear() { select({}); }

signals:
    void changed(const Selection& selection);

private:
    Selection selection_;
};

} // namespace contour
