#include "SelectionController.h"

#include "ImageView2D.h"
#include "Inspector.h"
#include "SceneView3D.h"

#include <algorithm>

namespace contour {

SelectionController::SelectionController(SceneView3D* scene, ImageView2D* image,
                                         Inspector* inspector, QObject* parent)
    : QObject(parent), scene_(scene), image_(image), inspector_(inspector) {
    connect(&model_, &SelectionModel::changed, this, &SelectionController::onSelectionChanged);
    connect(scene_, &SceneView3D::snapshotChanged, this, &SelectionController::onSnapshotChanged);
    connect(scene_, &SceneView3D::pickRequested, this, &SelectionController::select);
    connect(image_, &ImageView2D::pickRequested, this, &SelectionController::select);
    connect(inspector_, &Inspector::selectRequested, this, &SelectionController::select);
}

void SelectionController::select(const Selection& selection) {
    if (!selection.isEmpty() && !selectionExists(scene_->snapshot(), selection)) {
        emit message(
            tr("No %1 in phase %2")
                .arg(selection.describe(), QString::fromStdString(scene_->snapshot().phaseName)));
        model_.clear();
        return;
    }
    model_.select(selection);
}

bool SelectionController::selectNextInconsistentFace() {
    const Snapshot& snapshot = scene_->snapshot();
    const std::vector<Index> faces = inconsistentFaces(snapshot);
    if (faces.empty()) {
        emit message(
            tr("No inconsistent face in phase %1").arg(QString::fromStdString(snapshot.phaseName)));
        return false;
    }
    const Selection& current = model_.selection();
    const Index face = nextInconsistentFace(
        snapshot, current.kind == SelectionKind::Face ? current.id : kInvalidIndex);
    model_.select(Selection::face(face));
    scene_->frameFace(face);
    const auto position = std::lower_bound(faces.begin(), faces.end(), face) - faces.begin();
    emit message(
        tr("Inconsistent face %1 of %2: face %3").arg(position + 1).arg(faces.size()).arg(face));
    return true;
}

void SelectionController::onSnapshotChanged() {
    const Selection current = model_.selection();
    if (!current.isEmpty() && !selectionExists(scene_->snapshot(), current)) {
        emit message(
            tr("Selection cleared: no %1 in phase %2")
                .arg(current.describe(), QString::fromStdString(scene_->snapshot().phaseName)));
        model_.clear(); // onSelectionChanged updates the views
        return;
    }
    onSelectionChanged();
}

void SelectionController::onSelectionChanged() {
    const Selection& selection = model_.selection();
    scene_->setHighlight(selection);
    image_->setHighlight(selection);
    if (phaseNames_)
        inspector_->setPhaseNames(phaseNames_());
    inspector_->showSelection(scene_->snapshot(), selection);
}

} // namespace contour
