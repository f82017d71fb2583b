#include "SceneColors.h"

#include "Resources.h"
#include "ViewGraphStyle.h"

#include <QCoreApplication>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QString>
#include <mutex>

namespace contour {

namespace {

// Filled by loadSceneColors(); until then every colour is black.
struct Palette {
    SceneColor frontFace{}, backFace{}, edgeOnFace{}, unclassifiedFace{}, contour3D{}, contour2D{},
        boundary{}, intersection{}, frustum{}, controlCage{}, undefinedVbo{}, inconsistentOutline{},
        radialTint{}, standardRadialTint{}, comparisonOther{}, comparisonOnlyHere{}, groundTruth{},
        radialEdge{}, contourVertex{}, cuspVertex{}, patchEdge{}, macroPatchEdge{}, cutEdge{}, cone{}, selection{}, divergingNegative{},
        divergingPositive{}, nanValue{}, contourOverField{}, scalarBarText{}, backgroundTop{},
        backgroundBottom{};
};
Palette palette;

// The view graph's colours (ViewGraphStyle.h), filled by loadSceneColors().
struct ViewGraphPalette {
    std::array<SceneColor, 3> hiddenQi{};
    SceneColor unknownQi{}, simplified2D{}, simplified3D{}, curtainFold{}, boundaryCurtainFold{},
        tJunction{}, yJunction{}, bifurcation{}, curveEnd{}, hiddenFoldCrossing{}, unknownNode{};
};
ViewGraphPalette viewGraphPalette;

// The keys of resources/colormaps/scene-colors.json.
const std::pair<const char*, SceneColor*> kSceneKeys[] = {
    {"front-face", &palette.frontFace},
    {"back-face", &palette.backFace},
    {"edge-on-face", &palette.edgeOnFace},
    {"unclassified-face", &palette.unclassifiedFace},
    {"contour-3d", &palette.contour3D},
    {"contour-2d", &palette.contour2D},
    {"boundary", &palette.boundary},
    {"intersection", &palette.intersection},
    {"frustum", &palette.frustum},
    {"control-cage", &palette.controlCage},
    {"undefined-vbo", &palette.undefinedVbo},
    {"inconsistent-outline", &palette.inconsistentOutline},
    {"radial-tint", &palette.radialTint},
    {"standard-radial-tint", &palette.standardRadialTint},
    {"comparison-other", &palette.comparisonOther},
    {"comparison-only-here", &palette.comparisonOnlyHere},
    {"ground-truth", &palette.groundTruth},
    {"radial-edge", &palette.radialEdge},
    {"contour-vertex", &palette.contourVertex},
    {"cusp-vertex", &palette.cuspVertex},
    {"patch-edge", &palette.patchEdge},
    {"macro-patch-edge", &palette.macroPatchEdge},
    {"cut-edge", &palette.cutEdge},
    {"cone", &palette.cone},
    {"selection", &palette.selection},
    {"contour-over-field", &palette.contourOverField},
    {"scalar-bar-text", &palette.scalarBarText},
    {"background-top", &palette.backgroundTop},
    {"background-bottom", &palette.backgroundBottom},
};
// The keys of resources/colormaps/diverging.json.
const std::pair<const char*, SceneColor*> kDivergingKeys[] = {
    {"negative", &palette.divergingNegative},
    {"positive", &palette.divergingPositive},
    {"nan", &palette.nanValue},
};

// The keys of resources/colormaps/view-graph-colors.json.
const std::pair<const char*, SceneColor*> kViewGraphKeys[] = {
    {"hidden-qi-1", &viewGraphPalette.hiddenQi[0]},
    {"hidden-qi-2", &viewGraphPalette.hiddenQi[1]},
    {"hidden-qi-3", &viewGraphPalette.hiddenQi[2]},
    {"unknown-qi", &viewGraphPalette.unknownQi},
    {"simplified-2d", &viewGraphPalette.simplified2D},
    {"simplified-3d", &viewGraphPalette.simplified3D},
    {"curtain-fold", &viewGraphPalette.curtainFold},
    {"boundary-curtain-fold", &viewGraphPalette.boundaryCurtainFold},
    {"t-junction", &viewGraphPalette.tJunction},
    {"y-junction", &viewGraphPalette.yJunction},
    {"bifurcation", &viewGraphPalette.bifurcation},
    {"curve-end", &viewGraphPalette.curveEnd},
    {"hidden-fold-crossing", &viewGraphPalette.hiddenFoldCrossing},
    {"unknown-node", &viewGraphPalette.unknownNode},
};

[[noreturn]] void fail(const QString& path, const QString& why) {
    qFatal("%s: %s", qPrintable(path), qPrintable(why));
}

QJsonObject readObject(const QString& path) {
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        fail(path, QStringLiteral("cannot read the resource"));
    QJsonParseError error;
    const QJsonDocument document = QJsonDocument::fromJson(file.readAll(), &error);
    if (error.error != QJsonParseError::NoError || !document.isObject())
        fail(path, error.errorString());
    return document.object();
}

SceneColor toColor(const QJsonValue& value, const QString& path, const QString& key) {
    const QJsonArray rgb = value.toArray();
    if (rgb.size() != 3)
        fail(path, QStringLiteral("\"%1\" is not an [r, g, b] triple").arg(key));
    SceneColor c{rgb[0].toDouble(-1.0), rgb[1].toDouble(-1.0), rgb[2].toDouble(-1.0)};
    for (double v : {c.r, c.g, c.b})
        if (!(v >= 0.0 && v <= 1.0))
            fail(path, QStringLiteral("\"%1\" has a component outside [0, 1]").arg(key));
    return c;
}

// A file {"colors": {key: {"rgb": [r, g, b], "use": text}}}.
template <size_t N>
void readNamedColors(const QString& path, const std::pair<const char*, SceneColor*> (&keys)[N]) {
    const QJsonObject colors = readObject(path).value(QStringLiteral("colors")).toObject();
    for (const auto& [key, target] : keys) {
        const QString name = QString::fromLatin1(key);
        if (!colors.contains(name))
            fail(path, QStringLiteral("no colour \"%1\"").arg(name));
        *target = toColor(colors.value(name).toObject().value(QStringLiteral("rgb")), path, name);
    }
}

void readColors() {
    registerContourResources();
    readNamedColors(QStringLiteral(":/colormaps/scene-colors.json"), kSceneKeys);
    readNamedColors(QStringLiteral(":/colormaps/view-graph-colors.json"), kViewGraphKeys);
    const QString divergingPath = QStringLiteral(":/colormaps/diverging.json");
    const QJsonObject diverging = readObject(divergingPath);
    for (const auto& [key, target] : kDivergingKeys) {
        const QString name = QString::fromLatin1(key);
        if (!diverging.contains(name))
            fail(divergingPath, QStringLiteral("no colour \"%1\"").arg(name));
        *target = toColor(diverging.value(name), divergingPath, name);
    }
}

} // namespace

void loadSceneColors() {
    static std::once_flag once;
    std::call_once(once, readColors);
}

namespace sceneColors {

const SceneColor& kFrontFace = palette.frontFace;
const SceneColor& kBackFace = palette.backFace;
const SceneColor& kEdgeOnFace = palette.edgeOnFace;
const SceneColor& kUnclassifiedFace = palette.unclassifiedFace;
const SceneColor& kContour3D = palette.contour3D;
const SceneColor& kContour2D = palette.contour2D;
const SceneColor& kBoundary = palette.boundary;
const SceneColor& kIntersection = palette.intersection;
const SceneColor& kFrustum = palette.frustum;
const SceneColor& kControlCage = palette.controlCage;
const SceneColor& kUndefinedVbo = palette.undefinedVbo;
const SceneColor& kInconsistentOutline = palette.inconsistentOutline;
const SceneColor& kRadialTint = palette.radialTint;
const SceneColor& kStandardRadialTint = palette.standardRadialTint;
const SceneColor& kComparisonOther = palette.comparisonOther;
const SceneColor& kComparisonOnlyHere = palette.comparisonOnlyHere;
const SceneColor& kGroundTruth = palette.groundTruth;
const SceneColor& kRadialEdge = palette.radialEdge;
const SceneColor& kPatchEdge = palette.patchEdge;
const SceneColor& kMacroPatchEdge = palette.macroPatchEdge;
const SceneColor& kCutEdge = palette.cutEdge;
const SceneColor& kCone = palette.cone;
const SceneColor& kContourVertex = palette.contourVertex;
const SceneColor& kCuspVertex = palette.cuspVertex;
const SceneColor& kSelection = palette.selection;
const SceneColor& kDivergingNegative = palette.divergingNegative;
const SceneColor& kDivergingPositive = palette.divergingPositive;
const SceneColor& kNanValue = palette.nanValue;
const SceneColor& kContourOverField = palette.contourOverField;
const SceneColor& kScalarBarText = palette.scalarBarText;
const SceneColor& kBackgroundTop = palette.backgroundTop;
const SceneColor& kBackgroundBottom = palette.backgroundBottom;

} // namespace sceneColors

namespace viewGraphColors {

const std::array<SceneColor, 3>& kHiddenQi = viewGraphPalette.hiddenQi;
const SceneColor& kUnknownQi = viewGraphPalette.unknownQi;
const SceneColor& kSimplified2D = viewGraphPalette.simplified2D;
const SceneColor& kSimplified3D = viewGraphPalette.simplified3D;
const SceneColor& kCurtainFold = viewGraphPalette.curtainFold;
const SceneColor& kBoundaryCurtainFold = viewGraphPalette.boundaryCurtainFold;
const SceneColor& kTJunction = viewGraphPalette.tJunction;
const SceneColor& kYJunction = viewGraphPalette.yJunction;
const SceneColor& kBifurcation = viewGraphPalette.bifurcation;
const SceneColor& kCurveEnd = viewGraphPalette.curveEnd;
const SceneColor& kHiddenFoldCrossing = viewGraphPalette.hiddenFoldCrossing;
const SceneColor& kUnknownNode = viewGraphPalette.unknownNode;

} // namespace viewGraphColors

} // namespace contour

// With the application object, before any widget exists.
static void loadSceneColorsAtStartup() {
    contour::loadSceneColors();
}
Q_COREAPP_STARTUP_FUNCTION(loadSceneColorsAtStartup)
