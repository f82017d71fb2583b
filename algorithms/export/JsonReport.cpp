#include "export/JsonReport.h"

#include "core/AtomicFile.h"
#include "export/ProjectedCurves.h"
#include "pipeline/MethodOutputs.h"

#include <cmath>
#include <stdexcept>

namespace contour {

namespace {

nlohmann::json vec3(const Vec3& v) {
    return {v.x(), v.y(), v.z()};
}

// Counters are doubles; most are counts, which read better as integers.
nlohmann::json counterValue(double value) {
    if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 9.0e15)
        return static_cast<long long>(value);
    return value;
}

nlohmann::json meshJson(const std::string& path, const Snapshot& input) {
    nlohmann::json j;
    j["path"] = path;
    if (input.cage) {
        const PolygonMesh& cage = *input.cage;
        long long polygons = 0;
        for (Index f = 0; f < cage.faceCount(); ++f)
            polygons += cage.face(f).size() > 3;
        j["vertices"] = cage.vertexCount();
        j["faces"] = cage.faceCount();
        j["polygon_faces"] = polygons;
    }
    if (input.mesh) {
        const TriangleMesh& mesh = *input.mesh;
        if (!input.cage) {
            j["vertices"] = mesh.vertexCount();
            j["faces"] = mesh.faceCount();
            j["polygon_faces"] = 0;
        }
        j["triangles"] = mesh.faceCount();
        j["edges"] = mesh.edgeCount();
        j["boundary_edges"] = mesh.boundaryEdgeCount();
        const BoundingBox box = mesh.boundingBox();
        if (!box.isEmpty())
            j["bounding_box"] = {{"min", vec3(box.min)}, {"max", vec3(box.max)}};
    }
    j["notes"] = input.notes;
    return j;
}

} // namespace

nlohmann::json phaseJson(const Phase& phase, const Snapshot& snapshot, const Snapshot& previous) {
    nlohmann::json j;
    j["index"] = snapshot.phaseIndex;
    j["name"] = phase.name;
    j["description"] = phase.description;
    j["seconds"] = snapshot.phaseSeconds;
    nlohmann::json counters = nlohmann::json::object();
    for (const Counter& c : snapshot.counters) {
        const double before = previous.counter(c.name, std::nan(""));
        if (!(before == c.value))
            counters[c.name] = counterValue(c.value);
    }
    j["counters"] = std::move(counters);
    nlohmann::json invariants = nlohmann::json::array();
    for (const InvariantCheck& check : snapshot.invariants)
        invariants.push_back({{"name", check.name},
                              {"violations", check.violations},
                              {"first_example", check.firstExample}});
    j["invariants"] = std::move(invariants);
    j["violations"] = snapshot.invariantViolations();
    j["notes"] = snapshot.notes;
    return j;
}

namespace {
nlohmann::json curvesJson(const std::vector<ProjectedPolyline>& projected) {
    nlohmann::json curves = nlohmann::json::array();
    for (const ProjectedPolyline& p : projected)
        curves.push_back({{"index", p.index},
                          {"type", toString(p.type)},
                          {"closed", p.closed},
                          {"points", p.pointCount},
                          {"length_px", p.lengthPixels},
                          {"pieces", p.pieces.size()},
                          {"hidden_points", p.hiddenPoints}});
    return curves;
}
} // namespace

nlohmann::json curvesJson(const Snapshot& snapshot, const Camera& camera) {
    if (!snapshot.curves)
        return nlohmann::json::array();
    return curvesJson(projectCurves(*snapshot.curves, camera));
}

namespace {
// Pixels to 0.01 px: finer than any drawing needs, and a third of the text.
double roundPixel(double x) {
    return std::isfinite(x) ? std::round(x * 100.0) / 100.0 : x;
}
} // namespace

