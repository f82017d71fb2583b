// The rule-based parts of visibility on hand-built view graphs:
// - topological simplification (Bénard 2014 §9, Fig. 24): each rule (a)-(d)
//   fires on a minimal example and does not fire on its near miss; the
//   result is a fixed point (a second run hides nothing), never hides a
//   chain longer than the threshold, never hides a junction-to-junction
//   chain unless it is overlapped, and changes nothing but simplifiedAway;
// - consistent visibility (Bénard 2014 §8.4): the majority vote (ambiguous
//   segments left out, ties invisible), interior chains, rules (a)-(c) of
//   ambiguity resolution and their near misses, cusp consistency (Fig. 23b),
//   and the "consistent-vote" conflicts; real ray tests on a small mesh of
//   strips (the curves) behind a half-screen occluder;
// - end to end, once the visibility phase exists: sphere and torus with the
//   consistent method (no chain ambiguous; the sphere's contour fully
//   visible) and the interpolated method's visible length against the mesh
//   method's.
#include "ContourTestSupport.h"
#include "visibility/ConsistentVisibility.h"
#include "visibility/RayCaster.h"
#include "visibility/TopologicalSimplification.h"

#include <QtTest>
#include <algorithm>
#include <map>
#include <random>
#include <set>

using namespace contour;
using namespace contour::testing;

namespace {

// ---------------------------------------------------------------- graphs

Index addNode(ViewGraph& g, ViewNodeType type, const Vec2& image = Vec2::Zero()) {
    ViewNode n;
    n.type = type;
    n.image = image;
    g.nodes.push_back(n);
    return static_cast<Index>(g.nodes.size() - 1);
}

// A chain through the given image points (pixels), between two nodes
// (kInvalidIndex for an open end); lengthPixels from its points.
Index addChain(ViewGraph& g, Index start, Index end, const std::vector<Vec2>& image, int qi = 0,
               CurveType type = CurveType::Contour) {
    ViewChain c;
    c.type = type;
    c.image = image;
    for (const Vec2& p : image) {
        c.points.push_back(Vec3(p.x(), p.y(), 0.0));
        c.depth.push_back(1.0);
    }
    for (size_t i = 0; i + 1 < image.size(); ++i)
        c.lengthPixels += (image[i + 1] - image[i]).norm();
    c.segmentElement.assign(c.segmentCount(), kInvalidIndex);
    c.startNode = start;
    c.endNode = end;
    c.qi = qi;
    c.decidedBy = VisibilityRule::RayTest;
    const Index index = static_cast<Index>(g.chains.size());
    g.chains.push_back(std::move(c));
    if (start != kInvalidIndex)
        g.nodes[start].chains.push_back(index);
    if (end != kInvalidIndex)
        g.nodes[end].chains.push_back(index);
    return index;
}

// A straight chain from a to b sampled every pixel.
std::vector<Vec2> line(const Vec2& a, const Vec2& b) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm())));
    std::vector<Vec2> out;
    for (int i = 0; i <= n; ++i)
        out.push_back(a + (b - a) * (double(i) / n));
    return out;
}

std::vector<Vec2> join(std::vector<Vec2> a, const std::vector<Vec2>& b) {
    a.insert(a.end(), b.begin() + 1, b.end());
    return a;
}

constexpr double kThreshold = 15.0;

// End-to-end runs: every third protocol view in Release, every ninth in
// unoptimized builds.
#ifdef __OPTIMIZE__
constexpr size_t kEndToEndStride = 3;
#else
constexpr size_t kEndToEndStride = 9;
#endif

// One minimal example per case: the graph and the chains expected hidden.
struct SimplificationCase {
    ViewGraph graph;
    std::vector<int> hidden;
};

