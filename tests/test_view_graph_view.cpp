// The workbench's view graph display. First a hand-made
// view graph on a sphere, in a lone 2D and 3D view: as many solid, dashed and
// faint chains and node glyphs as the graph has in each state, and the
// grabbed images change with the toggles (hidden-QI purple pixels only while
// hidden curves are shown, curtain-fold cyan dots only while nodes are shown,
// chain hues only when colouring by chain). Then the real window on the spot
// sample with the mesh method run to the end: its visibility phase's graph is
// drawn chain for chain and node for node in both views, and the Overlays
// tool bar's toggles drive both views. Loose image checks (colour classes,
// not pixels). Needs a display: run under `xvfb-run -a -s "-screen 0
// 1600x1200x24"` (Mesa llvmpipe).
#include "ImageView2D.h"
#include "MainWindow.h"
#include "SceneView3D.h"
#include "SnapshotToVtk.h"
#include "SurfaceFormat.h"
#include "ViewGraphStyle.h"
#include "mesh/ProceduralShapes.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QLabel>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

using namespace contour;

namespace {

constexpr int kIdleTimeoutMs = 300000;

QString grabPath(const QString& name) {
    return QDir::temp().filePath(QStringLiteral("test_view_graph_view_%1.png").arg(name));
}

double hueDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

// Pixels whose hue is within `tolerance` degrees of `reference`'s, with at
// least `minSaturation` (antialiased lines on white lose saturation, not hue),
// outside `exclude` (the legend).
long long hueMatches(const QImage& image, const SceneColor& reference, double tolerance,
                     double minSaturation, const QRect& exclude = QRect()) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const double hue = reference.toQColor().hsvHueF() * 360.0;
    long long n = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            if (exclude.contains(x, y))
                continue;
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            if (c.hsvSaturationF() >= minSaturation && c.valueF() > 0.2 &&
                hueDistance(c.hsvHueF() * 360.0, hue) < tolerance)
                ++n;
        }
    return n;
}

// Hidden chains coloured by QI: purples (hue ~275-280°).
long long hiddenPixels(const QImage& image, const QRect& exclude) {
    return hueMatches(image, viewGraphColors::kHiddenQi[0], 14.0, 0.2, exclude);
}

// Dark, unsaturated pixels inside `area`: visible chains in black.
long long blackPixels(const QImage& image, const QRect& area) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    long long n = 0;
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            n += c.valueF() < 0.3 && c.hsvSaturationF() < 0.3;
        }
    return n;
}

QRect deviceRect(const QRectF& r, double ratio) {
    return QRectF(r.topLeft() * ratio, r.size() * ratio).toAlignedRect();
}

struct ExpectedCounts {
    int visible = 0, hidden = 0, simplified = 0, nodes = 0, hiddenNodes = 0;
    std::array<int, kViewNodeTypeCount> nodesByType{};
};

// What the views should draw, counted from the graph alone.
ExpectedCounts expectedCounts(const ViewGraph& graph) {
    ExpectedCounts e;
    for (const ViewChain& chain : graph.chains) {
        if (chain.points.size() < 2)
            continue;
        const bool visible = chain.qi == 0 && !chain.simplifiedAway;
        e.visible += visible;
        e.hidden += chain.qi != 0;
        e.simplified += chain.qi == 0 && chain.simplifiedAway;
    }
    for (const ViewNode& node : graph.nodes) {
        ++e.nodes;
        ++e.nodesByType[static_cast<size_t>(node.type)];
        bool anyVisible = false;
        for (Index c : node.chains)
            anyVisible |= graph.chains[c].qi == 0 && !graph.chains[c].simplifiedAway;
        e.hiddenNodes += !anyVisible;
    }
    return e;
}