nlohmann::json viewGraphJson(const ViewGraph& graph) {
    nlohmann::json chains = nlohmann::json::array();
    for (size_t c = 0; c < graph.chains.size(); ++c) {
        const ViewChain& chain = graph.chains[c];
        long long tested = 0, ambiguousSegments = 0;
        for (int q : chain.segmentRayQi)
            tested += q >= 0;
        for (std::uint8_t a : chain.segmentAmbiguous)
            ambiguousSegments += a != 0;
        nlohmann::json points = nlohmann::json::array();
        for (const Vec2& p : chain.image)
            points.push_back({roundPixel(p.x()), roundPixel(p.y())});
        chains.push_back({{"index", c},
                          {"type", toString(chain.type)},
                          {"curve", chain.curve},
                          {"closed", chain.closed},
                          {"qi", chain.qi},
                          {"qi_lower_bound", chain.qiLowerBound},
                          {"rule", toString(chain.decidedBy)},
                          {"propagated_from", chain.propagatedFrom},
                          {"propagated_via", chain.propagatedVia},
                          {"ambiguous", chain.ambiguous},
                          {"concave", chain.concave},
                          {"conflict", chain.conflict},
                          {"ray_qi", chain.rayQi},
                          {"simplified_away", chain.simplifiedAway},
                          {"visible", chain.visible()},
                          {"length_px", chain.lengthPixels},
                          {"start_node", chain.startNode},
                          {"end_node", chain.endNode},
                          {"segments", chain.segmentCount()},
                          {"ray_tested_segments", tested},
                          {"ambiguous_segments", ambiguousSegments},
                          {"points", std::move(points)}});
    }
    nlohmann::json nodes = nlohmann::json::array();
    nlohmann::json byType = nlohmann::json::object();
    for (size_t n = 0; n < graph.nodes.size(); ++n) {
        const ViewNode& node = graph.nodes[n];
        const std::string type = toString(node.type);
        byType[type] = byType.value(type, 0) + 1;
        nodes.push_back({{"index", n},
                         {"type", type},
                         {"class", toString(graph.nodeClass(static_cast<Index>(n)))},
                         {"image", {roundPixel(node.image.x()), roundPixel(node.image.y())}},
                         {"position", vec3(node.position)},
                         {"mesh_vertex", node.meshVertex},
                         {"chains", node.chains},
                         {"near_chains", {node.nearChains[0], node.nearChains[1]}},
                         {"far_chains", {node.farChains[0], node.farChains[1]}},
                         {"qi_step", node.qiStep},
                         {"unreliable", node.unreliable},
                         {"smooth_cusp", node.smoothCusp},
                         {"singular_cusp", node.singularCusp},
                         {"small_loop", node.smallLoop},
                         {"local_occluders", node.localOccluders}});
    }
    nlohmann::json conflicts = nlohmann::json::array();
    for (const VisibilityConflict& c : graph.conflicts)
        conflicts.push_back({{"chain", c.chain},
                             {"propagated_qi", c.propagatedQi},
                             {"ray_qi", c.rayQi},
                             {"reason", c.reason},
                             {"from_chain", c.fromChain},
                             {"via_node", c.viaNode},
                             {"ray_origin", vec3(c.rayOrigin)},
                             {"root", c.root}});
    const ViewChainTally tally = graph.chainTally();
    nlohmann::json totals = {
        {"chains", graph.chains.size()},
        {"visible_chains", tally.visible},
        {"hidden_chains", tally.hidden},
        {"simplified_chains", tally.simplified},
        {"ambiguous_chains", tally.ambiguous},
        {"conflict_chains", tally.conflicting},
        {"nodes", graph.nodes.size()},
        {"nodes_by_type", std::move(byType)},
        {"conflicts", graph.conflicts.size()},
        {"ray_tests", graph.rayTests},
        {"visible_length_px", graph.visibleLengthPixels()},
        {"hidden_length_px", graph.hiddenLengthPixels() - tally.simplifiedLengthPixels},
        {"simplified_length_px", tally.simplifiedLengthPixels}};
    return {{"totals", std::move(totals)},
            {"chains", std::move(chains)},
            {"nodes", std::move(nodes)},
            {"conflicts", std::move(conflicts)}};
}

namespace {

// Adds the members of a method's contribution (MethodOutputs.h) to the
// exporter's `target`; a method may add members but never replace one.
void addMethodMembers(nlohmann::json& target, const nlohmann::json& extra, const Method& method,
                      const char* where) {
    if (extra.is_null())
        return;
    if (!extra.is_object())
        throw std::logic_error("method " + method.name + ": its outputs for " + where +
                               " are not a JSON object");
    for (const auto& [key, value] : extra.items()) {
        if (target.contains(key))
            throw std::logic_error("method " + method.name + ": its outputs for " + where +
                                   " would replace \"" + key + "\"");
        target[key] = value;
    }
}

} // namespace

