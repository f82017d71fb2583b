// The illustration SVG (export/IllustrationSvg.h): strokes chained as the
// tutorial's §9.1 says on a hand-made view graph whose every chain and node
// is known, tapered outlines (§9.2), the document's Inkscape layers, and a
// real method's drawing of the bumpy torus.
#include "ContourTestSupport.h"
#include "SvgTestSupport.h"
#include "export/IllustrationSvg.h"
#include "pipeline/ViewGraph.h"

#include <QtTest>
#include <algorithm>
#include <set>

using namespace contour;
using namespace contour::testing;

namespace {

// Chains: 0 and 1 the near contour (curve 0) on both sides of the
// T-junction node 1, from the curtain fold node 0 to the curtain fold node
// 2; 2 the far contour (curve 1), visible from the open end node 3 to the
// T-junction, and 3 its hidden part (QI 2) on to node 4; 4 a closed
// boundary loop; 5 a contour chain simplified away; 6 and 7 one contour
// (curve 6) closed through two hidden-fold crossings, nodes 5 and 6.
Snapshot handMadeSnapshot(const Camera& camera) {
    auto graph = std::make_shared<ViewGraph>();
    auto& chains = graph->chains;
    const auto add = [&](CurveType type, Index curve, std::vector<Vec3> points, int qi, Index start,
                         Index end) {
        chains.push_back(
            chain(type, curve, std::move(points), camera, qi,
                  qi == 0 ? VisibilityRule::RayTest : VisibilityRule::ImageIntersection));
        chains.back().startNode = start;
        chains.back().endNode = end;
    };
    add(CurveType::Contour, 0, {{-1, 0, 0}, {-0.5, 0, 0}, {0, 0, 0}}, 0, 0, 1);
    add(CurveType::Contour, 0, {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}}, 0, 1, 2);
    add(CurveType::Contour, 1, {{0, 1, 0}, {0, 0.5, 0}, {0, 0, 0}}, 0, 3, 1);
    add(CurveType::Contour, 1, {{0, 0, 0}, {0, -1, 0}}, 2, 1, 4);
    add(CurveType::Boundary, 2, {{1.2, 1, 0}, {1.4, 1, 0}, {1.4, 1.2, 0}, {1.2, 1, 0}}, 0,
        kInvalidIndex, kInvalidIndex);
    chains.back().closed = true;
    add(CurveType::Contour, 5, {{-1.5, -1, 0}, {-1.2, -1, 0}}, 0, kInvalidIndex, kInvalidIndex);
    chains.back().simplifiedAway = true;
    add(CurveType::Contour, 6, {{-1, 1, 0}, {-0.8, 1.2, 0}, {-0.6, 1, 0}}, 0, 5, 6);
    add(CurveType::Contour, 6, {{-0.6, 1, 0}, {-0.8, 0.8, 0}, {-1, 1, 0}}, 0, 6, 5);

    const auto node = [&](ViewNodeType type, const Vec3& p, std::vector<Index> at) {
        ViewNode n;
        n.type = type;
        n.position = p;
        n.image = camera.project(p).pixel;
        n.chains = std::move(at);
        graph->nodes.push_back(n);
    };
    node(ViewNodeType::CurtainFold, {-1, 0, 0}, {0});
    node(ViewNodeType::ImageIntersection, {0, 0, 0}, {0, 1, 2, 3});
    graph->nodes[1].nearChains = {0, 1};
    graph->nodes[1].farChains = {2, 3};
    graph->nodes[1].qiStep = 2;
    node(ViewNodeType::CurtainFold, {1, 0, 0}, {1});
    node(ViewNodeType::CurveEnd, {0, 1, 0}, {2});
    node(ViewNodeType::CurveEnd, {0, -1, 0}, {3});
    node(ViewNodeType::HiddenFoldCrossing, {-1, 1, 0}, {6, 7});
    node(ViewNodeType::HiddenFoldCrossing, {-0.6, 1, 0}, {6, 7});

    Snapshot s;
    s.phaseName = "visibility";
    s.viewGraph = graph;
    return s;
}

const IllustrationStroke* strokeWith(const std::vector<IllustrationStroke>& strokes, Index chain) {
    for (const IllustrationStroke& s : strokes)
        if (std::find(s.chains.begin(), s.chains.end(), chain) != s.chains.end())
            return &s;
    return nullptr;
}

double length(const std::vector<Vec2>& points) {
    double l = 0.0;
    for (size_t i = 1; i < points.size(); ++i)
        l += (points[i] - points[i - 1]).norm();
    return l;
}

// A path of M, L and Z commands (what the writer emits) as its points.
std::vector<Vec2> pathPoints(const SvgElement& path) {
    QString d = path.attribute("d");
    return pointList(d.replace('M', ' ').replace('L', ' ').replace('Z', ' '));
}

} // namespace

