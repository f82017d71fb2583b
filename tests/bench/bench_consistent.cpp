// bench_consistent: the consistent-contours method (Bénard 2014) run to the
// end on the meshes ConTesse was measured on, from the views of the 26-view
// protocol (Camera::views26), with one CSV row per mesh in the columns of
// ConTesse's published statistics (../shared/bench/contesse-0927-stats.csv)
// where they make sense for us. A benchmark: it prints figures and asserts
// nothing.
//
//   bench_consistent [--meshes-dir DIR] [--mesh NAME]... [--views N]
//                    [--out stats.csv] [--threads N] [--counters counters.csv]
//                    [--shape NAME:RES]... [--set PARAM=VALUE]... [--classify]
//
// --shape runs a procedural shape (mesh/ProceduralShapes.h, e.g. torus:12,
// bumpy-torus:12, sphere:8 as in test_consistent_optimization) instead of
// (or, with --mesh, besides) the files. --set overrides a method parameter
// (compare a change switched by a parameter on the same tree). --classify
// sorts the final inconsistent faces by where they lie (see classify()).
//
// Columns (means are over the views whose run completed, unless said):
//   Input                 mesh name (file name without extension)
//   Success count         views whose run completed: every phase ran without
//                         an exception. NOT ConTesse's "success", which is
//                         its own (no failure case 1-5 after its retries).
//   Input count           views run
//   Input faces           the initialization phase's "initial faces" counter:
//                         triangles of the domain after one subdivision, each
//                         quad split in two (ConTesse counts its own faces).
//   Output faces          faces of the final mesh ("faces" counter)
//   Runtime               seconds per view, wall clock of Runner construction
//                         and every step (phases, post-condition checks and
//                         snapshot copies), mean over completed views
//   Phases s              mean sum of Snapshot::phaseSeconds (the method's
//                         own work, comparable to a run without checks)
//   Checks s              Runtime - Phases s: post-condition checks (counted
//                         in every build), snapshot copies, Runner set-up
//   Zero violation count  completed views with 0 post-condition violations
//   Consistent count      completed views whose final mesh has 0 inconsistent
//                         faces (Definition 2) -- the paper's goal
//   Max inconsistent %    max over completed views of inconsistent / faces
//   Violations            post-condition violations summed over all views
//   Peak RSS MiB          VmHWM while this mesh ran (reset per mesh through
//                         /proc/self/clear_refs when the kernel allows it,
//                         else the process's peak so far)
//   <phase> s             mean Snapshot::phaseSeconds, one per phase of the
//                         method in its order (names read from the Method)
//   <phase> inconsistent  mean "inconsistent faces" counter after that phase
//   ConTesse input        the row of the published CSV matched (exact name,
//                         else a unique "NAME_..." or prefix match), empty
//                         when none
//   ConTesse runtime      its "Runtime" (seconds per view)
// --counters writes, per view and phase, every counter but the times, the
// post-condition violations and a digest of the published mesh (positions'
// bits and faces): two builds that must give the same results (a speed-up)
// are compared with diff.
// Case 1-5 and Trial count of the published file are ConTesse's failure
// categories and retries: they have no counterpart here.
#include "BenchSupport.h"
#include "camera/Camera.h"
#include "contours/Methods.h"
#include "pipeline/FieldNames.h"
#include "pipeline/Runner.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
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
#include <tbb/info.h>
#include <thread>
#include <vector>

using namespace contour;
using namespace contour::bench;

