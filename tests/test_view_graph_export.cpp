// The view graph in the exporters: the SVG layers (visible,
// hidden dashed, simplified, node markers per type) and the JSON report's
// "view_graph", on a hand-made graph whose every value is known.
#include "SvgTestSupport.h"
#include "export/JsonReport.h"
#include "export/SvgWriter.h"
#include "pipeline/ViewGraph.h"

#include <QtTest>
#include <map>

using namespace contour;
using namespace contour::testing;

namespace {

// Chains: 0 visible contour (ray test) from node 0 to node 1; 1 hidden
// contour (QI 2, behind the T-junction) from node 1 to node 2; 2 a boundary
// chain simplified away; 3 a visible closed surface-intersection loop;
// 4 a concave contour chain in conflict. Nodes: 0 curtain fold, 1
// T-junction, 2 bifurcation.
Snapshot handMadeSnapshot(const Camera& camera) {
    auto graph = std::make_shared<ViewGraph>();
    graph->chains.push_back(chain(CurveType::Contour, 0, {{-1, 0, 0}, {0, 0.5, 0}, {1, 0, 0}},
                                  camera, 0, VisibilityRule::RayTest));
    graph->chains.push_back(chain(CurveType::Contour, 0, {{1, 0, 0}, {1, -1, 0}}, camera, 2,
                                  VisibilityRule::ImageIntersection));
    graph->chains.push_back(chain(CurveType::Boundary, 1, {{-1, -1, 0}, {-0.9, -1, 0}}, camera, 0,
                                  VisibilityRule::Propagation));
    graph->chains[2].simplifiedAway = true;
    graph->chains.push_back(chain(CurveType::SurfaceIntersection, 2,
                                  {{0, 0, 0}, {0.2, 0, 0}, {0.2, 0.2, 0}, {0, 0, 0}}, camera, 0,
                                  VisibilityRule::Propagation));
    graph->chains[3].closed = true;
    graph->chains.push_back(chain(CurveType::Contour, 3, {{-1, 1, 0}, {1, 1, 0}}, camera, 1,
                                  VisibilityRule::ConcaveContour));
    graph->chains[4].concave = true;
    graph->chains[4].conflict = true;
    graph->chains[4].rayQi = 0;
    graph->chains[0].startNode = 0;
    graph->chains[0].endNode = 1;
    graph->chains[1].startNode = 1;
    graph->chains[1].endNode = 2;

    auto node = [&](ViewNodeType type, const Vec3& p, std::vector<Index> chains) {
        ViewNode n;
        n.type = type;
        n.position = p;
        n.image = camera.project(p).pixel;
        n.chains = std::move(chains);
        graph->nodes.push_back(n);
    };
    node(ViewNodeType::CurtainFold, {-1, 0, 0}, {0});
    node(ViewNodeType::ImageIntersection, {1, 0, 0}, {0, 1});
    graph->nodes[1].farChains = {0, 1};
    graph->nodes[1].qiStep = 2;
    node(ViewNodeType::Bifurcation, {1, -1, 0}, {1});
    graph->conflicts.push_back({4, 1, 0, "ray-test"});
    graph->rayTests = 3;

    Snapshot s;
    s.phaseName = "visibility";
    s.curves = std::make_shared<const std::vector<Polyline>>(4);
    s.viewGraph = graph;
    return s;
}

} // namespace