// A hand-made graph on the unit sphere seen from `camera`: the rim circle
// (perpendicular to the view direction through the centre) cut into four
// chains, visible (QI 0), hidden (QI 1), hidden (QI 2) and visible but
// simplified away, with a node of a different type at each cut. Two nodes
// touch no visible chain (ViewNodeClass::Hidden).
std::shared_ptr<const ViewGraph> handMadeGraph(const Camera& camera) {
    const Vec3 forward = camera.forward();
    Vec3 a = forward.cross(Vec3(0, 0, 1));
    if (a.norm() < 0.1)
        a = forward.cross(Vec3(0, 1, 0));
    a.normalize();
    const Vec3 b = forward.cross(a).normalized();
    const auto rim = [&](double t) {
        const double angle = 2.0 * std::numbers::pi * t;
        return Vec3(std::cos(angle) * a + std::sin(angle) * b);
    };
    auto graph = std::make_shared<ViewGraph>();
    const int qi[4] = {0, 1, 2, 0};
    const ViewNodeType types[4] = {ViewNodeType::CurtainFold, ViewNodeType::ImageIntersection,
                                   ViewNodeType::ContourBoundaryJunction, ViewNodeType::CurveEnd};
    for (int c = 0; c < 4; ++c) {
        ViewChain chain;
        chain.qi = qi[c];
        chain.simplifiedAway = c == 3;
        chain.decidedBy = VisibilityRule::RayTest;
        chain.startNode = c;
        chain.endNode = (c + 1) % 4;
        for (int i = 0; i <= 40; ++i) {
            const Vec3 p = rim((c + i / 40.0) / 4.0);
            const ProjectedPoint q = camera.project(p);
            chain.points.push_back(p);
            chain.image.push_back(q.pixel);
            chain.depth.push_back(q.depth);
        }
        graph->chains.push_back(std::move(chain));
    }
    for (int n = 0; n < 4; ++n) {
        ViewNode node;
        node.type = types[n];
        node.position = rim(n / 4.0);
        node.image = camera.project(node.position).pixel;
        node.chains = {static_cast<Index>((n + 3) % 4), static_cast<Index>(n)};
        graph->nodes.push_back(std::move(node));
    }
    return graph;
}

} // namespace

class TestViewGraphView : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void handMadeGraphIn2D();
    void handMadeGraphIn3D();
    void meshMethodOnSpot();
    void consistentMethodOnSpot();

private:
    Snapshot handMadeSnapshot_;
    Camera camera_;
    MainWindow* window_ = nullptr;
};

void TestViewGraphView::initTestCase() {
    auto sphere = std::make_shared<const PolygonMesh>(makeProceduralShape("sphere", 24));
    handMadeSnapshot_ = makeInputSnapshot(sphere);
    handMadeSnapshot_.phaseName = "hand-made";
    camera_ = Camera::framing(sphere->boundingBox(), Vec3(0.55, 0.45, 1.0), Viewport{640, 480});
    handMadeSnapshot_.viewGraph = handMadeGraph(camera_);
}

void TestViewGraphView::cleanupTestCase() {
    delete window_;
    window_ = nullptr;
}

