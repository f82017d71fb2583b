// bench_powell_sabin_drawing: the powell-sabin method's drawing (Capouellez
// et al. 2023 §4) per view, against a dense oracle of its own spline
// (tests/SplineGroundTruth.h), on meshes of ../shared/meshes. A benchmark:
// it prints figures and asserts nothing.
//
//   bench_powell_sabin_drawing [--meshes spot_control_mesh,fertility] [--all] [--views 26]
//                              [--samples N] [--csv out.csv] [--verbose]
//
// Per mesh: the preprocessing (cones to factorization, run once and cached,
// reported apart), then per view of the 26-view protocol the wall time of
// the per-view phases from their snapshots (fit, patch-contours, chaining,
// cusps, visibility; the fit's tessellation for drawing also apart), and
// the view graph's contour components, cusps, T-junctions and conflicts
// against the oracle at N and N/2 lattice steps per layout face. Only views
// the two lattices agree on (components and cusps; T-junctions also need
// the crossings to agree) are judged. By default N gives the oracle about
// --sample-budget lattice points (N^2 / 2 per face), between 16 and 96:
// coarse cages have large patches, whose close cusp pairs a lattice of 16
// steps per face misses.
#include "BenchSupport.h"
#include "SplineGroundTruth.h"
#include "contours/Methods.h"
#include "pipeline/CounterNames.h"
#include "pipeline/Runner.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace contour;