SimplificationCase simplificationCase(const QString& name) {
    SimplificationCase k;
    ViewGraph& g = k.graph;
    const auto node = [&](double x, double y, ViewNodeType t = ViewNodeType::ImageIntersection) {
        return addNode(g, t, Vec2(x, y));
    };
    const ViewNodeType end = ViewNodeType::CurveEnd, fold = ViewNodeType::CurtainFold;
    if (name == "a: junction to dead-end spur") {
        const Index j = node(100, 100), a = node(0, 100, end), b = node(200, 100, end),
                    d = node(100, 105, fold);
        addChain(g, a, j, line({0, 100}, {100, 100}));
        addChain(g, j, b, line({100, 100}, {200, 100}));
        k.hidden.push_back(addChain(g, j, d, line({100, 100}, {100, 105})));
    } else if (name == "a: spur above the threshold stays") {
        const Index j = node(100, 100), a = node(0, 100, end), b = node(200, 100, end),
                    d = node(100, 120, fold);
        addChain(g, a, j, line({0, 100}, {100, 100}));
        addChain(g, j, b, line({100, 100}, {200, 100}));
        addChain(g, j, d, line({100, 100}, {100, 120}));
    } else if (name == "a: two spurs at one junction, shortest first") {
        // Hiding the 5 px spur leaves the junction a connector, so the 8 px
        // one continues the long chain and stays.
        const Index j = node(100, 100), a = node(0, 100, end), d1 = node(100, 105, fold),
                    d2 = node(108, 100, fold);
        addChain(g, a, j, line({0, 100}, {100, 100}));
        k.hidden.push_back(addChain(g, j, d1, line({100, 100}, {100, 105})));
        addChain(g, j, d2, line({100, 100}, {108, 100}));
    } else if (name == "b: isolated speck") {
        const Index a = node(0, 0, end), b = node(100, 0, end);
        addChain(g, a, b, line({0, 0}, {100, 0}));
        const Index c = node(50, 50, fold), d = node(56, 50, fold);
        k.hidden.push_back(addChain(g, c, d, line({50, 50}, {56, 50})));
    } else if (name == "b: run through a connector below the threshold") {
        const Index c = node(50, 50, fold), m = node(56, 50, fold), d = node(62, 50, end);
        k.hidden.push_back(addChain(g, c, m, line({50, 50}, {56, 50})));
        k.hidden.push_back(addChain(g, m, d, line({56, 50}, {62, 50})));
    } else if (name == "b: run through a connector above the threshold stays") {
        const Index c = node(50, 50, fold), m = node(60, 50, fold), d = node(70, 50, end);
        addChain(g, c, m, line({50, 50}, {60, 50}));
        addChain(g, m, d, line({60, 50}, {70, 50}));
    } else if (name == "b: open chain without nodes") {
        k.hidden.push_back(addChain(g, kInvalidIndex, kInvalidIndex, line({5, 5}, {12, 5})));
    } else if (name == "c: small loop at a junction") {
        const Index j = node(100, 100), a = node(0, 100, end), b = node(200, 100, end);
        addChain(g, a, j, line({0, 100}, {100, 100}));
        addChain(g, j, b, line({100, 100}, {200, 100}));
        k.hidden.push_back(
            addChain(g, j, j,
                     join(join(line({100, 100}, {103, 97}), line({103, 97}, {97, 97})),
                          line({97, 97}, {100, 100}))));
    } else if (name == "c: small closed chain") {
        const Index c = addChain(g, kInvalidIndex, kInvalidIndex,
                                 join(join(line({10, 10}, {14, 10}), line({14, 10}, {12, 13})),
                                      line({12, 13}, {10, 10})));
        g.chains[c].closed = true;
        k.hidden.push_back(c);
    } else if (name == "c: large closed chain stays") {
        const Index c = addChain(g, kInvalidIndex, kInvalidIndex,
                                 join(join(line({10, 10}, {30, 10}), line({30, 10}, {20, 30})),
                                      line({20, 30}, {10, 10})));
        g.chains[c].closed = true;
    } else if (name == "d: overlapped junction-to-junction chain") {
        // A line 0..100 cut at junctions x = 40 and 50, and a second chain
        // between the junctions half a pixel off it: the shorter of the two
        // overlapping pieces is hidden, after which the junctions are
        // connectors and the other piece continues the line.
        const Index e0 = node(0, 0, end), j1 = node(40, 0), j2 = node(50, 0),
                    e1 = node(100, 0, end);
        addChain(g, e0, j1, line({0, 0}, {40, 0}));
        k.hidden.push_back(addChain(g, j1, j2, line({40, 0}, {50, 0})));
        addChain(g, j2, e1, line({50, 0}, {100, 0}));
        addChain(g, j1, j2, join(line({40, 0}, {45, 0.5}), line({45, 0.5}, {50, 0})));
    } else if (name == "d: junction-to-junction chain not overlapped stays") {
        const Index e0 = node(0, 0, end), j1 = node(40, 0), j2 = node(50, 0),
                    e1 = node(100, 0, end);
        addChain(g, e0, j1, line({0, 0}, {40, 0}));
        addChain(g, j1, j2, line({40, 0}, {50, 0}));
        addChain(g, j2, e1, line({50, 0}, {100, 0}));
        addChain(g, j1, j2, join(line({40, 0}, {45, 4}), line({45, 4}, {50, 0})));
    } else if (name == "hidden chains do not count in node classes") {
        // The junction has one hidden chain: with visible chains only it is a
        // connector, so the short chain continues the long one.
        const Index j = node(100, 100), a = node(0, 100, end), b = node(200, 100, end),
                    d = node(100, 105, fold);
        addChain(g, a, j, line({0, 100}, {100, 100}));
        addChain(g, j, b, line({100, 100}, {200, 100}), 2);
        addChain(g, j, d, line({100, 100}, {100, 105}));
    }
    return k;
}

// A random graph: nodes on a 200 px square, chains between random node pairs
// (some self loops), wiggly, 80 % visible.
ViewGraph randomGraph(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(0.0, 200.0), jitter(-2.0, 2.0), unit(0.0, 1.0);
    ViewGraph g;
    const int nodes = 30;
    for (int i = 0; i < nodes; ++i)
        addNode(g, unit(rng) < 0.5 ? ViewNodeType::ImageIntersection : ViewNodeType::CurtainFold,
                Vec2(pos(rng), pos(rng)));
    std::uniform_int_distribution<int> pick(0, nodes - 1);
    for (int c = 0; c < 60; ++c) {
        const Index a = pick(rng);
        Index b = pick(rng);
        if (unit(rng) < 0.3) // short chains near a
            b = a;
        const Vec2 pa = g.nodes[a].image;
        const Vec2 pb = g.nodes[b].image;
        std::vector<Vec2> pts{pa};
        const Vec2 mid = a == b ? Vec2(pa + Vec2(jitter(rng) * 3, jitter(rng) * 3))
                                : Vec2(0.5 * (pa + pb) + Vec2(jitter(rng), jitter(rng)));
        pts.push_back(mid);
        pts.push_back(pb);
        addChain(g, a, b, pts, unit(rng) < 0.8 ? 0 : 1);
    }
    return g;
}

