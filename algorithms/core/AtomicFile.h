#pragma once
// Writes a whole file or nothing: the content goes to `path.tmp`, which is
// renamed to `path` once complete (docs/dev/conventions.md: no output file is ever left
// half-written). Every writer (meshes, cameras, exports) goes through this.
#include <string>
#include <string_view>

namespace contour {

// Throws std::runtime_error naming `path` and the reason on failure; the
// temporary file is removed then and an existing `path` is left untouched.
void writeFileAtomically(const std::string& path, std::string_view content);

} // namespace contour