namespace {

using Clock = std::chrono::steady_clock;

const std::vector<std::string> kDefaultMeshes{"spot_control_mesh",   "bob_controlmesh", "bigguy",
                                              "spot_quadrangulated", "bob_quad",        "fertility",
                                              "killeroo_small"};

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct ViewResult {
    bool completed = false;
    std::string error; // the exception of the phase that failed
    int completedPhases = 0;
    double totalSeconds = 0.0;
    std::vector<double> phaseSeconds;      // per completed phase
    std::vector<double> phaseInconsistent; // "inconsistent faces" after it, -1 if absent
    double initialFaces = -1.0, faces = -1.0, inconsistent = -1.0;
    long long violations = 0;
    std::vector<std::string> violationExamples; // "phase: check: first example"
    std::vector<long long> classes;             // classify() of the last snapshot
};

// --classify: the final inconsistent faces sorted by where they lie, from the
// published fields, first matching class in this order:
//   inside fan      a corner is a cusp vertex (Fig. 18e: the faces around a
//                   cusp on its inside side, or a radial face at the cusp)
//   cusp radial end a corner is the far end of a cusp's radial edge
//   touching C      a corner is a (non-cusp) C vertex
//   16f pair        two corners are far ends of radial edges (Fig. 16f)
//   one radial end  one corner is the far end of a radial edge
//   other           none of these (away from the contour)
const char* const kClassNames[] = {"inside fan", "cusp radial end", "touching C",
                                   "16f pair",   "one radial end",  "other"};
constexpr int kClassCount = 6;

std::vector<long long> classify(const Snapshot& s) {
    std::vector<long long> out(kClassCount, 0);
    const Field* consistentField = s.field(fields::kConsistent);
    const Field* labelField = s.field(fields::kLabel);
    const Field* cuspField = s.field(fields::kCusp);
    const Field* radialField = s.field(fields::kRadialEdge);
    if (!s.mesh || !consistentField || !labelField || !cuspField || !radialField)
        return out;
    const TriangleMesh& mesh = *s.mesh;
    const auto& consistent = *consistentField->labels();
    const auto& label = *labelField->labels();
    const auto& cusp = *cuspField->labels();
    const auto& radial = *radialField->labels();
    // Far ends of radial edges (the non-C end), and those of a cusp's.
    std::vector<char> end(static_cast<size_t>(mesh.vertexCount()), 0),
        cuspEnd(static_cast<size_t>(mesh.vertexCount()), 0);
    for (Index e = 0; e < mesh.edgeCount(); ++e) {
        if (!radial[static_cast<size_t>(e)])
            continue;
        const Index h = mesh.edgeHalfedge(e);
        Index p = mesh.from(h), r = mesh.to(h);
        if (label[static_cast<size_t>(r)] == 0)
            std::swap(p, r);
        end[static_cast<size_t>(r)] = 1;
        if (cusp[static_cast<size_t>(p)])
            cuspEnd[static_cast<size_t>(r)] = 1;
    }
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        if (consistent[static_cast<size_t>(f)])
            continue;
        int hasCusp = 0, hasCuspEnd = 0, hasC = 0, ends = 0;
        for (Index v : mesh.triangle(f)) {
            const auto i = static_cast<size_t>(v);
            hasCusp += cusp[i];
            hasCuspEnd += cuspEnd[i];
            hasC += label[i] == 0;
            ends += end[i];
        }
        const int k = hasCusp ? 0 : hasCuspEnd ? 1 : hasC ? 2 : ends >= 2 ? 3 : ends ? 4 : 5;
        ++out[static_cast<size_t>(k)];
    }
    return out;
}
bool gClassify = false;

// FNV-1a over the mesh's positions (bits) and faces: equal digests mean the
// same mesh, to the bit.
std::uint64_t meshDigest(const TriangleMesh& mesh) {
    std::uint64_t h = 1469598103934665603ull;
    const auto mix = [&h](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i)
            h = (h ^ p[i]) * 1099511628211ull;
    };
    for (Index v = 0; v < mesh.vertexCount(); ++v)
        mix(mesh.position(v).data(), 3 * sizeof(double));
    for (Index f = 0; f < mesh.faceCount(); ++f)
        mix(mesh.triangle(f).data(), 3 * sizeof(Index));
    return h;
}

// Where --counters writes (null: not asked), and the mesh being run.
std::ofstream* gCounters = nullptr;
std::string gMeshName;