// ------------------------------------------------------- consistent scenes

// Curves lying on the top edges of thin strips at z = 0, seen from z = 5;
// an occluder square at z = 1 covers every point with x < 0. A segment's
// ray test is therefore 1 for x < 0 and 0 for x > 0.
struct StripScene {
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    struct Strip {
        std::vector<Vec3> top;
        std::vector<Index> topFace; // per segment: the face whose corner 1 is the top edge
    };
    std::vector<Strip> strips;
    std::vector<std::uint8_t> faceInconsistent;
    std::vector<std::uint8_t> vertexIsCusp;
    std::unique_ptr<TriangleMesh> mesh;
    std::unique_ptr<RayCaster> rays;
    Camera camera;
    ViewGraph graph;

    StripScene() {
        const Index o = static_cast<Index>(positions.size());
        positions.insert(positions.end(),
                         {Vec3(-3, -3, 1), Vec3(0, -3, 1), Vec3(0, 3, 1), Vec3(-3, 3, 1)});
        triangles.push_back({o, o + 1, o + 2});
        triangles.push_back({o, o + 2, o + 3});
    }

    // A strip whose top row runs from x0 to x1 at height y, `segments` edges.
    int addStrip(double x0, double x1, double y, int segments) {
        Strip s;
        const Index base = static_cast<Index>(positions.size());
        for (int i = 0; i <= segments; ++i) {
            const double x = x0 + (x1 - x0) * i / segments;
            positions.push_back(Vec3(x, y, 0));        // top: base + 2i
            positions.push_back(Vec3(x, y - 0.04, 0)); // bottom: base + 2i + 1
            s.top.push_back(Vec3(x, y, 0));
        }
        for (int i = 0; i < segments; ++i) {
            const Index t0 = base + 2 * i, b0 = t0 + 1, t1 = t0 + 2, b1 = t0 + 3;
            triangles.push_back({b0, b1, t1});
            triangles.push_back({b0, t1, t0}); // corner 1 -> 2 is the top edge t1 -> t0
            s.topFace.push_back(static_cast<Index>(triangles.size() - 1));
        }
        strips.push_back(std::move(s));
        return static_cast<int>(strips.size() - 1);
    }

    void finish() {
        mesh = std::make_unique<TriangleMesh>(positions, triangles);
        rays = std::make_unique<RayCaster>(*mesh);
        faceInconsistent.assign(mesh->faceCount(), 0);
        vertexIsCusp.assign(mesh->vertexCount(), 0);
    }

    // Segments [from, to) of a strip lie on inconsistent faces.
    void inconsistent(int strip, int from, int to) {
        for (int i = from; i < to; ++i) {
            faceInconsistent[strips[strip].topFace[i]] = 1;
            faceInconsistent[strips[strip].topFace[i] - 1] = 1;
        }
    }

    Index chain(int strip, Index start, Index end, int propagatedQi,
                CurveType type = CurveType::Contour, bool concave = false) {
        const Strip& s = strips[strip];
        ViewChain c;
        c.type = type;
        c.concave = concave;
        c.points = s.top;
        for (const Vec3& p : s.top) {
            const ProjectedPoint q = camera.project(p);
            c.image.push_back(q.pixel);
            c.depth.push_back(q.depth);
        }
        for (size_t i = 0; i + 1 < c.image.size(); ++i)
            c.lengthPixels += (c.image[i + 1] - c.image[i]).norm();
        for (Index f : s.topFace)
            c.segmentElement.push_back(mesh->edge(TriangleMesh::halfedge(f, 1)));
        c.startNode = start;
        c.endNode = end;
        c.qi = propagatedQi;
        c.qiLowerBound = concave ? 1 : 0;
        c.decidedBy = VisibilityRule::Propagation;
        const Index index = static_cast<Index>(graph.chains.size());
        graph.chains.push_back(std::move(c));
        if (start != kInvalidIndex)
            graph.nodes[start].chains.push_back(index);
        if (end != kInvalidIndex)
            graph.nodes[end].chains.push_back(index);
        return index;
    }

    Index node(ViewNodeType type) { return addNode(graph, type); }

    void resolve(double shortChainPixels = 20.0) {
        resolveConsistentVisibility(graph, *mesh, camera, *rays, faceInconsistent, vertexIsCusp,
                                    {0.0, shortChainPixels});
    }
};

struct Expected {
    Index chain;
    bool visible;
    VisibilityRule rule;
};

} // namespace

