#pragma once
// Vertex normals of a triangle mesh as weighted averages of face normals
// (tutorial §6.2.1). Area weights are the tutorial's default; angle weights
// (Thürmer & Wüthrich) and Max (1999) weights are the usual alternatives.
#include "mesh/TriangleMesh.h"

#include <string>
#include <vector>

namespace contour {

enum class NormalWeighting { Area, Angle, Max };

NormalWeighting normalWeightingFromName(const std::string& name); // "area", "angle", "max"

std::vector<Vec3> vertexNormals(const TriangleMesh& mesh, NormalWeighting weighting);

} // namespace contour