void writeCounters(int view, const Snapshot& s) {
    std::ostream& out = *gCounters;
    const std::string prefix = gMeshName + "," + std::to_string(view) + "," + s.phaseName + ",";
    for (const Counter& c : s.counters) {
        // Times differ from run to run.
        if (c.name.find("second") != std::string::npos || c.name.find("time") != std::string::npos)
            continue;
        char value[64];
        std::snprintf(value, sizeof value, "%.17g", c.value);
        out << prefix << csvEscape(c.name) << "," << value << "\n";
    }
    for (const InvariantCheck& c : s.invariants)
        out << prefix << csvEscape("violations: " + c.name) << "," << c.violations << "\n";
    if (s.mesh)
        out << prefix << "mesh digest," << meshDigest(*s.mesh) << "\n";
}

ViewResult runView(const Method& method, const Snapshot& input, const Camera& camera,
                   const ParameterSet& parameters, int view) {
    ViewResult r;
    const auto start = Clock::now();
    Runner runner(method, input, camera, parameters);
    try {
        while (!runner.atEnd())
            runner.step();
        r.completed = true;
    } catch (const std::exception& e) {
        r.error = e.what();
    }
    r.totalSeconds = secondsSince(start);
    r.completedPhases = runner.completedPhases();
    for (int p = 1; p <= runner.completedPhases(); ++p) {
        const Snapshot& s = runner.snapshot(p);
        if (gCounters)
            writeCounters(view, s);
        r.phaseSeconds.push_back(s.phaseSeconds);
        r.phaseInconsistent.push_back(s.counter(counters::kInconsistentFaces));
        r.violations += s.invariantViolations();
        for (const InvariantCheck& c : s.invariants)
            if (c.violations > 0)
                r.violationExamples.push_back(s.phaseName + ": " + c.name + " (" +
                                              std::to_string(c.violations) + "x), first " +
                                              c.firstExample);
        if (r.initialFaces < 0.0)
            r.initialFaces = s.counter(counters::kInitialFaces);
    }
    const Snapshot& last = runner.current();
    r.faces = last.counter(counters::kFaces, last.mesh ? last.mesh->faceCount() : -1.0);
    r.inconsistent = last.counter(counters::kInconsistentFaces);
    if (gClassify)
        r.classes = classify(last);
    return r;
}

struct Mean {
    double sum = 0.0;
    int n = 0;
    void add(double x) {
        if (x >= 0.0 && std::isfinite(x)) {
            sum += x;
            ++n;
        }
    }
    std::optional<double> value() const {
        return n ? std::optional<double>(sum / n) : std::nullopt;
    }
};

std::string cell(std::optional<double> x, const char* format = "%.6g") {
    if (!x)
        return {};
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, *x);
    return buffer;
}

struct MeshSummary {
    std::string name;
    int views = 0, completed = 0, zeroViolation = 0, consistent = 0;
    int aboveTarget = 0; // completed views above 0.05 % inconsistent faces
    long long violations = 0;
    std::vector<long long> classes = std::vector<long long>(kClassCount, 0);
    Mean inputFaces, outputFaces, runtime, phases, checks;
    std::vector<Mean> phaseSeconds, phaseInconsistent;
    std::optional<double> maxInconsistentPercent;
    double peakRssMib = -1.0;
    bool peakIsPerMesh = false;
    std::optional<std::string> published;
    std::optional<double> publishedRuntime;
};

std::vector<std::string> csvHeader(const Method& method) {
    std::vector<std::string> h{"Input",
                               "Success count",
                               "Input count",
                               "Input faces",
                               "Output faces",
                               "Runtime",
                               "Phases s",
                               "Checks s",
                               "Zero violation count",
                               "Consistent count",
                               "Max inconsistent %",
                               "Violations",
                               "Peak RSS MiB"};
    for (const Phase& phase : method.phases)
        h.push_back(phase.name + " s");
    for (const Phase& phase : method.phases)
        h.push_back(phase.name + " inconsistent");
    h.push_back("ConTesse input");
    h.push_back("ConTesse runtime");
    return h;
}

