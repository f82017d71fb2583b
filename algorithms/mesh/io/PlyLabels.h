#pragma once
// Extra per-vertex and per-face properties of a PLY file: integer labels and
// double scalar fields, each stored under its PLY property name. writePly()
// writes them; readPly(path, &labels) reads them back.
#include <map>
#include <string>
#include <vector>

namespace contour {

struct PlyLabels {
    std::map<std::string, std::vector<int>> vertexLabels;
    std::map<std::string, std::vector<double>> vertexScalars;
    std::map<std::string, std::vector<int>> faceLabels;
    std::map<std::string, std::vector<double>> faceScalars;

    bool operator==(const PlyLabels&) const = default;
    bool empty() const {
        return vertexLabels.empty() && vertexScalars.empty() && faceLabels.empty() &&
               faceScalars.empty();
    }
};

} // namespace contour
