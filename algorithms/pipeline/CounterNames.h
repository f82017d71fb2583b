#pragma once
// Stable keys of the counters phases publish in a Snapshot, with the label a
// user reads (the stepper, the JSON report, the CLI summary). Declared in one
// place, as FieldNames.h does for fields: tests and readers look counters up
// by key, so a label can be reworded without breaking them.
#include <string_view>

namespace contour {

struct CounterName {
    std::string_view key;   // kebab-case, never changes once published
    std::string_view label; // what the stepper and the reports show
};

namespace counters {

// Every snapshot (makeInputSnapshot and the phases that rebuild the mesh).
inline constexpr CounterName kFaces{"faces", "faces"};
inline constexpr CounterName kVertices{"vertices", "vertices"};
inline constexpr CounterName kEdges{"edges", "edges"};
inline constexpr CounterName kBoundaryEdges{"boundary-edges", "boundary edges"};

} // namespace counters
} // namespace contour
