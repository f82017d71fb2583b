#include "export/IllustrationSvg.h"

#include "core/AtomicFile.h"
#include "export/ProjectedCurves.h"
#include "export/SvgText.h"
#include "pipeline/ViewGraph.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace contour {

const IllustrationStrokeStyle& IllustrationOptions::style(CurveType type) const {
    switch (type) {
    case CurveType::Boundary:
        return boundary;
    case CurveType::SurfaceIntersection:
        return surfaceIntersection;
    case CurveType::Contour:
        break;
    }
    return contour;
}

namespace {

bool stopsStrokes(ViewNodeType type) {
    // §9.1: a chain stops at a curtain-fold cusp.
    return type == ViewNodeType::CurtainFold || type == ViewNodeType::BoundaryCurtainFold;
}

// The chains of one layer (visible or hidden) joined into strokes.
class StrokeChaining {
public:
    StrokeChaining(const ViewGraph& graph, const Camera& camera, bool hidden)
        : graph_(graph), hidden_(hidden), used_(graph.chains.size(), 0),
          pieces_(graph.chains.size()) {
        for (size_t c = 0; c < graph.chains.size(); ++c)
            if (inLayer(graph.chains[c]))
                pieces_[c] = projectChain(graph.chains[c], camera);
    }

    std::vector<IllustrationStroke> strokes() {
        std::vector<IllustrationStroke> out;
        for (size_t c = 0; c < graph_.chains.size(); ++c) {
            const ViewChain& chain = graph_.chains[c];
            if (used_[c] || !inLayer(chain) || pieces_[c].empty())
                continue;
            used_[c] = 1;
            if (!whole(static_cast<Index>(c))) {
                // Cut by a perspective eye: each piece alone, ends untapered.
                for (const std::vector<Vec2>& piece : pieces_[c])
                    out.push_back(stroke(chain.type, piece, {static_cast<Index>(c)}));
                continue;
            }
            IllustrationStroke s = stroke(chain.type, pieces_[c].front(), {static_cast<Index>(c)});
            if (chain.closed) {
                s.closed = true;
                out.push_back(std::move(s));
                continue;
            }
            Index start = chain.startNode, end = chain.endNode;
            extend(s, static_cast<Index>(c), end, false);
            if (end == start && start != kInvalidIndex && s.chains.size() > 1 &&
                joins(start, s.chains.back(), s.chains.front())) {
                s.closed = true; // the walk came back to where it began
            } else {
                extend(s, static_cast<Index>(c), start, true);
                s.taperStart = tapers(start);
                s.taperEnd = tapers(end);
            }
            out.push_back(std::move(s));
        }
        return out;
    }

private:
    bool inLayer(const ViewChain& chain) const {
        if (chain.simplifiedAway)
            return false;
        return hidden_ ? chain.qi != 0 : chain.qi == 0;
    }

    bool whole(Index c) const {
        return pieces_[c].size() == 1 &&
               pieces_[c].front().size() == graph_.chains[static_cast<size_t>(c)].points.size();
    }

    IllustrationStroke stroke(CurveType type, const std::vector<Vec2>& points,
                              std::vector<Index> chains) const {
        IllustrationStroke s;
        s.type = type;
        s.hidden = hidden_;
        s.points = points;
        s.chains = std::move(chains);
        return s;
    }

    // May a stroke go on from chain `from` to chain `to` through `node`?
    bool joins(Index node, Index from, Index to) const {
        const ViewNode& n = graph_.nodes[static_cast<size_t>(node)];
        if (stopsStrokes(n.type))
            return false;
        const ViewChain &a = graph_.chains[static_cast<size_t>(from)],
                        &b = graph_.chains[static_cast<size_t>(to)];
        if (a.type != b.type || a.curve != b.curve)
            return false;
        if (n.type == ViewNodeType::ImageIntersection) {
            // §9.1: at a T-junction only the near (foreground) curve goes on.
            const auto near = [&](Index c) {
                return c == n.nearChains[0] || c == n.nearChains[1];
            };
            return near(from) && near(to);
        }
        return true;
    }

    // Follows the chains from `node` (an end of the stroke's chain `last`),
    // appending (or, atFront, prepending) their points; `node` becomes the
    // stroke's new end there.
    void extend(IllustrationStroke& s, Index last, Index& node, bool atFront) {
        while (node != kInvalidIndex) {
            Index next = kInvalidIndex;
            for (const Index c : graph_.nodes[static_cast<size_t>(node)].chains)
                if (!used_[static_cast<size_t>(c)] &&
                    inLayer(graph_.chains[static_cast<size_t>(c)]) && whole(c) &&
                    joins(node, last, c)) {
                    next = c;
                    break;
                }
            if (next == kInvalidIndex)
                return;
            used_[static_cast<size_t>(next)] = 1;
            const ViewChain& chain = graph_.chains[static_cast<size_t>(next)];
            std::vector<Vec2> points = pieces_[static_cast<size_t>(next)].front();
            // Oriented to leave `node`: forward when the chain starts there.
            if (chain.startNode != node)
                std::reverse(points.begin(), points.end());
            if (atFront) {
                std::reverse(points.begin(), points.end());
                s.points.insert(s.points.begin(), points.begin(), points.end() - 1);
                s.chains.insert(s.chains.begin(), next);
            } else {
                s.points.insert(s.points.end(), points.begin() + 1, points.end());
                s.chains.push_back(next);
            }
            node = chain.startNode == node ? chain.endNode : chain.startNode;
            last = next;
        }
    }