class TestIllustrationSvg : public QObject {
    Q_OBJECT

private slots:
    // §9.1: through the T-junction the near contour goes on (chains 0 and
    // 1 one stroke, tapered at both curtain folds); the far contour stops
    // against it untapered and tapers at its open end; closed curves and
    // chains closed through connectors are closed strokes without tapers;
    // simplified and hidden chains are not drawn (hidden ones only on
    // request, in their own strokes).
    void strokesFollowTheTutorialsChaining() {
        const Camera camera = frontCamera();
        const Snapshot s = handMadeSnapshot(camera);
        const std::vector<IllustrationStroke> strokes = illustrationStrokes(s, camera);
        QCOMPARE(strokes.size(), size_t(4));
        const IllustrationStroke* near = strokeWith(strokes, 0);
        QVERIFY(near && near == strokeWith(strokes, 1));
        QCOMPARE(near->chains, (std::vector<Index>{0, 1}));
        QVERIFY(near->taperStart && near->taperEnd && !near->closed);
        QVERIFY((near->points.front() - s.viewGraph->nodes[0].image).norm() < 1e-9);
        QVERIFY((near->points.back() - s.viewGraph->nodes[2].image).norm() < 1e-9);
        QCOMPARE(near->points.size(), size_t(5)); // the T-junction's point once

        const IllustrationStroke* far = strokeWith(strokes, 2);
        QVERIFY(far && far->chains.size() == 1);
        QVERIFY((far->points.front() - s.viewGraph->nodes[3].image).norm() < 1e-9);
        QVERIFY(far->taperStart);
        QVERIFY(!far->taperEnd);

        const IllustrationStroke* loop = strokeWith(strokes, 4);
        QVERIFY(loop && loop->closed && !loop->taperStart && !loop->taperEnd);
        const IllustrationStroke* connected = strokeWith(strokes, 6);
        QVERIFY(connected && connected == strokeWith(strokes, 7));
        QVERIFY(connected->closed && !connected->taperStart && !connected->taperEnd);

        QVERIFY(!strokeWith(strokes, 3));
        QVERIFY(!strokeWith(strokes, 5));
        IllustrationOptions withHidden;
        withHidden.drawHidden = true;
        const std::vector<IllustrationStroke> all = illustrationStrokes(s, camera, withHidden);
        QCOMPARE(all.size(), size_t(5));
        const IllustrationStroke* hidden = strokeWith(all, 3);
        QVERIFY(hidden && hidden->hidden && hidden->chains.size() == 1);
        QVERIFY(!strokeWith(all, 5));
    }

    // §9.2: ribs perpendicular to the stroke, the width narrowed linearly
    // to 0 over the taper length at a tapered end, never more than half the
    // stroke each when both ends taper.
    void taperedOutlineNarrowsToAPoint() {
        IllustrationStroke s;
        for (int i = 0; i <= 100; ++i)
            s.points.emplace_back(i, 50.0);
        s.taperStart = true;
        const std::vector<Vec2> outline = strokeOutline(s, 2.0, 12.0);
        QCOMPARE(outline.size(), size_t(202));
        const auto width = [&](size_t i) {
            return (outline[i] - outline[201 - i]).norm();
        };
        QVERIFY(width(0) < 1e-12);
        QVERIFY(std::abs(width(6) - 1.0) < 1e-12);
        QVERIFY(std::abs(width(12) - 2.0) < 1e-12);
        QVERIFY(std::abs(width(100) - 2.0) < 1e-12);
        // Ribs perpendicular: the outline's left side lies at y = 50 + w/2.
        QVERIFY(std::abs(outline[50].y() - 51.0) < 1e-12);

        IllustrationStroke shortStroke;
        for (int i = 0; i <= 10; ++i)
            shortStroke.points.emplace_back(i, 0.0);
        shortStroke.taperStart = shortStroke.taperEnd = true;
        const std::vector<Vec2> both = strokeOutline(shortStroke, 2.0, 12.0);
        const auto w = [&](size_t i) {
            return (both[i] - both[21 - i]).norm();
        };
        QVERIFY(w(0) < 1e-12 && w(10) < 1e-12);
        QVERIFY(std::abs(w(5) - 2.0) < 1e-12);
        QVERIFY(std::abs(w(2) - 0.8) < 1e-12);
    }

