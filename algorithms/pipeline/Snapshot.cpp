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
    counters.push_back({name, value});
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
    s.setCounter("faces", s.mesh->faceCount());
    s.setCounter("vertices", s.mesh->vertexCount());
    s.setCounter("edges", s.mesh->edgeCount());
    s.setCounter("boundary edges", s.mesh->boundaryEdgeCount());
    return s;
}

} // namespace contour
