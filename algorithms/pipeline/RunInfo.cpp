#include "pipeline/RunInfo.h"

namespace contour {

std::string RunInfo::describe() const {
    if (!branch)
        return {};
    const std::string n = std::to_string(branch->runs.size());
    if (run == 0) {
        if (branch->adopted > 0)
            return "first run, replaced by run " + std::to_string(branch->adopted) + " of " + n;
        return "first run, kept (" + n + " run" + (branch->runs.size() == 1 ? "" : "s") +
               " rejected)";
    }
    const BranchRunSummary& r = branch->runs.at(static_cast<size_t>(run - 1));
    return "run " + std::to_string(run) + " of " + n + (r.adopted ? ", adopted" : ", rejected") +
           (r.label.empty() ? "" : " (" + r.label + ")");
}

} // namespace contour
