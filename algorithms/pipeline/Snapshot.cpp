#include "pipeline/Snapshot.h"

namespace contour {

const char* toString(CurveType type) {
    switch (type) {
    case CurveType::Contour:
        return "contour";
    case CurveType::Boundary:
        return "boundary";
    case CurveType::SurfaceIntersection:
        return "surface-intersection";
    }
    return "unknown";
}

const Field* Snapshot::field(const std::string& name) const {
    const auto it = fields.find(name);
    return it == fields.end() ? nullptr : it->second.get();
}

void Snapshot::setField(const std::string& name, Field f) {
    fields[name] = std::make_shared<const Field>(std::move(f));
}

double Snapshot::counter(const std::string& name, double fallback) const {
    for (const Counter& c : counters)
        if (c.name == name)
            return c.value;
    return fallback;
}

void Snapshot::setCounter(const std::string& name, double value) {
    for (Counter& c : counters)
        if (c.name == name) {
            c.value = value;
            return;
        }
    counters.push_back({name, value, {}});
}

double Snapshot::counter(const CounterName& name, double fallback) const {
    for (const Counter& c : counters)
        if (c.key == name.key || (c.key.empty() && c.name == name.label))
            return c.value;
    return fallback;
}

void Snapshot::setCounter(const CounterName& name, double value) {
    // A counter first set by its label alone is the same counter.
    for (Counter& c : counters)
        if (c.key == name.key || (c.key.empty() && c.name == name.label)) {
            c.key = name.key;
            c.value = value;
            return;
        }
    counters.push_back({std::string(name.label), value, std::string(name.key)});
}

long long Snapshot::invariantViolations() const {
    long long n = 0;
    for (const InvariantCheck& c : invariants)
        n += c.violations;
    return n;
}

Snapshot makeInputSnapshot(std::shared_ptr<const PolygonMesh> cage) {
    Snapshot s;
    s.mesh = std::make_shared<const TriangleMesh>(cage->triangulate());
    s.cage = std::move(cage);
    s.curves = std::make_shared<const std::vector<Polyline>>();
    s.setCounter(counters::kFaces, s.mesh->faceCount());
    s.setCounter(counters::kVertices, s.mesh->vertexCount());
    s.setCounter(counters::kEdges, s.mesh->edgeCount());
    s.setCounter(counters::kBoundaryEdges, s.mesh->boundaryEdgeCount());
    return s;
}

} // namespace contour
