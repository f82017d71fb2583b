// bench_traced: the traced method (Summers 2016) per view on the 26-view
// protocol: the time of the traced contour without visibility (the phases
// edge-seeds, interior-seeds, tracing and cusps, run through
// contour::Runner as the GUI and the CLI run them), and its loops and cusps
// against the dense ground truth of the same limit surface. A view is judged
// where the ground truth at N and N/2 lattice steps agree (settled). A
// benchmark: it prints figures and asserts nothing.
//
//   bench_traced --meshes spot_control_mesh,bob_controlmesh --samples 64 [--ortho]
#include "BenchSupport.h"
#include "camera/Camera.h"
#include "contours/Methods.h"
#include "contours/traced/TracedState.h"
#include "pipeline/CounterNames.h"
#include "pipeline/Runner.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace contour;

int main(int argc, char** argv) {
    CLI::App app{"The traced method per view against the dense ground truth"};
    std::vector<std::string> meshes{"spot_control_mesh", "bob_controlmesh"};
    std::string dir = std::string(CONTOUR_SHARED_DIR) + "/meshes";
    int samples = 64;
    bool ortho = false;
    bool withGraph = false;
    std::vector<std::string> settings;
    app.add_option("--meshes", meshes, "Meshes of --dir (without extension), or shape:NAME[:RES]")
        ->delimiter(',');
    app.add_option("--dir", dir, "Folder of the meshes");
    app.add_option("--samples", samples, "Lattice steps per domain face of the ground truth");
    app.add_flag("--ortho", ortho, "Orthographic views (same directions)");
    app.add_flag("--t-junctions", withGraph,
                 "Also run the visibility phase and compare its T-junctions with the ground "
                 "truth's image crossings");
    app.add_option("--set", settings, "PARAM=VALUE for the traced method");
    CLI11_PARSE(app, argc, argv);

    const Method& method = *findMethod("traced");
    const ParameterSet parameters = bench::parametersWithSettings(method, settings);
    const std::vector<std::string> timed = {"edge-seeds", "interior-seeds", "tracing", "cusps"};
    std::printf("load average: %s\n", bench::loadAverage().c_str());
    for (const std::string& name : meshes) {
        const auto cage = bench::loadBenchInput(name, dir);
        if (!cage) {
            std::printf("%s: absent, skipped\n", name.c_str());
            continue;
        }
        const auto surface = cachedSmoothSurface(cage, automaticSurfaceKind(*cage)).surface;
        const DenseGroundTruth truth(surface, {samples, 4});
        const DenseGroundTruth half(surface, {std::max(4, samples / 2), 4});
        const BoundingBox box = cage->boundingBox();
        std::vector<Camera> views = Camera::views26(box, Viewport{800, 600});
        int settled = 0, loopsEqual = 0, cuspsEqual = 0, bothEqual = 0, withinTarget = 0;
        double worst = 0.0, total = 0.0;
        std::printf("%s (%s, %d ground-truth samples per face side)\n", name.c_str(),
                    ortho ? "orthographic" : "perspective", samples);
        std::printf("view  seconds  loops open truth  cusps truth  settled  steps  max|g|/diag  "
                    "closest cusps/diag  T-junctions truth\n");
        for (size_t v = 0; v < views.size(); ++v) {
            Camera camera = views[v];
            if (ortho) {
                camera.projection = Projection::Orthographic;
                camera.orthoHeight = box.diagonal();
            }
            // The surface, its tessellation and the view-independent edge
            // polynomials are built once per mesh, by the first view.
            Runner runner(method, makeInputSnapshot(cage), camera, parameters);
            double seconds = 0.0;
            while (runner.current().phaseName != "cusps" && runner.step()) {
                const Snapshot& s = runner.current();
                if (std::find(timed.begin(), timed.end(), s.phaseName) != timed.end())
                    seconds += s.phaseSeconds - (s.phaseName == "edge-seeds" && v == 0
                                                     ? s.counter(counters::kEdgeSetupSeconds)
                                                     : 0.0);
            }
            const Snapshot& s = runner.current();
            const GroundTruth t = truth.compute(camera);
            const GroundTruth h = half.compute(camera);
            const bool isSettled = t.sameTopology(h);
            const int loops = static_cast<int>(s.counter(counters::kLoops));
            const int open = static_cast<int>(s.counter(counters::kOpenCurves));
            const int cusps = static_cast<int>(s.counter(counters::kCusps));
            const bool sameLoops = loops == t.closedLoops() && open == t.openLoops();
            const bool sameCusps = cusps == static_cast<int>(t.cusps.size());
            // The closest two cusps of one curve (a pair the lattice may not resolve).
            double closestPair = -1.0;
            if (const auto* state = dynamic_cast<const traced::TracedState*>(s.methodState.get()))
                if (state->cusps)
                    for (size_t i = 0; i < state->cusps->size(); ++i)
                        for (size_t j = i + 1; j < state->cusps->size(); ++j) {
                            const traced::TracedCusp& a = (*state->cusps)[i];
                            const traced::TracedCusp& b = (*state->cusps)[j];
                            const double d = (a.position - b.position).norm() / box.diagonal();
                            if (a.curve == b.curve && (closestPair < 0.0 || d < closestPair))
                                closestPair = d;
                        }
            if (isSettled) {
                ++settled;
                loopsEqual += sameLoops;
                cuspsEqual += sameCusps;
                bothEqual += sameLoops && sameCusps;
            }
            worst = std::max(worst, seconds);
            total += seconds;
            withinTarget += seconds <= 0.1;
            const double steps = s.counter(counters::kTracingSteps);
            const double maxAbsG = s.counter(counters::kMaxAbsG);
            // The view graph's T-junctions against the ground truth's image
            // crossings (not timed).
            int tJunctions = -1;
            if (withGraph) {
                while (runner.current().phaseName != "visibility" && runner.step()) {
                }
                if (runner.current().viewGraph) {
                    tJunctions = 0;
                    for (const ViewNode& n : runner.current().viewGraph->nodes)
                        tJunctions += n.type == ViewNodeType::ImageIntersection;
                }
            }
            const int crossings = imageCrossings(t, camera);
            std::printf(
                "%4zu  %7.4f  %5d %4d %5d  %5d %5zu  %7s  %5.0f  %.2e     %.1e  %3d %3d%s\n", v,
                seconds, loops, open, t.closedLoops(), cusps, t.cusps.size(),
                isSettled ? "yes" : "no", steps, maxAbsG, closestPair, tJunctions, crossings,
                (sameLoops && sameCusps) ? "" : "  differs");
        }
        std::printf("%s: mean %.4f s, worst %.4f s, %d/26 views within 0.1 s; %d settled views: "
                    "loops equal on %d, cusps on %d, both on %d\n",
                    name.c_str(), total / 26.0, worst, withinTarget, settled, loopsEqual,
                    cuspsEqual, bothEqual);
    }
    return 0;
}
