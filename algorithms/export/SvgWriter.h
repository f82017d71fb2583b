#pragma once
// SVG export of a snapshot's curves as one camera sees them. The document is
// sized to the camera's viewport (width, height and viewBox in pixels, y
// down, like Camera::project).
//
// Without a view graph (no visibility phase, or --visibility false), it holds
// one <g> per curve type:
//   <g id="contour">, <g id="boundary"> (always present, maybe empty) and
//   <g id="surface-intersection"> (only when the snapshot has such curves).
// Each curve is one <polyline> with
//   data-index  its position in Snapshot::curves,
//   data-type   contour | boundary | surface-intersection,
//   data-closed true | false (a closed curve repeats its first point last,
//               so it draws closed),
//   data-points the number of points of the 3D curve.
// A curve that passes behind a perspective camera's eye is split into the
// pieces in front of it: each piece is a <polyline> with the same data-index
// and a data-part attribute (0, 1, ...), and class="clipped".
//
// With a view graph (Snapshot::viewGraph), the graph's chains are drawn
// instead of the raw curves, in layers:
//   <g id="visible">     chains with QI 0, solid;
//   <g id="hidden">      chains with QI > 0 (or unknown), dashed
//                        (stroke-dasharray); display="none" when
//                        SvgOptions::drawHidden is false;
//   <g id="simplified">  chains hidden by topological simplification
//                        (Bénard 2014 §9), display="none": kept so that
//                        nothing is lost silently;
// each holding one <g> per curve type that has chains there, with
// id="<layer>-<type>" and class="<type>" (contour, boundary,
// surface-intersection), and in it one <polyline> per chain (one per piece,
// with data-part and class="clipped", when it passes behind the eye) with
//   data-chain index in ViewGraph::chains,   data-curve index in
//   data-qi    QI (-1 unknown),                         Snapshot::curves,
//   data-rule  toString(VisibilityRule),     data-type  the curve type,
//   data-closed, and data-ambiguous / data-conflict / data-concave="true"
//   when set.
//   <g id="nodes">       one <g id="nodes-<type>" class="<type>"> per node
//                        type present (toString(ViewNodeType)), with one
//                        marker per node: curtain-fold red circle,
//                        boundary-curtain-fold orange diamond,
//                        image-intersection blue square,
//                        contour-boundary-junction green triangle,
//                        bifurcation purple cross, surface-intersection-end
//                        brown hollow circle, curve-end magenta X. Each marker
//                        has data-node (index in ViewGraph::nodes), data-type
//                        and data-class (toString(ViewNodeClass)); display="none"
//                        when SvgOptions::drawNodes is false.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <string>

namespace contour {

struct SvgOptions {
    std::string title;        // written as <title> when not empty
    double strokeWidth = 1.5; // pixels
    bool background = true;   // a white rectangle under the curves
    // View-graph layers (ignored without a view graph): false keeps the
    // layer in the document but hides it (display="none").
    bool drawHidden = true;
    bool drawNodes = true;
    double markerSize = 4.0; // pixels, half the width of a node marker
};

std::string svgDocument(const Snapshot& snapshot, const Camera& camera,
                        const SvgOptions& options = {});

// Writes svgDocument() to `path` atomically (path.tmp, then rename). Throws
// std::runtime_error naming the file on failure.
void writeSvg(const std::string& path, const Snapshot& snapshot, const Camera& camera,
              const SvgOptions& options = {});

} // namespace contour
