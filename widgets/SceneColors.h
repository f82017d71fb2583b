#pragma once
// The colours the views use, in one place so that tests can look for them in
// grabbed images. Faces are coloured by the face field fields::kFacing or
// fields::kVbo (the two facing colours differ in hue, yellow against blue,
// which survives shading because lighting only scales a colour) or by a
// signed scalar field. The colours themselves are data of the application:
// resources/colormaps/scene-colors.json (the views' colours) and
// diverging.json (the end and NaN colours of the diverging map), read by
// loadSceneColors(); the sizes and opacities below are part of the drawing.
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

extern const SceneColor& kFrontFace;
extern const SceneColor& kBackFace;
extern const SceneColor& kEdgeOnFace;
extern const SceneColor& kUnclassifiedFace;
extern const SceneColor& kContour3D;
extern const SceneColor& kContour2D;
extern const SceneColor& kBoundary;
extern const SceneColor& kIntersection;
extern const SceneColor& kFrustum;
extern const SceneColor& kControlCage;
// Consistent contours (Bénard 2014). Faces coloured by VBO use the facing
// colours for F and B and this green for an undefined VBO.
extern const SceneColor& kUndefinedVbo;
// Overlays: outlines of inconsistent faces (drawn over everything), tints of
// radial and standard radial triangles (translucent, kRadialTintOpacity),
// radial edges, contour (C) vertices as round dots, cusps as large squares.
extern const SceneColor& kInconsistentOutline;
extern const SceneColor& kRadialTint;
extern const SceneColor& kStandardRadialTint;
inline constexpr double kRadialTintOpacity = 0.6;
// Method comparison in the 2D view: the other method's curves thin in blue;
// the parts only one method draws under wide translucent highlights, red
// for the window's method (the 2D view draws nothing else red; T-junctions
// are orange), blue for the other.
extern const SceneColor& kComparisonOther;
extern const SceneColor& kComparisonOnlyHere;
inline constexpr double kComparisonHighlightOpacity = 0.45;
// The dense ground truth of the smooth contour (reference/DenseGroundTruth.h),
// when its toggle is on: thin teal lines in both views (hue ~172°, away from
// the black, purple and cyan of the drawing and from the facing colours),
// its cusps as teal rings in 2D (around the method's cusp glyph where they
// agree) and small dots in 3D.
extern const SceneColor& kGroundTruth;
inline constexpr double kGroundTruthLineWidth2D = 1.25; // pixels
inline constexpr double kGroundTruthLineWidth3D = 2.0;  // pixels
inline constexpr double kGroundTruthCuspSize2D = 13.0;  // pixels, around a 9 px fold glyph
inline constexpr double kGroundTruthCuspSize3D = 8.0;   // pixels
extern const SceneColor& kRadialEdge;
extern const SceneColor& kContourVertex;
extern const SceneColor& kCuspVertex;
// The Powell-Sabin spline: patch boundaries light grey, macro-patch
// boundaries (the layout's edges) charcoal, the cut magenta; cones black dots.
extern const SceneColor& kPatchEdge;
extern const SceneColor& kMacroPatchEdge;
extern const SceneColor& kCutEdge;
extern const SceneColor& kCone;
inline constexpr double kPatchEdgeWidth = 1.5; // pixels
inline constexpr double kConeSize = 11.0;      // pixels
inline constexpr double kInconsistentOutlineWidth = 3.0; // pixels
inline constexpr double kRadialEdgeWidth = 2.5;          // pixels
inline constexpr double kContourVertexSize = 7.0;        // pixels
inline constexpr double kCuspVertexSize = 15.0;          // pixels
// Linked selection (Selection.h): the selected face, vertex, edge or chain in
// both views, a lime no other colour of the views is near (hue ~87°), drawn
// unlit over everything in 3D.
extern const SceneColor& kSelection;
inline constexpr double kSelectionLineWidth = 4.0;  // pixels
inline constexpr double kSelectionPointSize = 14.0; // pixels
// Signed scalar fields (DivergingColorMap.h): Moreland's cool-to-warm end
// colours at -m and +m (the centre, 0, is a light grey, ~0.87), NaN in a
// darker neutral grey. Contours are black over a scalar field, which has red
// in it.
extern const SceneColor& kDivergingNegative;
extern const SceneColor& kDivergingPositive;
extern const SceneColor& kNanValue;
extern const SceneColor& kContourOverField;
extern const SceneColor& kScalarBarText;
extern const SceneColor& kBackgroundTop;
extern const SceneColor& kBackgroundBottom;

} // namespace sceneColors

// Reads the colours above, and the view graph's (ViewGraphStyle.h), from
// the compiled-in resources (once; later calls return at once). It runs when
// the QCoreApplication is constructed, and every widget calls it before it
// uses a colour. A resource that is missing or lacks a colour stops the
// program with a message naming it, since the resources are part of the
// build.
void loadSceneColors();

} // namespace contour
