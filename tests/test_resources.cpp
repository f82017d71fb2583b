// The application's resources (resources/contour-workbench.qrc): every icon
// the workbench's actions use is there and draws something, every action
// with an icon has a non-null one, the overlay and view-graph toggles show
// their SVGs, the colour maps read from the resource at start-up (the scene's
// and the view graph's) are the views' colours, and the window starts with
// the defaults of resources/settings/defaults.json. Needs a display: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"` (Mesa llvmpipe).
#include "DivergingColorMap.h"
#include "MainWindow.h"
#include "MethodPanel.h"
#include "Resources.h"
#include "SceneColors.h"
#include "SurfaceFormat.h"
#include "ViewGraphStyle.h"
#include "WorkbenchDefaults.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QImage>
#include <QSet>
#include <QSvgRenderer>
#include <QtTest>
#include <vtkLookupTable.h>

using namespace contour;

namespace {

// Pixels of the icon drawn at `size` that are not transparent.
int opaquePixels(const QIcon& icon, int size) {
    const QImage image = icon.pixmap(size, size).toImage();
    int count = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            count += qAlpha(image.pixel(x, y)) > 0;
    return count;
}

bool equal(const SceneColor& a, double r, double g, double b) {
    return a.r == r && a.g == g && a.b == b;
}

} // namespace

class TestResources : public QObject {
    Q_OBJECT

private slots:
    void everyIconIsADrawing();
    void actionsHaveTheirIcons();
    void colourMapsComeFromTheResource();
    void toggleIconsAreResourceDrawings();
    void viewGraphColoursComeFromTheResource();
    void windowStartsWithTheDefaults();
};

void TestResources::everyIconIsADrawing() {
    registerContourResources();
    const QStringList icons = QDir(QStringLiteral(":/icons")).entryList({QStringLiteral("*.svg")});
    QVERIFY(icons.size() >= 15);
    for (const QString& file : icons) {
        QSvgRenderer svg(QStringLiteral(":/icons/") + file);
        QVERIFY2(svg.isValid(), qPrintable(file));
        const QIcon icon = resourceIcon(QFileInfo(file).completeBaseName());
        QVERIFY2(!icon.isNull(), qPrintable(file));
        QVERIFY2(opaquePixels(icon, 24) > 20, qPrintable(file));
    }
    QVERIFY(resourceIcon(QStringLiteral("no-such-icon")).isNull());
}

void TestResources::actionsHaveTheirIcons() {
    MainWindow window;
    // The menu and tool-bar actions that are drawn with an icon.
    const QStringList withIcons{
        QStringLiteral("openMesh"),       QStringLiteral("openSession"),
        QStringLiteral("saveSession"),    QStringLiteral("exportSnapshot"),
        QStringLiteral("quit"),           QStringLiteral("step"),
        QStringLiteral("back"),           QStringLiteral("runToEnd"),
        QStringLiteral("reset"),          QStringLiteral("cancel"),
        QStringLiteral("cameraFromView"), QStringLiteral("lookThroughCamera"),
        QStringLiteral("controlCage"),    QStringLiteral("groundTruthContour"),
        QStringLiteral("layout-both"),    QStringLiteral("layout-3d"),
        QStringLiteral("layout-2d"),      QStringLiteral("nextInconsistentFace"),
        QStringLiteral("clearSelection"), QStringLiteral("about")};
    for (const QString& name : withIcons) {
        auto* action = window.findChild<QAction*>(name);
        QVERIFY2(action, qPrintable(name));
        QVERIFY2(!action->icon().isNull(), qPrintable(name));
        QVERIFY2(opaquePixels(action->icon(), 24) > 20, qPrintable(name));
    }
    // And no action shows an icon that draws nothing.
    for (const QAction* action : window.findChildren<QAction*>())
        if (!action->icon().isNull())
            QVERIFY2(opaquePixels(action->icon(), 16) > 0, qPrintable(action->text()));
    QVERIFY(!window.windowIcon().isNull());
}

