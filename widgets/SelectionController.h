#pragma once
// Links the selection (Selection.h) between the 3D view, the 2D view and the
// inspector: a click in either view or an index typed in the inspector
// selects in all three; each new snapshot keeps the selection when its index
// still exists there and clears it (with a message) otherwise; "next
// inconsistent face" walks the snapshot's inconsistent faces (Bénard 2014,
// Definition 2) and frames each one in the 3D view.
#include "Selection.h"

#include <QObject>
#include <QString>
#include <functional>
#include <string>
#include <vector>

namespace contour {

class ImageView2D;
class Inspector;
class SceneView3D;

class SelectionController : public QObject {
    Q_OBJECT

public:
    SelectionController(SceneView3D* scene, ImageView2D* image, Inspector* inspector,
                        QObject* parent = nullptr);

    SelectionModel* model() { return &model_; }
    const Selection& selection() const { return model_.selection(); }
    // Selects in every view and the inspector; an index the shown snapshot
    // does not have clears the selection and says so (message()).
    void select(const Selection& selection);
    void clear() { model_.clear(); }

    // The names of the method's phases, for the inspector's "phase" rows;
    // asked for each time the inspector is filled.
    void setPhaseNames(std::function<std::vector<std::string>()> provider) {
        phaseNames_ = std::move(provider);
    }

    // Selects the inconsistent face after the selected one (the first when
    // no face is selected), wrapping around, and frames it in the 3D view.
    // False, with a message, when the snapshot has none.
    bool selectNextInconsistentFace();

signals:
    // A short status message for the user.
    void message(const QString& text);

private:
    void onSnapshotChanged();
    void onSelectionChanged();

    SceneView3D* scene_;
    ImageView2D* image_;
    Inspector* inspector_;
    SelectionModel model_;
    std::function<std::vector<std::string>()> phaseNames_;
};

} // namespace contour
