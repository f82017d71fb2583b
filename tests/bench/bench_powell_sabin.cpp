// bench_powell_sabin: the Powell-Sabin method's preprocessing (cones,
// conformal map, layout, patches, factorization; Capouellez et al. 2023 §5)
// and its per-view fit (§3, §5.3) on meshes of ../shared/meshes, 26 views
// each. A benchmark: it prints figures and asserts nothing.
//
//   bench_powell_sabin [--meshes spot_control_mesh,fertility] [--all] [--views 26]
//                      [--csv out.csv]
//
// Per mesh: the preprocessing wall time (the sum of its phases, run once),
// the process's peak resident memory while it ran, then over the views the
// mean and largest fit time (back-substitution for x, y, z and the patches'
// Bezier points; the tessellation for drawing is timed apart), and the
// largest max and RMS distance of the fit to the input vertices relative to
// the bounding-box diagonal. The paper's preprocessing figures: fertility
// 4.4 s, killeroo 3 s (§7, on a 2.7 GHz laptop).
#include "BenchSupport.h"
#include "contours/Methods.h"
#include "pipeline/CounterNames.h"
#include "pipeline/Runner.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace contour;

namespace {

using Clock = std::chrono::steady_clock;

struct MeshFigures {
    std::string name;
    std::string error;
    long long faces = 0, layoutFaces = 0, cones = 0;
    double preprocessSeconds = 0.0;
    std::map<std::string, double> phaseSeconds;
    long long peakKb = -1;
    double meanFit = 0.0, maxFit = 0.0, meanTessellation = 0.0;
    double maxDistance = 0.0, rmsDistance = 0.0;
    int views = 0;
};

MeshFigures measure(const std::string& name, const std::filesystem::path& path, int viewCount) {
    MeshFigures m;
    m.name = name;
    const Method& method = *findMethod("powell-sabin");
    try {
        bench::resetPeakRss();
        auto cage = std::make_shared<const PolygonMesh>(readMesh(path.string()));
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        const ParameterSet parameters = ParameterSet::defaults(method.parameters);
        {
            Runner first(method, makeInputSnapshot(cage), views.front(), parameters);
            m.faces = first.current().mesh->faceCount();
            const auto start = Clock::now();
            while (first.current().phaseName != "factorization" && first.step()) {
            }
            m.preprocessSeconds = std::chrono::duration<double>(Clock::now() - start).count();
            for (const Snapshot& s : first.snapshots())
                if (s.phaseIndex >= 0)
                    m.phaseSeconds[s.phaseName] = s.phaseSeconds;
            m.peakKb = bench::statusKb("VmHWM");
            m.layoutFaces = first.current().mesh->faceCount();
            m.cones = static_cast<long long>(first.snapshot(1).counter(counters::kCones));
        }
        const int n = std::min<int>(viewCount, static_cast<int>(views.size()));
        for (int v = 0; v < n; ++v) {
            Runner r(method, makeInputSnapshot(cage), views[v], parameters);
            while (r.current().phaseName != "fit" && r.step()) {
            }
            const Snapshot& fit = r.current();
            const double seconds = fit.counter(counters::kStageSeconds);
            m.meanFit += seconds / n;
            m.maxFit = std::max(m.maxFit, seconds);
            m.meanTessellation += (fit.phaseSeconds - seconds) / n;
            m.maxDistance = std::max(m.maxDistance, fit.counter(counters::kFitMaxDistance));
            m.rmsDistance = std::max(m.rmsDistance, fit.counter(counters::kFitRmsDistance));
            ++m.views;
        }
    } catch (const std::exception& e) {
        m.error = e.what();
    }
    return m;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("Powell-Sabin preprocessing and per-view fit on the shared meshes");
    std::string meshList = "spot_control_mesh,bob_controlmesh,fertility,killeroo_small";
    std::string meshDir = CONTOUR_SHARED_DIR "/meshes";
    std::string csvPath;
    int views = 26;
    bool all = false;
    app.add_option("--meshes", meshList, "Comma-separated mesh names (without extension)");
    app.add_option("--mesh-dir", meshDir, "Folder of the meshes");
    app.add_option("--views", views, "Views of the 26-view protocol per mesh")
        ->check(CLI::Range(1, 26));
    app.add_option("--csv", csvPath, "Also write the table as CSV");
    app.add_flag("--all", all, "Every mesh of the folder");
    CLI11_PARSE(app, argc, argv);

    std::vector<std::string> names;
    if (all) {
        for (const auto& entry : std::filesystem::directory_iterator(meshDir))
            if (entry.path().extension() == ".obj")
                names.push_back(entry.path().stem().string());
        std::sort(names.begin(), names.end());
    } else {
        std::stringstream list(meshList);
        for (std::string name; std::getline(list, name, ',');)
            names.push_back(name);
    }
    std::printf("load average: %s\n", bench::loadAverage().c_str());
    std::printf("%-24s %7s %7s %5s %9s %9s %9s %9s %9s %9s %8s %10s %10s\n", "mesh", "faces",
                "layout", "cones", "prep s", "cones s", "map s", "layout s", "factor s", "peak MiB",
                "fit ms", "max fit ms", "max dist");
    std::ofstream csv;
    if (!csvPath.empty()) {
        csv.open(csvPath);
        csv << "mesh,faces,layout_faces,cones,preprocessing_s,cones_s,conformal_map_s,layout_s,"
               "patches_s,factorization_s,peak_rss_mib,views,mean_fit_ms,max_fit_ms,"
               "mean_tessellation_ms,max_distance_rel,max_rms_distance_rel,error\n";
    }
    for (const std::string& name : names) {
        const auto path = bench::findMeshFile(meshDir, name);
        if (!path) {
            std::printf("%-24s (not found)\n", name.c_str());
            continue;
        }
        const MeshFigures m = measure(name, *path, views);
        const auto phase = [&m](const char* p) {
            const auto it = m.phaseSeconds.find(p);
            return it == m.phaseSeconds.end() ? 0.0 : it->second;
        };
        if (!m.error.empty())
            std::printf("%-24s error: %s\n", name.c_str(), m.error.c_str());
        else
            std::printf("%-24s %7lld %7lld %5lld %9.3f %9.3f %9.3f %9.3f %9.3f %9.1f %8.2f %10.2f "
                        "%10.2e\n",
                        name.c_str(), m.faces, m.layoutFaces, m.cones, m.preprocessSeconds,
                        phase("cones"), phase("conformal-map"), phase("layout"),
                        phase("factorization"), m.peakKb / 1024.0, 1e3 * m.meanFit, 1e3 * m.maxFit,
                        m.maxDistance);
        if (csv) {
            std::string error = m.error;
            std::replace(error.begin(), error.end(), ',', ';');
            csv << name << ',' << m.faces << ',' << m.layoutFaces << ',' << m.cones << ','
                << m.preprocessSeconds << ',' << phase("cones") << ',' << phase("conformal-map")
                << ',' << phase("layout") << ',' << phase("patches") << ','
                << phase("factorization") << ',' << m.peakKb / 1024.0 << ',' << m.views << ','
                << 1e3 * m.meanFit << ',' << 1e3 * m.maxFit << ',' << 1e3 * m.meanTessellation
                << ',' << m.maxDistance << ',' << m.rmsDistance << ",\"" << error << "\"\n";
        }
    }
    return 0;
}