class TestViewGraphExport : public QObject {
    Q_OBJECT
private slots:
    void svgLayers() {
        const Camera camera = frontCamera();
        const Snapshot s = handMadeSnapshot(camera);
        const ParsedSvg svg = parse(svgDocument(s, camera));
        QVERIFY2(svg.error.isEmpty(), qPrintable(svg.error));
        QCOMPARE(svg.elements.front().attribute("width"), QString("400"));
        QCOMPARE(svg.elements.front().attribute("viewBox"), QString("0 0 400 300"));

        // Layers and per-type groups; the raw-curve groups are gone.
        for (const QString id :
             {"visible", "hidden", "simplified", "nodes", "visible-contour",
              "visible-surface-intersection", "hidden-contour", "simplified-boundary",
              "nodes-curtain-fold", "nodes-image-intersection", "nodes-bifurcation"})
            QVERIFY2(svg.group(id), qPrintable(id));
        QVERIFY(!svg.group("contour"));
        QVERIFY(!svg.group("visible-boundary")); // no such chain: no empty group
        QVERIFY(!svg.group("visible")->attributes.contains("display"));
        QVERIFY(!svg.group("hidden")->attribute("stroke-dasharray").isEmpty());
        QVERIFY(!svg.group("hidden")->attributes.contains("display"));
        QCOMPARE(svg.group("simplified")->attribute("display"), QString("none"));

        const auto visible = svg.in("visible", "polyline");
        const auto hidden = svg.in("hidden", "polyline");
        const auto simplified = svg.in("simplified", "polyline");
        QCOMPARE(visible.size(), size_t(2));
        QCOMPARE(hidden.size(), size_t(2));
        QCOMPARE(simplified.size(), size_t(1));
        const SvgElement& first = *visible[0];
        QCOMPARE(first.attribute("data-chain"), QString("0"));
        QCOMPARE(first.attribute("data-qi"), QString("0"));
        QCOMPARE(first.attribute("data-rule"), QString("ray-test"));
        QCOMPARE(first.attribute("data-type"), QString("contour"));
        const std::vector<Vec2> drawn = points(first);
        QCOMPARE(drawn.size(), size_t(3));
        for (size_t i = 0; i < drawn.size(); ++i)
            QVERIFY((drawn[i] - s.viewGraph->chains[0].image[i]).norm() < 1e-3);
        QCOMPARE(visible[1]->attribute("data-type"), QString("surface-intersection"));
        QCOMPARE(visible[1]->attribute("data-closed"), QString("true"));
        QCOMPARE(hidden[0]->attribute("data-qi"), QString("2"));
        QCOMPARE(hidden[0]->attribute("data-rule"), QString("image-intersection"));
        QCOMPARE(hidden[1]->attribute("data-conflict"), QString("true"));
        QCOMPARE(hidden[1]->attribute("data-concave"), QString("true"));
        QCOMPARE(simplified[0]->attribute("data-chain"), QString("2"));

        // One marker per node, each a different shape, at the node's pixel.
        QCOMPARE(svg.in("nodes-curtain-fold", "circle").size(), size_t(1));
        QCOMPARE(svg.in("nodes-image-intersection", "rect").size(), size_t(1));
        QCOMPARE(svg.in("nodes-bifurcation", "path").size(), size_t(1));
        const SvgElement& fold = *svg.in("nodes-curtain-fold", "circle")[0];
        QCOMPARE(fold.attribute("data-node"), QString("0"));
        QCOMPARE(fold.attribute("data-class"), QString("dead-end"));
        QVERIFY(std::abs(fold.attribute("cx").toDouble() - s.viewGraph->nodes[0].image.x()) < 1e-3);
        QCOMPARE(svg.in("nodes-image-intersection", "rect")[0]->attribute("data-class"),
                 QString("dead-end"));
        QCOMPARE(svg.in("nodes-bifurcation", "path")[0]->attribute("data-class"),
                 QString("hidden"));
    }

    void svgHiddenLayerCanBeHidden() {
        const Camera camera = frontCamera();
        SvgOptions options;
        options.drawHidden = false;
        options.drawNodes = false;
        const ParsedSvg svg = parse(svgDocument(handMadeSnapshot(camera), camera, options));
        QVERIFY2(svg.error.isEmpty(), qPrintable(svg.error));
        // Still in the document (nothing lost), but not displayed.
        QCOMPARE(svg.group("hidden")->attribute("display"), QString("none"));
        QCOMPARE(svg.group("nodes")->attribute("display"), QString("none"));
        QCOMPARE(svg.in("hidden", "polyline").size(), size_t(2));
    }

    // Without a view graph the document is the raw-curve one of before.
    void svgWithoutViewGraph() {
        const Camera camera = frontCamera();
        Snapshot s = handMadeSnapshot(camera);
        s.viewGraph.reset();
        const ParsedSvg svg = parse(svgDocument(s, camera));
        QVERIFY2(svg.error.isEmpty(), qPrintable(svg.error));
        QVERIFY(svg.group("contour") && svg.group("boundary"));
        QVERIFY(!svg.group("visible") && !svg.group("nodes"));
    }

