#pragma once
// The inspector: what the snapshot says about the selected
// face, vertex, edge or view-graph chain, read from its fields (FieldNames.h)
// and its view graph; nothing is recomputed. A face shows its vertices and
// their labels, facing against its vertex-based orientation (Bénard 2014,
// Definitions 1-2), whether it is consistent and which condition fails, its
// radial classes (Definition 5, §6.3), the phase that created or last
// changed it and its neighbours; a vertex its preimage, label, g, radial
// curvature, provenance, phase and cusp flag; an edge its endpoints, faces
// and tags; a chain its type, length, QI, the rule that decided it and its
// end nodes. A row is shown only when the snapshot has its field. The id box
// at the top selects an element by index.
#include "Selection.h"
#include "pipeline/Snapshot.h"

#include <QString>
#include <QWidget>
#include <string>
#include <vector>

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTreeWidget;

namespace contour {

struct InspectorRow {
    QString property; // e.g. "VBO", "g", "QI"
    QString value;
    // Starts a group: the rows after it, up to the next heading, are shown
    // under it.
    bool heading = false;
};

// The rows for `selection` in `snapshot` (empty when it does not exist).
// `phaseNames` names the phase indices of the changed-by-phase fields (may
// be empty: the index alone is shown).
//
// Face: face, vertices, vertex labels, facing, VBO, consistent, fails,
// radial, standard radial, folded, domain face, phase, neighbours; on the
// powell-sabin spline, under the heading "patch", the rows of describePatch
// (PatchDescription.h) for the face's patch.
// Vertex: vertex, position, preimage, label, g, κr, provenance, phase, cusp,
// normal offset, faces. Edge: edge, endpoints, faces, contour edge,
// boundary, radial edge, cusp edge, zero crossing. Chain: chain, type,
// source, points, length, QI, QI lower bound, ray QI, decided by,
// ambiguous, conflict, concave, simplified away, closed, start node, end
// node; on powell-sabin, patches (the first patches the chain crosses).
std::vector<InspectorRow> inspectorRows(const Snapshot& snapshot, const Selection& selection,
                                        const std::vector<std::string>& phaseNames);

class Inspector : public QWidget {
    Q_OBJECT

public:
    explicit Inspector(QWidget* parent = nullptr);

    // Shows `selection` in `snapshot` (an empty selection shows a hint).
    void showSelection(const Snapshot& snapshot, const Selection& selection);
    void setPhaseNames(std::vector<std::string> names) { phaseNames_ = std::move(names); }

    // The shown rows, and the value of one (empty when not shown).
    const std::vector<InspectorRow>& rows() const { return rows_; }
    QString value(const QString& property) const;
    const Selection& shownSelection() const { return shown_; }

    // The id box: the kind of element (item data: SelectionKind as int), the
    // index, and the button; Return in the index field selects too.
    QComboBox* kindSelector() const { return kind_; }
    QLineEdit* idEdit() const { return idEdit_; }
    QPushButton* selectButton() const { return selectButton_; }

signals:
    // The user asked for an element by index.
    void selectRequested(const Selection& selection);

private:
    void requestSelection();

    QComboBox* kind_ = nullptr;
    QLineEdit* idEdit_ = nullptr;
    QPushButton* selectButton_ = nullptr;
    QLabel* title_ = nullptr;
    QTreeWidget* table_ = nullptr;
    std::vector<std::string> phaseNames_;
    std::vector<InspectorRow> rows_;
    Selection shown_;
};

} // namespace contour
