#pragma once
// Help › About: what the program is and the versions of the libraries it was
// built with (and, where the library says so, runs with), read from their
// version macros and functions.
#include <QString>

class QWidget;

namespace contour {

// One "name version" line per library: Qt, VTK, CGAL, Eigen, OpenSubdiv,
// Embree, oneTBB, nlohmann-json, CLI11.
QString libraryVersionsText();

void showAboutDialog(QWidget* parent);

} // namespace contour
