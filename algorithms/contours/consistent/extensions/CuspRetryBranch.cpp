// Cusp retry: not in the paper. The faces still inconsistent after the last
// optimization lie next to cusps (the inside fan of Fig. 18e, the far ends of
// a cusp's radial edges). This branch (pipeline/Branch.h) runs the phases
// from cusp refinement to the last one of the optimization again with the
// mesh refined around those cusps only (CuspRefinement.h, between cusp
// detection and contour insertion) and adopts a run only when it has
// strictly fewer inconsistent faces (ties keep the first run), so no view
// ends worse and the views without such faces are untouched.
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/CuspRefinementTargets.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/MeshAnalysis.h"

#include <memory>
#include <set>
#include <sstream>

namespace contour::consistent {

namespace {

struct CuspRetryOptions {
    bool enabled = true;      // cusp-retry
    bool everyVariant = true; // cusp-retry-variants
    double pixels = 2.0;      // cusp-retry-pixels
};

CuspRetryOptions cuspRetryOptions(const ParameterSet& p) {
    return {p.getBool("cusp-retry"), p.getBool("cusp-retry-variants"),
            p.getDouble("cusp-retry-pixels")};
}

// What the report needs of the first run.
struct CuspRetryPlan : BranchData {
    long long before = 0;  // inconsistent faces of the first run
    long long targets = 0; // cusps at them
};

// f(u) of the cusp vertices that are a corner of an inconsistent face or
// joined by an edge (a radial edge, Fig. 18e) to one of its corners.
std::vector<Vec3> cuspsAtInconsistentFaces(const ConsistentMesh& m) {
    std::vector<Vec3> out;
    std::set<Index> seen;
    for (Index f : inconsistentFaces(m))
        for (Index v : m.face(f)) {
            std::vector<Index> near = m.neighbours(v);
            near.push_back(v);
            for (Index w : near) {
                const MeshVertex& x = m.vertex(w);
                if (x.cusp && seen.insert(w).second)
                    out.push_back(x.position - x.normalOffset * x.normal);
            }
        }
    return out;
}

BranchPlan planCuspRetry(const PhaseContext& ctx, const Snapshot& s) {
    const CuspRetryOptions o = cuspRetryOptions(ctx.parameters);
    const ConsistentMesh m = reload(ctx, s);
    auto plan = std::make_shared<CuspRetryPlan>();
    plan->before = static_cast<long long>(inconsistentFaces(m).size());
    const std::vector<Vec3> cusps = o.enabled ? cuspsAtInconsistentFaces(m) : std::vector<Vec3>{};
    plan->targets = static_cast<long long>(cusps.size());
    BranchPlan out;
    out.data = plan;
    if (cusps.empty())
        return out;
    auto targets = std::make_shared<CuspRefinementTargets>();
    targets->pixels = o.pixels;
    for (const Vec3& p : cusps)
        targets->at.push_back(ctx.camera.project(p).pixel);
    out.variants = cuspRefinementVariants(ctx.parameters, o.everyVariant, targets);
    return out;
}

std::optional<double> inconsistentFacesOf(const Snapshot& s) {
    const double n = s.counter("inconsistent faces", -1.0);
    return n >= 0.0 ? std::optional<double>(n) : std::nullopt;
}

std::string reportCuspRetry(const PhaseContext&, const BranchSummary& b, Snapshot& s) {
    const auto* plan = dynamic_cast<const CuspRetryPlan*>(b.data.get());
    if (!plan)
        return {};
    s.setCounter(counters::kInconsistentFacesBefore, static_cast<double>(plan->before));
    s.setCounter(counters::kCuspRetryTargets, static_cast<double>(plan->targets));
    if (plan->targets == 0)
        return {};
    long long broken = 0;
    for (const BranchRunSummary& r : b.runs)
        broken += r.better && !r.postconditionsKept;
    // The adopted run's cusp-refinement set its own figures.
    const BranchRunSummary* adopted = b.adoptedRun();
    const double cusps = adopted ? s.counter(counters::kCuspRetryCusps, 0.0) : 0.0;
    const double splits = adopted ? s.counter(counters::kCuspRetryEdgesHalved, 0.0) : 0.0;
    s.setCounter(counters::kCuspRetryRuns, static_cast<double>(b.runs.size()));
    s.setCounter(counters::kCuspRetryAdopted, b.adopted);
    s.setCounter(counters::kCuspRetryBroken, static_cast<double>(broken));
    s.setCounter(counters::kCuspRetryCusps, cusps);
    s.setCounter(counters::kCuspRetryEdgesHalved, splits);
    std::ostringstream note;
    if (adopted)
        note << "cusp retry: this mesh is run " << b.adopted << " of " << b.runs.size()
             << " (cusp-refinement to " << b.decideAfter << ") with the mesh refined around "
             << cusps << " cusp(s) (" << adopted->label << ", " << splits
             << " edges halved): inconsistent faces " << plan->before << " -> "
             << static_cast<long long>(*adopted->figure)
             << ". The snapshots from cusp-refinement on are that run's.";
    else
        note << "cusp retry: " << b.runs.size() << " runs refined around " << plan->targets
             << " cusps at inconsistent faces; none had fewer than " << plan->before
             << " inconsistent faces and kept every post-condition, so the first run's mesh is "
                "kept.";
    return note.str();
}

} // namespace

// The retry's parameters form their own group: no phase follows their
// declaration (the retry is a branch, not a phase).
constexpr const char* kCuspRetryGroup = "cusp-retry";

void addCuspRetryBranch(Method& m) {
    m.parameters.push_back(
        {"cusp-retry",
         "Cusp retry",
         "Not in the paper: when faces stay inconsistent next to a cusp, the runner re-runs "
         "from cusp-refinement with the faces around those cusps refined "
         "(cusp-refinement-*), and adopts that run only when it has fewer inconsistent "
         "faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {},
         kCuspRetryGroup});
    m.parameters.push_back(
        {"cusp-retry-variants",
         "Cusp retry: every variant",
         "With cusp-retry (not in the paper): after the retry with the cusp-refinement-* "
         "values, also retry with every smaller cusp-refinement-rings and "
         "cusp-refinement-levels, and keep the run with the fewest inconsistent faces. "
         "Off: the values set only.",
         ParameterType::Bool,
         true,
         0,
         0,
         {},
         kCuspRetryGroup});
    m.parameters.push_back(
        {"cusp-retry-pixels",
         "Cusp retry: pixels",
         "With cusp-retry (not in the paper): a cusp found by the retried run's cusp "
         "detection is refined around when it lies within this many pixels of a cusp at "
         "an inconsistent face of the first run.",
         ParameterType::Double,
         2.0,
         0.0,
         1000.0,
         {},
         kCuspRetryGroup});
    BranchRule rule;
    rule.name = "cusp-retry";
    rule.rerunFrom = "cusp-refinement";
    rule.decideAfter = m.phases.empty() ? std::string() : m.phases.back().name;
    rule.plan = planCuspRetry;
    rule.figure = inconsistentFacesOf;
    rule.perfect = 0.0;
    rule.report = reportCuspRetry;
    m.branches.push_back(std::move(rule));
}

} // namespace contour::consistent
