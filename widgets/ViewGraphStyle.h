#pragma once
// How the views draw a snapshot's view graph (pipeline/ViewGraph.h; tutorial
// §4.5, Bénard 2014 §8.3): which chains are visible, hidden or hidden by
// topological simplification, their colours (by chain or by quantitative
// invisibility) and one glyph and colour per node type. One place for the 2D
// view, the 3D view and the legends, so that tests can look for the colours in
// grabbed images.
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
inline constexpr std::array<SceneColor, 3> kHiddenQi{
    {{0.45, 0.10, 0.62}, {0.62, 0.36, 0.80}, {0.78, 0.63, 0.90}}};
inline constexpr SceneColor kUnknownQi{0.60, 0.60, 0.60};
// Simplified-away chains, when shown: very faint.
inline constexpr SceneColor kSimplified2D{0.82, 0.82, 0.82};
inline constexpr SceneColor kSimplified3D{0.70, 0.70, 0.70};
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
        return {{0.0, 0.80, 0.95}, NodeGlyph::Square, "curtain fold"};
    case ViewNodeType::BoundaryCurtainFold:
        return {{0.15, 0.75, 0.30}, NodeGlyph::Diamond, "boundary curtain fold"};
    case ViewNodeType::ImageIntersection:
        // Orange, not red: the 3D view's visible contours are red.
        return {{1.0, 0.55, 0.0}, NodeGlyph::TriangleUp, "T-junction"};
    case ViewNodeType::ContourBoundaryJunction:
        return {{0.55, 0.33, 0.10}, NodeGlyph::TriangleDown, "Y junction"};
    case ViewNodeType::Bifurcation:
        return {{1.0, 0.40, 0.70}, NodeGlyph::Circle, "bifurcation"};
    case ViewNodeType::SurfaceIntersectionEnd:
        return {sceneColors::kIntersection, NodeGlyph::Ring, "surface-intersection end"};
    case ViewNodeType::CurveEnd:
        return {{0.25, 0.25, 0.25}, NodeGlyph::Cross, "curve end"};
    case ViewNodeType::HiddenFoldCrossing:
        // A T-junction's glyph in a muted colour: something occludes there,
        // but it is a mesh fold next to inconsistent faces, not a drawn curve.
        return {{0.60, 0.50, 0.40}, NodeGlyph::TriangleUp, "crossing behind a hidden mesh fold"};
    }
    return {{0.5, 0.5, 0.5}, NodeGlyph::Cross, "unknown"};
}

// A node whose chains are all hidden (ViewNodeClass::Hidden) is drawn only
// with the hidden curves.
inline bool nodeIsHidden(const ViewGraph& graph, Index node) {
    return graph.nodeClass(node) == ViewNodeClass::Hidden;
}

} // namespace contour
