#pragma once
// The camera(s) of a contour-batch run: the one given by --camera or
// --session (with --width/--height applied), or placed around the mesh's
// bounding box (the default 3/4 view with --eye/--target/--up, or the 26
// views of --views26), with --ortho/--fov/--ortho-height applied.
#include "BatchOptions.h"
#include "camera/Camera.h"

#include <iosfwd>
#include <optional>
#include <vector>

namespace contour::batch {

// The camera of --camera or --session, if either is given; prints what
// reading the session noted. Throws BatchFailure for a bad camera file.
std::optional<Camera> givenCamera(const BatchOptions& options, std::ostream& out);

// The cameras to run from. Throws BatchFailure when a view of --views26 has
// no valid camera, UsageError when the command line's camera is invalid.
std::vector<Camera> placeCameras(const BatchOptions& options, const BoundingBox& box,
                                 const std::optional<Camera>& given);

} // namespace contour::batch