void TestViewGraphView::handMadeGraphIn2D() {
    ImageView2D view;
    view.resize(800, 620);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setScene(handMadeSnapshot_, camera_);
    QVERIFY(view.showsViewGraph());
    QCOMPARE(view.chainColoring(), ChainColoring::ByQi);
    QVERIFY(view.showsHiddenCurves() && view.showsNodes() && !view.showsSimplifiedCurves());
    QCOMPARE(view.visibleChainsDrawn(), 1);
    QCOMPARE(view.hiddenChainsDrawn(), 2);
    QCOMPARE(view.simplifiedChainsDrawn(), 0);
    QCOMPARE(view.nodeGlyphsDrawn(), 4);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::CurtainFold), 1);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::ImageIntersection), 1);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::Bifurcation), 0);

    const QImage shown = view.grab().toImage();
    QVERIFY(shown.save(grabPath(QStringLiteral("2d_hidden_shown"))));
    const double ratio = shown.devicePixelRatio();
    const QRect frame = deviceRect(view.imageRect(), ratio).adjusted(3, 3, -3, -3);
    const QRect legend = deviceRect(view.legendRect(), ratio);
    QVERIFY(!legend.isEmpty());
    const long long purpleShown = hiddenPixels(shown, legend);
    const long long blackShown = blackPixels(shown, frame) - blackPixels(shown, legend);
    qInfo("2D hand-made: hidden-colour pixels %lld, black pixels %lld", purpleShown, blackShown);
    QVERIFY2(purpleShown > 100, qPrintable(QString::number(purpleShown)));
    QVERIFY2(blackShown > 100, qPrintable(QString::number(blackShown)));

    // Hidden curves off: no dashed chain, and the nodes touching no visible
    // chain go with them (between the two hidden chains, and between the
    // QI 2 chain and the simplified one).
    view.setShowHiddenCurves(false);
    QCOMPARE(view.hiddenChainsDrawn(), 0);
    QCOMPARE(view.visibleChainsDrawn(), 1);
    QCOMPARE(view.nodeGlyphsDrawn(), 2);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::ContourBoundaryJunction), 0);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::CurveEnd), 0);
    QCOMPARE(view.nodeGlyphsDrawn(ViewNodeType::ImageIntersection), 1);
    const QImage hidden = view.grab().toImage();
    QVERIFY(hidden.save(grabPath(QStringLiteral("2d_hidden_off"))));
    QCOMPARE(hiddenPixels(hidden, QRect()), 0LL); // the legend lists only what is drawn
    view.setShowHiddenCurves(true);

    // Simplified-away chains, faint, on request.
    view.setShowSimplifiedCurves(true);
    QCOMPARE(view.simplifiedChainsDrawn(), 1);
    view.setShowSimplifiedCurves(false);

    // By chain: the visible chain (index 0) takes its chain colour (nodes
    // off: the T-junction glyph's orange is near that hue).
    view.setShowNodes(false);
    QCOMPARE(view.nodeGlyphsDrawn(), 0);
    const SceneColor chain0 = chainColor(0);
    const QImage byQi = view.grab().toImage();
    QCOMPARE(hueMatches(byQi, chain0, 10.0, 0.5, deviceRect(view.legendRect(), ratio)), 0LL);
    view.setChainColoring(ChainColoring::ByChain);
    const QImage byChain = view.grab().toImage();
    QVERIFY(byChain.save(grabPath(QStringLiteral("2d_by_chain"))));
    const QRect legendByChain = deviceRect(view.legendRect(), ratio);
    const long long chainPixels = hueMatches(byChain, chain0, 10.0, 0.5, legendByChain);
    qInfo("2D by chain: chain 0 hue pixels %lld", chainPixels);
    QVERIFY2(chainPixels > 100, qPrintable(QString::number(chainPixels)));
    QVERIFY(hiddenPixels(byChain, legendByChain) < purpleShown / 4);
    view.setChainColoring(ChainColoring::ByQi);
    view.setShowNodes(true);
    QCOMPARE(view.nodeGlyphsDrawn(), 4);

    // No view graph: today's drawing of the raw curves.
    Snapshot plain = handMadeSnapshot_;
    plain.viewGraph.reset();
    view.setScene(plain, camera_);
    QVERIFY(!view.showsViewGraph());
    QCOMPARE(view.visibleChainsDrawn() + view.hiddenChainsDrawn() + view.nodeGlyphsDrawn(), 0);
    QVERIFY(view.legendRect().isEmpty());
}

