#pragma once
// The state after a phase: immutable once the phase returns, self-contained,
// and cheap to copy (every large part is shared through shared_ptr<const>).
// Phases add or replace named fields on the working mesh; the GUI, the CLI and
// the exporters read fields by name (FieldNames.h), so they work for every
// method through this one type.
#include "mesh/PolygonMesh.h"
#include "pipeline/CounterNames.h"
#include "pipeline/Curve.h"
#include "pipeline/RunInfo.h"
#include "pipeline/ViewGraph.h"

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

struct Counter {
    std::string name; // the label (CounterName::label)
    double value = 0.0;
    std::string key; // CounterName::key; empty for a counter set by label only
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
    // The curves cut where their visibility may change, with each piece's
    // visibility and how it was decided; set by a method's visibility phase.
    std::shared_ptr<const ViewGraph> viewGraph;

    std::vector<Counter> counters;
    std::vector<InvariantCheck> invariants;
    std::vector<std::string> notes; // honest remarks a user should see
    // Within a branch's range (Branch.h): which run this snapshot belongs to.
    RunInfo run;

    // Optional working data a method publishes alongside the fields, so that
    // its next phase need not rebuild it (the consistent method's evaluated
    // vertices). A cache only: immutable once published, and every reader
    // must be able to rebuild the same data from the fields alone.
    std::shared_ptr<const MethodState> methodState;

    const Field* field(const std::string& name) const;
    void setField(const std::string& name, Field field);
    double counter(const std::string& name, double fallback = -1.0) const;
    void setCounter(const std::string& name, double value);
    // By key (CounterNames.h): the preferred form.
    double counter(const CounterName& name, double fallback = -1.0) const;
    void setCounter(const CounterName& name, double value);
    long long invariantViolations() const;
};

// The field `name` at `location` as values of type T, one per element
// (`count`), or null when the snapshot lacks it, stores it with another type
// or location, or its size does not match the mesh.
template <typename T>
const std::vector<T>* fieldValues(const Snapshot& s, const std::string& name,
                                  FieldLocation location, Index count) {
    const Field* field = s.field(name);
    if (!field || field->location != location)
        return nullptr;
    const auto* values = std::get_if<std::vector<T>>(&field->values);
    return values && values->size() == static_cast<std::size_t>(count) ? values : nullptr;
}

// The snapshot a method starts from: the cage as loaded and its triangulation.
Snapshot makeInputSnapshot(std::shared_ptr<const PolygonMesh> cage);

} // namespace contour