class TestVisibilityRules : public QObject {
    Q_OBJECT

private slots:
    // ---------------------------------------------------- simplification
    void simplificationRules_data() {
        QTest::addColumn<QString>("name");
        for (const char* name :
             {"a: junction to dead-end spur", "a: spur above the threshold stays",
              "a: two spurs at one junction, shortest first", "b: isolated speck",
              "b: run through a connector below the threshold",
              "b: run through a connector above the threshold stays", "b: open chain without nodes",
              "c: small loop at a junction", "c: small closed chain", "c: large closed chain stays",
              "d: overlapped junction-to-junction chain",
              "d: junction-to-junction chain not overlapped stays",
              "hidden chains do not count in node classes"})
            QTest::newRow(name) << QString(name);
    }
    void simplificationRules() {
        QFETCH(QString, name);
        SimplificationCase k = simplificationCase(name);
        QVERIFY(!k.graph.chains.empty());
        const ViewGraph before = k.graph;
        const SimplificationResult r = simplifyViewGraph(k.graph, kThreshold);
        std::vector<int> hidden;
        for (size_t c = 0; c < k.graph.chains.size(); ++c)
            if (k.graph.chains[c].simplifiedAway)
                hidden.push_back(static_cast<int>(c));
        std::sort(k.hidden.begin(), k.hidden.end());
        QCOMPARE(hidden, k.hidden);
        QCOMPARE(r.chainsHidden, static_cast<int>(k.hidden.size()));
        QVERIFY(r.iterations >= 1);
        // Only simplifiedAway changes, and never on a long chain.
        for (size_t c = 0; c < k.graph.chains.size(); ++c) {
            QCOMPARE(k.graph.chains[c].qi, before.chains[c].qi);
            if (k.graph.chains[c].simplifiedAway)
                QVERIFY(k.graph.chains[c].lengthPixels < kThreshold);
        }
        // Idempotent.
        const SimplificationResult again = simplifyViewGraph(k.graph, kThreshold);
        QCOMPARE(again.chainsHidden, 0);
        // A zero threshold hides nothing.
        ViewGraph zero = before;
        QCOMPARE(simplifyViewGraph(zero, 0.0).chainsHidden, 0);
    }

    void simplificationProperties_data() {
        QTest::addColumn<unsigned>("seed");
        QTest::addColumn<double>("threshold");
        for (unsigned seed = 1; seed <= 12; ++seed)
            QTest::newRow(qPrintable(QString("seed %1").arg(seed)))
                << seed << (seed % 3 == 0 ? 40.0 : 15.0);
    }
    void simplificationProperties() {
        QFETCH(unsigned, seed);
        QFETCH(double, threshold);
        ViewGraph g = randomGraph(seed);
        const ViewGraph before = g;
        const SimplificationResult r = simplifyViewGraph(g, threshold);
        int hidden = 0;
        for (size_t c = 0; c < g.chains.size(); ++c) {
            const ViewChain& chain = g.chains[c];
            QCOMPARE(chain.qi, before.chains[c].qi);
            if (!chain.simplifiedAway)
                continue;
            ++hidden;
            QVERIFY(before.chains[c].visible());
            QVERIFY2(
                chain.lengthPixels < threshold,
                qPrintable(QString("chain %1 of %2 px hidden").arg(c).arg(chain.lengthPixels)));
        }
        QCOMPARE(r.chainsHidden, hidden);
        ViewGraph again = g;
        QCOMPARE(simplifyViewGraph(again, threshold).chainsHidden, 0);
        QVERIFY(g.visibleLengthPixels() <= before.visibleLengthPixels());
    }

