// bench_topology: the consistent method's drawing against an independent
// oracle, on every mesh it is given, over the 26-view protocol. A benchmark:
// it prints figures and asserts nothing.
//
//   bench_topology [--meshes-dir DIR] [--mesh NAME]... [--all] [--shape NAME:RES]...
//                  [--views N] [--samples N | --sample-budget S] [--set PARAM=VALUE]...
//                  [--out summary.csv] [--per-view views.csv] [--cusps cusps.csv]
//                  [--threads N]
//
// Per view, the consistent method runs to the end and its final view graph
// is compared with reference/DenseGroundTruth (the g = 0 set of the same smooth
// surface sampled on a dense lattice, sharing no contour code):
//   loops       closed and open contour loops, matched by domain faces
//   cusps       the method's cusp vertices ("cusps" counter) vs the oracle's
//   folds       the view graph's curtain-fold nodes, split into those at a
//               cusp vertex of the consistent mesh and the others (the
//               near-face fallback, Bénard 2014 §8.1), vs the oracle's cusps
//   T-junctions the graph's image-intersection nodes where a contour passes
//               in front of a contour, vs the oracle's image crossings (the
//               smooth contour's projected self-crossings); "curve crossings"
//               counts the crossings of the method's contour polylines, to
//               tell the graph's exactness from its input's
//   conflicts   visibility conflicts (ray test vs propagation), ambiguous
//               chains, and both on views with no inconsistent face; "roots"
//               are the ray checks whose propagation source passed its own
//               check (the first wrong step of a path; the others repeat it)
//   inconsistent faces (% of the final mesh), post-condition violations,
//               seconds per view (the method only, not the oracle)
// The oracle misses what lies below its lattice step: loops inside one
// lattice cell and cusp pairs closer than one step. Each view is also
// extracted at half the lattice resolution; a view whose cusp or crossing
// count changes between the two is "oracle-unsettled" and counted apart
// (the targets exclude it, the tables say how many).
//
// The summary has one row per mesh with ConTesse's published runtime for the
// same model (../shared/bench/contesse-0927-stats.csv) beside ours.
#include "BenchSupport.h"
#include "camera/Camera.h"
#include "contours/Methods.h"
#include "pipeline/FieldNames.h"
#include "pipeline/Runner.h"
#include "reference/DenseGroundTruth.h"
#include "surface/SmoothSurfaceFactory.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tbb/global_control.h>
#include <vector>

using namespace contour;
using namespace contour::bench;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct ViewFigures {
    bool completed = false;
    std::string error;
    double seconds = 0.0;
    double faces = 0.0, inconsistent = 0.0;
    long long violations = 0;
    int loops = 0, truthLoops = 0;
    bool loopsMatch = false;
    int methodCusps = 0, truthCusps = 0, halfCusps = 0;
    int folds = 0, foldsAtCusps = 0, fallbackFolds = 0;
    int tJunctions = 0, truthCrossings = 0, halfCrossings = 0, curveCrossings = 0;
    int conflicts = 0, rootConflicts = 0, ambiguousChains = 0;
    // Image positions of the method's cusp vertices and of the oracle's
    // cusps (for --cusps).
    std::vector<Vec2> methodCuspPixels, truthCuspPixels;
    bool unsettled() const { return truthCusps != halfCusps || truthCrossings != halfCrossings; }
};

