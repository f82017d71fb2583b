#include "mesh/Orientation.h"

#include "core/UnionFind.h"
#include "mesh/PolygonEdges.h"

#include <algorithm>
#include <cstdio>

namespace contour {

namespace {

std::string volumeText(double volume) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", volume);
    return text;
}

std::string countText(int count, const char* noun) {
    return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// The enclosed volume of one closed component: the sum over its faces,
// fanned from their first corner, of the tetrahedra the triangles span with
// a reference point (the divergence theorem). Any reference point gives the
// same sum for a closed surface; the component's mean corner keeps the
// terms small, so that a mesh far from the origin loses no precision.
double signedVolume(const PolygonMesh& mesh, const std::vector<Index>& faces) {
    Vec3 reference = Vec3::Zero();
    long long corners = 0;
    for (const Index f : faces)
        for (const Index v : mesh.face(f)) {
            reference += mesh.positions[v];
            ++corners;
        }
    reference /= static_cast<double>(std::max(corners, 1LL));
    double sixfold = 0.0;
    for (const Index f : faces) {
        const auto face = mesh.face(f);
        const Vec3 a = mesh.positions[face[0]] - reference;
        for (size_t i = 2; i < face.size(); ++i) {
            const Vec3 b = mesh.positions[face[i - 1]] - reference;
            const Vec3 c = mesh.positions[face[i]] - reference;
            sixfold += a.dot(b.cross(c));
        }
    }
    return sixfold / 6.0;
}

// "the signed volume -0.31" or "signed volumes -0.31, -0.02".
std::string inwardVolumes(const OrientationReport& report) {
    std::string text;
    int listed = 0;
    for (const ComponentOrientation& c : report.components) {
        if (!c.inward())
            continue;
        if (listed == 6) {
            text += ", ...";
            break;
        }
        text += (listed++ == 0 ? "" : ", ") + volumeText(c.signedVolume);
    }
    return (report.inwardCount() == 1 ? "signed volume " : "signed volumes ") + text;
}

} // namespace

std::string ComponentOrientation::describe() const {
    if (!closed && !consistent)
        return "open and inconsistently oriented: its orientation cannot be decided by volume";
    if (!closed)
        return "open: its orientation cannot be decided by volume";
    if (!consistent)
        return "closed but inconsistently oriented: its orientation cannot be decided by volume";
    return std::string("closed, ") + (signedVolume < 0.0 ? "inward" : "outward") +
           " (signed volume " + volumeText(signedVolume) + ")" + (flipped ? ", flipped" : "");
}

int OrientationReport::decidableCount() const {
    return static_cast<int>(std::count_if(components.begin(), components.end(),
                                          [](const auto& c) { return c.decidable(); }));
}

int OrientationReport::inwardCount() const {
    return static_cast<int>(std::count_if(components.begin(), components.end(),
                                          [](const auto& c) { return c.inward(); }));
}

int OrientationReport::flippedCount() const {
    return static_cast<int>(std::count_if(components.begin(), components.end(),
                                          [](const auto& c) { return c.flipped; }));
}

int OrientationReport::openCount() const {
    return static_cast<int>(std::count_if(components.begin(), components.end(),
                                          [](const auto& c) { return !c.closed; }));
}

int OrientationReport::inconsistentCount() const {
    return static_cast<int>(std::count_if(components.begin(), components.end(),
                                          [](const auto& c) { return c.closed && !c.consistent; }));
}

bool OrientationReport::hasMessage() const {
    return inwardCount() > 0 || openCount() > 0 || inconsistentCount() > 0;
}

OrientationReport orientationReport(const PolygonMesh& mesh) {
    const PolygonEdges edges = polygonEdges(mesh);
    const std::vector<Index>& corner = mesh.indices;
    const Index faceCount = mesh.faceCount();
    UnionFind sets(static_cast<size_t>(faceCount));
    for (Index e = 0; e < edges.edgeCount(); ++e) {
        const auto halfedges = edges.halfedges(e);
        for (size_t i = 1; i < halfedges.size(); ++i)
            sets.unite(edges.cornerFace[halfedges[0]], edges.cornerFace[halfedges[i]]);
    }

    // Roots are each set's lowest face, so numbering roots in face order
    // orders the components by their first face.
    OrientationReport report;
    report.faceComponent.assign(static_cast<size_t>(faceCount), kInvalidIndex);
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < faceCount; ++f) {
        const Index root = sets.find(f);
        if (root == f) {
            report.faceComponent[f] = static_cast<Index>(report.components.size());
            ComponentOrientation component;
            component.firstFace = f;
            component.closed = true;
            component.consistent = true;
            report.components.push_back(component);
            faces.emplace_back();
        } else {
            report.faceComponent[f] = report.faceComponent[root];
        }
        const Index c = report.faceComponent[f];
        ++report.components[c].faces;
        faces[c].push_back(f);
    }

