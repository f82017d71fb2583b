#include "export/JsonReport.h"

#include "export/ProjectedCurves.h"
#include "core/AtomicFile.h"
#include "pipeline/FieldNames.h"

#include <cmath>

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
                         {"local_occluders", node.localOccluders}});
    }
    nlohmann::json conflicts = nlohmann::json::array();
    for (const VisibilityConflict& c : graph.conflicts)
        conflicts.push_back({{"chain", c.chain},
                             {"propagated_qi", c.propagatedQi},
                             {"ray_qi", c.rayQi},
                             {"reason", c.reason}});
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

const char* labelText(int label) {
    return label > 0 ? "F" : label < 0 ? "B" : "C";
}

const char* vboText(int vbo) {
    return vbo > 0 ? "F" : vbo < 0 ? "B" : "undefined";
}

const char* facingText(int facing) {
    return facing > 0 ? "front" : facing < 0 ? "back" : "edge-on";
}

// Which condition of Bénard 2014 Definitions 1-2 the face fails.
std::string inconsistencyReason(const int* vbo, const int* facing, const std::string& labels) {
    if (!vbo)
        return "marked inconsistent (no VBO field to say why)";
    if (*vbo == 0)
        return "VBO undefined: vertex labels " + labels +
               " (Definition 1: CCC, CFB, FFB and FBB have no VBO)";
    std::string reason = std::string("VBO ") + vboText(*vbo) + " but the face is ";
    if (!facing)
        return reason + "of unknown facing (Definition 2)";
    return reason + facingText(*facing) + "-facing (Definition 2: the VBO must equal the facing)";
}

} // namespace

