#include "contours/consistent/ConsistentOutputs.h"

#include "pipeline/FieldNames.h"

#include <cmath>
#include <string>

namespace contour::consistent {

namespace {

nlohmann::json vec3(const Vec3& v) {
    return {v.x(), v.y(), v.z()};
}

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

MethodOutputs consistentOutputs() {
    MethodOutputs outputs;
    // Only once a phase has classified the faces (Definition 2): the input
    // snapshot and a run stopped before that have nothing to list.
    outputs.viewJson = [](const MethodViewRun& run) -> nlohmann::json {
        if (run.snapshots.empty() || !run.last().field(fields::kConsistent))
            return nullptr;
        return {{"inconsistent_faces", inconsistentFacesJson(run.last(), run.method)}};
    };
    return outputs;
}

} // namespace contour::consistent
