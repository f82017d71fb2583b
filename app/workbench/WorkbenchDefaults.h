#pragma once
// What the workbench starts with, read from resources/settings/defaults.json:
// the method, the window's size and view layout, the direction and fallback
// viewport of the first analysis camera, the display toggles (by their
// session keys, SessionController.h) and the tolerance of the method
// comparison. Saved sessions and the user's saved window layout win over it.
#include "camera/Camera.h"

#include <QSize>
#include <QString>
#include <map>
#include <string>

namespace contour {

struct WorkbenchDefaults {
    QString method;
    QSize windowSize;
    // "both", "3d-only" or "2d-only" (the session file's layout names).
    QString layout;
    // The "3/4 view" the analysis camera of a new mesh looks from.
    Vec3 viewDirection = Vec3::Zero();
    // Its viewport while the 3D view is too small to take its size.
    Viewport fallbackViewport{1, 1};
    QString colourBy;
    // Display toggles by session key ("overlay.cusps", "view-graph.nodes").
    std::map<std::string, bool> display;
    // How far apart (image pixels) two methods' curves may be and still
    // count as the same curve.
    double comparisonTolerancePixels = 0.0;

    // The toggle's default; `fallback` when the file does not name it.
    bool toggle(const std::string& key, bool fallback) const;

    // Reads the compiled-in resource. A missing or malformed resource stops
    // the program with a message naming the file, since it is part of the
    // build.
    static WorkbenchDefaults load();
};

} // namespace contour
