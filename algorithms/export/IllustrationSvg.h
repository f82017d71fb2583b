#pragma once
// The illustration drawing of a snapshot: the view graph's visible chains
// as strokes, the way the tutorial's stylization pipeline draws them
// (Bénard & Hertzmann 2019 §9.1–9.2), for an illustrator rather than for
// debugging: no node glyphs and no data attributes, one stroke style per
// curve type, hidden lines optional, and tapered ends where a stroke ends
// at a curtain fold or a dead end.
//
// Strokes are chained greedily (§9.1): a stroke continues from a chain to
// the next one of the same curve through a node, stops at curtain folds,
// and at a T-junction only the near curve continues (the far one stops
// against it, untapered). A tapered end narrows linearly to a point over
// taperLength pixels (half the stroke's length at most) and is drawn as a
// filled outline with ribs perpendicular to the stroke (§9.2, skeletal
// strokes); strokes without a tapered end are plain stroked paths.
//
// The document opens in Inkscape with one layer per visibility and curve
// type (inkscape:groupmode="layer"): "Visible lines" holding "Contour",
// "Boundary", "Surface intersection"; and, with drawHidden, "Hidden lines"
// below it (dashed, lighter). Chains simplified away (Bénard 2014 §9) are
// left out. Without a view graph every curve is drawn in the visible layer,
// and the <desc> says that no visibility was computed.
#include "camera/Camera.h"
#include "pipeline/Snapshot.h"

#include <string>
#include <vector>

namespace contour {

struct IllustrationStrokeStyle {
    std::string colour;
    double width = 1.0; // pixels
};

struct IllustrationOptions {
    std::string title; // written as <title> when not empty
    bool background = false;
    bool drawHidden = false;
    IllustrationStrokeStyle contour{"#000000", 2.0};
    IllustrationStrokeStyle boundary{"#000000", 1.5};
    IllustrationStrokeStyle surfaceIntersection{"#000000", 1.0};
    std::string hiddenColour = "#8c8c8c";
    double hiddenWidthScale = 0.5; // hidden strokes' width, times the visible one
    double taperLength = 12.0;     // pixels; 0: no tapering
    double minSpacing = 0.5;       // pixels: closer points of a stroke are merged (§9.1)

    const IllustrationStrokeStyle& style(CurveType type) const;
};

// One stroke: chains joined through nodes, in pixels.
struct IllustrationStroke {
    CurveType type = CurveType::Contour;
    bool hidden = false;
    bool closed = false;
    std::vector<Vec2> points;
    bool taperStart = false, taperEnd = false;
    std::vector<Index> chains; // ViewGraph::chains drawn by this stroke, in order
};

// The strokes of the document, visible ones first (hidden ones only with
// drawHidden).
std::vector<IllustrationStroke> illustrationStrokes(const Snapshot& snapshot, const Camera& camera,
                                                    const IllustrationOptions& options = {});

// A tapered stroke's outline: the left ribs' ends forward, then the right
// ones back (a closed polygon); the width at each point is the style's
// width narrowed linearly to 0 over the taper length at each tapered end.
std::vector<Vec2> strokeOutline(const IllustrationStroke& stroke, double width, double taperLength);

std::string illustrationSvgDocument(const Snapshot& snapshot, const Camera& camera,
                                    const IllustrationOptions& options = {});

// Writes illustrationSvgDocument() to `path` atomically. Throws
// std::runtime_error naming the file on failure.
void writeIllustrationSvg(const std::string& path, const Snapshot& snapshot, const Camera& camera,
                          const IllustrationOptions& options = {});

} // namespace contour