std::vector<std::string> csvRow(const MeshSummary& m) {
    std::vector<std::string> row{
        m.name,
        std::to_string(m.completed),
        std::to_string(m.views),
        cell(m.inputFaces.value(), "%.2f"),
        cell(m.outputFaces.value(), "%.2f"),
        cell(m.runtime.value()),
        cell(m.phases.value()),
        cell(m.checks.value()),
        std::to_string(m.zeroViolation),
        std::to_string(m.consistent),
        cell(m.maxInconsistentPercent, "%.4f"),
        std::to_string(m.violations),
        cell(m.peakRssMib >= 0 ? std::optional(m.peakRssMib) : std::nullopt, "%.1f")};
    for (const Mean& s : m.phaseSeconds)
        row.push_back(cell(s.value()));
    for (const Mean& s : m.phaseInconsistent)
        row.push_back(cell(s.value(), "%.2f"));
    row.push_back(m.published.value_or(""));
    row.push_back(cell(m.publishedRuntime));
    return row;
}

std::string joinCsv(const std::vector<std::string>& cells) {
    std::string line;
    for (size_t i = 0; i < cells.size(); ++i)
        line += (i ? "," : "") + csvEscape(cells[i]);
    return line + "\n";
}

MeshSummary runMesh(const Method& method, const ParameterSet& parameters, const std::string& name,
                    const std::shared_ptr<const PolygonMesh>& cage, int views) {
    MeshSummary m;
    m.name = name;
    m.phaseSeconds.resize(method.phases.size());
    m.phaseInconsistent.resize(method.phases.size());
    m.peakIsPerMesh = resetPeakRss();
    const auto start = Clock::now();
    const Snapshot input = makeInputSnapshot(cage);
    const std::vector<Camera> cameras = Camera::views26(input.mesh->boundingBox(), Viewport{});
    m.views = std::min<int>(views, static_cast<int>(cameras.size()));
    std::printf("\n=== %s: %d cage vertices, %d cage faces, %d views ===\n", name.c_str(),
                cage->vertexCount(), cage->faceCount(), m.views);
    std::fflush(stdout);
    for (int v = 0; v < m.views; ++v) {
        gMeshName = name;
        const ViewResult r = runView(method, input, cameras[static_cast<size_t>(v)], parameters, v);
        m.violations += r.violations;
        for (size_t p = 0; p < r.phaseSeconds.size(); ++p) {
            m.phaseSeconds[p].add(r.phaseSeconds[p]);
            m.phaseInconsistent[p].add(r.phaseInconsistent[p]);
        }
        const double percent =
            r.faces > 0 && r.inconsistent >= 0 ? 100.0 * r.inconsistent / r.faces : -1.0;
        if (r.completed) {
            ++m.completed;
            m.zeroViolation += r.violations == 0;
            m.consistent += r.inconsistent == 0.0;
            m.inputFaces.add(r.initialFaces);
            m.outputFaces.add(r.faces);
            m.runtime.add(r.totalSeconds);
            double phaseSum = 0.0;
            for (const double seconds : r.phaseSeconds)
                phaseSum += seconds;
            m.phases.add(phaseSum);
            m.checks.add(r.totalSeconds - phaseSum);
            if (percent >= 0)
                m.maxInconsistentPercent =
                    std::max(m.maxInconsistentPercent.value_or(0.0), percent);
            m.aboveTarget += percent > 0.05;
        }
        for (size_t k = 0; k < r.classes.size(); ++k)
            m.classes[k] += r.classes[k];
        std::printf("  view %2d: %s, %6.2f s, %8.0f faces, %6.0f inconsistent (%.3f%%), %lld "
                    "violations%s%s\n",
                    v, r.completed ? "completed" : "FAILED", r.totalSeconds, r.faces,
                    r.inconsistent, percent, r.violations, r.completed ? "" : ": ",
                    r.error.c_str());
        for (const std::string& example : r.violationExamples)
            std::printf("    violated after %s\n", example.c_str());
        if (!r.classes.empty()) {
            std::printf("    classes:");
            for (int k = 0; k < kClassCount; ++k)
                std::printf(" %s %lld%s", kClassNames[k], r.classes[static_cast<size_t>(k)],
                            k + 1 < kClassCount ? "," : "\n");
        }
        std::fflush(stdout);
    }
    m.peakRssMib = static_cast<double>(statusKb("VmHWM")) / 1024.0;
    std::printf("  %s: %.1f s for %d views, peak RSS %.1f MiB%s; %d views above 0.05 %% "
                "inconsistent\n",
                name.c_str(), secondsSince(start), m.views, m.peakRssMib,
                m.peakIsPerMesh ? "" : " (process peak so far: clear_refs refused)", m.aboveTarget);
    if (gClassify) {
        std::printf("  %s, final inconsistent faces over %d views:", name.c_str(), m.views);
        for (int k = 0; k < kClassCount; ++k)
            std::printf(" %s %lld%s", kClassNames[k], m.classes[static_cast<size_t>(k)],
                        k + 1 < kClassCount ? "," : "\n");
    }
    return m;
}

