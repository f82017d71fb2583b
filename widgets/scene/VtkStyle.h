#pragma once
// Small helpers the scene layers share to put a SceneColor into VTK.
#include "SceneColors.h"

#include <algorithm>
#include <array>
#include <vtkLookupTable.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>

namespace contour::vtkStyle {

inline void setTableColor(vtkLookupTable* table, vtkIdType index, const SceneColor& color) {
    table->SetTableValue(index, color.r, color.g, color.b, 1.0);
}

inline void setColor(vtkProperty* property, const SceneColor& color) {
    property->SetColor(color.r, color.g, color.b);
}

// Appends `color` (scaled by `scale`, clamped) as one RGB byte tuple.
inline void insertColor(vtkUnsignedCharArray* colors, const SceneColor& c, double scale = 1.0) {
    const auto byte = [scale](double v) {
        return static_cast<unsigned char>(std::clamp(v * scale, 0.0, 1.0) * 255.0 + 0.5);
    };
    colors->InsertNextTypedTuple(
        std::array<unsigned char, 3>{byte(c.r), byte(c.g), byte(c.b)}.data());
}

} // namespace contour::vtkStyle
