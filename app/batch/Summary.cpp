#include "Summary.h"

#include "contours/Methods.h"
#include "export/ProjectedCurves.h"
#include "pipeline/ViewGraph.h"

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace contour::batch {

namespace {

std::string number(double x) {
    std::ostringstream s;
    if (std::isfinite(x) && x == std::floor(x) && std::abs(x) < 1e15)
        s << static_cast<long long>(x);
    else
        s << std::setprecision(6) << x;
    return s.str();
}

std::string vec(const Vec3& v) {
    // Appended piece by piece: GCC 12 flags `"(" + string` (-Wrestrict).
    std::string text(1, '(');
    text += number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
    return text;
}

const char* typeText(ParameterType type) {
    switch (type) {
    case ParameterType::Bool:
        return "bool";
    case ParameterType::Int:
        return "int";
    case ParameterType::Double:
        return "number";
    case ParameterType::Choice:
        return "choice";
    }
    return "value";
}

std::string plural(long long n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

} // namespace

void printMethodList(std::ostream& out) {
    for (const Method& m : contourMethods()) {
        out << m.name << " - " << m.label << "\n  " << m.description << "\n  phases:\n";
        for (size_t i = 0; i < m.phases.size(); ++i)
            out << "    " << i + 1 << ". " << m.phases[i].name << ": " << m.phases[i].description
                << "\n";
        out << "  parameters:" << (m.parameters.empty() ? " none" : "") << "\n";
        for (const std::string& group : m.parameterGroups()) {
            out << "    [" << group << "]\n";
            for (const ParameterSpec& p : m.parameters) {
                if (p.group != group)
                    continue;
                out << "    --" << p.name << " (" << typeText(p.type);
                if (p.type == ParameterType::Choice) {
                    out << ":";
                    for (size_t i = 0; i < p.choices.size(); ++i)
                        out << (i ? "|" : " ") << p.choices[i];
                } else if (p.type != ParameterType::Bool) {
                    out << " in [" << number(p.minimum) << ", " << number(p.maximum) << "]";
                }
                out << ", default " << toString(p.defaultValue) << ")\n      " << p.help << "\n";
            }
        }
        out << "  presets (--preset):\n";
        for (const ParameterPreset& preset : m.presets) {
            out << "    " << preset.name << ": " << preset.description << "\n";
            if (!preset.values.empty()) {
                out << "     ";
                for (const auto& [name, value] : preset.values)
                    out << " " << name << "=" << toString(value);
                out << "\n";
            }
        }
        out << "\n";
    }
    for (const PlannedMethod& m : plannedMethods())
        out << m.name << " - " << m.label << "\n  " << m.reason << "\n\n";
}

void printRunHeader(std::ostream& out, const std::string& meshPath, const Snapshot& input,
                    const Method& method, const ParameterSet& parameters) {
    out << "mesh    " << meshPath << ": ";
    if (input.cage) {
        long long polygons = 0;
        for (Index f = 0; f < input.cage->faceCount(); ++f)
            polygons += input.cage->face(f).size() > 3;
        out << input.cage->vertexCount() << " vertices"
            << ", " << plural(input.cage->faceCount(), "face") << " (" << polygons
            << " with more than 3 corners), ";
    }
    out << plural(input.mesh->faceCount(), "triangle") << ", "
        << plural(input.mesh->boundaryEdgeCount(), "boundary edge") << "\n";
    out << "method  " << method.name << " (" << method.label << ")";
    for (const auto& [name, value] : parameters.values())
        out << " " << name << "=" << toString(value);
    out << "\n";
}

void printViewHeader(std::ostream& out, int view, int viewCount, const Camera& camera) {
    if (viewCount > 1)
        out << "\nview " << std::setw(2) << std::setfill('0') << view << std::setfill(' ') << "/"
            << viewCount << "\n";
    out << "camera  " << (camera.isOrthographic() ? "orthographic" : "perspective") << ", eye "
        << vec(camera.eye) << ", target " << vec(camera.target) << ", up " << vec(camera.up);
    if (camera.isOrthographic())
        out << ", height " << number(camera.orthoHeight);
    else
        out << ", fov " << number(camera.fovYDegrees) << " deg";
    out << ", " << camera.viewport.width << "x" << camera.viewport.height << " px\n";
}

void printPhase(std::ostream& out, const Method& method, const Snapshot& snapshot,
                const Snapshot& previous) {
    std::ostringstream time;
    time << std::fixed << std::setprecision(2) << snapshot.phaseSeconds * 1000.0 << " ms";
    out << "  " << snapshot.phaseIndex + 1 << "/" << method.phases.size() << " " << std::left
        << std::setw(12) << snapshot.phaseName << std::right << std::setw(11) << time.str();
    std::string counters;
    for (const Counter& c : snapshot.counters) {
        const double before = previous.counter(c.name, std::nan(""));
        if (!(before == c.value))
            counters += (counters.empty() ? "  " : ", ") + c.name + ": " + number(c.value);
    }
    out << counters << "\n";
    for (const std::string& note : snapshot.notes)
        out << "      note: " << note << "\n";
    for (const InvariantCheck& check : snapshot.invariants)
        if (check.violations > 0)
            out << "      INVARIANT VIOLATED " << check.violations << "x: " << check.name
                << (check.firstExample.empty() ? "" : " (first: " + check.firstExample + ")")
                << "\n";
}

void printViewTotals(std::ostream& out, const Snapshot& last, const Camera& camera) {
    long long chains = 0, loops = 0, boundaries = 0;
    double length = 0.0;
    if (last.curves)
        for (const ProjectedPolyline& p : projectCurves(*last.curves, camera)) {
            if (p.type == CurveType::Contour) {
                ++chains;
                loops += p.closed;
                length += p.lengthPixels;
            } else if (p.type == CurveType::Boundary) {
                ++boundaries;
            }
        }
    std::ostringstream len;
    len << std::fixed << std::setprecision(1) << length;
    out << "result  after " << last.phaseName << ": " << plural(chains, "contour chain") << " ("
        << loops << " closed, " << chains - loops << " open), "
        << plural(boundaries, "boundary curve") << ", contour length " << len.str() << " px\n";
    if (last.viewGraph)
        printViewGraphTotals(out, *last.viewGraph);
}

void printViewGraphTotals(std::ostream& out, const ViewGraph& graph) {
    const ViewChainTally tally = graph.chainTally();
    long long tJunctions = 0, hiddenFolds = 0, curtainFolds = 0, boundaryFolds = 0, other = 0;
    for (const ViewNode& node : graph.nodes) {
        if (node.type == ViewNodeType::ImageIntersection)
            ++tJunctions;
        else if (node.type == ViewNodeType::HiddenFoldCrossing)
            ++hiddenFolds;
        else if (node.type == ViewNodeType::CurtainFold)
            ++curtainFolds;
        else if (node.type == ViewNodeType::BoundaryCurtainFold)
            ++boundaryFolds;
        else
            ++other;
    }
    std::ostringstream len;
    len << std::fixed << std::setprecision(1) << graph.visibleLengthPixels();
    out << "graph   " << plural(static_cast<long long>(graph.chains.size()), "chain") << ": "
        << tally.visible << " visible, " << tally.hidden << " hidden";
    if (tally.simplified > 0)
        out << ", " << tally.simplified << " simplified away";
    if (tally.ambiguous > 0)
        out << ", " << tally.ambiguous << " ambiguous";
    out << "; " << plural(tJunctions, "T-junction") << ", " << plural(curtainFolds, "curtain fold");
    if (boundaryFolds > 0)
        out << ", " << plural(boundaryFolds, "boundary curtain fold");
    if (hiddenFolds > 0)
        out << ", " << plural(hiddenFolds, "crossing") << " behind hidden mesh folds";
    if (other > 0)
        out << ", " << plural(other, "other node");
    out << "; " << plural(graph.rayTests, "ray test") << ", "
        << plural(static_cast<long long>(graph.conflicts.size()), "conflict") << "; visible length "
        << len.str() << " px\n";
}

void printMethodSummary(std::ostream& out, const MethodViewRun& run) {
    if (!run.method.outputs.summaryLines)
        return;
    for (const std::string& line : run.method.outputs.summaryLines(run))
        out << line << "\n";
}

void printWritten(std::ostream& out, const std::vector<std::string>& paths) {
    if (paths.empty())
        return;
    out << "wrote   ";
    for (size_t i = 0; i < paths.size(); ++i)
        out << (i ? ", " : "") << paths[i];
    out << "\n";
}

} // namespace contour::batch