namespace {

using Clock = std::chrono::steady_clock;

const std::vector<std::string> kPreprocessing{"cones", "conformal-map", "layout", "patches",
                                              "factorization"};
const std::vector<std::string> kPerView{"fit", "patch-contours", "chaining", "cusps", "visibility"};

struct ViewFigures {
    int view = 0;
    std::string error;
    bool cached = true;
    std::map<std::string, double> phaseSeconds;
    double fitSeconds = 0.0, tessellationSeconds = 0.0, totalSeconds = 0.0;
    testing::SplineViewComparison comparison;
};

struct MeshFigures {
    std::string name;
    std::string error;
    long long faces = 0, layoutFaces = 0, cones = 0;
    int samples = 0;
    double preprocessSeconds = 0.0;
    std::vector<ViewFigures> views;
};

// Even, within [16, 96], about `budget` lattice points over the faces.
int automaticSamples(long long layoutFaces, double budget) {
    const double n = std::sqrt(2.0 * budget / static_cast<double>(std::max(1LL, layoutFaces)));
    return 2 * std::clamp(static_cast<int>(std::lround(0.5 * n)), 8, 48);
}

MeshFigures measure(const std::string& name, const std::filesystem::path& path, int viewCount,
                    int samplesOption, double budget, bool verbose) {
    MeshFigures m;
    m.name = name;
    const Method& method = *findMethod("powell-sabin");
    std::vector<Camera> views;
    std::shared_ptr<const PolygonMesh> cage;
    const ParameterSet parameters = ParameterSet::defaults(method.parameters);
    try {
        cage = std::make_shared<const PolygonMesh>(readMesh(path.string()));
        views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        Runner first(method, makeInputSnapshot(cage), views.front(), parameters);
        m.faces = first.current().mesh->faceCount();
        while (first.current().phaseName != kPreprocessing.back() && first.step()) {
        }
        for (const Snapshot& s : first.snapshots())
            if (s.phaseIndex >= 0)
                m.preprocessSeconds += s.phaseSeconds;
        m.layoutFaces = first.current().mesh->faceCount();
        m.cones = static_cast<long long>(first.snapshot(1).counter(counters::kCones));
        m.samples = samplesOption > 0 ? samplesOption : automaticSamples(m.layoutFaces, budget);
    } catch (const std::exception& e) {
        m.error = e.what();
        return m;
    }
    const int n = std::min<int>(viewCount, static_cast<int>(views.size()));
    for (int v = 0; v < n; ++v) {
        ViewFigures f;
        f.view = v;
        try {
            Runner r(method, makeInputSnapshot(cage), views[static_cast<size_t>(v)], parameters);
            r.runToEnd();
            for (const Snapshot& s : r.snapshots()) {
                if (s.phaseIndex < 0)
                    continue;
                if (std::find(kPreprocessing.begin(), kPreprocessing.end(), s.phaseName) !=
                    kPreprocessing.end())
                    f.cached = f.cached && s.counter(counters::kPreprocessingCached) == 1.0;
                if (std::find(kPerView.begin(), kPerView.end(), s.phaseName) != kPerView.end()) {
                    f.phaseSeconds[s.phaseName] = s.phaseSeconds;
                    f.totalSeconds += s.phaseSeconds;
                }
                if (s.phaseName == "fit") {
                    f.fitSeconds = s.counter(counters::kStageSeconds);
                    f.tessellationSeconds = s.phaseSeconds - f.fitSeconds;
                }
            }
            f.comparison =
                testing::compareWithOracle(r.current(), views[static_cast<size_t>(v)], m.samples);
        } catch (const std::exception& e) {
            f.error = e.what();
        }
        if (verbose) {
            const testing::SplineViewComparison& c = f.comparison;
            if (!f.error.empty())
                std::printf("  view %2d: error: %s\n", v, f.error.c_str());
            else
                std::printf("  view %2d: %7.2f ms  components %d/%d(%d)  cusps %d/%d(%d)  "
                            "(raw %d)  T %d/%d(%d)  conflicts %d%s\n",
                            v, 1e3 * f.totalSeconds, c.method.components, c.fine.components,
                            c.coarse.components, c.method.cusps, c.fine.cusps, c.coarse.cusps,
                            c.fine.rawCusps, c.method.tJunctions, c.fine.crossings,
                            c.coarse.crossings, c.method.conflicts,
                            c.settled() ? "" : "  (not settled)");
            std::fflush(stdout);
        }
        m.views.push_back(std::move(f));
    }
    return m;
}

// The spec's per-view time targets (ms), 0 when it names none.
double timeTarget(const std::string& name) {
    if (name == "spot_control_mesh")
        return 50.0;
    if (name == "fertility" || name == "killeroo_small")
        return 100.0;
    return 0.0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("Powell-Sabin drawing per view against a dense oracle of the spline");
    std::string meshList = "spot_control_mesh,bob_controlmesh,fertility,killeroo_small";
    std::string meshDir = CONTOUR_SHARED_DIR "/meshes";
    std::string csvPath;
    int views = 26, samples = 0;
    double budget = 4e6;
    bool all = false, verbose = false;
    app.add_option("--meshes", meshList, "Comma-separated mesh names (without extension)");
    app.add_option("--mesh-dir", meshDir, "Folder of the meshes");
    app.add_option("--views", views, "Views of the 26-view protocol per mesh")
        ->check(CLI::Range(1, 26));
    app.add_option("--samples", samples,
                   "Oracle lattice steps N per layout face (also run at N/2); 0: from the budget")
        ->check(CLI::Range(0, 256));
    app.add_option("--sample-budget", budget, "Oracle lattice points per view when N is automatic")
        ->check(CLI::PositiveNumber);
    app.add_option("--csv", csvPath, "Also write one row per view as CSV");
    app.add_flag("--all", all, "Every mesh file of the folder");
    app.add_flag("--verbose", verbose, "One line per view");
    CLI11_PARSE(app, argc, argv);

    std::vector<std::string> names;
    if (all) {
        for (const auto& entry : std::filesystem::directory_iterator(meshDir)) {
            const std::string ext = entry.path().extension().string();
            if (entry.is_regular_file() && (ext == ".obj" || ext == ".off" || ext == ".ply"))
                names.push_back(entry.path().stem().string());
        }
        std::sort(names.begin(), names.end());
        names.erase(std::unique(names.begin(), names.end()), names.end());
    } else {
        std::stringstream list(meshList);
        for (std::string name; std::getline(list, name, ',');)
            names.push_back(name);
    }
    std::printf("load average: %s\n", bench::loadAverage().c_str());
    if (samples > 0)
        std::printf("oracle: N = %d and %d lattice steps per layout face\n", samples, samples / 2);
    else
        std::printf("oracle: N and N/2 lattice steps per layout face, N even in [16, 96] for "
                    "about %.3g lattice points\n",
                    budget);
    std::printf("targets: per view <= 50 ms spot, <= 100 ms fertility and killeroo_small; "
                "components and cusps = oracle on >= 95 %% of views; 0 conflicts on >= 95 %% "
                "of views\n");
    std::printf("%-24s %6s %5s %3s %8s %5s %7s %13s %13s %13s %13s %9s %9s %7s %7s\n", "mesh",
                "layout", "cones", "N", "prep s", "views", "settled",
                "components =", "cusps =", "T-junctions =", "0 conflicts", "mean ms", "max ms",
                "tess ms", "target");
    std::ofstream csv;
    if (!csvPath.empty()) {
        csv.open(csvPath);
        csv << "mesh,view,samples,preprocessing_s,cached,view_ms,fit_ms,tessellation_ms,"
               "patch_contours_ms,chaining_ms,cusps_ms,visibility_ms,settled,crossings_settled,"
               "components,oracle_components,oracle_components_half,cusps,oracle_cusps,"
               "oracle_cusps_half,oracle_raw_cusps,oracle_cone_cusps,t_junctions,oracle_crossings,"
               "oracle_crossings_half,"
               "oracle_cone_crossings,oracle_loops,conflicts,oracle_s,error\n";
    }
    const auto percent = [](int a, int b) {
        return b > 0 ? 100.0 * a / b : 0.0;
    };
    for (const std::string& name : names) {
        const auto path = bench::findMeshFile(meshDir, name);
        if (!path) {
            std::printf("%-24s (not found)\n", name.c_str());
            continue;
        }
        if (verbose)
            std::printf("%s:\n", name.c_str());
        const MeshFigures m = measure(name, *path, views, samples, budget, verbose);
        if (!m.error.empty()) {
            std::printf("%-24s error: %s\n", name.c_str(), m.error.c_str());
            if (csv)
                csv << name << ",,,,,,,,,,,,,,,,,,,,,,,,,,,,," << bench::csvEscape(m.error) << '\n';
            continue;
        }
        testing::OracleTally tally;
        int done = 0, clean = 0, failed = 0, uncached = 0;
        double sum = 0.0, worst = 0.0, tess = 0.0;
        std::string firstError;
        for (const ViewFigures& f : m.views) {
            const testing::SplineViewComparison& c = f.comparison;
            if (!f.error.empty()) {
                ++failed;
                if (firstError.empty())
                    firstError = "view " + std::to_string(f.view) + ": " + f.error;
            } else {
                ++done;
                uncached += !f.cached;
                sum += f.totalSeconds;
                worst = std::max(worst, f.totalSeconds);
                tess += f.tessellationSeconds;
                clean += c.method.conflicts == 0;
                tally.add(c);
            }
            if (csv) {
                const auto ms = [&f](const char* phase) {
                    const auto it = f.phaseSeconds.find(phase);
                    return it == f.phaseSeconds.end() ? 0.0 : 1e3 * it->second;
                };
                csv << name << ',' << f.view << ',' << m.samples << ',' << m.preprocessSeconds
                    << ',' << f.cached << ',' << 1e3 * f.totalSeconds << ',' << 1e3 * f.fitSeconds
                    << ',' << 1e3 * f.tessellationSeconds << ',' << ms("patch-contours") << ','
                    << ms("chaining") << ',' << ms("cusps") << ',' << ms("visibility") << ','
                    << c.settled() << ',' << c.crossingsSettled() << ',' << c.method.components
                    << ',' << c.fine.components << ',' << c.coarse.components << ','
                    << c.method.cusps << ',' << c.fine.cusps << ',' << c.coarse.cusps << ','
                    << c.fine.rawCusps << ',' << c.fine.coneCusps << ',' << c.method.tJunctions
                    << ',' << c.fine.crossings << ',' << c.coarse.crossings << ','
                    << c.fine.coneCrossings << ',' << c.fine.loops << ',' << c.method.conflicts
                    << ',' << c.oracleSeconds << ',' << bench::csvEscape(f.error) << '\n';
            }
        }
        const auto ratio = [&](int a, int b) {
            char text[32];
            std::snprintf(text, sizeof text, "%d/%d %3.0f%%", a, b, percent(a, b));
            return std::string(text);
        };
        const double target = timeTarget(name);
        char targetText[16] = "-";
        if (target > 0.0)
            std::snprintf(targetText, sizeof targetText, "%.0f", target);
        std::printf("%-24s %6lld %5lld %3d %8.3f %5d %7d %13s %13s %13s %13s %9.2f %9.2f %7.2f "
                    "%7s\n",
                    name.c_str(), m.layoutFaces, m.cones, m.samples, m.preprocessSeconds, done,
                    tally.settled, ratio(tally.components, tally.settled).c_str(),
                    ratio(tally.cusps, tally.settled).c_str(),
                    ratio(tally.tJunctions, tally.crossingsSettled).c_str(),
                    ratio(clean, done).c_str(), done > 0 ? 1e3 * sum / done : 0.0, 1e3 * worst,
                    done > 0 ? 1e3 * tess / done : 0.0, targetText);
        if (failed > 0)
            std::printf("%-24s %d view(s) failed; first: %s\n", "", failed, firstError.c_str());
        if (uncached > 0)
            std::printf("%-24s %d view(s) re-ran the preprocessing\n", "", uncached);
        std::fflush(stdout);
    }
    return 0;
}
