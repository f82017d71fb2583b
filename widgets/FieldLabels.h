#pragma once
// Readable names of snapshot fields for the "Colour by" selector and the
// scalar bar's title (UTF-8). Unknown fields keep their field name.
#include "pipeline/FieldNames.h"

#include <string>

namespace contour {

inline std::string fieldDisplayName(const std::string& field) {
    if (field == fields::kFacing)
        return "Front/back (facing)";
    if (field == fields::kVbo)
        return "Front/back (VBO)";
    if (field == fields::kG)
        return "g = (c \u2212 p) \u00b7 n";
    if (field == fields::kRadialCurvature)
        return "radial curvature \u03bar";
    if (field == fields::kGaussianCurvature)
        return "Gaussian curvature K";
    if (field == fields::kMeanCurvature)
        return "mean curvature H";
    return field;
}

} // namespace contour
