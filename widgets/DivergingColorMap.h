#pragma once
// The colour map of signed scalar fields (g, radial, Gaussian and mean
// curvature): Moreland's cool-to-warm diverging map (blue - light grey - red,
// interpolated in his Msh space), centred on 0 over a symmetric range
// [-m, m], where m is a robust maximum of |value| so that one huge value near
// an extraordinary vertex does not wash the rest out. Values beyond the range
// take the end colours; NaN (radial curvature where it is undefined) is drawn
// sceneColors::kNanValue. The end and NaN colours are read from
// resources/colormaps/diverging.json (SceneColors.h).
#include <span>
#include <vtkSmartPointer.h>

class vtkLookupTable;

namespace contour {

// The quantile of |value| taken as the half-width m of the range.
inline constexpr double kRobustRangeQuantile = 0.98;
// Entries of the lookup table.
inline constexpr int kDivergingTableSize = 256;

struct SymmetricRange {
    double halfWidth = 1.0;    // m > 0: the range is [-m, m]
    long long finiteCount = 0; // the values m is taken from
    long long nanCount = 0;    // NaN values (±inf are left out of m too)

    double low() const { return -halfWidth; }
    double high() const { return halfWidth; }
};

// The symmetric range of `values`: m is the `quantile` (in [0, 1], nearest
// rank) of |v| over the finite values. When that is 0 (mostly zeros) m is the
// largest finite |v|, and when that is 0 too (or nothing is finite) m = 1, so
// the range is never empty.
SymmetricRange symmetricRange(std::span<const double> values,
                              double quantile = kRobustRangeQuantile);

// Fills `table` with the diverging map over [-halfWidth, halfWidth]
// (kDivergingTableSize entries, NaN colour set, out-of-range values clamped).
void fillDivergingLookupTable(vtkLookupTable* table, double halfWidth);
vtkSmartPointer<vtkLookupTable> makeDivergingLookupTable(double halfWidth);

} // namespace contour