    // ---------------------------------------------- consistent visibility
    void consistentRules_data() {
        QTest::addColumn<QString>("name");
        for (const char* name :
             {"vote: 7 of 10 visible", "vote: tie is invisible",
              "vote: ambiguous segments left out", "vote: all ambiguous is invisible",
              "interior chain invisible without rays", "a: between two visible cusps",
              "a: one outgoing chain hidden", "b: short chain between T-junctions",
              "b: long chain between T-junctions", "c: boundary chains joined to a visible one",
              "c: boundary joined at a T-junction", "cusp consistency (Fig. 23b)"})
            QTest::newRow(name) << QString(name);
    }
    void consistentRules() {
        QFETCH(QString, name);
        StripScene s;
        std::vector<Expected> expected;
        std::vector<Index> conflicts; // chains expected in graph.conflicts
        double shortChain = 200.0;
        const ViewNodeType end = ViewNodeType::CurveEnd, fold = ViewNodeType::CurtainFold,
                           tj = ViewNodeType::ImageIntersection;
        // Strip layout per scenario; chains are added after finish().
        if (name == "vote: 7 of 10 visible") {
            s.addStrip(-0.3, 0.7, 1.0, 10);
            s.finish();
            const Index c = s.chain(0, s.node(end), s.node(end), 1);
            expected.push_back({c, true, VisibilityRule::MajorityVote});
            conflicts.push_back(c);
        } else if (name == "vote: tie is invisible") {
            s.addStrip(-0.5, 0.5, 1.0, 10); // 5 midpoints each side of x = 0
            s.finish();
            const Index c = s.chain(0, s.node(end), s.node(end), 0);
            expected.push_back({c, false, VisibilityRule::MajorityVote});
            conflicts.push_back(c);
        } else if (name == "vote: ambiguous segments left out") {
            // 8 hidden segments on inconsistent faces (9 ambiguous with the
            // one sharing their vertex), 4 visible: visible 3 : 0. Counting
            // the ambiguous rays would have made it 4 : 8, invisible.
            s.addStrip(-0.8, 0.4, 1.0, 12);
            s.finish();
            s.inconsistent(0, 0, 8);
            const Index c = s.chain(0, s.node(end), s.node(end), 0);
            expected.push_back({c, true, VisibilityRule::MajorityVote});
        } else if (name == "vote: all ambiguous is invisible") {
            s.addStrip(0.1, 0.6, 1.0, 5);
            s.finish();
            s.inconsistent(0, 0, 5);
            const Index c = s.chain(0, s.node(end), s.node(end), 0);
            expected.push_back({c, false, VisibilityRule::AmbiguousInvisible});
            conflicts.push_back(c);
        } else if (name == "interior chain invisible without rays") {
            s.addStrip(0.1, 0.6, 1.0, 5); // in the clear: a ray would say visible
            s.finish();
            const Index c = s.chain(0, s.node(end), s.node(end), 1, CurveType::Contour, true);
            expected.push_back({c, false, VisibilityRule::ConcaveContour});
        } else if (name == "a: between two visible cusps" ||
                   name == "a: one outgoing chain hidden") {
            const bool hidden = name == "a: one outgoing chain hidden";
            s.addStrip(0.1, 0.9, 1.0, 8);
            s.addStrip(0.1, 0.9, 0.8, 4); // X, all ambiguous
            if (hidden)
                s.addStrip(-0.9, -0.1, 0.6, 8);
            else
                s.addStrip(0.1, 0.9, 0.6, 8);
            s.finish();
            s.inconsistent(1, 0, 4);
            const Index c1 = s.node(fold), c2 = s.node(fold);
            const Index o1 = s.chain(0, s.node(end), c1, 0);
            const Index x = s.chain(1, c1, c2, 0);
            const Index o2 = s.chain(2, c2, s.node(end), hidden ? 1 : 0);
            expected.push_back({o1, true, VisibilityRule::MajorityVote});
            expected.push_back({o2, !hidden, VisibilityRule::MajorityVote});
            expected.push_back(
                {x, !hidden,
                 hidden ? VisibilityRule::AmbiguousInvisible : VisibilityRule::AmbiguityCusps});
            if (hidden)
                conflicts.push_back(x);
        } else if (name == "b: short chain between T-junctions" ||
                   name == "b: long chain between T-junctions") {
            const bool isShort = name == "b: short chain between T-junctions";
            s.addStrip(0.1, 0.5, 1.0, 4);   // mate at T1 (visible)
            s.addStrip(0.1, 0.5, 0.8, 4);   // X (ambiguous)
            s.addStrip(0.1, 0.5, 0.6, 4);   // mate at T2 (visible)
            s.addStrip(-0.5, -0.1, 0.4, 4); // near chains (hidden: they do not matter)
            s.addStrip(-0.5, -0.1, 0.2, 4);
            s.finish();
            s.inconsistent(1, 0, 4);
            const Index t1 = s.node(tj), t2 = s.node(tj);
            const Index m1 = s.chain(0, s.node(end), t1, 0);
            const Index x = s.chain(1, t1, t2, 0);
            const Index m2 = s.chain(2, t2, s.node(end), 0);
            const Index n1 = s.chain(3, s.node(end), t1, 1);
            const Index n2 = s.chain(4, t2, s.node(end), 1);
            s.graph.nodes[t1].farChains = {m1, x};
            s.graph.nodes[t1].nearChains = {n1, kInvalidIndex};
            s.graph.nodes[t2].farChains = {x, m2};
            s.graph.nodes[t2].nearChains = {n2, kInvalidIndex};
            shortChain = isShort ? s.graph.chains[x].lengthPixels + 1.0
                                 : s.graph.chains[x].lengthPixels - 1.0;
            expected.push_back({x, isShort,
                                isShort ? VisibilityRule::AmbiguityShortChain
                                        : VisibilityRule::AmbiguousInvisible});
            if (!isShort)
                conflicts.push_back(x);
        } else if (name == "c: boundary chains joined to a visible one" ||
                   name == "c: boundary joined at a T-junction") {
            const bool atT = name == "c: boundary joined at a T-junction";
            s.addStrip(0.1, 0.9, 1.0, 8); // visible contour
            s.addStrip(0.1, 0.5, 0.8, 4); // boundary B1, ambiguous
            s.addStrip(0.1, 0.5, 0.6, 4); // boundary B2, ambiguous, joined to B1 only
            s.finish();
            s.inconsistent(1, 0, 4);
            s.inconsistent(2, 0, 4);
            const Index y = s.node(atT ? tj : ViewNodeType::ContourBoundaryJunction);
            const Index bif = s.node(ViewNodeType::Bifurcation);
            const Index c = s.chain(0, s.node(end), y, 0);
            const Index b1 = s.chain(1, y, bif, 0, CurveType::Boundary);
            const Index b2 = s.chain(2, bif, s.node(end), 0, CurveType::Boundary);
            expected.push_back({c, true, VisibilityRule::MajorityVote});
            if (atT) {
                expected.push_back({b1, false, VisibilityRule::AmbiguousInvisible});
                expected.push_back({b2, false, VisibilityRule::AmbiguousInvisible});
                conflicts.push_back(b1);
                conflicts.push_back(b2);
            } else {
                // B2 is resolved through B1 (the rules run to a fixed point).
                expected.push_back({b1, true, VisibilityRule::AmbiguityBoundary});
                expected.push_back({b2, true, VisibilityRule::AmbiguityBoundary});
            }
        } else if (name == "cusp consistency (Fig. 23b)") {
            // A visible chain A ends at cusp c1; the interior piece between
            // c1 and c2 is cut by a T-junction into X (T–c1) and Y (T–c2); C
            // leaves c2 hidden. The chain from T to the visible cusp (X)
            // becomes visible; Y stays interior.
            s.addStrip(0.1, 0.9, 1.0, 8);   // A
            s.addStrip(0.1, 0.5, 0.8, 4);   // X, interior
            s.addStrip(0.1, 0.5, 0.6, 4);   // Y, interior
            s.addStrip(-0.9, -0.1, 0.4, 8); // C, hidden
            s.finish();
            const Index c1 = s.node(fold), c2 = s.node(fold), t = s.node(tj);
            const Index a = s.chain(0, s.node(end), c1, 0);
            const Index x = s.chain(1, c1, t, 1, CurveType::Contour, true);
            const Index y = s.chain(2, t, c2, 1, CurveType::Contour, true);
            const Index c = s.chain(3, c2, s.node(end), 1);
            s.graph.nodes[t].farChains = {x, y};
            expected.push_back({a, true, VisibilityRule::MajorityVote});
            expected.push_back({x, true, VisibilityRule::CuspConsistency});
            expected.push_back({y, false, VisibilityRule::ConcaveContour});
            expected.push_back({c, false, VisibilityRule::MajorityVote});
            conflicts.push_back(x);
        } else {
            QFAIL("unknown scenario");
        }
        s.resolve(shortChain);
        for (const Expected& e : expected) {
            const ViewChain& c = s.graph.chains[e.chain];
            const QString what = QString("chain %1: qi %2, %3 (expected %4, %5)")
                                     .arg(e.chain)
                                     .arg(c.qi)
                                     .arg(toString(c.decidedBy))
                                     .arg(e.visible ? "visible" : "hidden")
                                     .arg(toString(e.rule));
            QVERIFY2(c.visible() == e.visible, qPrintable(what));
            QVERIFY2(c.decidedBy == e.rule, qPrintable(what));
            QVERIFY2(c.ambiguous == (e.rule == VisibilityRule::AmbiguousInvisible),
                     qPrintable(what));
            QVERIFY2(c.visible() || c.qi >= 1, qPrintable(what));
            QCOMPARE(c.segmentRayQi.size(), c.segmentCount());
        }
        std::set<Index> reported;
        for (const VisibilityConflict& k : s.graph.conflicts) {
            QCOMPARE(QString::fromStdString(k.reason), QString("consistent-vote"));
            QVERIFY((k.propagatedQi > 0) != (k.rayQi > 0));
            reported.insert(k.chain);
        }
        QCOMPARE(reported, std::set<Index>(conflicts.begin(), conflicts.end()));
        // Interior chains away from cusps are never ray-tested.
        for (const ViewChain& c : s.graph.chains)
            if (c.concave && c.startNode != kInvalidIndex)
                for (size_t i = 1; i + 1 < c.segmentCount(); ++i)
                    QCOMPARE(c.segmentRayQi[i], -1);
    }

