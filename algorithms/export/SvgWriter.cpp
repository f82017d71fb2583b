#include "export/SvgWriter.h"

#include "core/AtomicFile.h"
#include "export/ProjectedCurves.h"
#include "export/SvgText.h"
#include "pipeline/ViewGraph.h"

#include <array>
#include <string_view>

namespace contour {

namespace {

void appendPoints(std::string& out, const std::vector<Vec2>& points) {
    out += " points=\"";
    bool first = true;
    for (const Vec2& p : points) {
        if (!first)
            out += ' ';
        first = false;
        appendSvgNumber(out, p.x());
        out += ',';
        appendSvgNumber(out, p.y());
    }
    out += "\"";
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
    appendSvgNumber(out, options.strokeWidth);
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
            appendPoints(out, curve.pieces[part]);
            out += "/>\n";
        }
    }
    out += "  </g>\n";
}

enum class Layer { Visible, Hidden, Simplified };

Layer layerOf(const ViewChain& chain) {
    if (chain.simplifiedAway)
        return Layer::Simplified;
    return chain.qi == 0 ? Layer::Visible : Layer::Hidden;
}

void appendChainLayer(std::string& out, const ViewGraph& graph, const Camera& camera, Layer layer,
                      const SvgOptions& options) {
    const char* id = layer == Layer::Visible  ? "visible"
                     : layer == Layer::Hidden ? "hidden"
                                              : "simplified";
    out += "  <g id=\"";
    out += id;
    out += "\" fill=\"none\" stroke-width=\"";
    appendSvgNumber(out, options.strokeWidth);
    out += "\" stroke-linejoin=\"round\" stroke-linecap=\"round\"";
    if (layer != Layer::Visible) {
        // Hidden lines dashed, a little lighter; simplified ones dotted.
        out += layer == Layer::Hidden ? " stroke-dasharray=\"6 4\" stroke-opacity=\"0.6\""
                                      : " stroke-dasharray=\"1 3\" stroke-opacity=\"0.6\"";
        if (layer == Layer::Simplified || !options.drawHidden)
            out += " display=\"none\"";
    }
    out += ">\n";
    for (const CurveType type :
         {CurveType::Contour, CurveType::Boundary, CurveType::SurfaceIntersection}) {
        bool any = false;
        for (const ViewChain& chain : graph.chains)
            any = any || (chain.type == type && layerOf(chain) == layer);
        if (!any)
            continue;
        out += "    <g id=\"";
        out += id;
        out += '-';
        out += toString(type);
        out += "\" class=\"";
        out += toString(type);
        out += "\" stroke=\"";
        out += strokeColour(type);
        out += "\">\n";
        for (size_t c = 0; c < graph.chains.size(); ++c) {
            const ViewChain& chain = graph.chains[c];
            if (chain.type != type || layerOf(chain) != layer)
                continue;
            const std::vector<std::vector<Vec2>> pieces = projectChain(chain, camera);
            std::string attributes =
                " data-chain=\"" + std::to_string(c) + "\" data-curve=\"" +
                std::to_string(chain.curve) + "\" data-qi=\"" + std::to_string(chain.qi) +
                "\" data-rule=\"" + toString(chain.decidedBy) + "\" data-type=\"" + toString(type) +
                "\" data-closed=\"" + (chain.closed ? "true" : "false") + "\"";
            if (chain.ambiguous)
                attributes += " data-ambiguous=\"true\"";
            if (chain.conflict)
                attributes += " data-conflict=\"true\"";
            if (chain.concave)
                attributes += " data-concave=\"true\"";
            for (size_t part = 0; part < pieces.size(); ++part) {
                out += "      <polyline" + attributes;
                if (pieces.size() > 1 || pieces[part].size() < chain.points.size())
                    out += " data-part=\"" + std::to_string(part) + "\" class=\"clipped\"";
                appendPoints(out, pieces[part]);
                out += "/>\n";
            }
        }
        out += "    </g>\n";
    }
    out += "  </g>\n";
}

const char* nodeColour(ViewNodeType type) {
    switch (type) {
    case ViewNodeType::CurtainFold:
        return "#e41a1c";
    case ViewNodeType::BoundaryCurtainFold:
        return "#ff7f00";
    case ViewNodeType::ImageIntersection:
        return "#377eb8";
    case ViewNodeType::ContourBoundaryJunction:
        return "#4daf4a";
    case ViewNodeType::Bifurcation:
        return "#984ea3";
    case ViewNodeType::SurfaceIntersectionEnd:
        return "#a65628";
    case ViewNodeType::CurveEnd:
        return "#f781bf";
    case ViewNodeType::HiddenFoldCrossing:
        return "#999999";
    }
    return "#7f7f7f";
}

