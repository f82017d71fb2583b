#include "DivergingColorMap.h"

#include "SceneColors.h"

#include <algorithm>
#include <cmath>
#include <vector>
#include <vtkColorTransferFunction.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>

namespace contour {

SymmetricRange symmetricRange(std::span<const double> values, double quantile) {
    SymmetricRange range;
    std::vector<double> magnitudes;
    magnitudes.reserve(values.size());
    for (double v : values) {
        if (std::isfinite(v))
            magnitudes.push_back(std::abs(v));
        else if (std::isnan(v))
            ++range.nanCount;
    }
    range.finiteCount = static_cast<long long>(magnitudes.size());
    if (magnitudes.empty())
        return range;
    // Nearest rank: the smallest value with at least `quantile` of the values
    // at or below it.
    const double q = std::clamp(std::isnan(quantile) ? 1.0 : quantile, 0.0, 1.0);
    const size_t n = magnitudes.size();
    const auto rank = static_cast<size_t>(std::ceil(q * static_cast<double>(n)));
    const size_t k = std::clamp<size_t>(rank, 1, n) - 1;
    std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(k),
                     magnitudes.end());
    double m = magnitudes[k];
    if (!(m > 0.0))
        m = *std::max_element(magnitudes.begin(), magnitudes.end());
    range.halfWidth = m > 0.0 ? m : 1.0;
    return range;
}

void fillDivergingLookupTable(vtkLookupTable* table, double halfWidth) {
    loadSceneColors(); // the map's colours: resources/colormaps/diverging.json
    const double m = halfWidth > 0.0 && std::isfinite(halfWidth) ? halfWidth : 1.0;
    vtkNew<vtkColorTransferFunction> map;
    map->SetColorSpaceToDiverging();
    const SceneColor& low = sceneColors::kDivergingNegative;
    const SceneColor& high = sceneColors::kDivergingPositive;
    map->AddRGBPoint(-m, low.r, low.g, low.b);
    map->AddRGBPoint(m, high.r, high.g, high.b);
    map->Build();

    table->SetNumberOfTableValues(kDivergingTableSize);
    table->SetTableRange(-m, m);
    table->Build();
    for (int i = 0; i < kDivergingTableSize; ++i) {
        // The centre of entry i's bin.
        const double x = -m + 2.0 * m * (i + 0.5) / kDivergingTableSize;
        double rgb[3];
        map->GetColor(x, rgb);
        table->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
    }
    const SceneColor& nan = sceneColors::kNanValue;
    table->SetNanColor(nan.r, nan.g, nan.b, 1.0);
    table->UseBelowRangeColorOff();
    table->UseAboveRangeColorOff();
    table->Modified();
}

vtkSmartPointer<vtkLookupTable> makeDivergingLookupTable(double halfWidth) {
    auto table = vtkSmartPointer<vtkLookupTable>::New();
    fillDivergingLookupTable(table, halfWidth);
    return table;
}

} // namespace contour