    // ------------------------------------------------------- end to end
    // The consistent method's visibility on the sphere and the torus over a
    // subset of the 26 views. Every chain is decided (a rule, QI >= 0), and
    // ViewChain::ambiguous marks exactly the chains that no rule resolved
    // (AmbiguousInvisible). The sphere, a closed convex object, is fully
    // visible with no chain left ambiguous (Bénard 2014 §8). The torus
    // should have none left either, but its contour near the real cusps is
    // cut by the view graph's near-face curtain folds (30-48 per view where
    // the smooth torus has 4 cusps) into chains of 1-3 segments, all of them
    // "adjacent to a cusp" or to an inconsistent face: a measured ceiling
    // (tests/baselines/test_visibility_rules.json), with the figures printed.
    void consistentEndToEnd_data() {
        QTest::addColumn<QString>("shapeName");
        QTest::newRow("sphere") << QString("sphere");
        QTest::newRow("torus") << QString("torus");
    }
    void consistentEndToEnd() {
        QFETCH(QString, shapeName);
        const bool sphere = shapeName == "sphere";
        const auto cage = shape(shapeName.toStdString(), sphere ? 8 : 12);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        std::map<VisibilityRule, int> rules;
        int ambiguous = 0, chains = 0, conflicts = 0, runs = 0;
        double visible = 0.0, total = 0.0, ambiguousLength = 0.0, ambiguousRaysVisible = 0.0;
        for (size_t v = 0; v < views.size(); v += kEndToEndStride) {
            const Snapshot s = runMethod("consistent", cage, views[v]);
            QCOMPARE(QString::fromStdString(s.phaseName), QString("simplification"));
            QVERIFY(s.viewGraph);
            ++runs;
            const ViewGraph& g = *s.viewGraph;
            conflicts += static_cast<int>(g.conflicts.size());
            for (size_t c = 0; c < g.chains.size(); ++c) {
                const ViewChain& chain = g.chains[c];
                const QString where = QString("view %1 chain %2").arg(v).arg(c);
                ++chains;
                ++rules[chain.decidedBy];
                QVERIFY2(chain.qi >= 0 && chain.decidedBy != VisibilityRule::Unknown,
                         qPrintable(where));
                QVERIFY2(chain.ambiguous == (chain.decidedBy == VisibilityRule::AmbiguousInvisible),
                         qPrintable(where));
                QCOMPARE(chain.segmentRayQi.size(), chain.segmentCount());
                QVERIFY(!chain.simplifiedAway); // simplification is off by default
                if (chain.ambiguous) {
                    ++ambiguous;
                    ambiguousLength += chain.lengthPixels;
                    // Its (ambiguous) rays mostly said visible: a likely gap.
                    int zero = 0, tested = 0;
                    for (int q : chain.segmentRayQi) {
                        tested += q >= 0;
                        zero += q == 0;
                    }
                    if (2 * zero > tested)
                        ambiguousRaysVisible += chain.lengthPixels;
                }
                if (chain.type != CurveType::Contour)
                    continue;
                total += chain.lengthPixels;
                if (chain.visible())
                    visible += chain.lengthPixels;
                if (sphere)
                    QVERIFY2(chain.visible(),
                             qPrintable(where + " hidden by " + toString(chain.decidedBy)));
            }
        }
        QString histogram;
        for (const auto& [rule, count] : rules)
            histogram += QString(" %1=%2").arg(toString(rule)).arg(count);
        qInfo("%s, consistent, %d views: %d chains, %d still ambiguous (%.0f px, of which "
              "%.0f px with mostly visible rays), %d consistent-vote conflicts, contour "
              "visible %.0f of %.0f px; rules:%s",
              qPrintable(shapeName), runs, chains, ambiguous, ambiguousLength, ambiguousRaysVisible,
              conflicts, visible, total, qPrintable(histogram));
        QVERIFY(total > 0.0);
        if (sphere) {
            QCOMPARE(ambiguous, 0);
        } else {
            // A known gap (README, closing note): 0 is the goal.
            const double chainShare =
                baseline("test_visibility_rules", "torus: chains left ambiguous / chains");
            const double lengthShare = baseline(
                "test_visibility_rules", "torus: contour length left ambiguous / contour length");
            QVERIFY2(ambiguous <= chainShare * chains,
                     "more torus chains left ambiguous than measured");
            QVERIFY2(ambiguousLength <= lengthShare * total,
                     "more torus contour length left ambiguous than measured");
        }
    }