// Counts the graph's figures; `cusp` is the final mesh's per-vertex flag.
void readGraph(const Snapshot& s, ViewFigures& out) {
    const ViewGraph& g = *s.viewGraph;
    const std::vector<int>* cusp =
        fieldValues<int>(s, fields::kCusp, FieldLocation::Vertex, s.mesh->vertexCount());
    for (const ViewNode& n : g.nodes) {
        if (n.type == ViewNodeType::CurtainFold) {
            ++out.folds;
            const bool atCusp = cusp && n.meshVertex != kInvalidIndex &&
                                (*cusp)[static_cast<size_t>(n.meshVertex)] != 0;
            (atCusp ? out.foldsAtCusps : out.fallbackFolds)++;
        } else if (n.type == ViewNodeType::ImageIntersection) {
            // The oracle's crossings are the contour's with itself: count the
            // T-junctions whose near and far curves are both contours.
            const auto contour = [&](Index chain) {
                return chain != kInvalidIndex && g.chains[chain].type == CurveType::Contour;
            };
            const bool near = contour(n.nearChains[0]) || contour(n.nearChains[1]);
            const bool far = contour(n.farChains[0]) || contour(n.farChains[1]);
            out.tJunctions += near && far && !n.smallLoop;
        }
    }
    out.conflicts = static_cast<int>(g.conflicts.size());
    for (const VisibilityConflict& k : g.conflicts)
        out.rootConflicts += k.root;
    for (const ViewChain& c : g.chains)
        out.ambiguousChains += c.ambiguous;
}

ViewFigures runView(const Method& method, const Snapshot& input, const Camera& camera,
                    const ParameterSet& parameters, const DenseGroundTruth& truth,
                    const DenseGroundTruth& half) {
    ViewFigures f;
    const auto start = Clock::now();
    Runner runner(method, input, camera, parameters);
    try {
        while (!runner.atEnd())
            runner.step();
        f.completed = true;
    } catch (const std::exception& e) {
        f.error = e.what();
    }
    f.seconds = secondsSince(start);
    for (int p = 1; p <= runner.completedPhases(); ++p)
        f.violations += runner.snapshot(p).invariantViolations();
    if (!f.completed)
        return f;
    const Snapshot& last = runner.current();
    f.faces = last.counter(counters::kFaces, last.mesh->faceCount());
    f.inconsistent = last.counter(counters::kInconsistentFaces, 0.0);
    f.methodCusps = static_cast<int>(last.counter(counters::kCusps, 0.0));
    if (last.viewGraph)
        readGraph(last, f);
    if (const std::vector<int>* cusp =
            fieldValues<int>(last, fields::kCusp, FieldLocation::Vertex, last.mesh->vertexCount()))
        for (Index v = 0; v < last.mesh->vertexCount(); ++v)
            if ((*cusp)[static_cast<size_t>(v)] != 0)
                f.methodCuspPixels.push_back(camera.project(last.mesh->position(v)).pixel);
    // Crossings bounding a sub-pixel loop are left out of every count alike:
    // the graph flags them by t-junction-min-loop (0 in the paper preset).
    const double minLoop = parameters.getDouble("t-junction-min-loop");
    if (last.curves)
        f.curveCrossings = imageCrossings(*last.curves, camera, minLoop);

    const GroundTruth t = truth.compute(camera);
    const GroundTruth h = half.compute(camera);
    f.truthLoops = static_cast<int>(t.loops.size());
    f.truthCusps = static_cast<int>(t.cusps.size());
    f.halfCusps = static_cast<int>(h.cusps.size());
    for (const GroundTruthCusp& cusp : t.cusps)
        f.truthCuspPixels.push_back(camera.project(cusp.position).pixel);
    f.truthCrossings = imageCrossings(t, camera, minLoop);
    f.halfCrossings = imageCrossings(h, camera, minLoop);
    const TopologyComparison c = compareTopology(t, last, truth.surfacePtr(), &camera);
    f.loops = c.methodLoops;
    f.loopsMatch = c.loopCountsMatch();
    return f;
}

struct MeshFigures {
    std::string name;
    std::string skipped; // why the mesh has no figures
    int samples = 0;
    std::vector<ViewFigures> views;
    std::optional<double> published; // ConTesse's runtime per view
};

double percent(double part, double whole) {
    return whole > 0 ? 100.0 * part / whole : 0.0;
}

