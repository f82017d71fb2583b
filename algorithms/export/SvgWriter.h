#pragma once
// SVG export of a snapshot's curves as one camera sees them. The document is
// sized to the camera's viewport (width, height and viewBox in pixels, y
// down, like Camera::project) and holds one <g> per curve type:
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
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <string>

namespace contour {

struct SvgOptions {
    std::string title;        // written as <title> when not empty
    double strokeWidth = 1.5; // pixels
    bool background = true;   // a white rectangle under the curves
};

std::string svgDocument(const Snapshot& snapshot, const Camera& camera,
                        const SvgOptions& options = {});

// Writes svgDocument() to `path` atomically (path.tmp, then rename). Throws
// std::runtime_error naming the file on failure.
void writeSvg(const std::string& path, const Snapshot& snapshot, const Camera& camera,
              const SvgOptions& options = {});

} // namespace contour