    // Interpolated contours' heuristic visibility (tutorial §6.2.4) against
    // the mesh method's exact one on the same views: every chain is decided
    // by the vote, with min(votes, segments) ray tests; the visible contour
    // length of each method is reported (the interpolated one is expected
    // lower: gaps and halos).
    void interpolatedEndToEnd_data() {
        QTest::addColumn<QString>("shapeName");
        QTest::newRow("sphere") << QString("sphere");
        QTest::newRow("torus") << QString("torus");
    }
    void interpolatedEndToEnd() {
        QFETCH(QString, shapeName);
        const auto cage = shape(shapeName.toStdString(), 32);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        const Method& interpolated = *findMethod("interpolated");
        const int votes =
            ParameterSet::defaults(interpolated.parameters).getInt("visibility-votes");
        double length[2][2] = {{0, 0}, {0, 0}}; // [mesh, interpolated][visible, total]
        int runs = 0;
        for (size_t v = 0; v < views.size(); v += kEndToEndStride) {
            ++runs;
            for (int k = 0; k < 2; ++k) {
                const Snapshot s = runMethod(k == 0 ? "mesh" : "interpolated", cage, views[v]);
                QVERIFY(s.viewGraph);
                for (const ViewChain& c : s.viewGraph->chains) {
                    if (k == 1) {
                        QCOMPARE(c.decidedBy, VisibilityRule::HeuristicVote);
                        const long tested =
                            std::count_if(c.segmentRayQi.begin(), c.segmentRayQi.end(),
                                          [](int q) { return q >= 0; });
                        QCOMPARE(tested, std::min<long>(votes, long(c.segmentCount())));
                    }
                    if (c.type != CurveType::Contour)
                        continue;
                    length[k][1] += c.lengthPixels;
                    if (c.visible())
                        length[k][0] += c.lengthPixels;
                }
            }
        }
        const double mesh = length[0][0] / length[0][1], interp = length[1][0] / length[1][1];
        qInfo("%s, %d views: visible contour length mesh %.0f of %.0f px (%.1f %%), "
              "interpolated %.0f of %.0f px (%.1f %%)",
              qPrintable(shapeName), runs, length[0][0], length[0][1], 100 * mesh, length[1][0],
              length[1][1], 100 * interp);
        if (shapeName == "sphere")
            QVERIFY2(mesh > 0.99, "the mesh sphere's contour is not all visible");
        QVERIFY(interp > 0.0);
    }

