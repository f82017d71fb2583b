#pragma once
// What the inspector shows about one quadratic patch of the fitted spline
// and about the patches a view-graph chain crosses (Capouellez et al. 2023
// §4.1-§4.2, §5.2): read from the method's working data (PowellSabinState.h),
// as (property, value) rows of plain text, so that the widgets only display
// them.
#include "contours/powell_sabin/PowellSabinState.h"
#include "pipeline/ViewGraph.h"

#include <string>
#include <utility>
#include <vector>

namespace contour::powell_sabin {

using DescriptionRows = std::vector<std::pair<std::string, std::string>>;

// Patch `patch` of the state's spline (numbers with 9 significant digits,
// points in the view's transformed coordinates, ProjectiveTransform.h):
//   "patch"                 its id
//   "layout face"           the macro-patch 12 f + l lies in, and its vertices
//   "sub-triangle"          l and its split points (Ps12Patch.h)
//   "b0", "b1", "b2", "b01", "b12", "b20"   the Bezier control points
//   "uv domain"             the sub-triangle's corners in the face's uv
//   "τ·n: A", "τ·n: b", "τ·n: c"   eq. 2 for tau = (0, 0, 1): A as
//                           [[a11, a12], [a12, a22]], b as (b1, b2)
//   "conic case"            Table 1's case the segments carry; without a
//                           segment "no contour", with the form's case
//   "contour interval k"    per segment (k from 1): its index, [t0, t1],
//                           the sides of its ends and its chain
//   "rational form k"       X(t), Y(t), W(t) of r(t) = (X, Y) / W
//   "interior cusp"         the cusps (PatchCusps.h) that lie in the patch
//   "cone corner"           the patch's corners at a cone of the layout
// Rows the state cannot give yet (before patch-contours, chaining or cusps)
// say which phase computes them. Throws std::out_of_range when the state
// has no spline or layout or `patch` is not one of its patches.
DescriptionRows describePatch(const PowellSabinState& state, Index patch);

// The patches a view-graph chain of the powell-sabin method crosses (its
// segmentElement, SplineViewGraph.h), in the order it meets them, each once.
std::vector<Index> chainPatches(const ViewChain& chain);
// "n patches: a, b, c, …" with the first `shown` of them.
std::string describeChainPatches(const ViewChain& chain, std::size_t shown = 6);

} // namespace contour::powell_sabin
