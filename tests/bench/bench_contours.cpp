// bench_contours: per-view run times and memory of the contour methods on
// procedural meshes of growing size, run through contour::Runner exactly as
// the GUI and the CLI run them. A benchmark: it prints figures and asserts
// nothing.
//
//   bench_contours --faces 10000,100000,1000000 --views 26 --csv bench.csv
#include "BenchSupport.h"
#include "camera/Camera.h"
#include "contours/Methods.h"
#include "mesh/ProceduralShapes.h"
#include "pipeline/Runner.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <malloc.h>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tbb/info.h>
#include <thread>
#include <time.h>
#include <vector>

// Live and peak bytes allocated through operator new (the whole process: the
// algorithms library is linked into this executable). The allocator keeps
// freed pages, so resident-set deltas of a repeated run say little; these
// counters do not depend on that.
namespace heap {
std::atomic<long long> live{0};
std::atomic<long long> peak{0};

void add(void* p) {
    const long long now = live += static_cast<long long>(malloc_usable_size(p));
    long long seen = peak.load(std::memory_order_relaxed);
    while (now > seen && !peak.compare_exchange_weak(seen, now, std::memory_order_relaxed)) {
    }
}
void remove(void* p) {
    if (p)
        live -= static_cast<long long>(malloc_usable_size(p));
}
void* allocate(std::size_t n, std::size_t alignment) {
    void* p = alignment <= alignof(std::max_align_t)
                  ? std::malloc(n ? n : 1)
                  : std::aligned_alloc(alignment, (n + alignment - 1) / alignment * alignment);
    if (!p)
        throw std::bad_alloc();
    add(p);
    return p;
}
void release(void* p) noexcept {
    remove(p);
    std::free(p);
}
void resetPeak() {
    peak = live.load();
}
} // namespace heap