JsonReport::JsonReport(const std::string& toolName, const std::string& toolVersion,
                       const std::string& meshPath, const Snapshot& input, const Method& method,
                       const ParameterSet& parameters, const std::string& presetName)
    : method_(&method) {
    const ParameterPreset* preset = method.preset(presetName);
    if (!preset)
        throw std::invalid_argument("report: method " + method.name + " has no preset \"" +
                                    presetName + "\"");
    report_["tool"] = {{"name", toolName}, {"version", toolVersion}};
    report_["mesh"] = meshJson(meshPath, input);
    nlohmann::json phases = nlohmann::json::array();
    for (const Phase& phase : method.phases)
        phases.push_back(phase.name);
    report_["method"] = {
        {"name", method.name},
        {"label", method.label},
        {"parameters", parameters.toJson()},
        {"preset",
         {{"name", preset->name},
          {"changed", changedFromPreset(method.parameters, *preset, parameters).toJson()}}},
        {"phases", std::move(phases)}};
    report_["views"] = nlohmann::json::array();
}

void JsonReport::addView(const Camera& camera, const std::vector<Snapshot>& snapshots) {
    nlohmann::json view;
    view["index"] = report_["views"].size();
    view["camera"] = camera.toJson();
    const int completed = snapshots.empty() ? 0 : static_cast<int>(snapshots.size()) - 1;
    view["completed_phases"] = completed;
    view["phase_count"] = method_->phases.size();

    const MethodOutputs& extra = method_->outputs;
    const MethodViewRun run{*method_, camera, snapshots};
    nlohmann::json phases = nlohmann::json::array();
    double seconds = 0.0;
    long long violations = 0;
    for (int i = 1; i <= completed; ++i) {
        const Snapshot& s = snapshots[static_cast<size_t>(i)];
        nlohmann::json phase = phaseJson(method_->phases.at(static_cast<size_t>(i - 1)), s,
                                         snapshots[static_cast<size_t>(i - 1)]);
        if (extra.phaseJson)
            addMethodMembers(phase, extra.phaseJson(run, static_cast<std::size_t>(i)), *method_,
                             "a phase");
        phases.push_back(std::move(phase));
        seconds += s.phaseSeconds;
        violations += s.invariantViolations();
    }
    view["phases"] = std::move(phases);

    nlohmann::json totals;
    totals["seconds"] = seconds;
    totals["invariant_violations"] = violations;
    long long chains = 0, loops = 0, boundaries = 0, contourPoints = 0, clipped = 0, curveCount = 0;
    double contourLength = 0.0, boundaryLength = 0.0;
    nlohmann::json curves = nlohmann::json::array();
    nlohmann::json counters = nlohmann::json::object();
    if (!snapshots.empty()) {
        const Snapshot& last = snapshots.back();
        if (last.curves) {
            const std::vector<ProjectedPolyline> projected = projectCurves(*last.curves, camera);
            for (const ProjectedPolyline& p : projected) {
                ++curveCount;
                clipped += p.clipped();
                if (p.type == CurveType::Contour) {
                    ++chains;
                    loops += p.closed;
                    contourPoints += static_cast<long long>(p.pointCount);
                    contourLength += p.lengthPixels;
                } else if (p.type == CurveType::Boundary) {
                    ++boundaries;
                    boundaryLength += p.lengthPixels;
                }
            }
            curves = curvesJson(projected);
        }
        for (const Counter& c : last.counters)
            counters[c.name] = counterValue(c.value);
    }
    totals["curves"] = curveCount;
    totals["contour_chains"] = chains;
    totals["closed_loops"] = loops;
    totals["open_chains"] = chains - loops;
    totals["boundary_curves"] = boundaries;
    totals["contour_points"] = contourPoints;
    totals["contour_length_px"] = contourLength;
    totals["boundary_length_px"] = boundaryLength;
    totals["clipped_curves"] = clipped;
    totals["counters"] = std::move(counters);
    if (extra.totalsJson && !snapshots.empty())
        addMethodMembers(totals, extra.totalsJson(run), *method_, "the totals");
    view["totals"] = std::move(totals);
    view["curves"] = std::move(curves);
    if (!snapshots.empty() && snapshots.back().viewGraph)
        view["view_graph"] = viewGraphJson(*snapshots.back().viewGraph);
    if (extra.viewJson && !snapshots.empty())
        addMethodMembers(view, extra.viewJson(run), *method_, "the view");
    report_["views"].push_back(std::move(view));
}

void JsonReport::write(const std::string& path) const {
    writeFileAtomically(path, text());
}

} // namespace contour