void TestViewGraphView::handMadeGraphIn3D() {
    SceneView3D view;
    view.resize(640, 480);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setViewCamera(camera_);
    QSignalSpy overlays(&view, &SceneView3D::overlaysChanged);
    view.setSnapshot(handMadeSnapshot_);
    QVERIFY(view.hasViewGraph());
    QCOMPARE(overlays.count(), 1);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Visible), 1LL);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Hidden), 2LL);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Simplified), 0LL);
    QCOMPARE(view.viewGraphNodesShown(), 4LL);
    // Nodes 0 and 1 touch the visible chain (drawn over everything), 2 and 3
    // only hidden ones (depth-tested).
    for (const bool hidden : {false, true}) {
        vtkPolyData* nodes = view.viewGraphNodeData(hidden);
        QVERIFY(nodes);
        QCOMPARE(nodes->GetNumberOfVerts(), vtkIdType(2));
        auto* types = vtkIntArray::SafeDownCast(nodes->GetPointData()->GetArray(kVtkNodeTypeArray));
        QVERIFY(types);
        for (vtkIdType i = 0; i < 2; ++i) {
            const ViewNode& node = handMadeSnapshot_.viewGraph->nodes[(hidden ? 2 : 0) + i];
            QCOMPARE(types->GetValue(i), static_cast<int>(node.type));
            double p[3];
            nodes->GetPoint(i, p);
            QVERIFY((Vec3(p[0], p[1], p[2]) - node.position).norm() < 1e-12);
        }
    }
    // Chains keep their 3D points: 41 per chain.
    QCOMPARE(view.viewGraphChainData(ChainState::Hidden)->GetNumberOfPoints(), vtkIdType(82));

    // The curtain-fold dot (cyan, drawn over everything) is in the image
    // exactly while nodes are shown.
    const SceneColor cyan = nodeStyle(ViewNodeType::CurtainFold).color;
    const QImage on = view.grabImage();
    QVERIFY(on.save(grabPath(QStringLiteral("3d_nodes_on"))));
    const long long cyanOn = hueMatches(on, cyan, 8.0, 0.8);
    view.setShowViewGraphNodes(false);
    QCOMPARE(view.viewGraphNodesShown(), 0LL);
    const long long cyanOff = hueMatches(view.grabImage(), cyan, 8.0, 0.8);
    qInfo("3D hand-made: curtain-fold cyan pixels %lld with nodes, %lld without", cyanOn, cyanOff);
    QVERIFY2(cyanOn >= 30, qPrintable(QString::number(cyanOn)));
    QCOMPARE(cyanOff, 0LL);
    view.setShowViewGraphNodes(true);

    view.setShowHiddenCurves(false);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Hidden), 0LL);
    QCOMPARE(view.viewGraphNodesShown(), 2LL);
    view.setShowHiddenCurves(true);
    view.setShowSimplifiedCurves(true);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Simplified), 1LL);

    // Without a view graph: nothing of it, and the change is signalled.
    Snapshot plain = handMadeSnapshot_;
    plain.viewGraph.reset();
    view.setSnapshot(plain);
    QVERIFY(!view.hasViewGraph());
    QCOMPARE(overlays.count(), 2);
    QCOMPARE(view.viewGraphNodesShown(), 0LL);
    QCOMPARE(view.viewGraphChainsShown(ChainState::Visible), 0LL);
}

