#pragma once
// Shared set-up of the suites that drive the real main window: show it at a
// given size, open a mesh, switch to a method and run it to its last phase.
#include "MainWindow.h"
#include "pipeline/Runner.h"

#include <QSize>
#include <QString>
#include <QtTest>

namespace contour::testing {

// Empty on success, else what went wrong (for QVERIFY2).
inline QString showAndRunToEnd(MainWindow& window, const QString& meshPath, const QString& method,
                               QSize size = {1400, 850}, int timeoutMs = 300000) {
    window.setInteractive(false);
    window.resize(size);
    window.show();
    if (!QTest::qWaitForWindowExposed(&window))
        return QStringLiteral("the window was not exposed");
    if (!window.openMesh(meshPath) || !window.waitForIdle(timeoutMs))
        return QStringLiteral("cannot open %1: %2").arg(meshPath, window.lastError());
    if (!window.setMethod(method) || !window.waitForIdle(timeoutMs))
        return QStringLiteral("cannot run %1: %2").arg(method, window.lastError());
    if (!window.lastError().isEmpty())
        return window.lastError();
    if (!window.runner() || !window.runner()->atEnd())
        return QStringLiteral("%1 did not run to its end").arg(method);
    return {};
}

} // namespace contour::testing
