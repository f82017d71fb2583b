#pragma once
// The dense ground truth of the smooth contour (reference/DenseGroundTruth.h)
// for the window's mesh, smooth surface and analysis camera, computed on a
// worker thread whenever one of them changes while it is asked for. The
// view-independent sampling of the surface (positions and normals on the
// lattice) is kept for the last surface, so that a new camera only extracts
// the contour again. A request made while a computation runs waits for it
// to end (a computation cannot be interrupted; it takes about a second on
// the bundled samples), and the stale result is dropped.
#include "camera/Camera.h"
#include "mesh/PolygonMesh.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurface.h"

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <memory>
#include <optional>

namespace contour {

// What the ground truth is computed for.
struct GroundTruthRequest {
    std::shared_ptr<const PolygonMesh> cage;
    SurfaceKind kind = SurfaceKind::CatmullClark;
    Camera camera;
    // Crossings bounding a loop smaller than this are not counted
    // (imageCrossings; the method's t-junction-min-loop, 0 without one).
    double smallLoopPixels = 0.0;

    bool operator==(const GroundTruthRequest&) const = default;
};

struct GroundTruthResult {
    std::shared_ptr<const GroundTruth> truth;
    int imageCrossings = 0; // imageCrossings(truth, camera, request's smallLoopPixels)
    int samples = 0;        // lattice steps N per domain face side
    Index domainFaces = 0;
    size_t latticePoints = 0;
    bool samplingReused = false;  // the sampling of an earlier request was used
    double samplingSeconds = 0.0; // 0 when reused
    double contourSeconds = 0.0;  // GroundTruth::seconds
    double crossingSeconds = 0.0;
    double totalSeconds = 0.0; // of the whole job, the surface's build included
};

class GroundTruthComputation : public QObject {
    Q_OBJECT

public:
    // Lattice points per mesh the default lattice aims for, as
    // bench_topology's --sample-budget.
    static constexpr double kSampleBudget = 8e6;
    static constexpr int kMinSamples = 8;
    static constexpr int kMaxSamples = 64;
    // N = clamp(sqrt(budget / domain faces), kMinSamples, kMaxSamples).
    static int latticeSteps(Index domainFaces, double sampleBudget = kSampleBudget);

    explicit GroundTruthComputation(QObject* parent = nullptr);
    // Waits for a running computation.
    ~GroundTruthComputation() override;

    // Computes for `request` unless the result (or the running computation)
    // is already for it; nothing clears the result and lets the cached
    // sampling go.
    void setRequest(std::optional<GroundTruthRequest> request);
    const std::optional<GroundTruthRequest>& request() const { return request_; }

    bool isRunning() const { return running_; }
    // The result for request(), once its computation has ended.
    const std::optional<GroundTruthResult>& result() const { return result_; }
    // Why the last computation failed (empty when it did not).
    QString error() const { return error_; }
    // Processes events until no computation runs; false on timeout.
    bool waitForResult(int timeoutMs = 120000);

signals:
    // A computation started or ended (result() or error() is set), or the
    // request was cleared.
    void changed();

private:
    struct Outcome {
        GroundTruthRequest request;
        std::optional<GroundTruthResult> result;
        std::shared_ptr<const DenseGroundTruth> sampling;
        QString error;
    };
    void start();
    void onFinished();

    std::optional<GroundTruthRequest> request_;
    // The sampling of the last surface, and what it samples.
    std::shared_ptr<const DenseGroundTruth> sampling_;
    std::shared_ptr<const PolygonMesh> samplingCage_;
    SurfaceKind samplingKind_ = SurfaceKind::CatmullClark;
    QFutureWatcher<Outcome> watcher_;
    bool running_ = false;
    std::optional<GroundTruthResult> result_;
    QString error_;
};

} // namespace contour