    // A chain passing behind a perspective eye is drawn in front of it only.
    void svgChainBehindTheEye() {
        const Camera camera = frontCamera();
        Snapshot s = handMadeSnapshot(camera);
        auto graph = std::make_shared<ViewGraph>(*s.viewGraph);
        graph->chains[0].points = {{-1, 0, 0}, {0, 0, 6}, {1, 0, 0}, {1, 0.5, 0}};
        s.viewGraph = graph;
        const ParsedSvg svg = parse(svgDocument(s, camera));
        const auto visible = svg.in("visible-contour", "polyline");
        QCOMPARE(visible.size(), size_t(1)); // the piece [1, 0, 0] - [1, 0.5, 0]
        QCOMPARE(visible[0]->attribute("class"), QString("clipped"));
        QCOMPARE(points(*visible[0]).size(), size_t(2));
    }

    void jsonViewGraph() {
        const Camera camera = frontCamera();
        const Snapshot s = handMadeSnapshot(camera);
        const nlohmann::json j = viewGraphJson(*s.viewGraph);
        const nlohmann::json& totals = j["totals"];
        QCOMPARE(totals["chains"].get<int>(), 5);
        QCOMPARE(totals["visible_chains"].get<int>(), 2);
        QCOMPARE(totals["hidden_chains"].get<int>(), 2);
        QCOMPARE(totals["simplified_chains"].get<int>(), 1);
        QCOMPARE(totals["conflicts"].get<int>(), 1);
        QCOMPARE(totals["ray_tests"].get<int>(), 3);
        QCOMPARE(totals["nodes"].get<int>(), 3);
        QCOMPARE(totals["nodes_by_type"]["image-intersection"].get<int>(), 1);
        const ViewGraph& g = *s.viewGraph;
        QVERIFY(std::abs(totals["visible_length_px"].get<double>() - g.visibleLengthPixels()) <
                1e-9);
        QVERIFY(std::abs(totals["hidden_length_px"].get<double>() +
                         totals["simplified_length_px"].get<double>() - g.hiddenLengthPixels()) <
                1e-9);

        QCOMPARE(j["chains"].size(), size_t(5));
        const nlohmann::json& c1 = j["chains"][1];
        QCOMPARE(c1["type"].get<std::string>(), std::string("contour"));
        QCOMPARE(c1["qi"].get<int>(), 2);
        QCOMPARE(c1["rule"].get<std::string>(), std::string("image-intersection"));
        QCOMPARE(c1["start_node"].get<int>(), 1);
        QCOMPARE(c1["end_node"].get<int>(), 2);
        QCOMPARE(c1["visible"].get<bool>(), false);
        QCOMPARE(c1["points"].size(), size_t(2));
        QVERIFY(std::abs(c1["points"][1][0].get<double>() - g.chains[1].image[1].x()) <= 0.005);
        QCOMPARE(j["chains"][2]["simplified_away"].get<bool>(), true);
        QCOMPARE(j["chains"][4]["conflict"].get<bool>(), true);
        QCOMPARE(j["chains"][4]["ray_qi"].get<int>(), 0);

        QCOMPARE(j["nodes"].size(), size_t(3));
        const nlohmann::json& t = j["nodes"][1];
        QCOMPARE(t["type"].get<std::string>(), std::string("image-intersection"));
        QCOMPARE(t["class"].get<std::string>(), std::string("dead-end"));
        QCOMPARE(t["far_chains"][1].get<int>(), 1);
        QCOMPARE(t["near_chains"][0].get<int>(), -1);
        QCOMPARE(t["qi_step"].get<int>(), 2);
        QCOMPARE(t["chains"].size(), size_t(2));
        QCOMPARE(j["conflicts"][0]["chain"].get<int>(), 4);
        QCOMPARE(j["conflicts"][0]["reason"].get<std::string>(), std::string("ray-test"));
    }
};

QTEST_GUILESS_MAIN(TestViewGraphExport)
#include "test_view_graph_export.moc"
