#pragma once
// Shared set-up for the contour suites: run a method on a shape with named
// parameter overrides and keep its snapshots, the shapes and views of the
// protocols, and the measured figures the tests assert (tests/baselines/).
#include "contours/Methods.h"
#include "mesh/ProceduralShapes.h"
#include "mesh/io/MeshReader.h"
#include "pipeline/Runner.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace contour::testing {

// Parameters of one run by name, over the method's defaults: built from a
// list ({{"surface", "catmull-clark"}, {"cusp-retry", false}}) or set one by
// one. run() refuses a name the method does not have.
class Overrides {
public:
    struct Entry {
        std::string name;
        ParameterValue value;
        Entry(std::string n, bool v) : name(std::move(n)), value(v) {}
        Entry(std::string n, int v) : name(std::move(n)), value(v) {}
        Entry(std::string n, double v) : name(std::move(n)), value(v) {}
        Entry(std::string n, const char* v) : name(std::move(n)), value(std::string(v)) {}
        Entry(std::string n, std::string v) : name(std::move(n)), value(std::move(v)) {}
        Entry(std::string n, ParameterValue v) : name(std::move(n)), value(std::move(v)) {}
    };
    Overrides() = default;
    Overrides(std::initializer_list<Entry> entries) {
        for (const Entry& e : entries)
            set(e.name, e.value);
    }
    // The later value of a name wins.
    Overrides& set(const std::string& name, ParameterValue value) {
        for (Entry& e : entries_)
            if (e.name == name) {
                e.value = std::move(value);
                return *this;
            }
        entries_.emplace_back(name, std::move(value));
        return *this;
    }
    // One overload per parameter type, so that a literal 0 is an int, not
    // a null const char*.
    Overrides& set(const std::string& name, bool value) { return set(name, ParameterValue(value)); }
    Overrides& set(const std::string& name, int value) { return set(name, ParameterValue(value)); }
    Overrides& set(const std::string& name, double value) {
        return set(name, ParameterValue(value));
    }
    Overrides& set(const std::string& name, const char* value) {
        return set(name, ParameterValue(std::string(value)));
    }
    Overrides& set(const std::string& name, std::string value) {
        return set(name, ParameterValue(std::move(value)));
    }
    const std::vector<Entry>& entries() const { return entries_; }

private:
    std::vector<Entry> entries_;
};

// The method's defaults with `overrides` applied.
inline ParameterSet parametersOf(const Method& method, const Overrides& overrides) {
    ParameterSet p = ParameterSet::defaults(method.parameters);
    for (const Overrides::Entry& e : overrides.entries()) {
        if (!p.has(e.name))
            throw std::invalid_argument("method " + method.name + " has no parameter " + e.name);
        p.set(e.name, e.value);
    }
    return p;
}

// Every snapshot of one run (the input first); phases are looked up by name,
// never by index, since sub-phases get inserted between others.
struct MethodRun {
    std::vector<Snapshot> snapshots;
    // The snapshot after `name`, or null when the method has no such phase
    // (or the run stopped before it).
    const Snapshot* findPhase(const std::string& name) const {
        for (const Snapshot& s : snapshots)
            if (s.phaseName == name)
                return &s;
        return nullptr;
    }
    const Snapshot& phase(const std::string& name) const {
        if (const Snapshot* s = findPhase(name))
            return *s;
        throw std::runtime_error("no phase " + name);
    }
    const Snapshot& last() const { return snapshots.back(); }
};

// Runs `method` on `mesh` seen from `camera` to the end, or up to and
// including the phase named `stopAfter` (which the method must have), and
// keeps every snapshot.
inline MethodRun run(const std::string& method, std::shared_ptr<const PolygonMesh> mesh,
                     const Camera& camera, const Overrides& overrides = {},
                     const std::string& stopAfter = {}) {
    const Method* m = findMethod(method);
    if (!m)
        throw std::invalid_argument("no method " + method);
    Runner runner(*m, makeInputSnapshot(std::move(mesh)), camera, parametersOf(*m, overrides));
    if (stopAfter.empty())
        runner.runToEnd();
    else
        while (runner.current().phaseName != stopAfter && runner.step()) {
        }
    if (!stopAfter.empty() && runner.current().phaseName != stopAfter)
        throw std::invalid_argument("method " + method + " has no phase " + stopAfter);
    return {runner.snapshots()};
}

// The last snapshot of run().
inline Snapshot runMethod(const std::string& method, std::shared_ptr<const PolygonMesh> mesh,
                          const Camera& camera, const Overrides& overrides = {}) {
    return run(method, std::move(mesh), camera, overrides).last();
}

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

// A measured figure a test asserts (a ceiling or a floor, with its margin),
// from tests/baselines/<file>.json: {"<key>": {"value": 0.235, "what": "...",
// "command": "..."}}, "command" being how the figure was measured. Throws
// when the file or the key is absent, so a renamed key fails the test.
inline double baseline(const std::string& file, const std::string& key) {
    static std::map<std::string, nlohmann::json> loaded;
    auto it = loaded.find(file);
    if (it == loaded.end()) {
        const std::string path =
            std::string(CONTOUR_SOURCE_DIR) + "/tests/baselines/" + file + ".json";
        std::ifstream in(path);
        if (!in)
            throw std::runtime_error("cannot read " + path);
        it = loaded.emplace(file, nlohmann::json::parse(in)).first;
    }
    const auto entry = it->second.find(key);
    if (entry == it->second.end() || !entry->contains("value"))
        throw std::runtime_error("tests/baselines/" + file + ".json has no value for \"" + key +
                                 "\"");
    return entry->at("value").get<double>();
}

// Writes `mesh` as an OBJ file with positions to full precision (the tests
// that hand a mesh to contour-batch); false when the file cannot be written.
inline bool writeObjFile(const PolygonMesh& mesh, const std::string& path) {
    std::ofstream out(path);
    char line[128];
    for (const Vec3& p : mesh.positions) {
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
        out << line;
    }
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        out << "f";
        for (Index v : mesh.face(f))
            out << ' ' << v + 1;
        out << '\n';
    }
    return out.good();
}

// `mesh` with the listed faces (every face when `faces` is empty) written the
// other way round, as a file with inward normals has them: the first corner
// stays and the others run backwards.
inline PolygonMesh reversedFaces(const PolygonMesh& mesh, std::vector<Index> faces = {}) {
    if (faces.empty())
        for (Index f = 0; f < mesh.faceCount(); ++f)
            faces.push_back(f);
    PolygonMesh out = mesh;
    for (const Index f : faces) {
        const auto face = mesh.face(f);
        for (size_t i = 1; i < face.size(); ++i)
            out.indices[static_cast<size_t>(mesh.offsets[f]) + i] = face[face.size() - i];
    }
    return out;
}

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