struct Summary {
    int views = 0, completed = 0, settled = 0;
    int loopsMatch = 0, cuspsMatch = 0, foldsMatch = 0, tMatch = 0;
    long long folds = 0, foldsAtCusps = 0, fallbackFolds = 0, truthCusps = 0;
    long long tJunctions = 0, truthCrossings = 0;
    long long conflicts = 0, conflictsOnConsistentViews = 0, consistentViews = 0;
    long long rootConflictsOnConsistentViews = 0;
    long long ambiguous = 0, ambiguousOnConsistentViews = 0;
    long long violations = 0, viewsWithViolations = 0;
    double maxInconsistentPercent = 0.0, meanSeconds = 0.0, maxSeconds = 0.0;
    int viewsAboveTarget = 0; // inconsistent faces > 0.05 %
};

Summary summarize(const MeshFigures& m) {
    Summary s;
    s.views = static_cast<int>(m.views.size());
    for (const ViewFigures& v : m.views) {
        s.violations += v.violations;
        s.viewsWithViolations += v.violations > 0;
        if (!v.completed)
            continue;
        ++s.completed;
        s.loopsMatch += v.loopsMatch;
        s.cuspsMatch += v.methodCusps == v.truthCusps;
        s.folds += v.folds;
        s.foldsAtCusps += v.foldsAtCusps;
        s.fallbackFolds += v.fallbackFolds;
        s.truthCusps += v.truthCusps;
        s.tJunctions += v.tJunctions;
        s.truthCrossings += v.truthCrossings;
        s.conflicts += v.conflicts;
        s.ambiguous += v.ambiguousChains;
        if (v.inconsistent == 0.0) {
            ++s.consistentViews;
            s.conflictsOnConsistentViews += v.conflicts;
            s.rootConflictsOnConsistentViews += v.rootConflicts;
            s.ambiguousOnConsistentViews += v.ambiguousChains;
        }
        const double p = percent(v.inconsistent, v.faces);
        s.maxInconsistentPercent = std::max(s.maxInconsistentPercent, p);
        s.viewsAboveTarget += p > 0.05;
        s.meanSeconds += v.seconds;
        s.maxSeconds = std::max(s.maxSeconds, v.seconds);
        if (!v.unsettled()) {
            ++s.settled;
            s.foldsMatch += v.folds == v.truthCusps;
            s.tMatch += v.tJunctions == v.truthCrossings;
        }
    }
    if (s.completed > 0)
        s.meanSeconds /= s.completed;
    return s;
}

const char* kSummaryHeader =
    "Input,Input count,Success count,Oracle samples,Oracle-settled views,Loops match,"
    "Cusps match,Folds = cusps (settled),T-junctions = crossings (settled),Curtain folds,"
    "Folds at cusps,Fallback folds,Oracle cusps,T-junctions,Oracle crossings,Conflicts,"
    "Views with 0 inconsistent,Conflicts on those,Root conflicts on those,Ambiguous "
    "chains,Ambiguous on those,"
    "Max inconsistent %,Views above 0.05 %,Violations,Views with violations,Runtime,"
    "Max runtime,ConTesse runtime,Skipped\n";

std::string summaryRow(const MeshFigures& m) {
    const Summary s = summarize(m);
    std::ostringstream o;
    o << csvEscape(m.name) << ',' << s.views << ',' << s.completed << ',' << m.samples << ','
      << s.settled << ',' << s.loopsMatch << ',' << s.cuspsMatch << ',' << s.foldsMatch << ','
      << s.tMatch << ',' << s.folds << ',' << s.foldsAtCusps << ',' << s.fallbackFolds << ','
      << s.truthCusps << ',' << s.tJunctions << ',' << s.truthCrossings << ',' << s.conflicts << ','
      << s.consistentViews << ',' << s.conflictsOnConsistentViews << ','
      << s.rootConflictsOnConsistentViews << ',' << s.ambiguous << ','
      << s.ambiguousOnConsistentViews << ',' << s.maxInconsistentPercent << ','
      << s.viewsAboveTarget << ',' << s.violations << ',' << s.viewsWithViolations << ','
      << s.meanSeconds << ',' << s.maxSeconds << ',';
    if (m.published)
        o << *m.published;
    o << ',' << csvEscape(m.skipped) << '\n';
    return o.str();
}