void printTable(const Method& method, const std::vector<MeshSummary>& meshes) {
    std::printf("\n%-20s %5s %5s %5s %5s %10s %10s %9s %9s %9s %9s %8s %7s %-20s %9s\n", "mesh",
                "views", "done", "0viol", "0inc", "in faces", "out faces", "s/view", "phases s",
                "checks s", "max inc%", "viol", "RSS MiB", "ConTesse row", "ConT s/v");
    for (const MeshSummary& m : meshes)
        std::printf("%-20s %5d %5d %5d %5d %10s %10s %9s %9s %9s %9s %8lld %7.0f %-20s %9s\n",
                    m.name.c_str(), m.views, m.completed, m.zeroViolation, m.consistent,
                    cell(m.inputFaces.value(), "%.0f").c_str(),
                    cell(m.outputFaces.value(), "%.0f").c_str(),
                    cell(m.runtime.value(), "%.3f").c_str(), cell(m.phases.value(), "%.3f").c_str(),
                    cell(m.checks.value(), "%.3f").c_str(),
                    cell(m.maxInconsistentPercent, "%.3f").c_str(), m.violations, m.peakRssMib,
                    m.published.value_or("-").c_str(), cell(m.publishedRuntime, "%.3f").c_str());

    std::printf("\nper phase, mean seconds per view / mean inconsistent faces after it\n%-20s",
                "mesh");
    for (const Phase& phase : method.phases)
        std::printf(" %21s", phase.name.c_str());
    std::printf("\n");
    for (const MeshSummary& m : meshes) {
        std::printf("%-20s", m.name.c_str());
        for (size_t p = 0; p < method.phases.size(); ++p) {
            const std::string text = cell(m.phaseSeconds[p].value(), "%.3f") + " / " +
                                     cell(m.phaseInconsistent[p].value(), "%.1f");
            std::printf(" %21s", text.c_str());
        }
        std::printf("\n");
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"The consistent-contours method run to the end on ConTesse's test meshes from "
                 "the 26-view protocol, with a CSV in the columns of ConTesse's published "
                 "statistics."};
    std::string meshesDir = CONTOUR_SHARED_DIR "/meshes";
    std::string publishedPath = CONTOUR_SHARED_DIR "/bench/contesse-0927-stats.csv";
    std::vector<std::string> meshes;
    int views = 26;
    int threads = 0;
    std::string outPath, countersPath;
    std::vector<std::string> shapes, settings;
    app.add_option("--meshes-dir", meshesDir, "Folder of the meshes")->capture_default_str();
    app.add_option("--mesh", meshes,
                   "Mesh name (file name without extension), repeat to choose several; default: "
                   "spot_control_mesh bob_controlmesh bigguy spot_quadrangulated bob_quad "
                   "fertility killeroo_small");
    app.add_option("--views", views, "Views of the 26-view protocol to run (the first N)")
        ->check(CLI::Range(1, 26))
        ->capture_default_str();
    app.add_option("--out", outPath, "Write the per-mesh statistics to this CSV file");
    app.add_option("--threads", threads, "TBB worker threads (0: TBB's default)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    app.add_option("--counters", countersPath,
                   "Write every phase's counters (times excepted), post-condition violations "
                   "and mesh digest per view to this CSV file (for diffing two builds)");
    app.add_option("--published", publishedPath, "ConTesse's published statistics (CSV)")
        ->capture_default_str();
    app.add_option("--shape", shapes,
                   "Procedural shape NAME:RESOLUTION (mesh/ProceduralShapes.h), e.g. torus:12; "
                   "repeat for several; without --mesh only the shapes run");
    app.add_option("--set", settings,
                   "Method parameter NAME=VALUE overriding its default; repeat for several");
    app.add_flag("--classify", gClassify,
                 "Sort the final inconsistent faces by where they lie (inside fan, cusp radial "
                 "end, touching C, 16f pair, one radial end, other) per view and per mesh");
    CLI11_PARSE(app, argc, argv);
    if (meshes.empty() && shapes.empty())
        meshes = kDefaultMeshes;

    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));

    try {
        const Method* method = findMethod("consistent");
        if (!method)
            throw std::runtime_error("the consistent method is not registered");
        const ParameterSet parameters = parametersWithSettings(*method, settings);
        for (const std::string& setting : settings)
            std::printf("bench_consistent: %s\n", setting.c_str());
        const std::map<std::string, double> published = readPublished(publishedPath);
        if (published.empty())
            std::printf("bench_consistent: no published statistics read from %s; the ConTesse "
                        "columns stay empty\n",
                        publishedPath.c_str());

        std::ofstream counters;
        if (!countersPath.empty()) {
            counters.open(countersPath);
            if (!counters)
                throw std::runtime_error("cannot write " + countersPath);
            counters << "mesh,view,phase,counter,value\n";
            gCounters = &counters;
        }
        std::ofstream csv;
        if (!outPath.empty()) {
            csv.open(outPath);
            if (!csv)
                throw std::runtime_error("cannot write " + outPath);
            csv << joinCsv(csvHeader(*method)) << std::flush;
        }
        std::printf("bench_consistent: %u hardware threads, TBB threads %d, load average %s, "
                    "viewport 800x600, %d views per mesh\nphases:",
                    std::thread::hardware_concurrency(),
                    threads > 0 ? threads : tbb::info::default_concurrency(), loadAverage().c_str(),
                    views);
        for (const Phase& phase : method->phases)
            std::printf(" %s", phase.name.c_str());
        std::printf("\n");

        std::vector<MeshSummary> results;
        std::vector<std::string> inputs = meshes;
        for (const std::string& shape : shapes)
            inputs.push_back("shape:" + shape);
        for (const std::string& name : inputs) {
            // A mesh the reader refuses (Hexagon, Pentagon: zero-area faces)
            // is skipped with the reason, like a run that fails.
            MeshSummary m;
            try {
                const std::shared_ptr<const PolygonMesh> cage = loadBenchInput(name, meshesDir);
                if (!cage) {
                    std::printf("\nskipping %s: no %s/%s.{obj,off,ply}\n", name.c_str(),
                                meshesDir.c_str(), name.c_str());
                    continue;
                }
                m = runMesh(*method, parameters, name, cage, views);
            } catch (const std::exception& e) {
                std::printf("\nskipping %s: %s\n", name.c_str(), e.what());
                continue;
            }
            m.published = matchPublished(published, name);
            if (m.published)
                m.publishedRuntime = published.at(*m.published);
            if (csv)
                csv << joinCsv(csvRow(m)) << std::flush;
            results.push_back(std::move(m));
        }
        printTable(*method, results);
        std::printf("\ndone: success = every phase ran (not ConTesse's success); 0viol = "
                    "completed with 0 post-condition violations; 0inc = completed with 0 "
                    "inconsistent faces; load average %s\n",
                    loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_consistent: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