    // A stroke's end tapers at a curtain fold and at a dead end (one chain
    // of the layer ends there: a visible cusp, an open end).
    bool tapers(Index node) const {
        if (node == kInvalidIndex)
            return false;
        const ViewNode& n = graph_.nodes[static_cast<size_t>(node)];
        if (stopsStrokes(n.type) || n.type == ViewNodeType::CurveEnd)
            return true;
        int ends = 0;
        for (const Index c : n.chains)
            ends += inLayer(graph_.chains[static_cast<size_t>(c)]) ? 1 : 0;
        return ends == 1;
    }

    const ViewGraph& graph_;
    bool hidden_;
    std::vector<char> used_;
    std::vector<std::vector<std::vector<Vec2>>> pieces_;
};

// Points closer than `spacing` to the last one kept are merged (§9.1's
// smoothing step keeps no control points closer than about 2 px); the last
// point is kept.
void thin(std::vector<Vec2>& points, double spacing) {
    if (points.size() < 3 || !(spacing > 0.0))
        return;
    std::vector<Vec2> out{points.front()};
    for (size_t i = 1; i + 1 < points.size(); ++i)
        if ((points[i] - out.back()).norm() >= spacing)
            out.push_back(points[i]);
    if ((points.back() - out.back()).norm() < spacing && out.size() > 1)
        out.back() = points.back();
    else
        out.push_back(points.back());
    points = std::move(out);
}

std::string pathData(const std::vector<Vec2>& points, bool close) {
    std::string d;
    for (size_t i = 0; i < points.size(); ++i) {
        d += i == 0 ? 'M' : 'L';
        appendSvgNumber(d, points[i].x());
        d += ',';
        appendSvgNumber(d, points[i].y());
    }
    if (close)
        d += 'Z';
    return d;
}

const char* layerLabel(CurveType type) {
    switch (type) {
    case CurveType::Boundary:
        return "Boundary";
    case CurveType::SurfaceIntersection:
        return "Surface intersection";
    case CurveType::Contour:
        break;
    }
    return "Contour";
}

void appendLayer(std::string& out, const std::vector<IllustrationStroke>& strokes, bool hidden,
                 const IllustrationOptions& options) {
    out += hidden ? "  <g id=\"hidden\" inkscape:groupmode=\"layer\" inkscape:label=\"Hidden "
                    "lines\">\n"
                  : "  <g id=\"visible\" inkscape:groupmode=\"layer\" inkscape:label=\"Visible "
                    "lines\">\n";
    for (const CurveType type :
         {CurveType::Contour, CurveType::Boundary, CurveType::SurfaceIntersection}) {
        const bool any = std::any_of(strokes.begin(), strokes.end(), [&](const auto& s) {
            return s.type == type && s.hidden == hidden;
        });
        if (!any)
            continue;
        const IllustrationStrokeStyle& style = options.style(type);
        const std::string colour = hidden ? options.hiddenColour : style.colour;
        const double width = hidden ? style.width * options.hiddenWidthScale : style.width;
        out += "    <g id=\"";
        out += hidden ? "hidden-" : "visible-";
        out += toString(type);
        out += "\" inkscape:groupmode=\"layer\" inkscape:label=\"";
        std::string label = layerLabel(type);
        if (hidden) {
            label[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(label[0])));
            label = "Hidden " + label;
        }
        out += label;
        out += "\" fill=\"none\" stroke=\"" + escapeXml(colour) + "\" stroke-width=\"";
        appendSvgNumber(out, width);
        out += "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
        if (hidden) {
            std::string dash;
            appendSvgNumber(dash, 4.0 * std::max(width, 0.5));
            dash += ' ';
            appendSvgNumber(dash, 3.0 * std::max(width, 0.5));
            out += " stroke-dasharray=\"" + dash + "\"";
        }
        out += ">\n";
        for (const IllustrationStroke& s : strokes) {
            if (s.type != type || s.hidden != hidden)
                continue;
            const bool tapered = !hidden && options.taperLength > 0.0 &&
                                 (s.taperStart || s.taperEnd) && s.points.size() >= 2;
            if (tapered)
                out += "      <path class=\"tapered\" fill=\"" + escapeXml(colour) +
                       "\" stroke=\"none\" d=\"" +
                       pathData(strokeOutline(s, width, options.taperLength), true) + "\"/>\n";
            else
                out += "      <path d=\"" + pathData(s.points, s.closed) + "\"/>\n";
        }
        out += "    </g>\n";
    }
    out += "  </g>\n";
}

} // namespace