    // The document: well-formed, Inkscape layers per visibility and curve
    // type, the styles given, tapered strokes as filled outlines whose
    // tapered end is a point, no node glyph and no diagnostic attribute.
    void documentHasInkscapeLayersAndNoGlyphs() {
        const Camera camera = frontCamera();
        const Snapshot s = handMadeSnapshot(camera);
        IllustrationOptions options;
        options.contour = {"#aa0000", 3.0};
        options.title = "hand-made <graph>";
        const ParsedSvg svg = parse(illustrationSvgDocument(s, camera, options));
        QVERIFY2(svg.error.isEmpty(), qPrintable(svg.error));
        QVERIFY(!svg.group("hidden"));
        const SvgElement* visible = svg.group("visible");
        QVERIFY(visible);
        QCOMPARE(visible->attribute("groupmode"), QString("layer"));
        QCOMPARE(visible->attribute("label"), QString("Visible lines"));
        const SvgElement* contour = svg.group("visible-contour");
        QVERIFY(contour);
        QCOMPARE(contour->attribute("label"), QString("Contour"));
        QCOMPARE(contour->attribute("stroke"), QString("#aa0000"));
        QCOMPARE(contour->attribute("stroke-width"), QString("3.000"));
        QVERIFY(svg.group("visible-boundary"));
        for (const SvgElement& e : svg.elements) {
            QVERIFY2(e.name == "svg" || e.name == "g" || e.name == "path" || e.name == "title" ||
                         e.name == "desc",
                     qPrintable(e.name));
            for (const auto& [key, value] : e.attributes)
                QVERIFY2(!key.startsWith("data-"), qPrintable(key));
        }
        const std::vector<const SvgElement*> contourPaths = svg.in("visible-contour", "path");
        QCOMPARE(contourPaths.size(), size_t(3)); // near, far, the closed one
        int tapered = 0;
        for (const SvgElement* p : contourPaths) {
            if (p->attribute("class") != "tapered")
                continue;
            ++tapered;
            QCOMPARE(p->attribute("fill"), QString("#aa0000"));
            QCOMPARE(p->attribute("stroke"), QString("none"));
            const std::vector<Vec2> outline = pathPoints(*p);
            // The first point is the tapered start: the stroke's end itself.
            const Vec2 start = outline.front();
            QVERIFY((start - s.viewGraph->nodes[0].image).norm() < 1e-3 ||
                    (start - s.viewGraph->nodes[3].image).norm() < 1e-3);
        }
        QCOMPARE(tapered, 2);

        options.drawHidden = true;
        const ParsedSvg withHidden = parse(illustrationSvgDocument(s, camera, options));
        const SvgElement* hidden = withHidden.group("hidden-contour");
        QVERIFY(hidden);
        QCOMPARE(hidden->attribute("label"), QString("Hidden contour"));
        QVERIFY(!hidden->attribute("stroke-dasharray").isEmpty());
        QCOMPARE(hidden->attribute("stroke-width"), QString("1.500"));
        QCOMPARE(withHidden.in("hidden-contour", "path").size(), size_t(1));
    }

    // A real drawing: the consistent contours of the bumpy torus from the
    // 26 views. Every visible chain is drawn by exactly one stroke, the
    // strokes' length is the visible length, and every end of a stroke at a
    // curtain fold is tapered.
    void methodDrawingIsTheVisibleViewGraph() {
        const auto cage = shape("bumpy-torus", 12);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        int folds = 0, tapersAtFolds = 0;
        for (size_t v = 0; v < views.size(); ++v) {
            const Snapshot s = runMethod("consistent", cage, views[v]);
            QVERIFY(s.viewGraph);
            const ViewGraph& g = *s.viewGraph;
            IllustrationOptions options;
            options.minSpacing = 0.0; // compare lengths exactly
            const std::vector<IllustrationStroke> strokes =
                illustrationStrokes(s, views[v], options);
            std::multiset<Index> drawn;
            double strokeLength = 0.0;
            for (const IllustrationStroke& st : strokes) {
                drawn.insert(st.chains.begin(), st.chains.end());
                strokeLength += length(st.points);
                for (const bool atStart : {true, false}) {
                    if (st.closed)
                        continue;
                    const Index c = atStart ? st.chains.front() : st.chains.back();
                    const ViewChain& ch = g.chains[static_cast<size_t>(c)];
                    // The stroke end's node: the chain's end that is not
                    // joined to the neighbouring chain of the stroke.
                    const Vec2 end = atStart ? st.points.front() : st.points.back();
                    for (const Index n : {ch.startNode, ch.endNode}) {
                        if (n == kInvalidIndex)
                            continue;
                        const ViewNode& node = g.nodes[static_cast<size_t>(n)];
                        if (node.type != ViewNodeType::CurtainFold ||
                            (node.image - end).norm() > 1e-6)
                            continue;
                        ++folds;
                        tapersAtFolds += (atStart ? st.taperStart : st.taperEnd) ? 1 : 0;
                    }
                }
            }
            for (size_t c = 0; c < g.chains.size(); ++c)
                QCOMPARE(drawn.count(static_cast<Index>(c)), size_t(g.chains[c].visible() ? 1 : 0));
            QVERIFY2(
                std::abs(strokeLength - g.visibleLengthPixels()) <
                    1e-6 * g.visibleLengthPixels() + 1e-6,
                qPrintable(QString("%1 vs %2").arg(strokeLength).arg(g.visibleLengthPixels())));
        }
        qInfo("bumpy torus, 26 views: %d stroke ends at curtain folds, %d tapered", folds,
              tapersAtFolds);
        QVERIFY(folds > 0);
        QCOMPARE(tapersAtFolds, folds);
    }
};

QTEST_GUILESS_MAIN(TestIllustrationSvg)
#include "test_illustration_svg.moc"
