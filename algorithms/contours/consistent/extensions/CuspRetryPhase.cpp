// Cusp retry: not in the paper. The faces still inconsistent after the last
// optimization lie next to cusps (the inside fan of Fig. 18e, the far ends of
// a cusp's radial edges). This phase runs the method again from the input
// with the mesh refined around those cusps only (CuspRefinement.h, between
// cusp detection and contour insertion) and keeps the new mesh only when it
// has strictly fewer inconsistent faces (ties keep the first run), so no view
// ends worse and the views without such faces are untouched.
#include "contours/consistent/edits/CuspRefinement.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace contour::consistent {

namespace {

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

// Runs phase `i` of `phases` on a copy of `prev`, as Runner::step does
// (post-conditions enforced in builds that check invariants).
Snapshot runPhase(const PhaseContext& ctx, const std::vector<Phase>& phases, size_t i,
                  const Snapshot& prev) {
    Snapshot next = prev;
    next.phaseIndex = static_cast<int>(i);
    next.phaseName = phases[i].name;
    next.invariants.clear();
    next.notes.clear();
    phases[i].run(ctx, next);
    return next;
}

void enforce([[maybe_unused]] const PhaseContext& ctx, [[maybe_unused]] const Phase& phase,
             [[maybe_unused]] const Snapshot& s) {
#ifdef CONTOUR_CHECK_INVARIANTS
    if (phase.postconditions)
        for (const InvariantCheck& c : phase.postconditions(ctx, s))
            if (c.violations > 0)
                throw std::logic_error("cusp retry, " + phase.name + ": post-condition \"" +
                                       c.name + "\" violated (first: " + c.firstExample + ")");
#endif
}

// The post-conditions every phase after contour insertion keeps (notes
// §6.1 items 1-4) hold on the run's mesh.
bool keepsPostconditions(const PhaseContext& ctx, const Snapshot& r) {
    const ConsistentMesh m = reload(ctx, r);
    for (const InvariantCheck& c : phaseChecks(ctx, r, m, true))
        if (c.violations > 0)
            return false;
    return true;
}

void runCuspRetry(const PhaseContext& ctx, Snapshot& s, const std::vector<Phase>& phases) {
    const ConsistentMesh m = reload(ctx, s);
    const long long before = static_cast<long long>(inconsistentFaces(m).size());
    s.setCounter("inconsistent faces before", static_cast<double>(before));
    const std::vector<Vec3> targets =
        ctx.parameters.getBool("cusp-retry") ? cuspsAtInconsistentFaces(m) : std::vector<Vec3>{};
    s.setCounter("cusp retry: cusps at inconsistent faces", static_cast<double>(targets.size()));
    if (targets.empty())
        return;
    const double pixels = ctx.parameters.getDouble("cusp-retry-pixels");
    std::vector<Vec2> at;
    for (const Vec3& p : targets)
        at.push_back(ctx.camera.project(p).pixel);
    const auto select = [&](const Vec3& cusp) {
        const Vec2 q = ctx.camera.project(cusp).pixel;
        for (const Vec2& p : at)
            if ((p - q).norm() <= pixels)
                return true;
        return false;
    };
    // The values set first; with cusp-retry-variants, then every other
    // rings <= cusp-refinement-rings and levels <= cusp-refinement-levels,
    // fewest levels, then rings, first.
    const CuspRefinementSettings settings = cuspRefinementSettings(ctx.parameters);
    std::vector<CuspRefinementSettings> variants{settings};
    if (ctx.parameters.getBool("cusp-retry-variants"))
        for (int levels = 1; levels <= settings.levels; ++levels)
            for (int rings = 0; rings <= settings.rings; ++rings)
                if (rings != settings.rings || levels != settings.levels) {
                    CuspRefinementSettings v = settings;
                    v.rings = rings;
                    v.levels = levels;
                    variants.push_back(v);
                }
    // Initialization and cusp detection do not depend on the refinement:
    // run once.
    size_t detection = 0;
    while (detection < phases.size() && phases[detection].name != "cusp-detection")
        ++detection;
    if (detection == phases.size())
        throw std::logic_error("cusp retry: the method has no cusp-detection phase");
    Snapshot detected = makeInputSnapshot(s.cage);
    for (size_t i = 0; i <= detection; ++i) {
        detected = runPhase(ctx, phases, i, detected);
        enforce(ctx, phases[i], detected);
    }
    // One variant's run, from the detected mesh to the last phase before
    // this one.
    struct Run {
        Snapshot snapshot;
        CuspRefinementCounts counts;
    };
    const auto runVariant = [&](const CuspRefinementSettings& variant) {
        Run run{detected, {}};
        ConsistentMesh x = reload(ctx, run.snapshot);
        refineAroundCusps(x, variant, select, static_cast<int>(detection), run.counts);
        publish(run.snapshot, x);
        enforce(ctx, phases[detection], run.snapshot);
        for (size_t i = detection + 1; i < phases.size(); ++i) {
            run.snapshot = runPhase(ctx, phases, i, run.snapshot);
            enforce(ctx, phases[i], run.snapshot);
        }
        return run;
    };
    // The variants run in waves of as many as the machine has cores (the
    // runs are independent and mostly serial), and are then judged in order
    // as if run one by one: the same run is adopted, and a wave starts only
    // while no run has reached 0.
    const size_t wave =
        std::max<size_t>(1, static_cast<size_t>(tbb::this_task_arena::max_concurrency()));
    long long best = before;
    int tried = 0, adopted = 0, broken = 0;
    CuspRefinementCounts kept;
    CuspRefinementSettings keptVariant = settings;
    for (size_t first = 0; first < variants.size() && best > 0; first += wave) {
        const size_t count = std::min(wave, variants.size() - first);
        std::vector<Run> runs(count);
        tbb::parallel_for(size_t(0), count,
                          [&](size_t k) { runs[k] = runVariant(variants[first + k]); });
        for (size_t k = 0; k < count; ++k) {
            Run& run = runs[k];
            if (best == 0)
                break;
            ++tried;
            const double after = run.snapshot.counter("inconsistent faces", -1.0);
            if (!(after >= 0.0 && after < static_cast<double>(best)))
                continue;
            // A run whose mesh breaks a post-condition (contour insertion
            // can leave a face without a common chart on the refined mesh)
            // is not kept.
            if (!keepsPostconditions(ctx, run.snapshot)) {
                ++broken;
                continue;
            }
            best = static_cast<long long>(after);
            adopted = tried;
            kept = run.counts;
            keptVariant = variants[first + k];
            const int index = s.phaseIndex;
            const std::string name = s.phaseName;
            s = std::move(run.snapshot);
            s.phaseIndex = index;
            s.phaseName = name;
            s.invariants.clear();
            s.notes.clear();
        }
    }
    s.setCounter("inconsistent faces before", static_cast<double>(before));
    s.setCounter("cusp retry: cusps at inconsistent faces", static_cast<double>(targets.size()));
    s.setCounter("cusp retry: runs", tried);
    s.setCounter("cusp retry: run adopted (0: none)", adopted);
    s.setCounter("cusp retry: better runs breaking a post-condition", broken);
    s.setCounter("cusp retry: cusps refined around", static_cast<double>(kept.cusps));
    s.setCounter("cusp retry: edges halved", static_cast<double>(kept.splits));
    // The stepper shows the first run before this phase: say so when this
    // snapshot is another run's mesh.
    std::ostringstream note;
    if (adopted > 0)
        note << "cusp retry: this mesh is a second run (initialization to contour-refinement) "
                "with the mesh refined around "
             << kept.cusps << " cusp(s) (" << keptVariant.rings << " ring(s), "
             << keptVariant.levels << " level(s), " << kept.splits << " edges halved; run "
             << adopted << " of " << tried << "): inconsistent faces " << before << " -> " << best
             << ". The earlier phases' snapshots show the first run.";
    else
        note << "cusp retry: " << tried << " runs refined around " << targets.size()
             << " cusps at inconsistent faces; none had fewer than " << before
             << " inconsistent faces and kept every post-condition, so the first run's mesh is "
                "kept.";
    s.notes.push_back(note.str());
}

std::vector<InvariantCheck> checkCuspRetry(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, false);
}

} // namespace

