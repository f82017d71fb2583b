#pragma once
// Shared set-up for the contour suites: run a method to the end on a shape.
#include "contours/Methods.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/Runner.h"

#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour::testing {

inline Snapshot runMethod(const std::string& method, std::shared_ptr<const PolygonMesh> mesh,
                          const Camera& camera, ParameterSet parameters = {}) {
    const Method& m = *findMethod(method);
    ParameterSet p = ParameterSet::defaults(m.parameters);
    for (const auto& [name, value] : parameters.values())
        p.set(name, value);
    Runner runner(m, makeInputSnapshot(std::move(mesh)), camera, p);
    runner.runToEnd();
    return runner.current();
}

// Every snapshot of one run (the input first); phases are looked up by name,
// never by index, since sub-phases get inserted between others.
struct PhaseRun {
    std::vector<Snapshot> snapshots;
    const Snapshot& after(const std::string& phase) const {
        for (const Snapshot& s : snapshots)
            if (s.phaseName == phase)
                return s;
        throw std::runtime_error("no phase " + phase);
    }
};

// The final inconsistent faces of one view run without and with a change
// (the last snapshot of each run): totals over the views and how many views
// end better. add() returns "" or why the view fails: a run without the
// counter, or more faces with the change than without (no move may make a
// view worse).
struct OnOffCounts {
    double without = 0.0, with = 0.0;
    int better = 0;
    std::string add(const Snapshot& offLast, const Snapshot& onLast, size_t view) {
        const double a = offLast.counter(counters::kInconsistentFaces, -1.0);
        const double b = onLast.counter(counters::kInconsistentFaces, -1.0);
        if (a < 0.0 || b < 0.0)
            return "view " + std::to_string(view) + ": no inconsistent faces counter";
        if (b > a)
            return "view " + std::to_string(view) + ": " +
                   std::to_string(static_cast<long long>(a)) + " -> " +
                   std::to_string(static_cast<long long>(b));
        better += b < a;
        without += a;
        with += b;
        return {};
    }
};

inline int contourLoops(const Snapshot& s, int* open = nullptr) {
    int loops = 0, opened = 0;
    for (const Polyline& line : *s.curves)
        if (line.type == CurveType::Contour)
            (line.closed ? loops : opened)++;
    if (open)
        *open = opened;
    return loops;
}

// The 26-view protocol plus `randomViews` cameras from a fixed seed, on a
// sphere of directions around the box at 1.2 to 3 diagonals.
inline std::vector<Camera> protocolViews(const BoundingBox& box, int randomViews,
                                         unsigned seed = 2014) {
    std::vector<Camera> cameras = Camera::views26(box, Viewport{800, 600});
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, 1.0);
    std::uniform_real_distribution<double> d(1.2, 3.0);
    for (int i = 0; i < randomViews; ++i) {
        const Vec3 dir(n(rng), n(rng), n(rng));
        Camera c = Camera::framing(box, dir, Viewport{800, 600});
        c.eye = c.target + d(rng) * box.diagonal() * dir.normalized();
        cameras.push_back(c);
    }
    return cameras;
}

inline std::shared_ptr<const PolygonMesh> shape(const std::string& name, int resolution) {
    return std::make_shared<const PolygonMesh>(makeProceduralShape(name, resolution));
}

// "spot" and "bob": the sample control meshes (samples/); any other name: a
// procedural shape at `resolution`.
inline std::shared_ptr<const PolygonMesh> sampleOrShape(const std::string& name, int resolution) {
    if (name == "spot" || name == "bob") {
        const std::string file = name == "spot" ? "spot_control_mesh.obj" : "bob_controlmesh.obj";
        const std::string path = std::string(CONTOUR_SOURCE_DIR) + "/samples/" + file;
        if (!std::filesystem::exists(path))
            throw std::runtime_error("samples/" + file + " is absent");
        return std::make_shared<const PolygonMesh>(readMesh(path));
    }
    return shape(name, resolution);
}

// A mesh of ../shared/meshes (`name` without extension), or null when it is
// absent: the caller skips (QSKIP must be called from the test function).
inline std::shared_ptr<const PolygonMesh> sharedMesh(const std::string& name) {
    const std::string path = std::string(CONTOUR_SHARED_DIR) + "/meshes/" + name + ".obj";
    if (!std::filesystem::exists(path))
        return nullptr;
    return std::make_shared<const PolygonMesh>(readMesh(path));
}

} // namespace contour::testing