void* operator new(std::size_t n) {
    return heap::allocate(n, alignof(std::max_align_t));
}
void* operator new[](std::size_t n) {
    return heap::allocate(n, alignof(std::max_align_t));
}
void* operator new(std::size_t n, std::align_val_t a) {
    return heap::allocate(n, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t n, std::align_val_t a) {
    return heap::allocate(n, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept {
    heap::release(p);
}
void operator delete[](void* p) noexcept {
    heap::release(p);
}
void operator delete(void* p, std::size_t) noexcept {
    heap::release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    heap::release(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
    heap::release(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
    heap::release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
    heap::release(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
    heap::release(p);
}

using contour::bench::loadAverage;
using contour::bench::statusKb;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the whole process (all threads), in seconds.
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double kbToMib(long long kb) {
    return static_cast<double>(kb) / 1024.0;
}
double bytesToMib(long long bytes) {
    return static_cast<double>(bytes) / (1024.0 * 1024.0);
}

struct Stat {
    double sum = 0.0;
    double max = 0.0;
    double min = 0.0;
    int n = 0;
    void add(double x) {
        min = n == 0 ? x : std::min(min, x);
        max = n == 0 ? x : std::max(max, x);
        sum += x;
        ++n;
    }
    double mean() const { return n ? sum / n : 0.0; }
};

struct ViewResult {
    std::vector<double> phaseSeconds; // Snapshot::phaseSeconds, one per phase
    double checkSeconds = 0.0;        // post-conditions and snapshot copies (Runner::step)
    double totalSeconds = 0.0;        // Runner construction + runToEnd
    double cpuSeconds = 0.0;          // process CPU time over the same span
    double contourEdges = 0.0;
    double segments = 0.0;
    double chains = 0.0;
    long long violations = 0;
};

// "contour edges" for the mesh method, "crossing edges" (edges the
// interpolated contour crosses) for the interpolated one.
double contourEdgeCount(const contour::Snapshot& s) {
    const double edges = s.counter(contour::counters::kContourEdges);
    return edges >= 0 ? edges : s.counter(contour::counters::kCrossingEdges);
}

ViewResult runView(const contour::Method& method, const contour::Snapshot& input,
                   const contour::Camera& camera, const contour::ParameterSet& parameters,
                   std::unique_ptr<contour::Runner>* keep = nullptr) {
    ViewResult r;
    const double cpuStart = processCpuSeconds();
    const auto start = Clock::now();
    auto runner = std::make_unique<contour::Runner>(method, input, camera, parameters);
    double stepSeconds = 0.0;
    while (!runner->atEnd()) {
        const auto stepStart = Clock::now();
        runner->step();
        stepSeconds += secondsSince(stepStart);
    }
    r.totalSeconds = secondsSince(start);
    r.cpuSeconds = processCpuSeconds() - cpuStart;
    double phaseSum = 0.0;
    for (int p = 1; p <= runner->completedPhases(); ++p) {
        const contour::Snapshot& s = runner->snapshot(p);
        r.phaseSeconds.push_back(s.phaseSeconds);
        phaseSum += s.phaseSeconds;
        r.violations += s.invariantViolations();
    }
    r.checkSeconds = stepSeconds - phaseSum;
    const contour::Snapshot& last = runner->current();
    r.contourEdges = contourEdgeCount(last);
    r.chains = last.counter(contour::counters::kContourChains);
    for (const contour::Polyline& line : *last.curves)
        if (line.type == contour::CurveType::Contour)
            r.segments += static_cast<double>(line.segmentCount());
    if (keep)
        *keep = std::move(runner);
    return r;
}

std::string csvEscape(const std::string& s) {
    return s.find_first_of(",\"") == std::string::npos ? s : "\"" + s + "\"";
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"Per-view run times and memory of the mesh and interpolated contour methods on "
                 "procedural meshes (bumpy torus and sphere)."};
    std::vector<long long> faces{10000, 100000, 1000000};
    int views = 26;
    std::string csvPath;
    std::vector<std::string> shapes{"bumpy-torus", "sphere"};
    std::vector<std::string> methods{"mesh", "interpolated"};
    int width = 800, height = 600;
    app.add_option("--faces", faces, "Target triangle counts, comma separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--views", views, "Views of the 26-view protocol to run (the first N)")
        ->check(CLI::Range(1, 26))
        ->capture_default_str();
    app.add_option("--csv", csvPath, "Also write one row per view and phase to this CSV file");
    app.add_option("--shapes", shapes, "Procedural shapes, comma separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--methods", methods, "Contour methods, comma separated")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--width", width, "Viewport width in pixels")->capture_default_str();
    app.add_option("--height", height, "Viewport height in pixels")->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        std::vector<const contour::Method*> selected;
        for (const std::string& name : methods) {
            const contour::Method* m = contour::findMethod(name);
            if (!m)
                throw std::invalid_argument("unknown or unimplemented method \"" + name + "\"");
            selected.push_back(m);
        }
        std::ofstream csv;
        if (!csvPath.empty()) {
            csv.open(csvPath);
            if (!csv)
                throw std::runtime_error("cannot write " + csvPath);
            csv << "shape,requested_faces,triangles,vertices,method,view,phase,seconds,"
                   "contour_edges,segments,chains\n";
        }
        std::printf("bench_contours: %u hardware threads, TBB concurrency %d, load average %s, "
                    "viewport %dx%d, %d views per mesh and method\n",
                    std::thread::hardware_concurrency(), tbb::info::default_concurrency(),
                    loadAverage().c_str(), width, height, views);
        std::printf("Times are per view. phase: Snapshot::phaseSeconds. checks: post-conditions "
                    "(counted in every build) and snapshot copies inside Runner::step. total: "
                    "Runner construction + runToEnd, wall clock; cpu: process CPU time of the "
                    "same span (all threads). The one-off input triangulation is not in the "
                    "per-view times. One unmeasured warm-up view per method and mesh.\n");

        for (const std::string& shape : shapes) {
            for (const long long target : faces) {
                const long long heapStart = heap::live.load();
                auto start = Clock::now();
                auto cage = std::make_shared<const contour::PolygonMesh>(
                    contour::makeProceduralShapeWithFaces(shape, target));
                const double generateSeconds = secondsSince(start);
                start = Clock::now();
                const contour::Snapshot input = contour::makeInputSnapshot(cage);
                const double triangulateSeconds = secondsSince(start);
                const long long heapInput = heap::live.load();
                const contour::TriangleMesh& mesh = *input.mesh;
                const std::vector<contour::Camera> cameras =
                    contour::Camera::views26(mesh.boundingBox(), {width, height});
                const int viewCount = std::min<int>(views, static_cast<int>(cameras.size()));

                std::printf("\n=== %s, %lld faces requested: %d triangles, %d vertices, %d "
                            "edges ===\n",
                            shape.c_str(), target, mesh.faceCount(), mesh.vertexCount(),
                            mesh.edgeCount());
                std::printf("one-off: shape generation %.1f ms, input triangulation "
                            "(makeInputSnapshot) %.1f ms; cage + triangle mesh hold %.1f MiB\n",
                            1e3 * generateSeconds, 1e3 * triangulateSeconds,
                            bytesToMib(heapInput - heapStart));

                for (const contour::Method* method : selected) {
                    const contour::ParameterSet parameters =
                        contour::ParameterSet::defaults(method->parameters);
                    runView(*method, input, cameras[0], parameters); // warm-up

                    // The first measured view also measures memory: the heap
                    // peak during the run and what the finished run keeps.
                    std::vector<ViewResult> results;
                    const long long heapBefore = heap::live.load();
                    heap::resetPeak();
                    long long heapKept = 0;
                    {
                        std::unique_ptr<contour::Runner> held;
                        results.push_back(runView(*method, input, cameras[0], parameters, &held));
                        heapKept = heap::live.load() - heapBefore;
                    }
                    const long long heapPeak = heap::peak.load() - heapBefore;
                    for (int v = 1; v < viewCount; ++v)
                        results.push_back(runView(*method, input, cameras[v], parameters));

                    const size_t phaseCount = method->phases.size();
                    std::vector<Stat> phase(phaseCount);
                    Stat checks, total, cpu, edges, segments, chains;
                    long long violations = 0;
                    for (size_t v = 0; v < results.size(); ++v) {
                        const ViewResult& r = results[v];
                        for (size_t p = 0; p < phaseCount; ++p)
                            phase[p].add(r.phaseSeconds[p]);
                        checks.add(r.checkSeconds);
                        total.add(r.totalSeconds);
                        cpu.add(r.cpuSeconds);
                        edges.add(r.contourEdges);
                        segments.add(r.segments);
                        chains.add(r.chains);
                        violations += r.violations;
                        if (csv) {
                            const std::string prefix =
                                csvEscape(shape) + "," + std::to_string(target) + "," +
                                std::to_string(mesh.faceCount()) + "," +
                                std::to_string(mesh.vertexCount()) + "," + csvEscape(method->name) +
                                "," + std::to_string(v) + ",";
                            const auto count = [](double x) {
                                return std::to_string(std::llround(x));
                            };
                            const std::string counts = "," + count(r.contourEdges) + "," +
                                                       count(r.segments) + "," + count(r.chains) +
                                                       "\n";
                            for (size_t p = 0; p < phaseCount; ++p)
                                csv << prefix << method->phases[p].name << "," << r.phaseSeconds[p]
                                    << counts;
                            csv << prefix << "checks," << r.checkSeconds << counts;
                            csv << prefix << "total," << r.totalSeconds << counts;
                            csv << prefix << "cpu," << r.cpuSeconds << counts;
                        }
                    }
                    std::printf("--- method %s, %zu views\n", method->name.c_str(), results.size());
                    std::printf("    %-26s %9s %9s\n", "per view", "mean ms", "max ms");
                    for (size_t p = 0; p < phaseCount; ++p)
                        std::printf("    %-26s %9.2f %9.2f\n",
                                    ("phase " + method->phases[p].name).c_str(),
                                    1e3 * phase[p].mean(), 1e3 * phase[p].max);
                    std::printf("    %-26s %9.2f %9.2f\n", "post-condition checks",
                                1e3 * checks.mean(), 1e3 * checks.max);
                    std::printf("    %-26s %9.2f %9.2f\n", "total (wall)", 1e3 * total.mean(),
                                1e3 * total.max);
                    std::printf("    %-26s %9.2f %9.2f\n", "total (cpu, all threads)",
                                1e3 * cpu.mean(), 1e3 * cpu.max);
                    std::printf("    %-26s %9s %9s %9s\n", "per view", "mean", "min", "max");
                    std::printf("    %-26s %9.0f %9.0f %9.0f\n",
                                method->name == "mesh" ? "contour edges" : "crossing edges",
                                edges.mean(), edges.min, edges.max);
                    std::printf("    %-26s %9.0f %9.0f %9.0f\n", "contour segments",
                                segments.mean(), segments.min, segments.max);
                    std::printf("    %-26s %9.0f %9.0f %9.0f\n", "contour chains", chains.mean(),
                                chains.min, chains.max);
                    std::printf("    memory of one run: heap peak +%.1f MiB over %.1f MiB before "
                                "it; its snapshots keep +%.1f MiB; process VmHWM so far %.1f "
                                "MiB\n",
                                bytesToMib(heapPeak), bytesToMib(heapBefore), bytesToMib(heapKept),
                                kbToMib(statusKb("VmHWM")));
                    if (violations > 0)
                        std::printf("    post-condition violations over all views: %lld\n",
                                    violations);
                }
            }
        }
        std::printf("\nprocess peak resident memory (VmHWM): %.1f MiB; load average %s\n",
                    kbToMib(statusKb("VmHWM")), loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_contours: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
