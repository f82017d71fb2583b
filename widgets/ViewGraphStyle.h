#pragma once
// How the views draw a snapshot's view graph (pipeline/ViewGraph.h; tutorial
// §4.5, Bénard 2014 §8.3): which chains are visible, hidden or hidden by
// topological simplification, their colours (by chain or by quantitative
// invisibility) and one glyph and colour per node type. One place for the 2D
// view, the 3D view and the legends, so that tests can look for the colours in
// grabbed images. The colours are data of the application,
// resources/colormaps/view-graph-colors.json, read by loadSceneColors()
// (SceneColors.h) with the scene's colours.
#include "SceneColors.h"
#include "pipeline/ViewGraph.h"

#include <array>
#include <cmath>

namespace contour {

enum class ChainColoring {
    ByQi,    // QI 0 in the visible-curve colour, 1, 2, 3+ on a small sequential palette
    ByChain, // one hue per chain index (neighbouring indices far apart)
};

// A chain as the views see it. A chain with QI 0 that simplification hid
// (Bénard 2014 §9, ViewChain::simplifiedAway) is neither visible nor an
// occluded curve: the views leave it out unless asked. A chain whose QI is
// still unknown (-1) is drawn with the hidden ones, in its own colour.
enum class ChainState { Visible, Hidden, Simplified };

inline ChainState chainState(const ViewChain& chain) {
    if (chain.qi == 0)
        return chain.simplifiedAway ? ChainState::Simplified : ChainState::Visible;
    return ChainState::Hidden;
}

namespace viewGraphColors {

// QI 1, 2 and 3+: purple, light to lighter (hue ~280°, away from the facing
// colours yellow and blue and from the black or red of visible curves).
extern const std::array<SceneColor, 3>& kHiddenQi;
extern const SceneColor& kUnknownQi;
// Simplified-away chains, when shown: very faint.
extern const SceneColor& kSimplified2D;
extern const SceneColor& kSimplified3D;
// One colour per node type (nodeStyle below).
extern const SceneColor& kCurtainFold;
extern const SceneColor& kBoundaryCurtainFold;
extern const SceneColor& kTJunction;
extern const SceneColor& kYJunction;
extern const SceneColor& kBifurcation;
extern const SceneColor& kCurveEnd;
extern const SceneColor& kHiddenFoldCrossing;
extern const SceneColor& kUnknownNode;
// Hidden chains coloured by chain in 3D: the chain's colour scaled by this.
inline constexpr double kHiddenDarken = 0.55;

} // namespace viewGraphColors

// QI colour: 0 is `visible` (black in the 2D image, the contour colour in 3D).
inline SceneColor qiColor(int qi, const SceneColor& visible) {
    if (qi < 0)
        return viewGraphColors::kUnknownQi;
    if (qi == 0)
        return visible;
    return viewGraphColors::kHiddenQi[static_cast<size_t>(std::min(qi, 3) - 1)];
}

// Chain colours: hues stepped by the golden ratio, so consecutive chains
// (usually neighbours on a curve) get far-apart hues.
inline SceneColor chainColor(Index chain) {
    const double hue = std::fmod(0.08 + 0.6180339887498949 * static_cast<double>(chain), 1.0);
    const QColor c = QColor::fromHsvF(static_cast<float>(hue), 0.85f, 0.88f);
    return {c.redF(), c.greenF(), c.blueF()};
}

enum class NodeGlyph { Square, Diamond, TriangleUp, TriangleDown, Circle, Ring, Cross };

struct NodeStyle {
    SceneColor color;
    NodeGlyph glyph; // 2D; the 3D view draws every node as a round dot of its colour
    const char* label;
};

inline constexpr int kViewNodeTypeCount = 8;

inline NodeStyle nodeStyle(ViewNodeType type) {
    switch (type) {
    case ViewNodeType::CurtainFold:
        return {viewGraphColors::kCurtainFold, NodeGlyph::Square, "curtain fold"};
    case ViewNodeType::BoundaryCurtainFold:
        return {viewGraphColors::kBoundaryCurtainFold, NodeGlyph::Diamond, "boundary curtain fold"};
    case ViewNodeType::ImageIntersection:
        // Orange, not red: the 3D view's visible contours are red.
        return {viewGraphColors::kTJunction, NodeGlyph::TriangleUp, "T-junction"};
    case ViewNodeType::ContourBoundaryJunction:
        return {viewGraphColors::kYJunction, NodeGlyph::TriangleDown, "Y junction"};
    case ViewNodeType::Bifurcation:
        return {viewGraphColors::kBifurcation, NodeGlyph::Circle, "bifurcation"};
    case ViewNodeType::SurfaceIntersectionEnd:
        return {sceneColors::kIntersection, NodeGlyph::Ring, "surface-intersection end"};
    case ViewNodeType::CurveEnd:
        return {viewGraphColors::kCurveEnd, NodeGlyph::Cross, "curve end"};
    case ViewNodeType::HiddenFoldCrossing:
        // A T-junction's glyph in a muted colour: something occludes there,
        // but it is a mesh fold next to inconsistent faces, not a drawn curve.
        return {viewGraphColors::kHiddenFoldCrossing, NodeGlyph::TriangleUp,
                "crossing behind a hidden mesh fold"};
    }
    return {viewGraphColors::kUnknownNode, NodeGlyph::Cross, "unknown"};
}

// A node whose chains are all hidden (ViewNodeClass::Hidden) is drawn only
// with the hidden curves.
inline bool nodeIsHidden(const ViewGraph& graph, Index node) {
    return graph.nodeClass(node) == ViewNodeClass::Hidden;
}

} // namespace contour