// One marker, centred on the node's pixel; the shape tells the type even in
// grey scale.
void appendMarker(std::string& out, ViewNodeType type, const Vec2& at, double r,
                  const std::string& attributes) {
    auto xy = [&](double dx, double dy) {
        std::string text;
        appendSvgNumber(text, at.x() + dx);
        text += ',';
        appendSvgNumber(text, at.y() + dy);
        return text;
    };
    auto num = [](double x) {
        std::string text;
        appendSvgNumber(text, x);
        return text;
    };
    out += "      ";
    switch (type) {
    case ViewNodeType::CurtainFold:
    case ViewNodeType::SurfaceIntersectionEnd:
        out += "<circle" + attributes + " cx=\"" + num(at.x()) + "\" cy=\"" + num(at.y()) +
               "\" r=\"" + num(r) + "\"/>";
        break;
    case ViewNodeType::BoundaryCurtainFold:
        out += "<polygon" + attributes + " points=\"" + xy(0, -r) + " " + xy(r, 0) + " " +
               xy(0, r) + " " + xy(-r, 0) + "\"/>";
        break;
    case ViewNodeType::ImageIntersection:
    case ViewNodeType::HiddenFoldCrossing:
        out += "<rect" + attributes + " x=\"" + num(at.x() - 0.8 * r) + "\" y=\"" +
               num(at.y() - 0.8 * r) + "\" width=\"" + num(1.6 * r) + "\" height=\"" +
               num(1.6 * r) + "\"/>";
        break;
    case ViewNodeType::ContourBoundaryJunction:
        out += "<polygon" + attributes + " points=\"" + xy(0, -r) + " " + xy(0.87 * r, 0.5 * r) +
               " " + xy(-0.87 * r, 0.5 * r) + "\"/>";
        break;
    case ViewNodeType::Bifurcation:
        out += "<path" + attributes + " d=\"M" + xy(-r, 0) + "H" + num(at.x() + r) + "M" +
               xy(0, -r) + "V" + num(at.y() + r) + "\"/>";
        break;
    case ViewNodeType::CurveEnd:
        out += "<path" + attributes + " d=\"M" + xy(-r, -r) + "L" + xy(r, r) + "M" + xy(-r, r) +
               "L" + xy(r, -r) + "\"/>";
        break;
    }
    out += "\n";
}

void appendNodes(std::string& out, const ViewGraph& graph, const Camera& camera,
                 const SvgOptions& options) {
    out += "  <g id=\"nodes\"";
    if (!options.drawNodes)
        out += " display=\"none\"";
    out += ">\n";
    for (const ViewNodeType type :
         {ViewNodeType::CurtainFold, ViewNodeType::BoundaryCurtainFold,
          ViewNodeType::ImageIntersection, ViewNodeType::ContourBoundaryJunction,
          ViewNodeType::Bifurcation, ViewNodeType::SurfaceIntersectionEnd, ViewNodeType::CurveEnd,
          ViewNodeType::HiddenFoldCrossing}) {
        bool any = false;
        for (const ViewNode& node : graph.nodes)
            any = any || node.type == type;
        if (!any)
            continue;
        const bool stroked = type == ViewNodeType::Bifurcation || type == ViewNodeType::CurveEnd ||
                             type == ViewNodeType::SurfaceIntersectionEnd;
        out += "    <g id=\"nodes-";
        out += toString(type);
        out += "\" class=\"";
        out += toString(type);
        out += "\" ";
        out += stroked ? "fill=\"none\" stroke=\"" : "stroke=\"none\" fill=\"";
        out += nodeColour(type);
        out += stroked ? "\" stroke-width=\"1.5\">\n" : "\">\n";
        for (size_t n = 0; n < graph.nodes.size(); ++n) {
            const ViewNode& node = graph.nodes[n];
            if (node.type != type)
                continue;
            const ProjectedPoint p = camera.project(node.position);
            if (!((camera.isOrthographic() || p.depth > 0.0) && p.pixel.allFinite()))
                continue; // behind the eye: no pixel to mark
            const std::string attributes = " data-node=\"" + std::to_string(n) + "\" data-type=\"" +
                                           toString(type) + "\" data-class=\"" +
                                           toString(graph.nodeClass(static_cast<Index>(n))) + "\"";
            appendMarker(out, type, p.pixel, options.markerSize, attributes);
        }
        out += "    </g>\n";
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
           " curves";
    if (snapshot.viewGraph) {
        const ViewGraph& graph = *snapshot.viewGraph;
        const ViewChainTally tally = graph.chainTally();
        out += "; view graph: " + std::to_string(graph.chains.size()) + " chains (" +
               std::to_string(tally.visible) + " visible, " + std::to_string(tally.simplified) +
               " simplified away), " + std::to_string(graph.nodes.size()) + " nodes, " +
               std::to_string(graph.conflicts.size()) + " conflicts";
    }
    out += "</desc>\n";
    if (options.background)
        out += "  <rect id=\"background\" x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h +
               "\" fill=\"#ffffff\"/>\n";
    if (snapshot.viewGraph) {
        const ViewGraph& graph = *snapshot.viewGraph;
        appendChainLayer(out, graph, camera, Layer::Hidden, options);
        appendChainLayer(out, graph, camera, Layer::Simplified, options);
        appendChainLayer(out, graph, camera, Layer::Visible, options);
        appendNodes(out, graph, camera, options);
        out += "</svg>\n";
        return out;
    }
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