void TestResources::colourMapsComeFromTheResource() {
    loadSceneColors();
    // The colours as the views have always drawn them (image tests rely on
    // them).
    QVERIFY(equal(sceneColors::kFrontFace, 1.00, 0.84, 0.42));
    QVERIFY(equal(sceneColors::kBackFace, 0.22, 0.42, 0.95));
    QVERIFY(equal(sceneColors::kUnclassifiedFace, 0.78, 0.78, 0.78));
    QVERIFY(equal(sceneColors::kContour3D, 0.90, 0.08, 0.08));
    QVERIFY(equal(sceneColors::kUndefinedVbo, 0.25, 0.85, 0.15));
    QVERIFY(equal(sceneColors::kInconsistentOutline, 1.0, 0.0, 1.0));
    QVERIFY(equal(sceneColors::kRadialTint, 1.0, 0.50, 0.05));
    QVERIFY(equal(sceneColors::kCuspVertex, 0.0, 0.90, 1.0));
    QVERIFY(equal(sceneColors::kSelection, 0.55, 1.0, 0.0));
    QVERIFY(equal(sceneColors::kBackgroundBottom, 0.10, 0.10, 0.11));
    // The diverging map: Moreland's end colours and the NaN grey.
    QVERIFY(equal(sceneColors::kDivergingNegative, 0.230, 0.299, 0.754));
    QVERIFY(equal(sceneColors::kDivergingPositive, 0.706, 0.016, 0.150));
    QVERIFY(equal(sceneColors::kNanValue, 0.40, 0.40, 0.40));
    const vtkSmartPointer<vtkLookupTable> table = makeDivergingLookupTable(2.0);
    QCOMPARE(table->GetNumberOfTableValues(), vtkIdType(kDivergingTableSize));
    double nan[4];
    table->GetNanColor(nan);
    QCOMPARE(nan[0], 0.40);
    double low[4], high[4];
    table->GetTableValue(0, low);
    table->GetTableValue(kDivergingTableSize - 1, high);
    // The first and last bins are within a bin of the end colours.
    QVERIFY(std::abs(low[2] - 0.754) < 0.02 && std::abs(low[0] - 0.230) < 0.02);
    QVERIFY(std::abs(high[0] - 0.706) < 0.02 && std::abs(high[2] - 0.150) < 0.02);
}

void TestResources::toggleIconsAreResourceDrawings() {
    MainWindow window;
    // The overlay and view-graph toggles, in their enums' order, show the
    // SVG of resources/icons/ named after them.
    const QStringList overlayIcons{QStringLiteral("overlay-inconsistent-faces"),
                                   QStringLiteral("overlay-radial-faces"),
                                   QStringLiteral("overlay-contour-vertices"),
                                   QStringLiteral("overlay-cusps"),
                                   QStringLiteral("overlay-radial-edges"),
                                   QStringLiteral("overlay-patch-edges"),
                                   QStringLiteral("overlay-cones")};
    const QStringList viewGraphIcons{
        QStringLiteral("view-graph-hidden-curves"), QStringLiteral("view-graph-colour-by-qi"),
        QStringLiteral("view-graph-nodes"), QStringLiteral("view-graph-simplified-curves")};
    QCOMPARE(overlayIcons.size(), kSceneOverlayCount);
    QCOMPARE(viewGraphIcons.size(), MainWindow::kViewGraphToggleCount);
    std::vector<std::pair<const QAction*, QString>> toggles;
    for (int i = 0; i < kSceneOverlayCount; ++i)
        toggles.emplace_back(window.overlayAction(static_cast<SceneOverlay>(i)), overlayIcons[i]);
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        toggles.emplace_back(window.viewGraphAction(static_cast<MainWindow::ViewGraphToggle>(i)),
                             viewGraphIcons[i]);
    QSet<QByteArray> drawings;
    for (const auto& [action, name] : toggles) {
        QVERIFY2(action, qPrintable(name));
        const QIcon resource = resourceIcon(name);
        QVERIFY2(!resource.isNull(), qPrintable(name));
        // Drawn from the SVG at any size (a painted pixmap would be 16 px).
        for (int size : {16, 24, 48}) {
            const QImage shown = action->icon().pixmap(size, size).toImage();
            QCOMPARE(shown.size(), QSize(size, size));
            QVERIFY2(shown == resource.pixmap(size, size).toImage(), qPrintable(name));
        }
        QVERIFY2(opaquePixels(resource, 24) > 20, qPrintable(name));
        const QImage image = resource.pixmap(24, 24).toImage();
        drawings.insert(QByteArray(reinterpret_cast<const char*>(image.constBits()),
                                   static_cast<int>(image.sizeInBytes())));
    }
    QCOMPARE(drawings.size(), static_cast<qsizetype>(toggles.size())); // all different
}

