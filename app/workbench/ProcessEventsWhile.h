#pragma once
// Waiting for a background job on the GUI thread: events keep being
// processed, so that the job's finished signal (queued to this thread) is
// delivered and its handler runs.
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QEventLoop>

namespace contour {

// Processes events until `busy()` is false or `timeoutMs` have passed;
// returns !busy().
template <class Busy> bool processEventsWhile(Busy busy, int timeoutMs) {
    QElapsedTimer timer;
    timer.start();
    while (busy() && timer.elapsed() < timeoutMs)
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
    return !busy();
}

} // namespace contour