std::vector<IllustrationStroke> illustrationStrokes(const Snapshot& snapshot, const Camera& camera,
                                                    const IllustrationOptions& options) {
    std::vector<IllustrationStroke> out;
    if (snapshot.viewGraph) {
        out = StrokeChaining(*snapshot.viewGraph, camera, false).strokes();
        if (options.drawHidden) {
            std::vector<IllustrationStroke> hidden =
                StrokeChaining(*snapshot.viewGraph, camera, true).strokes();
            out.insert(out.end(), hidden.begin(), hidden.end());
        }
    } else if (snapshot.curves) {
        for (const ProjectedPolyline& curve : projectCurves(*snapshot.curves, camera))
            for (const std::vector<Vec2>& piece : curve.pieces) {
                IllustrationStroke s;
                s.type = curve.type;
                s.points = piece;
                s.closed = curve.closed && !curve.clipped();
                // An open curve's ends are dead ends; a piece cut by the eye
                // is not.
                s.taperStart = s.taperEnd = !curve.closed && !curve.clipped();
                out.push_back(std::move(s));
            }
    }
    for (IllustrationStroke& s : out)
        thin(s.points, options.minSpacing);
    return out;
}

std::vector<Vec2> strokeOutline(const IllustrationStroke& stroke, double width,
                                double taperLength) {
    const std::vector<Vec2>& p = stroke.points;
    const size_t n = p.size();
    if (n < 2)
        return p;
    std::vector<double> along(n, 0.0);
    for (size_t i = 1; i < n; ++i)
        along[i] = along[i - 1] + (p[i] - p[i - 1]).norm();
    const double length = along.back();
    const int tapered = (stroke.taperStart ? 1 : 0) + (stroke.taperEnd ? 1 : 0);
    const double taper = tapered == 0 ? 0.0 : std::min(taperLength, length / tapered);
    std::vector<Vec2> left(n), right(n);
    for (size_t i = 0; i < n; ++i) {
        double f = 1.0;
        if (taper > 0.0 && stroke.taperStart)
            f = std::min(f, along[i] / taper);
        if (taper > 0.0 && stroke.taperEnd)
            f = std::min(f, (length - along[i]) / taper);
        // Rib direction (§9.2): R90 times the central difference.
        Vec2 t = p[std::min(i + 1, n - 1)] - p[i == 0 ? 0 : i - 1];
        const double norm = t.norm();
        t = norm > 0.0 ? Vec2(t / norm) : Vec2(1.0, 0.0);
        const Vec2 rib = 0.5 * width * std::max(0.0, f) * Vec2(-t.y(), t.x());
        left[i] = p[i] + rib;
        right[i] = p[i] - rib;
    }
    std::vector<Vec2> outline = left;
    outline.insert(outline.end(), right.rbegin(), right.rend());
    return outline;
}

std::string illustrationSvgDocument(const Snapshot& snapshot, const Camera& camera,
                                    const IllustrationOptions& options) {
    const std::vector<IllustrationStroke> strokes = illustrationStrokes(snapshot, camera, options);
    const std::string w = std::to_string(camera.viewport.width);
    const std::string h = std::to_string(camera.viewport.height);
    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out +=
        "<svg xmlns=\"http://www.w3.org/2000/svg\" "
        "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" version=\"1.1\" width=\"" +
        w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
    if (!options.title.empty())
        out += "  <title>" + escapeXml(options.title) + "</title>\n";
    long long visible = 0, hidden = 0, tapers = 0;
    for (const IllustrationStroke& s : strokes) {
        (s.hidden ? hidden : visible) += 1;
        tapers += s.hidden ? 0 : (s.taperStart ? 1 : 0) + (s.taperEnd ? 1 : 0);
    }
    out += "  <desc>illustration of phase " + escapeXml(snapshot.phaseName) + ": " +
           std::to_string(visible) + " visible strokes, " + std::to_string(tapers) +
           " tapered ends" +
           (options.drawHidden ? ", " + std::to_string(hidden) + " hidden strokes" : "") +
           (snapshot.viewGraph ? "" : "; no visibility computed: every curve drawn as visible") +
           "</desc>\n";
    if (options.background)
        out += "  <rect id=\"background\" x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h +
               "\" fill=\"#ffffff\"/>\n";
    if (options.drawHidden)
        appendLayer(out, strokes, true, options);
    appendLayer(out, strokes, false, options);
    out += "</svg>\n";
    return out;
}

void writeIllustrationSvg(const std::string& path, const Snapshot& snapshot, const Camera& camera,
                          const IllustrationOptions& options) {
    writeFileAtomically(path, illustrationSvgDocument(snapshot, camera, options));
}

} // namespace contour
