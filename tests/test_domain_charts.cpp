// The appendix-B charts of a smooth surface's domain (Bénard, Hertzmann &
// Kass 2014 appendix B) on their own, and the per-vertex evaluation of f, n,
// g and the label (§4): DomainCharts and VertexEvaluator without a mesh.
//
// The surface is the Catmull-Clark limit of the unit cube of
// tests/data/good/cube_quads.obj: its domain (the cage subdivided once) is
// 24 unit quads; the cube's corners are domain vertices of valence 3, the
// cage's face centres and edge midpoints regular ones (valence 4). Expected values come from the
// linear formula in one face's chart and from SmoothSurface::transferAcrossEdge / evaluate.
#include "camera/Camera.h"
#include "contours/consistent/mesh/ConsistentMesh.h"
#include "contours/consistent/mesh/DomainCharts.h"
#include "contours/consistent/mesh/VertexEvaluator.h"
#include "core/Predicates.h"
#include "mesh/io/MeshReader.h"
#include "surface/SmoothSurfaceFactory.h"
#include "surface/SurfaceFields.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace contour;
using namespace contour::consistent;

namespace {

constexpr double kChartTolerance = 1e-9;

std::shared_ptr<const SmoothSurface> cubeSurface() {
    static const auto surface = makeSmoothSurface(
        readMesh(std::string(CONTOUR_SOURCE_DIR) + "/tests/data/good/cube_quads.obj"),
        SurfaceKind::CatmullClark);
    return surface;
}

DomainCharts charts(bool vertexRings = false) {
    DomainCharts c(cubeSurface(), kChartTolerance);
    c.setVertexRingCharts(vertexRings);
    return c;
}

bool near(const Preimage& p, const Preimage& q, double tolerance = 1e-12) {
    return p.face == q.face && std::abs(p.u - q.u) <= tolerance && std::abs(p.v - q.v) <= tolerance;
}

QString describe(const std::optional<Preimage>& p) {
    return p ? QString("(%1, %2, %3)").arg(p->face).arg(p->u, 0, 'g', 17).arg(p->v, 0, 'g', 17)
             : QString("nullopt");
}

Vec3 position(const Preimage& p) {
    return cubeSurface()->evaluate(p).position;
}

// The domain faces around domain vertex w.
std::vector<Index> facesAround(Index w) {
    const PolygonMesh& domain = cubeSurface()->domain();
    std::vector<Index> out;
    for (Index f = 0; f < domain.faceCount(); ++f)
        for (Index x : domain.face(f))
            if (x == w)
                out.push_back(f);
    return out;
}

// The first domain vertex of valence 3 (a corner of the cube).
Index valenceThreeVertex() {
    for (Index x = 0; x < cubeSurface()->domain().vertexCount(); ++x)
        if (facesAround(x).size() == 3)
            return x;
    return kInvalidIndex;
}

// Local corner index of domain vertex w in face f, or -1.
int cornerOf(Index f, Index w) {
    const auto corners = cubeSurface()->domain().face(f);
    for (size_t i = 0; i < corners.size(); ++i)
        if (corners[i] == w)
            return static_cast<int>(i);
    return -1;
}

// Two domain faces that share exactly one corner, a regular domain vertex.
struct DiagonalPair {
    Index vertex = kInvalidIndex;
    Index faces[2] = {kInvalidIndex, kInvalidIndex};
    int corners[2] = {-1, -1};
};

DiagonalPair diagonalAtRegularCorner() {
    const PolygonMesh& domain = cubeSurface()->domain();
    DiagonalPair out;
    for (Index w = 0; w < domain.vertexCount(); ++w) {
        const std::vector<Index> around = facesAround(w);
        if (around.size() != 4)
            continue;
        for (Index a : around)
            for (Index c : around) {
                int shared = 0;
                for (Index x : domain.face(a))
                    shared += cornerOf(c, x) >= 0 ? 1 : 0;
                if (a != c && shared == 1) {
                    out.vertex = w;
                    out.faces[0] = a;
                    out.faces[1] = c;
                    out.corners[0] = cornerOf(a, w);
                    out.corners[1] = cornerOf(c, w);
                    return out;
                }
            }
    }
    return out;
}

// A point a tenth of the way from corner `corner` of `face` to its centre.
Preimage nearCorner(Index face, int corner) {
    const Vec2 c = SmoothSurface::cornerCoordinates(true, corner);
    const Vec2 x = c + 0.1 * (Vec2(0.5, 0.5) - c);
    return {face, x.x(), x.y()};
}

Preimage atCorner(Index face, int corner) {
    const Vec2 c = SmoothSurface::cornerCoordinates(true, corner);
    return {face, c.x(), c.y()};
}

// Domain face 0 and the face farthest from it on the surface (on the
// cube's opposite side): no corner, edge or neighbour in common.
std::array<Index, 2> farApartFaces() {
    const PolygonMesh& domain = cubeSurface()->domain();
    const Vec3 centre = position({0, 0.5, 0.5});
    Index far = kInvalidIndex;
    double farthest = 0.0;
    for (Index f = 1; f < domain.faceCount(); ++f)
        if (const double d = (position({f, 0.5, 0.5}) - centre).norm(); d > farthest) {
            farthest = d;
            far = f;
        }
    return {0, far};
}

// Domain face 0, its local edge 0 (v = 0, corner 0 to corner 1) and the
// face across it; a in face 0 and b in the neighbour, with b at (0.6, -0.2)
// in face 0's chart: the segment from a crosses the shared edge at
// t = a.v / (a.v + 0.2).
struct EdgePair {
    Index f = 0, g = kInvalidIndex;
    int edgeInG = -1;
    Preimage a{0, 0.4, 0.3};
    Preimage bInF{0, 0.6, -0.2};
    Preimage b;
    EdgePair() {
        const SmoothSurface& s = *cubeSurface();
        const SmoothSurface::EdgeNeighbor nb = s.neighbor(f, 0);
        g = nb.face;
        edgeInG = nb.edge;
        b = s.transferAcrossEdge(bInF, 0);
    }
    // The linear formula in face 0's chart, b carried back from its face.
    Preimage linear(double t) const {
        const Preimage y = cubeSurface()->transferAcrossEdge(b, edgeInG);
        return {f, (1.0 - t) * a.u + t * y.u, (1.0 - t) * a.v + t * y.v};
    }
};

} // namespace

