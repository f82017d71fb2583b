#pragma once
// The application's resources (resources/contour-workbench.qrc, compiled into
// this library): icons, colour maps, default settings.
#include <QIcon>
#include <QString>

namespace contour {

// Registers the compiled-in resources (once); every reader calls it first.
void registerContourResources();

// The icon :/icons/<name>.svg (hand-drawn SVG, scaled to any size); a null
// icon when there is no such file.
QIcon resourceIcon(const QString& name);

} // namespace contour
