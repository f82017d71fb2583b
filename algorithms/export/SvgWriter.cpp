#include "export/SvgWriter.h"

#include "io/AtomicFile.h"
#include "export/ProjectedCurves.h"

#include <array>
#include <charconv>

namespace contour {

namespace {

void appendNumber(std::string& out, double x) {
    std::array<char, 64> buffer{};
    const auto result =
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), x, std::chars_format::fixed, 3);
    out.append(buffer.data(), result.ptr);
}

std::string escapeXml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

const char* strokeColour(CurveType type) {
    switch (type) {
    case CurveType::Contour:
        return "#000000";
    case CurveType::Boundary:
        return "#1f77b4";
    case CurveType::SurfaceIntersection:
        return "#d62728";
    }
    return "#7f7f7f";
}

void appendGroup(std::string& out, CurveType type, const std::vector<ProjectedPolyline>& curves,
                 const SvgOptions& options) {
    out += "  <g id=\"";
    out += toString(type);
    out += "\" fill=\"none\" stroke=\"";
    out += strokeColour(type);
    out += "\" stroke-width=\"";
    appendNumber(out, options.strokeWidth);
    out += "\" stroke-linejoin=\"round\" stroke-linecap=\"round\">\n";
    for (const ProjectedPolyline& curve : curves) {
        if (curve.type != type)
            continue;
        for (size_t part = 0; part < curve.pieces.size(); ++part) {
            out += "    <polyline data-index=\"" + std::to_string(curve.index) + "\" data-type=\"" +
                   toString(type) + "\" data-closed=\"" + (curve.closed ? "true" : "false") +
                   "\" data-points=\"" + std::to_string(curve.pointCount) + "\"";
            if (curve.clipped())
                out += " data-part=\"" + std::to_string(part) + "\" class=\"clipped\"";
            out += " points=\"";
            bool first = true;
            for (const Vec2& p : curve.pieces[part]) {
                if (!first)
                    out += ' ';
                first = false;
                appendNumber(out, p.x());
                out += ',';
                appendNumber(out, p.y());
            }
            out += "\"/>\n";
        }
    }
    out += "  </g>\n";
}

} // namespace

std::string svgDocument(const Snapshot& snapshot, const Camera& camera, const SvgOptions& options) {
    static const std::vector<Polyline> none;
    const std::vector<Polyline>& curves = snapshot.curves ? *snapshot.curves : none;
    const std::vector<ProjectedPolyline> projected = projectCurves(curves, camera);
    const std::string w = std::to_string(camera.viewport.width);
    const std::string h = std::to_string(camera.viewport.height);

    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + w +
           "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
    if (!options.title.empty())
        out += "  <title>" + escapeXml(options.title) + "</title>\n";
    out += "  <desc>phase " + escapeXml(snapshot.phaseName) + "; " + std::to_string(curves.size()) +
           " curves</desc>\n";
    if (options.background)
        out += "  <rect id=\"background\" x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h +
               "\" fill=\"#ffffff\"/>\n";
    appendGroup(out, CurveType::Contour, projected, options);
    appendGroup(out, CurveType::Boundary, projected, options);
    bool intersections = false;
    for (const ProjectedPolyline& curve : projected)
        intersections = intersections || curve.type == CurveType::SurfaceIntersection;
    if (intersections)
        appendGroup(out, CurveType::SurfaceIntersection, projected, options);
    out += "</svg>\n";
    return out;
}

void writeSvg(const std::string& path, const Snapshot& snapshot, const Camera& camera,
              const SvgOptions& options) {
    writeFileAtomically(path, svgDocument(snapshot, camera, options));
}

} // namespace contour