void TestViewGraphView::meshMethodOnSpot() {
    window_ = new MainWindow;
    window_->setInteractive(false);
    window_->resize(1400, 850);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_));
    QVERIFY(window_->openMesh(QStringLiteral(CONTOUR_SOURCE_DIR "/samples/spot_control_mesh.obj")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QCOMPARE(window_->methodName(), QStringLiteral("mesh"));
    const Runner* runner = window_->runner();
    QVERIFY(runner && runner->atEnd());
    const Snapshot s = window_->currentSnapshot();
    QVERIFY2(s.viewGraph, "the mesh method's last snapshot has no view graph");
    const ViewGraph& graph = *s.viewGraph;
    const ExpectedCounts e = expectedCounts(graph);
    qInfo("spot, mesh method (%s): %zu chains (%d visible, %d hidden, %d simplified), %d nodes",
          s.phaseName.c_str(), graph.chains.size(), e.visible, e.hidden, e.simplified, e.nodes);
    QVERIFY(e.visible > 0);

    using T = MainWindow::ViewGraphToggle;
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        QVERIFY(window_->viewGraphAction(static_cast<T>(i))->isVisible());
    QVERIFY(!window_->viewGraphLegend()->text().isEmpty());

    ImageView2D* image = window_->imageView();
    SceneView3D* scene = window_->sceneView();
    QVERIFY(image->showsViewGraph() && scene->hasViewGraph());
    QCOMPARE(image->visibleChainsDrawn(), e.visible);
    QCOMPARE(image->hiddenChainsDrawn(), e.hidden);
    QCOMPARE(image->simplifiedChainsDrawn(), 0);
    QCOMPARE(image->nodeGlyphsDrawn(), e.nodes);
    for (int t = 0; t < kViewNodeTypeCount; ++t)
        QCOMPARE(image->nodeGlyphsDrawn(static_cast<ViewNodeType>(t)),
                 e.nodesByType[static_cast<size_t>(t)]);
    QCOMPARE(scene->viewGraphChainsShown(ChainState::Visible), static_cast<long long>(e.visible));
    QCOMPARE(scene->viewGraphChainsShown(ChainState::Hidden), static_cast<long long>(e.hidden));
    QCOMPARE(scene->viewGraphNodesShown(), static_cast<long long>(e.nodes));
    // The raw curves are still counted (drawn only without a view graph).
    QCOMPARE(image->curveCount(), static_cast<int>(s.curves->size()));

    const QImage shown = image->grab().toImage();
    QVERIFY(shown.save(grabPath(QStringLiteral("spot_2d"))));
    QVERIFY(scene->grabImage().save(grabPath(QStringLiteral("spot_3d"))));
    const double ratio = shown.devicePixelRatio();
    const long long purpleShown = hiddenPixels(shown, deviceRect(image->legendRect(), ratio));

    // The tool bar's hidden-curve toggle drives both views.
    window_->viewGraphAction(T::HiddenCurves)->trigger();
    QVERIFY(!image->showsHiddenCurves() && !scene->showsHiddenCurves());
    QCOMPARE(image->hiddenChainsDrawn(), 0);
    QCOMPARE(scene->viewGraphChainsShown(ChainState::Hidden), 0LL);
    QCOMPARE(image->nodeGlyphsDrawn(), e.nodes - e.hiddenNodes);
    QCOMPARE(scene->viewGraphNodesShown(), static_cast<long long>(e.nodes - e.hiddenNodes));
    const QImage off = image->grab().toImage();
    QVERIFY(off.save(grabPath(QStringLiteral("spot_2d_hidden_off"))));
    const long long purpleOff = hiddenPixels(off, QRect());
    qInfo("spot 2D: hidden-colour pixels %lld with hidden curves, %lld without", purpleShown,
          purpleOff);
    if (e.hidden > 0)
        QVERIFY2(purpleShown > 50, qPrintable(QString::number(purpleShown)));
    // Antialiased edges of overlapping node glyphs (a pink glyph over a cyan
    // one) can blend into a purple pixel or two when the view is narrow.
    QVERIFY2(purpleOff <= purpleShown / 100, qPrintable(QString::number(purpleOff)));
    window_->viewGraphAction(T::HiddenCurves)->trigger();
    QCOMPARE(image->hiddenChainsDrawn(), e.hidden);

    // 3D, seen from behind (where the hidden chains are not occluded by the
    // surface): the purple of hidden chains comes and goes with the toggle.
    scene->orbit(180.0, 0.0);
    const QImage behind = scene->grabImage();
    QVERIFY(behind.save(grabPath(QStringLiteral("spot_3d_behind"))));
    const long long purple3dOn = hiddenPixels(behind, QRect());
    window_->viewGraphAction(T::HiddenCurves)->trigger();
    const long long purple3dOff = hiddenPixels(scene->grabImage(), QRect());
    window_->viewGraphAction(T::HiddenCurves)->trigger();
    window_->resetViewToAnalysisCamera();
    qInfo("spot 3D from behind: hidden-colour pixels %lld with hidden curves, %lld without",
          purple3dOn, purple3dOff);
    if (e.hidden > 0)
        QVERIFY2(purple3dOn > 50, qPrintable(QString::number(purple3dOn)));
    // 0 under Mesa llvmpipe; a multisampled GPU may blend a magenta dot's
    // edge over a blue face into a purple hue.
    QVERIFY2(purple3dOff <= purple3dOn / 100, qPrintable(QString::number(purple3dOff)));
    QVERIFY(window_->grab().toImage().save(grabPath(QStringLiteral("spot_window"))));

    window_->viewGraphAction(T::ColourByQi)->trigger();
    QCOMPARE(image->chainColoring(), ChainColoring::ByChain);
    QCOMPARE(scene->chainColoring(), ChainColoring::ByChain);
    window_->viewGraphAction(T::ColourByQi)->trigger();
    window_->viewGraphAction(T::Nodes)->trigger();
    QCOMPARE(image->nodeGlyphsDrawn(), 0);
    QCOMPARE(scene->viewGraphNodesShown(), 0LL);
    window_->viewGraphAction(T::Nodes)->trigger();

    // Back at the input: no view graph, no toggles.
    window_->resetPhases();
    QVERIFY(!image->showsViewGraph() && !scene->hasViewGraph());
    for (int i = 0; i < MainWindow::kViewGraphToggleCount; ++i)
        QVERIFY(!window_->viewGraphAction(static_cast<T>(i))->isVisible());
}

void TestViewGraphView::consistentMethodOnSpot() {
    // The window of meshMethodOnSpot, still on spot.
    QVERIFY(window_);
    QVERIFY(window_->setMethod(QStringLiteral("consistent")));
    QVERIFY(window_->waitForIdle(kIdleTimeoutMs));
    QVERIFY2(window_->lastError().isEmpty(), qPrintable(window_->lastError()));
    QVERIFY(window_->runner() && window_->runner()->atEnd());
    const Snapshot s = window_->currentSnapshot();
    QVERIFY2(s.viewGraph, "the consistent method's last snapshot has no view graph");
    const ExpectedCounts e = expectedCounts(*s.viewGraph);
    qInfo("spot, consistent method (%s): %zu chains (%d visible, %d hidden), %d nodes",
          s.phaseName.c_str(), s.viewGraph->chains.size(), e.visible, e.hidden, e.nodes);
    QVERIFY(e.visible > 0);
    ImageView2D* image = window_->imageView();
    SceneView3D* scene = window_->sceneView();
    QCOMPARE(image->visibleChainsDrawn(), e.visible);
    QCOMPARE(image->hiddenChainsDrawn(), e.hidden);
    QCOMPARE(image->nodeGlyphsDrawn(), e.nodes);
    QCOMPARE(scene->viewGraphChainsShown(ChainState::Visible), static_cast<long long>(e.visible));
    QCOMPARE(scene->viewGraphChainsShown(ChainState::Hidden), static_cast<long long>(e.hidden));
    QCOMPARE(scene->viewGraphNodesShown(), static_cast<long long>(e.nodes));
    // The legend counts the curtain folds at the surface's cusps and those
    // of a mesh test apart (every node is drawn from this camera).
    int folds = 0, atCusps = 0;
    for (const ViewNode& n : s.viewGraph->nodes)
        if (n.type == ViewNodeType::CurtainFold) {
            ++folds;
            atCusps += n.smoothCusp;
        }
    QVERIFY(atCusps > 0);
    qInfo("legend: %s", qPrintable(image->legendTexts().join(QStringLiteral(" | "))));
    if (image->nodeGlyphsDrawn() == static_cast<int>(s.viewGraph->nodes.size())) {
        const QString expected =
            QStringLiteral("(%1 at cusps, %2 by a mesh test)").arg(atCusps).arg(folds - atCusps);
        QVERIFY2(image->legendTexts().filter(expected).size() == 1,
                 qPrintable(image->legendTexts().join(QStringLiteral(" | "))));
        // T-junctions of sub-pixel loops (ViewNode::smallLoop) are counted
        // apart, and only when there are some.
        int junctions = 0, smallLoops = 0;
        for (const ViewNode& n : s.viewGraph->nodes)
            if (n.type == ViewNodeType::ImageIntersection) {
                ++junctions;
                smallLoops += n.smallLoop;
            }
        qInfo("T-junctions: %d, of which %d in sub-pixel loops", junctions, smallLoops);
        const QStringList subPixel = image->legendTexts().filter(QStringLiteral("sub-pixel"));
        if (smallLoops > 0)
            QCOMPARE(subPixel, QStringList{QStringLiteral("T-junction (%1, %2 in sub-pixel loops)")
                                               .arg(junctions - smallLoops)
                                               .arg(smallLoops)});
        else
            QVERIFY(subPixel.isEmpty());
    }
    QVERIFY(image->grab().toImage().save(grabPath(QStringLiteral("spot_consistent_2d"))));
    QVERIFY(scene->grabImage().save(grabPath(QStringLiteral("spot_consistent_3d"))));
}

int main(int argc, char** argv) {
    setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    TestViewGraphView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_view_graph_view.moc"
