// contour-batch: runs a contour method headless on a mesh and writes the
// curves (SVG) and a report of every phase (JSON). Exit codes: 0 success,
// 1 bad input (mesh, camera file), a failed phase or an unwritable output,
// 2 bad arguments, 3 post-conditions violated (or a visibility conflict of
// exact propagation) under --strict.
#include "BatchOptions.h"
#include "BatchRun.h"
#include "Summary.h"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    using namespace contour::batch;
    try {
        const ParseResult parsed = parseBatchOptions(argc, argv);
        if (parsed.status == ParseStatus::Exit)
            return parsed.exitCode;
        if (parsed.options.listMethods) {
            printMethodList(std::cout);
            return 0;
        }
        return runBatch(parsed.options, std::cout);
    } catch (const UsageError& e) {
        std::cout.flush();
        std::cerr << "contour-batch: error: " << e.what()
                  << "\nRun with --help for more information.\n";
        return 2;
    } catch (const BatchFailure& e) {
        std::cout.flush();
        std::cerr << "contour-batch: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cout.flush();
        std::cerr << "contour-batch: internal error: " << e.what() << "\n";
        return 1;
    }
}
