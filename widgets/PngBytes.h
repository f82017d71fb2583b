#pragma once
// A QImage as the bytes of a PNG file, for writers that take bytes
// (writeSnapshotFiles, DiagnosticSnapshot.h).
#include <string>

class QImage;

namespace contour {

// Empty when the image is null or cannot be encoded.
std::string pngBytes(const QImage& image);

} // namespace contour
