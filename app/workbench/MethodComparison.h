#pragma once
// A second contour method run on the same mesh and analysis camera as the
// window's method, for the 2D view's comparison. It runs to
// its last phase on a worker thread whenever the mesh, the camera or the
// method to compare with changes; a run made stale by a newer request is
// cancelled and its result dropped. Parameters the two methods share (the
// smooth surface, its tessellation, ...) are copied from the window's method;
// the others keep their defaults.
#include "camera/Camera.h"
#include "pipeline/Parameters.h"
#include "pipeline/Runner.h"
#include "pipeline/Snapshot.h"

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <memory>
#include <optional>

namespace contour {

class MethodComparison : public QObject {
    Q_OBJECT

public:
    explicit MethodComparison(QObject* parent = nullptr);
    ~MethodComparison() override;

    // The method to compare with (its registry name); empty turns it off.
    void setOtherMethod(const QString& name);
    QString otherMethod() const { return otherName_; }
    // The window's input, camera and parameters; re-runs the other method
    // when the input or the camera changed or a shared parameter differs.
    void setPrimary(const std::optional<Snapshot>& input, const std::optional<Camera>& camera,
                    const ParameterSet& primaryParameters);

    bool isRunning() const { return running_; }
    // The other method's last snapshot, once its run has ended.
    const std::optional<Snapshot>& result() const { return result_; }
    // Why the last run failed (empty when it did not).
    QString error() const { return error_; }
    // Processes events until no run is going on; false on timeout.
    bool waitForResult(int timeoutMs = 300000);

signals:
    // A run ended (result() or error() is set) or the comparison was cleared.
    void changed();

private:
    struct Outcome {
        std::optional<Snapshot> snapshot;
        QString error;
    };
    void restart();
    void cancelAndWait();
    void onFinished();

    QString otherName_;
    std::optional<Snapshot> input_;
    std::optional<Camera> camera_;
    ParameterSet shared_; // the primary's values of the parameters the other method has
    std::unique_ptr<Runner> runner_;
    QFutureWatcher<Outcome> watcher_;
    bool running_ = false;
    std::optional<Snapshot> result_;
    QString error_;
};

} // namespace contour