nlohmann::json inconsistentFacesJson(const Snapshot& s, const Method& method) {
    nlohmann::json out = nlohmann::json::array();
    if (!s.mesh)
        return out;
    const TriangleMesh& mesh = *s.mesh;
    const Index nf = mesh.faceCount(), nv = mesh.vertexCount();
    using L = FieldLocation;
    const auto* consistent = fieldValues<int>(s, fields::kConsistent, L::Face, nf);
    if (!consistent)
        return out;
    const auto* vbo = fieldValues<int>(s, fields::kVbo, L::Face, nf);
    const auto* facing = fieldValues<int>(s, fields::kFacing, L::Face, nf);
    const auto* radial = fieldValues<int>(s, fields::kRadial, L::Face, nf);
    const auto* standard = fieldValues<int>(s, fields::kStandardRadial, L::Face, nf);
    const auto* folded = fieldValues<int>(s, fields::kFolded, L::Face, nf);
    const auto* domain = fieldValues<int>(s, fields::kDomainFace, L::Face, nf);
    const auto* changed = fieldValues<int>(s, fields::kChangedByPhase, L::Face, nf);
    const auto* label = fieldValues<int>(s, fields::kLabel, L::Vertex, nv);
    const auto* g = fieldValues<double>(s, fields::kG, L::Vertex, nv);
    const auto* kr = fieldValues<double>(s, fields::kRadialCurvature, L::Vertex, nv);
    const auto* provenance = fieldValues<int>(s, fields::kProvenance, L::Vertex, nv);
    const auto* cusp = fieldValues<int>(s, fields::kCusp, L::Vertex, nv);
    const auto* vchanged = fieldValues<int>(s, fields::kVertexChangedByPhase, L::Vertex, nv);
    const auto* preFace = fieldValues<int>(s, fields::kPreimageFace, L::Vertex, nv);
    const auto* preUv = fieldValues<Vec3>(s, fields::kPreimageUv, L::Vertex, nv);
    const auto phaseName = [&](int index) -> std::string {
        if (index < 0)
            return "input";
        return static_cast<size_t>(index) < method.phases.size()
                   ? method.phases[static_cast<size_t>(index)].name
                   : std::string();
    };
    // JSON has no NaN: null where a value is not finite.
    const auto number = [](double x) {
        return std::isfinite(x) ? nlohmann::json(x) : nullptr;
    };
    for (Index f = 0; f < nf; ++f) {
        const size_t fi = static_cast<size_t>(f);
        if ((*consistent)[fi] != 0)
            continue;
        const Triangle& t = mesh.triangle(f);
        nlohmann::json face;
        face["face"] = f;
        face["vertices"] = {t[0], t[1], t[2]};
        std::string labels;
        if (label)
            for (Index v : t)
                labels += labelText((*label)[static_cast<size_t>(v)]);
        face["reason"] =
            inconsistencyReason(vbo ? &(*vbo)[fi] : nullptr, facing ? &(*facing)[fi] : nullptr,
                                labels.empty() ? "unknown" : labels);
        if (vbo)
            face["vbo"] = vboText((*vbo)[fi]);
        if (facing)
            face["facing"] = facingText((*facing)[fi]);
        nlohmann::json positions = nlohmann::json::array(), vertexLabels = nlohmann::json::array(),
                       gs = nlohmann::json::array(), krs = nlohmann::json::array(),
                       preimages = nlohmann::json::array(), provenances = nlohmann::json::array(),
                       cusps = nlohmann::json::array(), vphases = nlohmann::json::array();
        for (Index v : t) {
            const size_t vi = static_cast<size_t>(v);
            positions.push_back(vec3(mesh.position(v)));
            if (label)
                vertexLabels.push_back(labelText((*label)[vi]));
            if (g)
                gs.push_back(number((*g)[vi]));
            if (kr)
                krs.push_back(number((*kr)[vi]));
            if (preFace && preUv)
                preimages.push_back(
                    {{"face", (*preFace)[vi]}, {"uv", {(*preUv)[vi].x(), (*preUv)[vi].y()}}});
            if (provenance)
                provenances.push_back((*provenance)[vi]);
            if (cusp)
                cusps.push_back((*cusp)[vi] != 0);
            if (vchanged)
                vphases.push_back((*vchanged)[vi]);
        }
        face["positions"] = std::move(positions);
        if (label)
            face["vertex_labels"] = std::move(vertexLabels);
        if (g)
            face["g"] = std::move(gs);
        if (kr)
            face["radial_curvature"] = std::move(krs);
        if (preFace && preUv)
            face["preimages"] = std::move(preimages);
        if (provenance)
            face["provenance"] = std::move(provenances);
        if (cusp)
            face["cusp"] = std::move(cusps);
        if (vchanged)
            face["vertex_changed_by_phase"] = std::move(vphases);
        if (radial)
            face["radial"] = (*radial)[fi] != 0;
        if (standard)
            face["standard_radial"] = (*standard)[fi] != 0;
        if (folded)
            face["folded"] = (*folded)[fi] != 0;
        if (domain)
            face["domain_face"] = (*domain)[fi];
        if (changed) {
            face["changed_by_phase"] = (*changed)[fi];
            face["changed_by_phase_name"] = phaseName((*changed)[fi]);
        }
        nlohmann::json neighbours = nlohmann::json::array();
        int inconsistentNeighbours = 0;
        for (int i = 0; i < 3; ++i) {
            const Index h = 3 * f + i;
            const Index across = mesh.isBoundary(h) ? kInvalidIndex : mesh.opposite(h) / 3;
            neighbours.push_back(across == kInvalidIndex ? -1 : across);
            if (across != kInvalidIndex)
                inconsistentNeighbours += (*consistent)[static_cast<size_t>(across)] == 0;
        }
        face["neighbours"] = std::move(neighbours);
        face["inconsistent_neighbours"] = inconsistentNeighbours;
        out.push_back(std::move(face));
    }
    return out;
}

JsonReport::JsonReport(const std::string& toolName, const std::string& toolVersion,
                       const std::string& meshPath, const Snapshot& input, const Method& method,
                       const ParameterSet& parameters)
    : method_(&method) {
    report_["tool"] = {{"name", toolName}, {"version", toolVersion}};
    report_["mesh"] = meshJson(meshPath, input);
    nlohmann::json phases = nlohmann::json::array();
    for (const Phase& phase : method.phases)
        phases.push_back(phase.name);
    report_["method"] = {{"name", method.name},
                         {"label", method.label},
                         {"parameters", parameters.toJson()},
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

    nlohmann::json phases = nlohmann::json::array();
    double seconds = 0.0;
    long long violations = 0;
    for (int i = 1; i <= completed; ++i) {
        const Snapshot& s = snapshots[static_cast<size_t>(i)];
        phases.push_back(phaseJson(method_->phases.at(static_cast<size_t>(i - 1)), s,
                                   snapshots[static_cast<size_t>(i - 1)]));
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
    view["totals"] = std::move(totals);
    view["curves"] = std::move(curves);
    if (!snapshots.empty() && snapshots.back().viewGraph)
        view["view_graph"] = viewGraphJson(*snapshots.back().viewGraph);
    if (!snapshots.empty() && snapshots.back().field(fields::kConsistent))
        view["inconsistent_faces"] = inconsistentFacesJson(snapshots.back(), *method_);
    report_["views"].push_back(std::move(view));
}

void JsonReport::write(const std::string& path) const {
    writeFileAtomically(path, text());
}

} // namespace contour
