#include "GroundTruthComputation.h"

#include "ProcessEventsWhile.h"
#include "surface/SmoothSurfaceFactory.h"

#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <chrono>
#include <cmath>

namespace contour {

int GroundTruthComputation::latticeSteps(Index domainFaces, double sampleBudget) {
    const double faces = std::max<double>(1.0, static_cast<double>(domainFaces));
    const double steps = std::sqrt(std::max(0.0, sampleBudget) / faces);
    return std::clamp(static_cast<int>(steps), kMinSamples, kMaxSamples);
}

GroundTruthComputation::GroundTruthComputation(QObject* parent) : QObject(parent) {
    connect(&watcher_, &QFutureWatcher<Outcome>::finished, this,
            &GroundTruthComputation::onFinished);
}

GroundTruthComputation::~GroundTruthComputation() {
    watcher_.disconnect(this);
    watcher_.waitForFinished();
}

void GroundTruthComputation::setRequest(std::optional<GroundTruthRequest> request) {
    if (request == request_)
        return;
    request_ = std::move(request);
    result_.reset();
    error_.clear();
    if (!request_) {
        // Off: the sampling (about 50 bytes per lattice point) is let go.
        sampling_.reset();
        samplingCage_.reset();
    }
    // A running computation ends first; onFinished() starts the next one.
    if (!running_)
        start();
    else
        emit changed();
}

void GroundTruthComputation::start() {
    if (!request_ || !request_->cage) {
        emit changed();
        return;
    }
    const GroundTruthRequest request = *request_;
    // The cached sampling when it is of the same surface.
    std::shared_ptr<const DenseGroundTruth> cached =
        samplingCage_ == request.cage && samplingKind_ == request.kind ? sampling_ : nullptr;
    running_ = true;
    watcher_.setFuture(QtConcurrent::run([request, cached]() {
        using Clock = std::chrono::steady_clock;
        const auto since = [](Clock::time_point t) {
            return std::chrono::duration<double>(Clock::now() - t).count();
        };
        const auto start = Clock::now();
        Outcome outcome{request, std::nullopt, cached, {}};
        try {
            GroundTruthResult r;
            if (!outcome.sampling) {
                const std::shared_ptr<const SmoothSurface> surface =
                    cachedSmoothSurface(request.cage, request.kind).surface;
                const int samples = latticeSteps(surface->domain().faceCount());
                outcome.sampling = std::make_shared<const DenseGroundTruth>(
                    surface, GroundTruthOptions{samples, GroundTruthOptions{}.refineSteps});
                r.samplingSeconds = outcome.sampling->samplingSeconds();
            } else {
                r.samplingReused = true;
            }
            const DenseGroundTruth& sampling = *outcome.sampling;
            auto truth = std::make_shared<GroundTruth>(sampling.compute(request.camera));
            const auto crossingsStart = Clock::now();
            r.imageCrossings = imageCrossings(*truth, request.camera, request.smallLoopPixels);
            r.crossingSeconds = since(crossingsStart);
            r.samples = sampling.options().samples;
            r.domainFaces = sampling.surface().domain().faceCount();
            r.latticePoints = sampling.sampleCount();
            r.contourSeconds = truth->seconds;
            r.truth = std::move(truth);
            r.totalSeconds = since(start);
            outcome.result = std::move(r);
        } catch (const std::exception& e) {
            outcome.error = QString::fromStdString(e.what());
        }
        return outcome;
    }));
    emit changed();
}

void GroundTruthComputation::onFinished() {
    if (!running_ || !watcher_.future().isFinished())
        return;
    running_ = false;
    Outcome outcome = watcher_.result();
    if (outcome.sampling && request_) {
        sampling_ = outcome.sampling;
        samplingCage_ = outcome.request.cage;
        samplingKind_ = outcome.request.kind;
    }
    if (!request_ || !(outcome.request == *request_)) {
        // Asked for something else meanwhile.
        start();
        return;
    }
    result_ = std::move(outcome.result);
    error_ = outcome.error;
    emit changed();
}

bool GroundTruthComputation::waitForResult(int timeoutMs) {
    return processEventsWhile([this] { return running_; }, timeoutMs);
}

} // namespace contour
