#pragma once
// Runs contour-batch once options are parsed: reads the camera file and the
// mesh, places the camera(s), steps the method phase by phase (printing a
// summary as it goes), then writes the outputs. Outputs are written only
// after every view has run, each one atomically, so a failure leaves no
// output file behind (and no half-written one).
#include "BatchOptions.h"

#include <iosfwd>
#include <stdexcept>
#include <string>

namespace contour::batch {

// Bad input (mesh, camera file), a failed phase or an output that cannot be
// written: exit code 1.
class BatchFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "out.svg", 3 -> "out_view03.svg"; "out", 3 -> "out_view03".
std::string viewOutputPath(const std::string& path, int view);

// Returns the exit code (0). Throws UsageError or BatchFailure.
int runBatch(const BatchOptions& options, std::ostream& out);

} // namespace contour::batch