    for (Index e = 0; e < edges.edgeCount(); ++e) {
        const auto halfedges = edges.halfedges(e);
        ComponentOrientation& component =
            report.components[report.faceComponent[edges.cornerFace[halfedges[0]]]];
        if (halfedges.size() == 1)
            component.closed = false;
        else if (halfedges.size() > 2 || corner[halfedges[0]] == corner[halfedges[1]])
            component.consistent = false;
    }
    for (size_t c = 0; c < report.components.size(); ++c)
        if (report.components[c].decidable())
            report.components[c].signedVolume = signedVolume(mesh, faces[c]);
    return report;
}

PolygonMesh orientOutward(const PolygonMesh& mesh, OrientationReport* reportOut) {
    OrientationReport report = orientationReport(mesh);
    PolygonMesh oriented = mesh;
    for (ComponentOrientation& component : report.components)
        component.flipped = component.inward();
    if (report.flippedCount() > 0)
        for (Index f = 0; f < mesh.faceCount(); ++f)
            if (report.components[report.faceComponent[f]].flipped) {
                std::reverse(oriented.indices.begin() + mesh.offsets[f] + 1,
                             oriented.indices.begin() + mesh.offsets[f + 1]);
                // Texture coordinates stay with their corners.
                if (oriented.hasTextureCoordinates())
                    std::reverse(oriented.cornerTexture.begin() + mesh.offsets[f] + 1,
                                 oriented.cornerTexture.begin() + mesh.offsets[f + 1]);
            }
    if (reportOut)
        *reportOut = std::move(report);
    return oriented;
}

PolygonMesh orientForContours(const PolygonMesh& mesh, bool keepFileOrientation,
                              OrientationReport& report) {
    if (!keepFileOrientation)
        return orientOutward(mesh, &report);
    report = orientationReport(mesh);
    return mesh;
}

std::string orientationMessage(const OrientationReport& report, const std::string& keepSwitch) {
    std::vector<std::string> parts;
    if (const int inward = report.inwardCount(); inward > 0) {
        const std::string which = std::to_string(inward) + " of " +
                                  std::to_string(report.decidableCount()) + " closed components";
        if (report.flippedCount() > 0)
            parts.push_back(which + " had inward normals (" + inwardVolumes(report) +
                            "); flipped (" + keepSwitch + " keeps them)");
        else
            parts.push_back(which + (inward == 1 ? " has" : " have") + " inward normals (" +
                            inwardVolumes(report) + "); kept as in the file (" + keepSwitch +
                            "): " + (inward == 1 ? "its" : "their") +
                            " contours will read as hidden");
    }
    const int open = report.openCount(), inconsistent = report.inconsistentCount();
    if (open + inconsistent > 0) {
        std::string which;
        if (open > 0)
            which = countText(open, "open component");
        if (inconsistent > 0)
            which += (which.empty() ? "" : " and ") +
                     countText(inconsistent, "inconsistently oriented closed component");
        parts.push_back(which +
                        " left as in the file: " + (open + inconsistent == 1 ? "its" : "their") +
                        " orientation cannot be decided by volume");
    }
    std::string message;
    for (const std::string& part : parts)
        message += (message.empty() ? "" : "; ") + part;
    return message;
}

} // namespace contour