    // Tutorial §6.2.4's "ignore faces adjacent to the contour's face", per
    // choice of visibility-ignored-faces, on the sphere, whose outline is one
    // closed chain (so one vote decides all of it): with vertex-neighbours
    // (the default) the whole outline must be visible in every view; the
    // other choices' figures are reported. Each choice must hide no chain
    // that "face" shows (a wider ignored ring only removes occluders), and
    // the votes must be spread along the chain (no gap between tested
    // segments longer than about segments / votes).
    void interpolatedIgnoredFaces_data() {
        QTest::addColumn<QString>("ignored");
        for (const char* c : {"face", "edge-neighbours", "vertex-neighbours"})
            QTest::newRow(c) << QString(c);
    }
    void interpolatedIgnoredFaces() {
        QFETCH(QString, ignored);
        const Method& interpolated = *findMethod("interpolated");
        const ParameterSet defaults = ParameterSet::defaults(interpolated.parameters);
        QCOMPARE(defaults.getChoice("visibility-ignored-faces"), std::string("vertex-neighbours"));
        const int votes = defaults.getInt("visibility-votes");
        const auto cage = shape("sphere", 32);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        Overrides chosen, face;
        chosen.set("visibility-ignored-faces", ignored.toStdString());
        face.set("visibility-ignored-faces", std::string("face"));
        double visible = 0, total = 0;
        int runs = 0, viewsLosingOutline = 0;
        for (size_t v = 0; v < views.size(); v += kEndToEndStride) {
            ++runs;
            const Snapshot s = runMethod("interpolated", cage, views[v], chosen);
            const Snapshot f = runMethod("interpolated", cage, views[v], face);
            QVERIFY(s.viewGraph && f.viewGraph);
            QCOMPARE(s.viewGraph->chains.size(), f.viewGraph->chains.size());
            bool lost = false;
            for (size_t ci = 0; ci < s.viewGraph->chains.size(); ++ci) {
                const ViewChain& c = s.viewGraph->chains[ci];
                const QString where = QString("view %1 chain %2").arg(v).arg(ci);
                QVERIFY2(c.visible() || !f.viewGraph->chains[ci].visible(),
                         qPrintable(where + ": hidden, but visible when ignoring its face only"));
                std::vector<size_t> tested;
                for (size_t i = 0; i < c.segmentRayQi.size(); ++i)
                    if (c.segmentRayQi[i] >= 0)
                        tested.push_back(i);
                const size_t n = c.segmentCount();
                QCOMPARE(tested.size(), std::min<size_t>(size_t(votes), n));
                size_t gap = tested.front() + (n - 1 - tested.back());
                for (size_t k = 1; k < tested.size(); ++k)
                    gap = std::max(gap, tested[k] - tested[k - 1] - 1);
                QVERIFY2(
                    gap <= n / tested.size() + 1,
                    qPrintable(where +
                               QString(": %1 untested segments in a row of %2").arg(gap).arg(n)));
                if (c.type != CurveType::Contour)
                    continue;
                total += c.lengthPixels;
                if (c.visible())
                    visible += c.lengthPixels;
                else
                    lost = true;
            }
            viewsLosingOutline += lost ? 1 : 0;
        }
        qInfo("sphere, ignored faces %s, %d votes, %d views: visible outline %.0f of %.0f px "
              "(%.1f %%), %d views lose (part of) the outline",
              qPrintable(ignored), votes, runs, visible, total, 100 * visible / total,
              viewsLosingOutline);
        QVERIFY(total > 0.0);
        if (ignored == "vertex-neighbours")
            QCOMPARE(viewsLosingOutline, 0);
    }

    // The simplification phase on real graphs (every method, a bumpy torus
    // with many small chains): its post-conditions hold, it hides only short
    // visible chains, and the visibility snapshot keeps the unsimplified
    // graph (reversible). Figures: chains hidden, visible length before/after.
    void simplificationPhase_data() {
        QTest::addColumn<QString>("method");
        for (const char* m : {"mesh", "interpolated", "consistent"})
            QTest::newRow(m) << QString(m);
    }
    void simplificationPhase() {
        QFETCH(QString, method);
        const bool consistent = method == "consistent";
        const auto cage = shape(consistent ? "torus" : "bumpy-torus", consistent ? 12 : 48);
        const std::vector<Camera> views = Camera::views26(cage->boundingBox(), Viewport{800, 600});
        const Method& m = *findMethod(method.toStdString());
        const ParameterSet defaults = ParameterSet::defaults(m.parameters);
        QCOMPARE(defaults.getBool("simplify"), false);
        QCOMPARE(defaults.getDouble("simplify-threshold"), 15.0);
        double hidden = 0, before = 0, after = 0;
        for (size_t v = 0; v < views.size(); v += 3 * kEndToEndStride) {
            const MethodRun r = run(m.name, cage, views[v], {{"simplify", true}});
            const Snapshot& vis = r.phase("visibility");
            const Snapshot& simp = r.phase("simplification");
            QVERIFY(vis.viewGraph && simp.viewGraph);
            for (const InvariantCheck& c : simp.invariants)
                QVERIFY2(c.violations == 0,
                         qPrintable(QString::fromStdString(c.name + ": " + c.firstExample)));
            const ViewGraph &a = *vis.viewGraph, &b = *simp.viewGraph;
            QCOMPARE(a.chains.size(), b.chains.size());
            for (size_t c = 0; c < a.chains.size(); ++c) {
                QVERIFY(!a.chains[c].simplifiedAway);
                QCOMPARE(a.chains[c].qi, b.chains[c].qi);
                if (b.chains[c].simplifiedAway)
                    QVERIFY(a.chains[c].visible() && a.chains[c].lengthPixels < 15.0);
            }
            hidden += simp.counter(counters::kChainsHiddenBySimplification);
            before += a.visibleLengthPixels();
            after += b.visibleLengthPixels();
        }
        qInfo("%s: simplification (15 px) hid %.0f chains, visible length %.0f -> %.0f px",
              qPrintable(method), hidden, before, after);
        QVERIFY(after <= before);
    }

    // Rays really count the occluder (the scenes above rely on it).
    void stripSceneRays() {
        StripScene s;
        s.addStrip(-0.5, 0.5, 1.0, 2);
        s.finish();
        std::vector<Index> ignore{s.strips[0].topFace[0], s.strips[0].topFace[0] - 1};
        QCOMPARE(s.rays->occluders(Vec3(-0.25, 1.0, 0), s.camera, ignore), 1);
        QCOMPARE(s.rays->occluders(Vec3(0.25, 1.0, 0), s.camera, ignore), 0);
    }
};

QTEST_GUILESS_MAIN(TestVisibilityRules)
#include "test_visibility_rules.moc"
