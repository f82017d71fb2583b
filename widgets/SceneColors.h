#pragma once
// The colours the views use, in one place so that tests can look for them in
// grabbed images. Faces are coloured by the face field fields::kFacing or
// fields::kVbo (the two facing colours differ in hue, yellow against blue,
// which survives shading because lighting only scales a colour) or by a
// signed scalar field.
#include <QColor>

namespace contour {

struct SceneColor {
    double r, g, b; // in [0, 1]

    QColor toQColor() const {
        return QColor::fromRgbF(static_cast<float>(r), static_cast<float>(g),
                                static_cast<float>(b));
    }
};

namespace sceneColors {

inline constexpr SceneColor kFrontFace{1.00, 0.84, 0.42};        // warm light yellow, hue ~43°
inline constexpr SceneColor kBackFace{0.22, 0.42, 0.95};         // blue, hue ~224°
inline constexpr SceneColor kEdgeOnFace{0.55, 0.55, 0.55};       // facing 0 (not generic)
inline constexpr SceneColor kUnclassifiedFace{0.78, 0.78, 0.78}; // no facing field yet
inline constexpr SceneColor kContour3D{0.90, 0.08, 0.08};        // red
inline constexpr SceneColor kContour2D{0.0, 0.0, 0.0};           // black on the white image
inline constexpr SceneColor kBoundary{0.10, 0.70, 0.25};         // green
inline constexpr SceneColor kIntersection{0.85, 0.20, 0.85};     // magenta
inline constexpr SceneColor kFrustum{0.92, 0.92, 0.92};          // light grey
inline constexpr SceneColor kControlCage{0.10, 0.10, 0.10};      // near black wireframe
// Consistent contours (Bénard 2014). Faces coloured by VBO use the facing
// colours for F and B and this green for an undefined VBO.
inline constexpr SceneColor kUndefinedVbo{0.25, 0.85, 0.15}; // green, hue ~109°
// Overlays: outlines of inconsistent faces (drawn over everything), tints of
// radial and standard radial triangles (translucent, kRadialTintOpacity),
// radial edges, contour (C) vertices as round dots, cusps as large squares.
inline constexpr SceneColor kInconsistentOutline{1.0, 0.0, 1.0};   // magenta, hue 300°
inline constexpr SceneColor kRadialTint{1.0, 0.50, 0.05};          // orange, hue ~28°
inline constexpr SceneColor kStandardRadialTint{0.10, 0.70, 0.65}; // teal, hue ~177°
inline constexpr double kRadialTintOpacity = 0.6;
// Method comparison in the 2D view: the other method's curves thin in blue;
// the parts only one method draws under wide translucent highlights, red
// for the window's method (the 2D view draws nothing else red; T-junctions
// are orange), blue for the other.
inline constexpr SceneColor kComparisonOther{0.15, 0.45, 0.95};    // blue, hue ~219°
inline constexpr SceneColor kComparisonOnlyHere{0.90, 0.10, 0.10}; // red, hue 0°
inline constexpr double kComparisonHighlightOpacity = 0.45;
inline constexpr SceneColor kRadialEdge{0.12, 0.12, 0.12}; // charcoal
inline constexpr SceneColor kContourVertex{1.0, 1.0, 1.0}; // white
inline constexpr SceneColor kCuspVertex{0.0, 0.90, 1.0};   // cyan, hue ~186°
inline constexpr double kInconsistentOutlineWidth = 3.0;   // pixels
inline constexpr double kRadialEdgeWidth = 2.5;            // pixels
inline constexpr double kContourVertexSize = 7.0;          // pixels
inline constexpr double kCuspVertexSize = 15.0;            // pixels
// Linked selection (Selection.h): the selected face, vertex, edge or chain in
// both views, a lime no other colour of the views is near (hue ~87°), drawn
// unlit over everything in 3D.
inline constexpr SceneColor kSelection{0.55, 1.0, 0.0};
inline constexpr double kSelectionLineWidth = 4.0;  // pixels
inline constexpr double kSelectionPointSize = 14.0; // pixels
// Signed scalar fields (DivergingColorMap.h): Moreland's cool-to-warm end
// colours at -m and +m (the centre, 0, is a light grey, ~0.87), NaN in a
// darker neutral grey. Contours are black over a scalar field, which has red
// in it.
inline constexpr SceneColor kDivergingNegative{0.230, 0.299, 0.754}; // blue, hue ~232°
inline constexpr SceneColor kDivergingPositive{0.706, 0.016, 0.150}; // red, hue ~348°
inline constexpr SceneColor kNanValue{0.40, 0.40, 0.40};
inline constexpr SceneColor kContourOverField{0.0, 0.0, 0.0};
inline constexpr SceneColor kScalarBarText{0.95, 0.95, 0.95};
inline constexpr SceneColor kBackgroundTop{0.30, 0.30, 0.32};
inline constexpr SceneColor kBackgroundBottom{0.10, 0.10, 0.11};

} // namespace sceneColors
} // namespace contour