void TestResources::viewGraphColoursComeFromTheResource() {
    loadSceneColors();
    // The values the views have always drawn with (image tests rely on them).
    QVERIFY(equal(viewGraphColors::kHiddenQi[0], 0.45, 0.10, 0.62));
    QVERIFY(equal(viewGraphColors::kHiddenQi[1], 0.62, 0.36, 0.80));
    QVERIFY(equal(viewGraphColors::kHiddenQi[2], 0.78, 0.63, 0.90));
    QVERIFY(equal(viewGraphColors::kUnknownQi, 0.60, 0.60, 0.60));
    QVERIFY(equal(viewGraphColors::kSimplified2D, 0.82, 0.82, 0.82));
    QVERIFY(equal(viewGraphColors::kSimplified3D, 0.70, 0.70, 0.70));
    QVERIFY(equal(nodeStyle(ViewNodeType::CurtainFold).color, 0.0, 0.80, 0.95));
    QVERIFY(equal(nodeStyle(ViewNodeType::BoundaryCurtainFold).color, 0.15, 0.75, 0.30));
    QVERIFY(equal(nodeStyle(ViewNodeType::ImageIntersection).color, 1.0, 0.55, 0.0));
    QVERIFY(equal(nodeStyle(ViewNodeType::ContourBoundaryJunction).color, 0.55, 0.33, 0.10));
    QVERIFY(equal(nodeStyle(ViewNodeType::Bifurcation).color, 1.0, 0.40, 0.70));
    QVERIFY(equal(nodeStyle(ViewNodeType::CurveEnd).color, 0.25, 0.25, 0.25));
    QVERIFY(equal(nodeStyle(ViewNodeType::HiddenFoldCrossing).color, 0.60, 0.50, 0.40));
    const SceneColor intersection = nodeStyle(ViewNodeType::SurfaceIntersectionEnd).color;
    QVERIFY(equal(intersection, sceneColors::kIntersection.r, sceneColors::kIntersection.g,
                  sceneColors::kIntersection.b));
    // QI colours as the views pick them.
    QVERIFY(equal(qiColor(2, sceneColors::kContour3D), 0.62, 0.36, 0.80));
    QVERIFY(equal(qiColor(7, sceneColors::kContour3D), 0.78, 0.63, 0.90));
    QVERIFY(equal(qiColor(-1, sceneColors::kContour3D), 0.60, 0.60, 0.60));
}

void TestResources::windowStartsWithTheDefaults() {
    const WorkbenchDefaults defaults = WorkbenchDefaults::load();
    QCOMPARE(defaults.method, QStringLiteral("mesh"));
    QCOMPARE(defaults.windowSize, QSize(1400, 850));
    QVERIFY(defaults.toggle("view-graph.hidden-curves", false));
    QVERIFY(!defaults.toggle("view-graph.simplified-curves", true));
    MainWindow window;
    QCOMPARE(window.methodName(), defaults.method);
    QCOMPARE(window.size(), defaults.windowSize);
    QCOMPARE(window.viewLayout(), MainWindow::ViewLayout::Both);
    QVERIFY(!window.controlCageAction()->isChecked());
    QVERIFY(window.viewGraphAction(MainWindow::ViewGraphToggle::HiddenCurves)->isChecked());
    QVERIFY(!window.viewGraphAction(MainWindow::ViewGraphToggle::SimplifiedCurves)->isChecked());
    QCOMPARE(window.colorField(), QStringLiteral("facing"));
}

int main(int argc, char* argv[]) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestResources test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_resources.moc"