const char* kViewHeader =
    "mesh,view,completed,seconds,faces,inconsistent,violations,loops,oracle loops,loops match,"
    "cusps,oracle cusps,oracle cusps at half,curtain folds,folds at cusps,fallback folds,"
    "T-junctions,oracle crossings,oracle crossings at half,curve crossings,conflicts,"
    "root conflicts,ambiguous chains,error\n";

std::string viewRow(const std::string& mesh, int view, const ViewFigures& v) {
    std::ostringstream o;
    o << csvEscape(mesh) << ',' << view << ',' << v.completed << ',' << v.seconds << ',' << v.faces
      << ',' << v.inconsistent << ',' << v.violations << ',' << v.loops << ',' << v.truthLoops
      << ',' << v.loopsMatch << ',' << v.methodCusps << ',' << v.truthCusps << ',' << v.halfCusps
      << ',' << v.folds << ',' << v.foldsAtCusps << ',' << v.fallbackFolds << ',' << v.tJunctions
      << ',' << v.truthCrossings << ',' << v.halfCrossings << ',' << v.curveCrossings << ','
      << v.conflicts << ',' << v.rootConflicts << ',' << v.ambiguousChains << ','
      << csvEscape(v.error) << '\n';
    return o.str();
}

std::string cuspRows(const std::string& mesh, int view, const ViewFigures& v) {
    std::ostringstream o;
    const auto rows = [&](const char* source, const std::vector<Vec2>& pixels) {
        for (const Vec2& p : pixels)
            o << csvEscape(mesh) << ',' << view << ',' << source << ',' << p.x() << ',' << p.y()
              << '\n';
    };
    rows("method", v.methodCuspPixels);
    rows("oracle", v.truthCuspPixels);
    return o.str();
}

void printSummary(const MeshFigures& m) {
    if (!m.skipped.empty()) {
        std::printf("%-22s skipped: %s\n", m.name.c_str(), m.skipped.c_str());
        return;
    }
    const Summary s = summarize(m);
    std::printf(
        "%-22s N=%-3d ok %2d/%-2d settled %2d | loops %2d cusps %2d folds=cusps %2d "
        "T=cross %2d | folds %lld (at cusps %lld, fallback %lld) vs %lld | T %lld vs "
        "%lld | conflicts %lld (%lld on %lld consistent views, %lld roots) | max inc %.3f%% | "
        "viol %lld on %lld views | %.3f s/view (max %.3f)",
        m.name.c_str(), m.samples, s.completed, s.views, s.settled, s.loopsMatch, s.cuspsMatch,
        s.foldsMatch, s.tMatch, s.folds, s.foldsAtCusps, s.fallbackFolds, s.truthCusps,
        s.tJunctions, s.truthCrossings, s.conflicts, s.conflictsOnConsistentViews,
        s.consistentViews, s.rootConflictsOnConsistentViews, s.maxInconsistentPercent, s.violations,
        s.viewsWithViolations, s.meanSeconds, s.maxSeconds);
    if (m.published)
        std::printf(" | ConTesse %.3f s", *m.published);
    std::printf("\n");
    std::fflush(stdout);
}

