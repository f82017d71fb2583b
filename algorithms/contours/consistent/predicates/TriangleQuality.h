#pragma once
// The triangle shape-quality metric of Bank & Smith 1997, used by Bénard 2014
// §6.4 to break ties between optimization moves ("the best aspect ratio";
// the paper does not quote the formula):
//   q = 4√3 · A / (l1² + l2² + l3²),
// 1 for an equilateral triangle, 0 for a degenerate one.
#include "core/Types.h"

namespace contour::consistent {

double bankSmithQuality(const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace contour::consistent
