#pragma once
// The state after a phase: immutable once the phase returns, self-contained,
// and cheap to copy (every large part is shared through shared_ptr<const>).
// Phases add or replace named fields on the working mesh; the GUI, the CLI and
// the exporters read fields by name (FieldNames.h), so they work for every
// method through this one type.
#include "mesh/PolygonMesh.h"

#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace contour {

enum class FieldLocation { Vertex, Face, Edge };

struct Field {
    FieldLocation location = FieldLocation::Vertex;
    std::variant<std::vector<double>, std::vector<int>, std::vector<Vec3>> values;
    std::string description;

    const std::vector<double>* scalars() const { return std::get_if<std::vector<double>>(&values); }
    const std::vector<int>* labels() const { return std::get_if<std::vector<int>>(&values); }
    const std::vector<Vec3>* vectors() const { return std::get_if<std::vector<Vec3>>(&values); }
};

enum class CurveType { Contour, Boundary, SurfaceIntersection };
const char* toString(CurveType type);

// A point of a curve, with the mesh element it lies on: a vertex (mesh
// contours) or a point at parameter t along an edge (interpolated contours).
struct CurvePoint {
    Vec3 position;
    Index vertex = kInvalidIndex;
    Index edge = kInvalidIndex;
    double t = 0.0;
};

enum class SegmentSource { MeshEdge, Face };

struct Polyline {
    CurveType type = CurveType::Contour;
    bool closed = false;
    std::vector<CurvePoint> points;
    // Per segment i (points i -> i+1, and last -> first when closed): the mesh
    // element it comes from, an edge or a face according to `source`.
    SegmentSource source = SegmentSource::MeshEdge;
    std::vector<Index> segmentElement;

    size_t segmentCount() const {
        return points.size() < 2 ? 0 : closed ? points.size() : points.size() - 1;
    }
};

struct Counter {
    std::string name;
    double value = 0.0;
};

struct InvariantCheck {
    std::string name; // the post-condition, stated positively
    long long violations = 0;
    std::string firstExample; // the first offending element, for the inspector
};

// Base of the working data a method may attach to a snapshot (see
// Snapshot::methodState); readers dynamic_pointer_cast to their own type.
struct MethodState {
    virtual ~MethodState() = default;
};

struct Snapshot {
    int phaseIndex = -1; // -1 for the input snapshot
    std::string phaseName = "input";
    double phaseSeconds = 0.0;

    std::shared_ptr<const PolygonMesh> cage;
    std::shared_ptr<const TriangleMesh> mesh;
    std::map<std::string, std::shared_ptr<const Field>> fields;
    std::shared_ptr<const std::vector<Polyline>> curves;

    std::vector<Counter> counters;
    std::vector<InvariantCheck> invariants;
    std::vector<std::string> notes; // honest remarks a user should see

    // Optional working data a method publishes alongside the fields, so that
    // its next phase need not rebuild it (the consistent method's evaluated
    // vertices). A cache only: immutable once published, and every reader
    // must be able to rebuild the same data from the fields alone.
    std::shared_ptr<const MethodState> methodState;

    const Field* field(const std::string& name) const;
    void setField(const std::string& name, Field field);
    double counter(const std::string& name, double fallback = -1.0) const;
    void setCounter(const std::string& name, double value);
    long long invariantViolations() const;
};

// The snapshot a method starts from: the cage as loaded and its triangulation.
Snapshot makeInputSnapshot(std::shared_ptr<const PolygonMesh> cage);

} // namespace contour