void addCuspRetryPhase(Method& m) {
    m.parameters.push_back(
        {"cusp-retry",
         "Cusp retry",
         "Not in the paper: when faces stay inconsistent next to a cusp (a corner is the cusp "
         "or joined to it by an edge), the method runs again from the input with the faces "
         "around those cusps refined before contour insertion (the cusp-refinement-* "
         "settings), and keeps that mesh only when it has strictly fewer inconsistent faces. "
         "Measured alone on session 10's first tree (26 views, 7 meshes): 54 views better, "
         "none worse (spot_control 10 -> 1, bigguy 49 -> 26, killeroo 163 -> 112; bumpy torus "
         "5 -> 3), at up to twice the time of a view with such faces.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"cusp-retry-variants",
         "Cusp retry: every variant",
         "After the retry with the cusp-refinement-* values set, retry with every other "
         "cusp-refinement-rings from 0 and cusp-refinement-levels from 1 up to those values "
         "(fewest levels, then rings, first; none once a run has no inconsistent face) and "
         "keep the run with the fewest; off: the values set only. At session 10's defaults, "
         "26 views, off -> on: spot_control 1 -> 0, bigguy 23 -> 16, bob_quad 10 -> 8, "
         "fertility 11 -> 9, killeroo 91 -> 68, bumpy torus 2 -> 0 (view 21), "
         "no view worse; killeroo_small 2.1 -> 4.4 s per view (limit 11.3), bigguy 0.56 -> "
         "1.05 (limit 1.75) on 2 cores (the variants run in parallel waves).",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back({"cusp-retry-pixels",
                            "Cusp retry: pixels",
                            "A cusp found by the second run's cusp detection is refined around "
                            "when it lies within this many pixels of a cusp at an inconsistent "
                            "face of the first run.",
                            ParameterType::Double,
                            2.0,
                            0.0,
                            1000.0,
                            {}});
    // The phases so far (initialization to the last one before this),
    // rerun by the retry.
    const std::vector<Phase> phases = m.phases;
    m.phases.push_back(
        {"cusp-retry",
         "Not in the paper: with cusp-retry, the method so far runs again with the mesh "
         "refined around the cusps next to the faces left inconsistent, and that mesh replaces "
         "this one when it has strictly fewer inconsistent faces.",
         [phases](const PhaseContext& ctx, Snapshot& s) { runCuspRetry(ctx, s, phases); },
         checkCuspRetry});
}

} // namespace contour::consistent
