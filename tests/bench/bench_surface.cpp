// bench_surface: limit-surface evaluations per second (position plus first
// and second derivatives) of the Catmull-Clark and Loop surfaces, on one
// thread and on all cores, and their set-up time (topology refiner, adaptive
// patch table, domain). A benchmark: it prints figures and asserts nothing.
//
//   bench_surface --evaluations 2000000 --repeats 3 --isolation 8 [--ordered]
//
// Preimages are uniformly random over the domain (the worst case for the
// caches: every evaluation gathers control points from a random patch), or
// sorted by face with --ordered (as tessellation and contour extraction
// visit them). Besides wall-clock rates, the one-thread rate per second of
// process CPU time is printed: it stays meaningful when other processes
// share the cores.
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "surface/SubdivisionSurface.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <time.h>
#include <vector>

using namespace contour;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The same shape as triangles only (Loop needs them).
PolygonMesh triangulated(const PolygonMesh& mesh) {
    const TriangleMesh triangles = mesh.triangulate();
    PolygonMesh out;
    out.positions.assign(triangles.positions().begin(), triangles.positions().end());
    for (const Triangle& t : triangles.triangles())
        out.addFace({t[0], t[1], t[2]});
    return out;
}

struct Case {
    std::string name;
    SurfaceKind kind;
    PolygonMesh cage;
};

// Uniformly random preimages over the domain faces (fixed seed).
std::vector<Preimage> randomPreimages(const SmoothSurface& s, size_t count) {
    std::mt19937 rng(1234);
    std::uniform_int_distribution<Index> face(0, s.domain().faceCount() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Preimage> out(count);
    for (Preimage& p : out) {
        p.face = face(rng);
        p.u = unit(rng);
        p.v = unit(rng);
        if (!s.isQuad(p.face) && p.u + p.v > 1.0) {
            p.u = 1.0 - p.u;
            p.v = 1.0 - p.v;
        }
    }
    return out;
}

// Best of `repeats` batch evaluations, in evaluations per second of wall
// clock and of process CPU time.
struct Rate {
    double wall = 0.0, cpu = 0.0;
};
Rate throughput(const SmoothSurface& s, const std::vector<Preimage>& preimages,
                std::vector<SurfacePoint>& out, int repeats) {
    double bestWall = 1e300, bestCpu = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto start = Clock::now();
        const double cpuStart = processCpuSeconds();
        s.evaluate(preimages, out);
        bestCpu = std::min(bestCpu, processCpuSeconds() - cpuStart);
        bestWall = std::min(bestWall, secondsSince(start));
    }
    const auto n = static_cast<double>(preimages.size());
    return {n / bestWall, n / bestCpu};
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("Limit-surface evaluation throughput of the Catmull-Clark and Loop surfaces");
    size_t evaluations = 2000000;
    int repeats = 3;
    int isolation = 8;
    int torusResolution = 48;
    std::string meshDir = CONTOUR_SHARED_DIR "/meshes";
    bool ordered = false;
    app.add_option("--evaluations", evaluations, "Preimages per timed batch")
        ->check(CLI::Range(size_t(1000), size_t(100000000)));
    app.add_option("--repeats", repeats, "Timed batches per figure (the best counts)")
        ->check(CLI::Range(1, 100));
    app.add_option("--isolation", isolation, "Adaptive isolation level")->check(CLI::Range(1, 10));
    app.add_option("--torus-resolution", torusResolution, "Resolution of the procedural torus")
        ->check(CLI::Range(8, 2000));
    app.add_option("--mesh-dir", meshDir, "Folder with spot and bob (skipped when absent)");
    app.add_flag("--ordered", ordered, "Sort the preimages by face (coherent access)");
    CLI11_PARSE(app, argc, argv);

    std::vector<Case> cases;
    for (const char* file : {"spot_control_mesh.obj", "bob_controlmesh.obj"}) {
        const std::filesystem::path path = std::filesystem::path(meshDir) / file;
        if (std::filesystem::exists(path))
            cases.push_back(
                {path.stem().string(), SurfaceKind::CatmullClark, readMesh(path.string())});
        else
            std::printf("(skipping %s: not found)\n", path.string().c_str());
    }
    const PolygonMesh torus = makeProceduralShape("torus", torusResolution);
    cases.push_back({"torus", SurfaceKind::CatmullClark, torus});
    cases.push_back({"sphere (triangulated)", SurfaceKind::Loop,
                     triangulated(makeProceduralShape("sphere", 32))});
    cases.push_back({"torus (triangulated)", SurfaceKind::Loop, triangulated(torus)});

    const int cores = tbb::info::default_concurrency();
    SubdivisionOptions options;
    options.isolationLevel = isolation;
    std::printf("limit evaluations (position, 1st and 2nd derivatives), %zu %s preimages per "
                "batch, best of %d; isolation level %d; %d cores\n",
                evaluations, ordered ? "face-ordered" : "random", repeats, isolation, cores);
    std::printf("%-22s %-13s %7s %8s %8s %9s %13s %13s %13s\n", "surface", "scheme", "cage F",
                "domain F", "patches", "setup ms", "1 thread /s", "1 thr /CPU-s", "all cores /s");
    for (const Case& c : cases) {
        const auto start = Clock::now();
        const auto surface = SubdivisionSurface::create(c.cage, c.kind, options);
        const double setup = secondsSince(start);
        std::vector<Preimage> preimages = randomPreimages(*surface, evaluations);
        if (ordered)
            std::stable_sort(preimages.begin(), preimages.end(),
                             [](const Preimage& a, const Preimage& b) { return a.face < b.face; });
        std::vector<SurfacePoint> out(preimages.size());
        Rate single;
        {
            const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
            single = throughput(*surface, preimages, out, repeats);
        }
        const Rate all = throughput(*surface, preimages, out, repeats);
        std::printf("%-22s %-13s %7d %8d %8d %9.1f %13.3e %13.3e %13.3e\n", c.name.c_str(),
                    toString(c.kind), c.cage.faceCount(), surface->domain().faceCount(),
                    surface->patchCount(), setup * 1e3, single.wall, single.cpu, all.wall);
    }
    return 0;
}