std::vector<std::string> everyMesh(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(dir, error))
        if (entry.is_regular_file() && entry.path().extension() == ".obj")
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"The consistent method's view graph against the dense ground truth"};
    std::string meshesDir = std::string(CONTOUR_SHARED_DIR) + "/meshes";
    std::string publishedPath = std::string(CONTOUR_SHARED_DIR) + "/bench/contesse-0927-stats.csv";
    std::vector<std::string> meshes, shapes, sets;
    bool all = false;
    int views = 26, samples = 0, threads = 0;
    double budget = 8e6;
    std::string outPath, perViewPath, cuspsPath;
    app.add_option("--meshes-dir", meshesDir, "Folder of the meshes");
    app.add_option("--mesh", meshes, "Mesh name (file name without extension), repeatable");
    app.add_flag("--all", all, "Every .obj of the meshes folder");
    app.add_option("--shape", shapes, "A procedural shape NAME:RES, repeatable");
    app.add_option("--views", views, "Views of the 26-view protocol to run (the first N)");
    app.add_option("--samples", samples, "Oracle lattice steps per domain face side (0: budget)");
    app.add_option("--sample-budget", budget,
                   "Oracle lattice points per mesh when --samples is 0 (N = sqrt(S / faces), "
                   "8 to 64)");
    app.add_option("--set", sets, "Method parameter PARAM=VALUE, repeatable");
    app.add_option("--out", outPath, "Summary CSV, one row per mesh");
    app.add_option("--per-view", perViewPath, "CSV, one row per view");
    app.add_option("--cusps", cuspsPath,
                   "CSV, one row per cusp: the method's cusp vertices and the oracle's cusps, "
                   "in image pixels");
    app.add_option("--threads", threads, "TBB worker threads (0: TBB's default)");
    CLI11_PARSE(app, argc, argv);
    try {
        std::unique_ptr<tbb::global_control> limit;
        if (threads > 0)
            limit = std::make_unique<tbb::global_control>(
                tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
        const Method* method = findMethod("consistent");
        if (!method)
            throw std::runtime_error("no consistent method");
        const ParameterSet parameters = parametersWithSettings(*method, sets);
        if (all)
            for (const std::string& name : everyMesh(meshesDir))
                if (std::find(meshes.begin(), meshes.end(), name) == meshes.end())
                    meshes.push_back(name);
        const std::map<std::string, double> published = readPublished(publishedPath);
        std::ofstream summaryCsv, viewCsv, cuspCsv;
        if (!cuspsPath.empty()) {
            cuspCsv.open(cuspsPath);
            cuspCsv << "mesh,view,source,x,y\n" << std::flush;
        }
        if (!outPath.empty()) {
            summaryCsv.open(outPath);
            summaryCsv << kSummaryHeader << std::flush;
        }
        if (!perViewPath.empty()) {
            viewCsv.open(perViewPath);
            viewCsv << kViewHeader << std::flush;
        }
        std::printf("bench_topology: load average %s, %d views per mesh\n", loadAverage().c_str(),
                    views);
        std::vector<std::string> inputs = meshes;
        for (const std::string& shape : shapes)
            inputs.push_back("shape:" + shape);
        for (const std::string& name : inputs) {
            MeshFigures m;
            m.name = name;
            try {
                const std::shared_ptr<const PolygonMesh> cage = loadBenchInput(name, meshesDir);
                if (!cage)
                    throw std::runtime_error("no file " + meshesDir + "/" + name + ".obj");
                const auto surface = cachedSmoothSurface(cage, automaticSurfaceKind(*cage)).surface;
                const double faces = std::max(1, cage->faceCount());
                m.samples = samples > 0
                                ? samples
                                : std::clamp(static_cast<int>(std::sqrt(budget / faces)), 8, 64);
                const DenseGroundTruth truth(surface, {m.samples, 4});
                const DenseGroundTruth half(surface, {std::max(4, m.samples / 2), 4});
                const Snapshot input = makeInputSnapshot(cage);
                const std::vector<Camera> cameras =
                    Camera::views26(input.mesh->boundingBox(), Viewport{});
                const int n = std::min<int>(views, static_cast<int>(cameras.size()));
                for (int v = 0; v < n; ++v) {
                    m.views.push_back(runView(*method, input, cameras[static_cast<size_t>(v)],
                                              parameters, truth, half));
                    if (viewCsv)
                        viewCsv << viewRow(name, v, m.views.back()) << std::flush;
                    if (cuspCsv)
                        cuspCsv << cuspRows(name, v, m.views.back()) << std::flush;
                }
                if (const auto row = matchPublished(published, name))
                    m.published = published.at(*row);
            } catch (const std::exception& e) {
                m.skipped = e.what();
            }
            printSummary(m);
            if (summaryCsv)
                summaryCsv << summaryRow(m) << std::flush;
        }
        std::printf("done; load average %s\n", loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_topology: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