class TestDomainCharts : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        const SmoothSurface& s = *cubeSurface();
        QCOMPARE(s.domain().faceCount(), Index(24));
        for (Index f = 0; f < s.domain().faceCount(); ++f)
            QVERIFY(s.isQuad(f));
    }

    // u(t) = (1 - t) u_a + t u_b when both preimages lie in one face, by
    // every entry point (one t, several t, a segment).
    void interpolationInsideOneFace() {
        const DomainCharts c = charts();
        const Preimage a{5, 0.2, 0.3}, b{5, 0.6, 0.9};
        const std::vector<double> ts{0.0, 0.25, 0.5, 0.7, 1.0};
        std::vector<std::optional<Preimage>> many(ts.size());
        c.interpolate(a, b, ts, many);
        const DomainCharts::Segment segment = c.segment(a, b);
        for (size_t i = 0; i < ts.size(); ++i) {
            const double t = ts[i];
            const Preimage expected{5, (1.0 - t) * a.u + t * b.u, (1.0 - t) * a.v + t * b.v};
            const std::optional<Preimage> one = c.interpolate(a, b, t);
            QVERIFY2(one && near(*one, expected, 0.0), qPrintable(describe(one)));
            QVERIFY2(many[i] && near(*many[i], expected, 0.0), qPrintable(describe(many[i])));
            const std::optional<Preimage> at = segment.at(t);
            QVERIFY2(at && near(*at, expected, 0.0), qPrintable(describe(at)));
        }
    }

    // Preimages in two edge-adjacent faces: interpolated in the first
    // face's chart extended across the shared edge; the point reaches the
    // edge at the crossing t and lies in the second face after it.
    void interpolationAcrossAnEdge() {
        const DomainCharts c = charts();
        const EdgePair e;
        QVERIFY(e.g != kInvalidIndex && e.g != e.f);
        QVERIFY(cubeSurface()->contains(e.b));
        QVERIFY2(e.b.u > 0.0 && e.b.u < 1.0 && e.b.v > 0.0 && e.b.v < 1.0,
                 qPrintable(describe(e.b)));
        // Before the edge: in face f, on the line.
        const std::optional<Preimage> before = c.interpolate(e.a, e.b, 0.3);
        QVERIFY2(before && near(*before, e.linear(0.3)), qPrintable(describe(before)));
        // At the crossing: on the shared edge, so a preimage in both faces.
        const double crossing = e.a.v / (e.a.v - e.bInF.v);
        const std::optional<Preimage> on = c.interpolate(e.a, e.b, crossing);
        QVERIFY2(on && (on->face == e.f || on->face == e.g), qPrintable(describe(on)));
        const Preimage expectedOn{e.f, (1.0 - crossing) * e.a.u + crossing * e.bInF.u, 0.0};
        QVERIFY2((position(*on) - position(expectedOn)).norm() < 1e-9, qPrintable(describe(on)));
        const DomainCharts::Preimages onBoth = c.equivalents(*on);
        QCOMPARE(onBoth.size(), size_t(2));
        QCOMPARE(std::set<Index>({onBoth[0].face, onBoth[1].face}), std::set<Index>({e.f, e.g}));
        // After the edge: mapped back into the second face, which holds it.
        for (const double t : {0.8, 1.0}) {
            const std::optional<Preimage> after = c.interpolate(e.a, e.b, t);
            QVERIFY2(after && after->face == e.g && cubeSurface()->contains(*after),
                     qPrintable(describe(after)));
            const Preimage expected = cubeSurface()->transferAcrossEdge(e.linear(t), 0);
            QVERIFY2(near(*after, expected), qPrintable(describe(after)));
        }
        // The segment gives the same preimages as interpolate().
        const DomainCharts::Segment segment = c.segment(e.a, e.b);
        for (const double t : {0.3, crossing, 0.8}) {
            const std::optional<Preimage> x = segment.at(t), y = c.interpolate(e.a, e.b, t);
            QVERIFY(x && y && near(*x, *y, 0.0));
        }
    }

    // One preimage per domain face around the point: 1 inside a face, 2 on
    // an edge, k at a corner of valence k (3 and 4 on the cube); all of the
    // same surface point.
    void equivalentsOnEdgesAndCorners() {
        const DomainCharts c = charts();
        QCOMPARE(c.equivalents({7, 0.3, 0.6}).size(), size_t(1));
        const Preimage onEdge{7, 0.5, 0.0};
        const DomainCharts::Preimages e = c.equivalents(onEdge);
        QCOMPARE(e.size(), size_t(2));
        QCOMPARE(e[0].face, Index(7));
        QCOMPARE(e[1].face, cubeSurface()->neighbor(7, 0).face);
        QVERIFY((position(e[1]) - position(onEdge)).norm() < 1e-9);

        const PolygonMesh& domain = cubeSurface()->domain();
        std::set<size_t> valences;
        for (Index f = 0; f < domain.faceCount(); ++f)
            for (int k = 0; k < 4; ++k) {
                const Index w = domain.face(f)[static_cast<size_t>(k)];
                const std::vector<Index> around = facesAround(w);
                const Preimage corner = atCorner(f, k);
                const DomainCharts::Preimages r = c.equivalents(corner);
                QCOMPARE(r.size(), around.size());
                std::set<Index> faces;
                for (const Preimage& x : r) {
                    faces.insert(x.face);
                    QVERIFY((position(x) - position(corner)).norm() < 1e-9);
                }
                QCOMPARE(faces, std::set<Index>(around.begin(), around.end()));
                valences.insert(around.size());
            }
        QCOMPARE(valences, std::set<size_t>({3, 4}));
    }

    // +1 for a counter-clockwise triple (the domain's orientation), -1 for
    // it reversed, 0 for a degenerate one; in one face and across an edge.
    void parameterOrientationOfATriple() {
        const DomainCharts c = charts();
        const std::array<Preimage, 3> ccw{Preimage{3, 0.2, 0.2}, Preimage{3, 0.8, 0.2},
                                          Preimage{3, 0.5, 0.8}};
        QCOMPARE(c.parameterOrientation(ccw), std::optional<int>(1));
        QCOMPARE(c.parameterOrientation({ccw[2], ccw[1], ccw[0]}), std::optional<int>(-1));
        QCOMPARE(c.parameterOrientation(
                     {Preimage{3, 0.2, 0.2}, Preimage{3, 0.5, 0.5}, Preimage{3, 0.8, 0.8}}),
                 std::optional<int>(0));

        const EdgePair e;
        const Preimage left{e.f, 0.2, 0.5}, right{e.f, 0.8, 0.5};
        // (0.2, 0.5), (0.6, -0.2), (0.8, 0.5) in face f's chart.
        QCOMPARE(c.parameterOrientation({left, e.b, right}), std::optional<int>(1));
        QCOMPARE(c.parameterOrientation({right, e.b, left}), std::optional<int>(-1));
        // Both faces' charts hold the three; face f's coordinates are b's
        // carried across the edge.
        const std::vector<std::array<Vec2, 3>> coordinates = c.chartCoordinates({left, e.b, right});
        QCOMPARE(coordinates.size(), size_t(2));
        const bool hasF = std::any_of(coordinates.begin(), coordinates.end(), [&](const auto& x) {
            return (x[0] - Vec2(0.2, 0.5)).norm() < 1e-12 &&
                   (x[1] - Vec2(0.6, -0.2)).norm() < 1e-12 &&
                   (x[2] - Vec2(0.8, 0.5)).norm() < 1e-12;
        });
        QVERIFY(hasF);
        // Given the corners' equivalents: the same answers.
        const DomainCharts::Preimages r0 = c.equivalents(left), r1 = c.equivalents(e.b),
                                      r2 = c.equivalents(right);
        QCOMPARE(c.parameterOrientationIn(
                     {DomainCharts::span(r0), DomainCharts::span(r1), DomainCharts::span(r2)}),
                 std::optional<int>(1));
        QCOMPARE(c.parameterOrientationIn(
                     {DomainCharts::span(r2), DomainCharts::span(r1), DomainCharts::span(r0)}),
                 std::optional<int>(-1));
    }

    // At a domain vertex of valence 3 (a cube corner) the third face's
    // chart extended across its two edges is cut along the other two
    // faces' shared edge: a triangle with a corner at the vertex and one in
    // each of those faces reads a quarter turn too much there. Every chart
    // offered must agree on the triangle's orientation (the two faces' own
    // charts do), and a point on the cut edge is held once.
    void chartCutAtAValenceThreeCorner() {
        const Index w = valenceThreeVertex();
        QVERIFY(w != kInvalidIndex);
        const std::vector<Index> around = facesAround(w);
        const DomainCharts c = charts();
        for (int k = 0; k < 3; ++k) {
            const Index n1 = around[static_cast<size_t>(k)];
            const Index n2 = around[static_cast<size_t>((k + 1) % 3)];
            const Preimage vertex = atCorner(n1, cornerOf(n1, w));
            int triangles = 0, disagreements = 0;
            for (int i = 1; i < 10; i += 2)
                for (int j = 1; j < 10; j += 2)
                    for (int i2 = 1; i2 < 10; i2 += 2)
                        for (int j2 = 1; j2 < 10; j2 += 2) {
                            const std::array<Preimage, 3> t{vertex, Preimage{n1, 0.1 * i, 0.1 * j},
                                                            Preimage{n2, 0.1 * i2, 0.1 * j2}};
                            const std::vector<std::array<Vec2, 3>> in = c.chartCoordinates(t);
                            QVERIFY(!in.empty());
                            std::set<int> signs;
                            for (const auto& x : in)
                                if (const int o = orientation2d(x[0], x[1], x[2]); o != 0)
                                    signs.insert(o);
                            ++triangles;
                            disagreements += signs.size() > 1 ? 1 : 0;
                        }
            QCOMPARE(triangles, 625);
            QCOMPARE(disagreements, 0);
        }
        // A corner in each of the three faces: every chart is cut, and the
        // cut ones still give the triangle an orientation (no chart would
        // leave the face without one).
        const std::array<Preimage, 3> ring{nearCorner(around[0], cornerOf(around[0], w)),
                                           nearCorner(around[1], cornerOf(around[1], w)),
                                           nearCorner(around[2], cornerOf(around[2], w))};
        QCOMPARE(c.chartCoordinates(ring).size(), size_t(3));
        QVERIFY(c.parameterOrientation(ring).has_value());
        // A point on the shared edge of two of the faces, with a corner in
        // each of them: the third face's chart would hold it twice.
        const Index n1 = around[0], n2 = around[1];
        Preimage onEdge{};
        for (int e = 0; e < 4; ++e)
            if (cubeSurface()->neighbor(n1, e).face == n2) {
                const Vec2 a = SmoothSurface::cornerCoordinates(true, e);
                const Vec2 b = SmoothSurface::cornerCoordinates(true, (e + 1) % 4);
                const Vec2 m = 0.5 * (a + b);
                onEdge = {n1, m.x(), m.y()};
            }
        QCOMPARE(c.equivalents(onEdge).size(), size_t(2));
        const std::array<Preimage, 3> t{onEdge, Preimage{n1, 0.5, 0.5}, Preimage{n2, 0.5, 0.5}};
        for (const auto& x : c.chartCoordinates(t))
            QCOMPARE(orientation2d(x[0], x[1], x[2]), *c.parameterOrientation(t));
        QVERIFY(c.parameterOrientation(t).has_value());
    }

    // Around a domain vertex of valence 3 two preimages can have several
    // common charts that disagree on where the straight segment between
    // them runs: from a point near the vertex in one face to the far end of
    // the other two faces' shared edge, the segment runs through the second
    // face in its chart and through the third in the third's. Contour
    // insertion bisects in another chart when its split would fold
    // (interpolateInChart); chart 0 is interpolateIn's.
    void segmentChartsDisagreeAtAValenceThreeCorner() {
        const Index w = valenceThreeVertex();
        QVERIFY(w != kInvalidIndex);
        const std::vector<Index> around = facesAround(w);
        const Index n1 = around[0], n2 = around[1], n3 = around[2];
        int far = -1;
        for (int e = 0; e < 4; ++e)
            if (cubeSurface()->neighbor(n2, e).face == n3)
                far = e == cornerOf(n2, w) ? (e + 1) % 4 : e;
        QVERIFY(far >= 0);
        const DomainCharts c = charts();
        const Preimage x = nearCorner(n1, cornerOf(n1, w)), y = atCorner(n2, far);
        const int count = c.interpolationCharts(x, y);
        QCOMPARE(count, 2);
        const DomainCharts::Preimages rx = c.equivalents(x), ry = c.equivalents(y);
        const auto rs = DomainCharts::span(rx), ys = DomainCharts::span(ry);
        for (const double t : {0.1, 0.5, 0.9}) {
            const std::optional<Preimage> first = c.interpolateInChart(rs, ys, t, 0);
            const std::optional<Preimage> second = c.interpolateInChart(rs, ys, t, 1);
            QVERIFY(first && second);
            QVERIFY2(near(*first, *c.interpolateIn(rs, ys, t)), qPrintable(describe(first)));
            QVERIFY(!c.interpolateInChart(rs, ys, t, count));
            // The two straight segments: through different faces away from
            // the ends.
            if (t == 0.5) {
                QVERIFY2(first->face != second->face,
                         qPrintable(describe(first) + " " + describe(second)));
                QVERIFY((position(*first) - position(*second)).norm() > 1e-3);
            }
            QVERIFY(near(*c.segmentInChart(x, y, 1).at(t), *second));
        }
    }

    // Two faces sharing only a regular corner: no edge chart joins them
    // (withinEdgeCharts false, with or without the one-ring charts), and
    // the interpolation through the corner exists only with the one-ring
    // charts, its midpoint at the corner itself (the quadrant chart mirrors
    // the two points through it).
    void regularCornerCharts() {
        const DiagonalPair d = diagonalAtRegularCorner();
        QVERIFY(d.faces[0] != kInvalidIndex);
        const Preimage p = nearCorner(d.faces[0], d.corners[0]);
        const Preimage q = nearCorner(d.faces[1], d.corners[1]);
        const Preimage pCentre{d.faces[0], 0.5, 0.5};
        // A face around the corner edge-adjacent to both.
        Index side = kInvalidIndex;
        for (Index f : facesAround(d.vertex))
            if (f != d.faces[0] && f != d.faces[1])
                side = f;
        QVERIFY(side != kInvalidIndex);
        const Preimage s = nearCorner(side, cornerOf(side, d.vertex));

        for (const bool rings : {false, true}) {
            const DomainCharts c = charts(rings);
            QVERIFY(!c.withinEdgeCharts({p, q, pCentre}));
            QVERIFY(c.withinEdgeCharts({p, s, pCentre}));
        }
        QVERIFY(!charts(false).interpolate(p, q, 0.5));
        QVERIFY(!charts(false).acrossRegularCorner(q, d.faces[0]));
        const DomainCharts c = charts(true);
        const std::optional<Preimage> mid = c.interpolate(p, q, 0.5);
        QVERIFY2(mid, "no chart through the regular corner");
        const Vec3 corner = position(atCorner(d.faces[0], d.corners[0]));
        QVERIFY2((position(*mid) - corner).norm() < 1e-9, qPrintable(describe(mid)));
        // q in the first face's quadrant chart: p mirrored through the corner.
        const std::optional<Preimage> qInP = c.acrossRegularCorner(q, d.faces[0]);
        const Vec2 cornerUv = SmoothSurface::cornerCoordinates(true, d.corners[0]);
        const Vec2 mirrored = 2.0 * cornerUv - Vec2(p.u, p.v);
        QVERIFY2(qInP && std::abs(qInP->u - mirrored.x()) < 1e-12 &&
                     std::abs(qInP->v - mirrored.y()) < 1e-12,
                 qPrintable(describe(qInP)));
    }

    // Two corners in faces that share only an irregular domain vertex (the
    // apex of a pentagonal pyramid, five faces around it) and the third in
    // the first face: neither corner's face holds the three, the chart of
    // the face next to both does (the third tier of forEachChart), and it
    // reads the reversed triangle reversed. Around a regular vertex the
    // same triangle keeps no chart without the one-ring charts (those
    // decide there).
    void chartOfAFaceNoCornerLiesIn() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const std::string path = dir.filePath("pentagonal_pyramid.obj").toStdString();
        {
            std::ofstream obj(path);
            obj << "v 0 0 1\n";
            for (int i = 0; i < 5; ++i)
                obj << "v " << std::cos(2.0 * M_PI * i / 5) << ' ' << std::sin(2.0 * M_PI * i / 5)
                    << " 0\n";
            for (int i = 0; i < 5; ++i)
                obj << "f 1 " << 2 + i << ' ' << 2 + (i + 1) % 5 << "\n";
            obj << "f 6 5 4 3 2\n";
        }
        const auto surface = makeSmoothSurface(readMesh(path), SurfaceKind::CatmullClark);
        const PolygonMesh& domain = surface->domain();
        Index apex = kInvalidIndex;
        std::vector<Index> around;
        for (Index w = 0; w < domain.vertexCount() && apex == kInvalidIndex; ++w) {
            around.clear();
            for (Index f = 0; f < domain.faceCount(); ++f)
                for (Index x : domain.face(f))
                    if (x == w)
                        around.push_back(f);
            if (around.size() == 5)
                apex = w;
        }
        QVERIFY(apex != kInvalidIndex);
        const auto adjacent = [&](Index a, Index b) {
            for (int e = 0; e < 4; ++e)
                if (surface->neighbor(a, e).face == b)
                    return true;
            return false;
        };
        Index a = around[0], c = kInvalidIndex;
        for (Index f : around)
            if (f != a && !adjacent(a, f))
                c = f;
        QVERIFY(c != kInvalidIndex);
        const auto cornerIn = [&](Index f) {
            const auto corners = domain.face(f);
            return static_cast<int>(std::find(corners.begin(), corners.end(), apex) -
                                    corners.begin());
        };
        const Vec2 corner = SmoothSurface::cornerCoordinates(true, cornerIn(a));
        const Preimage p = nearCorner(a, cornerIn(a));
        const Preimage pOff{a, 0.5 * corner.x() + 0.25, 0.8 * corner.y() + 0.1};
        const Preimage q = nearCorner(c, cornerIn(c));
        for (const bool rings : {false, true}) {
            DomainCharts charts(surface, kChartTolerance);
            charts.setVertexRingCharts(rings);
            const std::optional<int> o = charts.parameterOrientation({p, q, pOff});
            const std::optional<int> reversed = charts.parameterOrientation({p, pOff, q});
            QVERIFY(o && reversed && *o != 0);
            QCOMPARE(*reversed, -*o);
            QCOMPARE(charts.chartCoordinates({p, q, pOff}).size(), size_t(1));
        }
        // The same at a regular corner of the cube's domain: no chart
        // without the one-ring charts, one with them.
        const DiagonalPair d = diagonalAtRegularCorner();
        QVERIFY(d.faces[0] != kInvalidIndex);
        const Vec2 cc = SmoothSurface::cornerCoordinates(true, d.corners[0]);
        const std::array<Preimage, 3> t{
            nearCorner(d.faces[0], d.corners[0]), nearCorner(d.faces[1], d.corners[1]),
            Preimage{d.faces[0], 0.5 * cc.x() + 0.25, 0.8 * cc.y() + 0.1}};
        QVERIFY(!charts(false).parameterOrientation(t));
        QVERIFY(charts(true).parameterOrientation(t));
    }

    // Faces far apart: no common chart, whatever is asked.
    void noCommonChart() {
        const std::array<Index, 2> f = farApartFaces();
        QVERIFY(f[0] != kInvalidIndex);
        const Preimage a{f[0], 0.4, 0.6}, b{f[1], 0.3, 0.2}, a2{f[0], 0.7, 0.2};
        for (const bool rings : {false, true}) {
            const DomainCharts c = charts(rings);
            QVERIFY(!c.interpolate(a, b, 0.5));
            const std::vector<double> ts{0.25, 0.75};
            std::vector<std::optional<Preimage>> out(ts.size(), Preimage{});
            c.interpolate(a, b, ts, out);
            QVERIFY(!out[0] && !out[1]);
            QVERIFY(!c.segment(a, b).at(0.5));
            QVERIFY(!c.parameterOrientation({a, b, a2}));
            QVERIFY(c.chartCoordinates({a, b, a2}).empty());
            QVERIFY(!c.withinEdgeCharts({a, b, a2}));
            QVERIFY(!c.inChart(DomainCharts::span(c.equivalents(b)), f[0]));
        }
    }

    // g = (c - f) · n at the evaluated point, with f and n from
    // SmoothSurface::evaluate and c the camera (the direction towards it in
    // orthographic projection), and the label sign(g), over a lattice of
    // every face: both labels occur.
    void evaluatorComputesGAndLabel() {
        const auto surface = cubeSurface();
        Camera perspective;
        perspective.eye = Vec3(3.0, 2.0, 4.0);
        perspective.target = Vec3(0.5, 0.5, 0.5);
        Camera orthographic = perspective;
        orthographic.projection = Projection::Orthographic;
        for (const Camera& camera : {perspective, orthographic}) {
            const VertexEvaluator evaluator(surface, camera);
            int labels[3] = {0, 0, 0};
            for (Index f = 0; f < surface->domain().faceCount(); ++f)
                for (const double u : {0.1, 0.5, 0.9})
                    for (const double v : {0.2, 0.7}) {
                        const Preimage p{f, u, v};
                        const SurfacePoint sp = surface->evaluate(p);
                        const Vec3 n = sp.du.cross(sp.dv).normalized();
                        const Vec3 towards = camera.isOrthographic()
                                                 ? Vec3(camera.eye - camera.target)
                                                 : Vec3(camera.eye - sp.position);
                        const double g = towards.dot(n);
                        const MeshVertex x = evaluator.evaluate(p);
                        QVERIFY(near(x.preimage, p, 0.0));
                        QVERIFY(x.position == sp.position);
                        QVERIFY((x.normal - n).norm() < 1e-12);
                        QVERIFY2(std::abs(x.g - g) <= 1e-12 * (1.0 + std::abs(g)),
                                 qPrintable(QString("g %1, expected %2").arg(x.g).arg(g)));
                        const VertexLabel expected = g > 1e-9    ? VertexLabel::Front
                                                     : g < -1e-9 ? VertexLabel::Back
                                                                 : x.label;
                        QCOMPARE(x.label, expected);
                        QCOMPARE(x.label, labelFromG(x.g));
                        ++labels[static_cast<int>(x.label) + 1];
                        // The radial curvature of SurfaceFields; without it,
                        // every other field the same.
                        const double kr = radialCurvature(sp, camera);
                        QVERIFY(x.radialCurvature == kr ||
                                (std::isnan(x.radialCurvature) && std::isnan(kr)));
                        const MeshVertex y = evaluator.evaluateWithoutCurvature(p);
                        QVERIFY(y.position == x.position && y.normal == x.normal && y.g == x.g &&
                                y.label == x.label);
                        QVERIFY(std::isnan(y.radialCurvature));
                        const MeshVertex z = evaluator.evaluated(p, sp);
                        QVERIFY(z.position == x.position && z.normal == x.normal && z.g == x.g &&
                                z.label == x.label);
                    }
            QVERIFY(labels[0] > 0 && labels[2] > 0);
        }
        QCOMPARE(labelFromG(0.5), VertexLabel::Front);
        QCOMPARE(labelFromG(-0.5), VertexLabel::Back);
        QCOMPARE(labelFromG(0.0), VertexLabel::Contour);
    }

    // The mesh's charts and evaluator are the ones it was built with.
    void meshOwnsItsChartsAndEvaluator() {
        Camera camera;
        camera.eye = Vec3(-2.0, 3.0, 1.0);
        ConsistentMesh m(cubeSurface(), camera, 1e-7);
        m.setVertexRingCharts(true);
        QCOMPARE(m.charts().tolerance(), 1e-7);
        QVERIFY(m.charts().vertexRingCharts());
        QVERIFY(&m.charts().surface() == cubeSurface().get());
        QVERIFY(m.evaluator().camera() == camera);
        const Preimage p{2, 0.3, 0.4};
        QCOMPARE(m.evaluate(p).g, VertexEvaluator(cubeSurface(), camera).evaluate(p).g);
    }
};

QTEST_APPLESS_MAIN(TestDomainCharts)
#include "test_domain_charts.moc"
