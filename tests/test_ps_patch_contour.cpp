// The contour generator of one quadratic patch (contours/powell_sabin/
// PatchContour.h, Capouellez et al. 2023 §4.1, Table 1): the form
// tau . (p_u x p_v) against direct evaluation; every Table-1 case from forms
// built for it and from Bezier patches that produce it, checked for the
// residual on the curve, ends on the recorded sides, pieces inside the
// domain, at most three pieces per branch, and the crossings of random
// chords against the sign changes of f sampled densely along them; the same
// on a fitted Powell-Sabin sphere under random views, with the segment ends
// matched across patches; degenerate trimming; bad input; timing.
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/ConeSelection.h"
#include "contours/powell_sabin/PatchContour.h"
#include "contours/powell_sabin/ThinPlateFit.h"
#include "mesh/ProceduralShapes.h"

#include <QElapsedTimer>
#include <QtTest>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

using namespace contour;
using namespace contour::powell_sabin;

namespace {

using Domain = std::array<Vec2, 3>;
using Field = std::function<double(const Vec2&)>;

constexpr double kPi = std::numbers::pi;
constexpr double kResidual = 1e-10; // |f(r(t))| relative to the form's scale
constexpr double kOnSide = 1e-12;   // distance to the side, relative to the domain

double uniform(std::mt19937& g, double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(g);
}

double cross2(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

double longestSide(const Domain& d) {
    return std::max({(d[1] - d[0]).norm(), (d[2] - d[1]).norm(), (d[0] - d[2]).norm()});
}

Vec2 centroid(const Domain& d) {
    return (d[0] + d[1] + d[2]) / 3.0;
}

Domain randomDomain(std::mt19937& g) {
    for (;;) {
        const Vec2 c(uniform(g, -3, 3), uniform(g, -3, 3));
        const double size = uniform(g, 0.3, 2.0);
        double angle = uniform(g, 0, 2 * kPi);
        Domain d;
        for (Vec2& p : d) {
            p = c + size * uniform(g, 0.5, 1.0) * Vec2(std::cos(angle), std::sin(angle));
            angle += uniform(g, 0.8, 2.4);
        }
        const double h = longestSide(d);
        if (cross2(d[1] - d[0], d[2] - d[0]) > 0.1 * h * h)
            return d;
    }
}

Vec3 randomUnit(std::mt19937& g) {
    std::normal_distribution<double> n;
    Vec3 v(n(g), n(g), n(g));
    return v.normalized();
}

Eigen::Matrix3d randomRotation(std::mt19937& g) {
    const Vec3 a = randomUnit(g);
    Vec3 b = randomUnit(g);
    b = (b - b.dot(a) * a).normalized();
    Eigen::Matrix3d r;
    r.col(0) = a;
    r.col(1) = b;
    r.col(2) = a.cross(b);
    return r;
}

// The local coordinates of the implementation's units: s = (r - centroid) / h.
struct Local {
    Eigen::Matrix2d A;
    Vec2 b;
    double c;
};

Local localOf(const QuadraticForm2& f, const Domain& d) {
    const Vec2 o = centroid(d);
    const double h = longestSide(d);
    return {h * h * f.A, h * f.gradient(o), f(o)};
}

QuadraticForm2 fromLocal(const Local& l, const Domain& d) {
    const Vec2 o = centroid(d);
    const double h = longestSide(d);
    QuadraticForm2 f;
    f.A = l.A / (h * h);
    const Vec2 bl = l.b / h;
    f.b = bl - f.A * o;
    f.c = l.c - bl.dot(o) + 0.5 * o.dot(f.A * o);
    return f;
}

double formScale(const QuadraticForm2& f, const Domain& d) {
    const Local l = localOf(f, d);
    return l.A.norm() + l.b.norm() + std::abs(l.c);
}

double minBarycentric(const Domain& d, const Vec2& r) {
    return barycentricOf(d, r).minCoeff();
}

double distanceToSide(const Domain& d, int side, const Vec2& r) {
    const Vec2 a = d[side], b = d[(side + 1) % 3];
    return std::abs(cross2(b - a, r - a)) / (b - a).norm();
}

int realRoots(double a, double b, double c, std::array<double, 2>& r) {
    const double disc = b * b - 4 * a * c;
    if (disc < 0 || (a == 0 && b == 0))
        return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    int n = 0;
    if (a != 0)
        r[n++] = q / a;
    if (q != 0)
        r[n++] = c / q;
    return n;
}

// Chord statistics of one check.
struct Stats {
    int forms = 0, withSegments = 0, segments = 0, insideEllipses = 0;
    int chords = 0, skippedChords = 0, unresolvedSamples = 0, chordsWithCrossings = 0;
    int maxPerBranch = 0;
    std::map<int, int> piecesPerBranch;
};

// Sign changes of `field` sampled densely along random chords of the
// domain against the crossings of the segments with the chord (and the
// exact roots of the form on the chord).
std::string checkChords(const QuadraticForm2& form, const Field& field, const Domain& d,
                        const std::vector<ContourSegment>& segs, std::mt19937& g, int chords,
                        Stats& st) {
    constexpr int kSamples = 2000;
    for (int k = 0; k < chords; ++k) {
        const int sa = static_cast<int>(uniform(g, 0, 3)) % 3;
        const int sb = (sa + 1 + static_cast<int>(uniform(g, 0, 2)) % 2) % 3;
        const Vec2 p = d[sa] + uniform(g, 0.02, 0.98) * (d[(sa + 1) % 3] - d[sa]);
        const Vec2 q = d[sb] + uniform(g, 0.02, 0.98) * (d[(sb + 1) % 3] - d[sb]);
        const Vec2 dir = q - p;
        // Exact roots of f on the chord: f(p + l dir) is quadratic in l.
        std::array<double, 2> rr{};
        const int nr =
            realRoots(0.5 * dir.dot(form.A * dir), form.gradient(p).dot(dir), form(p), rr);
        std::vector<double> exact;
        for (int i = 0; i < nr; ++i)
            if (rr[i] > 0 && rr[i] < 1)
                exact.push_back(rr[i]);
        bool degenerate = false;
        for (double l : exact)
            degenerate |= l < 1e-7 || l > 1 - 1e-7;
        if (exact.size() == 2)
            degenerate |= std::abs(exact[0] - exact[1]) < 1e-7;
        if (nr == 2 && std::abs(rr[0] - rr[1]) < 1e-4)
            degenerate = true; // tangent chord, or across a double line
        if (degenerate) {
            ++st.skippedChords;
            continue;
        }
        ++st.chords;
        // Crossings of the segments with the chord.
        const Vec2 m(-dir.y(), dir.x());
        int crossings = 0;
        for (const ContourSegment& s : segs) {
            const Eigen::Matrix3d& c = s.curve.coefficients;
            const Eigen::RowVector3d l = m.x() * c.row(0) + m.y() * c.row(1) - m.dot(p) * c.row(2);
            std::array<double, 2> tr{};
            const int nt = realRoots(l[2], l[1], l[0], tr);
            for (int i = 0; i < nt; ++i) {
                if (!(tr[i] >= s.t0 && tr[i] <= s.t1))
                    continue;
                const double lam = (s.curve.at(tr[i]) - p).dot(dir) / dir.squaredNorm();
                if (lam > 0 && lam < 1)
                    ++crossings;
            }
        }
        if (crossings != static_cast<int>(exact.size())) {
            std::ostringstream o;
            o << "chord: " << crossings << " segment crossings, " << exact.size() << " roots of f";
            return o.str();
        }
        if (crossings > 0)
            ++st.chordsWithCrossings;
        // The dense sampling: resolvable unless two roots are within a few
        // samples of each other or of an end.
        bool resolvable = true;
        for (double l : exact)
            resolvable &= l > 2.0 / kSamples && l < 1 - 2.0 / kSamples;
        if (exact.size() == 2)
            resolvable &= std::abs(exact[0] - exact[1]) > 3.0 / kSamples;
        if (!resolvable) {
            ++st.unresolvedSamples;
            continue;
        }
        int changes = 0;
        bool prev = field(p) >= 0;
        for (int i = 1; i <= kSamples; ++i) {
            const bool now = field(p + (double(i) / kSamples) * dir) >= 0;
            changes += now != prev;
            prev = now;
        }
        if (changes != crossings) {
            std::ostringstream o;
            o << "chord: " << crossings << " segment crossings, " << changes
              << " sampled sign changes";
            return o.str();
        }
    }
    return {};
}

// Every segment: its kind and patch, |f| on samples, inside the domain, ends
// on the recorded sides, at most three pieces per branch; an ellipse inside
// the domain as two halves that close up.
std::string checkSegments(const QuadraticForm2& form, const Domain& d,
                          const std::vector<ContourSegment>& segs, ConicKind kind, Index id,
                          Stats& st) {
    const double scale = formScale(form, d);
    const double h = longestSide(d);
    std::ostringstream o;
    std::vector<const ContourSegment*> open;
    std::map<std::vector<double>, int> branches;
    for (const ContourSegment& s : segs) {
        if (s.kind != kind) {
            o << "kind " << toString(s.kind) << ", expected " << toString(kind);
            return o.str();
        }
        if (s.patch != id || !(s.t0 < s.t1) || !std::isfinite(s.t0) || !std::isfinite(s.t1))
            return "bad patch id or t range";
        for (int i = 0; i <= 16; ++i) {
            const double t = s.t0 + (s.t1 - s.t0) * i / 16.0;
            const Vec2 r = s.curve.at(t);
            if (!(std::abs(form(r)) <= kResidual * scale)) {
                o << toString(kind) << ": |f(r(t))| = " << std::abs(form(r)) / scale << " relative";
                return o.str();
            }
            if (!(minBarycentric(d, r) >= -kOnSide)) {
                o << toString(kind) << ": sample outside the domain, barycentric "
                  << minBarycentric(d, r);
                return o.str();
            }
        }
        if (!(minBarycentric(d, s.curve.at(0.5 * (s.t0 + s.t1))) > 0))
            return "midpoint not inside";
        for (const auto& [side, t] : {std::pair{s.startSide, s.t0}, std::pair{s.endSide, s.t1}}) {
            if (side == -1)
                continue;
            if (side < 0 || side > 2)
                return "bad side index";
            const double dist = distanceToSide(d, side, s.curve.at(t)) / h;
            if (!(dist <= kOnSide)) {
                o << toString(kind) << ": end off its side by " << dist << " relative";
                return o.str();
            }
        }
        if (s.startSide == -1 || s.endSide == -1)
            open.push_back(&s);
        const Eigen::Matrix3d& c = s.curve.coefficients;
        ++branches[std::vector<double>(c.data(), c.data() + 9)];
    }
    if (!open.empty()) {
        // Only an ellipse inside the domain has ends inside: two halves.
        if (kind != ConicKind::Ellipse || open.size() != 2 || segs.size() != 2)
            return "ends inside the domain other than an inside ellipse";
        const ContourSegment &a = *open[0], &b = *open[1];
        if (a.startSide != -1 || a.endSide != -1 || b.startSide != -1 || b.endSide != -1)
            return "inside ellipse with an end on a side";
        if ((a.curve.at(a.t1) - b.curve.at(b.t0)).norm() > kOnSide * h ||
            (b.curve.at(b.t1) - a.curve.at(a.t0)).norm() > kOnSide * h)
            return "the ellipse halves do not close up";
        ++st.insideEllipses;
    }
    for (const auto& [key, count] : branches) {
        if (count > 3)
            return "more than three pieces of one branch";
        st.maxPerBranch = std::max(st.maxPerBranch, count);
        ++st.piecesPerBranch[count];
    }
    ++st.forms;
    st.segments += static_cast<int>(segs.size());
    st.withSegments += !segs.empty();
    return {};
}

std::string checkForm(const QuadraticForm2& form, const Domain& d, ConicKind kind, std::mt19937& g,
                      Stats& st) {
    const ConicKind got = classifyConic(form, d);
    if (got != kind)
        return std::string("classified ") + toString(got) + ", built " + toString(kind);
    const std::vector<ContourSegment> segs = conicContours(form, d, 7);
    std::string e = checkSegments(form, d, segs, kind, 7, st);
    if (e.empty())
        e = checkChords(form, form, d, segs, g, 6, st);
    return e;
}

Eigen::Matrix2d outer(const Vec2& a) {
    return a * a.transpose();
}

// A form of the given case in local coordinates, with a random magnitude
// and sign; most meet the domain.
Local caseForm(ConicKind kind, std::mt19937& g, int variant) {
    const double angle = uniform(g, 0, 2 * kPi);
    const Vec2 e1(std::cos(angle), std::sin(angle)), e2(-e1.y(), e1.x());
    const Vec2 center(uniform(g, -0.5, 0.5), uniform(g, -0.5, 0.5));
    const double k1 = uniform(g, 0.05, 0.8);
    Local l{Eigen::Matrix2d::Zero(), Vec2::Zero(), 0.0};
    auto centered = [&](double s1, double s2, double chat) {
        l.A = s1 * outer(e1) + s2 * outer(e2);
        l.b = -l.A * center;
        l.c = chat + 0.5 * center.dot(l.A * center);
    };
    switch (kind) {
    case ConicKind::Ellipse: {
        const double s1 = -uniform(g, 0.5, 5), s2 = -uniform(g, 0.5, 5);
        centered(s1, s2, 0.5 * k1 * k1 * std::abs(s1));
        break;
    }
    case ConicKind::Hyperbola: {
        double s1 = -uniform(g, 0.5, 5), s2 = uniform(g, 0.5, 5);
        if (variant % 2)
            std::swap(s1, s2);
        centered(s1, s2, 0.5 * k1 * k1 * std::abs(s1));
        break;
    }
    case ConicKind::IntersectingLines: {
        const double s1 = -uniform(g, 0.2, 5), s2 = uniform(g, 0.2, 5);
        centered(s1, s2, 0.0);
        break;
    }
    case ConicKind::Parabola: {
        if (variant % 3 == 2) {
            // A = 0: a linear form, the parabola with sigma_1 = 0.
            l.b = uniform(g, 0.2, 2) * e2;
            l.c = uniform(g, -0.5, 0.5) * l.b.norm();
            break;
        }
        const double s1 = (variant % 2 ? 1 : -1) * uniform(g, 0.5, 5);
        // Near-singular A (a cylinder-like patch): sigma_2 below the tolerance.
        const double s2 = variant % 3 == 1 ? uniform(g, -1, 1) * 1e-12 : 0.0;
        l.A = s1 * outer(e1) + s2 * outer(e2);
        l.b = uniform(g, -1, 1) * e1 + (variant % 4 < 2 ? 1 : -1) * uniform(g, 0.2, 2) * e2;
        l.c = uniform(g, -0.5, 0.5);
        break;
    }
    case ConicKind::ParallelLines: {
        const double r1 = uniform(g, -0.7, 0.7);
        double r2 = uniform(g, -0.7, 0.7);
        while (std::abs(r2 - r1) < 0.05)
            r2 = uniform(g, -0.7, 0.7);
        const double s1 = (variant % 2 ? 1 : -1) * uniform(g, 0.5, 5);
        l.A = s1 * outer(e1) + (variant % 3 == 1 ? 1e-12 : 0.0) * outer(e2);
        l.b = -0.5 * s1 * (r1 + r2) * e1 + uniform(g, -1, 1) * 1e-13 * e2;
        l.c = 0.5 * s1 * r1 * r2;
        break;
    }
    case ConicKind::Empty: {
        const double s1 = uniform(g, 0.5, 5), s2 = uniform(g, 0.5, 5);
        if (variant % 3 == 0) {
            centered(s1, s2, uniform(g, 0.01, 1)); // definite, c^ of the form's sign
        } else if (variant % 3 == 1) {
            centered(s1, s2, 0.0); // an isolated zero
        } else {
            // A double line: f = 1/2 s1 (z1 - rho)^2.
            const double rho = uniform(g, -0.5, 0.5);
            l.A = s1 * outer(e1);
            l.b = -s1 * rho * e1;
            l.c = 0.5 * s1 * rho * rho;
        }
        break;
    }
    }
    const double magnitude = (variant % 5 == 0 ? -1 : 1) * std::pow(10.0, uniform(g, -3, 3));
    l.A *= magnitude;
    l.b *= magnitude;
    l.c *= magnitude;
    return l;
}

// The quadratic Bezier triangle of a quadratic polynomial over a domain.
QuadraticBezier<Vec3> bezierOf(const std::function<Vec3(const Vec2&)>& p, const Domain& d) {
    QuadraticBezier<Vec3> b;
    b.domain = d;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        b.control[i] = p(d[i]);
        b.control[3 + i] = 2.0 * p(0.5 * (d[i] + d[j])) - 0.5 * (p(d[i]) + p(d[j]));
    }
    return b;
}

QuadraticBezier<Vec3> randomPatch(std::mt19937& g, const Domain& d) {
    QuadraticBezier<Vec3> b;
    b.domain = d;
    for (Vec3& c : b.control)
        c = Vec3(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
    return b;
}

double direct(const QuadraticBezier<Vec3>& patch, const Vec3& tau, const Vec2& r) {
    Vec3 du, dv;
    uvDerivatives(patch, barycentricOf(patch.domain, r), du, dv);
    return tau.dot(du.cross(dv));
}

std::string checkPatch(const QuadraticBezier<Vec3>& patch, const Vec3& tau, ConicKind expected,
                       std::mt19937& g, Stats& st, ConicKind* classified = nullptr) {
    const QuadraticForm2 form = contourFunction(patch, tau);
    const ConicKind kind = classifyConic(form, patch.domain);
    if (classified)
        *classified = kind;
    if (expected != ConicKind::Empty && kind != expected)
        return std::string("patch classified ") + toString(kind) + ", expected " +
               toString(expected);
    const std::vector<ContourSegment> segs = patchContours(patch, 3, tau);
    std::string e = checkSegments(form, patch.domain, segs, kind, 3, st);
    if (e.empty())
        e = checkChords(
            form, [&](const Vec2& r) { return direct(patch, tau, r); }, patch.domain, segs, g, 4,
            st);
    return e;
}

std::string summary(const Stats& st) {
    std::ostringstream o;
    o << st.forms << " forms, " << st.withSegments << " with segments, " << st.segments
      << " segments, " << st.insideEllipses << " inside ellipses, pieces per branch:";
    for (const auto& [n, c] : st.piecesPerBranch)
        o << " " << n << "x" << c;
    o << "; chords " << st.chords << " (" << st.chordsWithCrossings << " crossing, "
      << st.skippedChords << " degenerate skipped, " << st.unresolvedSamples
      << " not resolvable by sampling)";
    return o.str();
}

} // namespace

class TestPsPatchContour : public QObject {
    Q_OBJECT

    PowellSabinSpline sphere_;

private slots:
    void initTestCase() {
        // A fitted Powell-Sabin sphere: cones, refinement, conformal map,
        // layout (uv scaled to a mean side of 1), thin-plate fit (§5).
        const TriangleMesh mesh = makeSphere(1.0, 10).triangulate();
        const Cones cones = selectCones(mesh);
        const ConeRefinement refined = refineAroundCones(mesh, cones.vertices);
        const ConformalMap map = computeConformalMap(refined.mesh, refined.cones);
        ConeLayout layout = layoutConformalMap(refined.mesh.positions(), map, refined.cones);
        double sides = 0;
        for (const auto& uv : layout.cornerUv)
            for (int c = 0; c < 3; ++c)
                sides += (uv[(c + 1) % 3] - uv[c]).norm();
        const double mean = sides / (3.0 * static_cast<double>(layout.cornerUv.size()));
        for (auto& uv : layout.cornerUv)
            for (Vec2& p : uv)
                p /= mean;
        const ThinPlateFit fit(layout);
        sphere_ = fit.fit(layout.mesh.positions());
        QVERIFY(!sphere_.patches.empty());
    }

    void contourFunctionMatchesDirectEvaluation() {
        std::mt19937 g(11);
        double worst = 0;
        for (int k = 0; k < 500; ++k) {
            const Domain d = randomDomain(g);
            const QuadraticBezier<Vec3> patch = randomPatch(g, d);
            const Vec3 tau = uniform(g, 0.1, 10) * randomUnit(g);
            const QuadraticForm2 f = contourFunction(patch, tau);
            QVERIFY((f.A - f.A.transpose()).norm() == 0.0);
            double scale = 0;
            for (const Vec2& c : d) {
                Vec3 du, dv;
                uvDerivatives(patch, barycentricOf(d, c), du, dv);
                scale = std::max(scale, tau.norm() * du.norm() * dv.norm());
            }
            for (int i = 0; i < 20; ++i) {
                // Inside the domain and around it.
                Vec3 w(uniform(g, -0.5, 1.5), uniform(g, -0.5, 1.5), 0);
                w.z() = 1 - w.x() - w.y();
                const Vec2 r = w.x() * d[0] + w.y() * d[1] + w.z() * d[2];
                worst = std::max(worst, std::abs(f(r) - direct(patch, tau, r)) / scale);
            }
        }
        qInfo("contourFunction vs tau.(p_u x p_v): worst relative difference %.2e", worst);
        QVERIFY(worst < 1e-12);
    }

    void constructedCases_data() {
        QTest::addColumn<int>("kind");
        QTest::newRow("ellipse") << int(ConicKind::Ellipse);
        QTest::newRow("hyperbola") << int(ConicKind::Hyperbola);
        QTest::newRow("intersecting lines") << int(ConicKind::IntersectingLines);
        QTest::newRow("parabola") << int(ConicKind::Parabola);
        QTest::newRow("parallel lines") << int(ConicKind::ParallelLines);
        QTest::newRow("empty") << int(ConicKind::Empty);
    }

    void constructedCases() {
        QFETCH(int, kind);
        const auto k = static_cast<ConicKind>(kind);
        std::mt19937 g(100 + kind);
        Stats st;
        for (int i = 0; i < 3000; ++i) {
            const Domain d = randomDomain(g);
            Local l = caseForm(k, g, i);
            if (k == ConicKind::IntersectingLines && i % 3 == 0) {
                // Centered at a corner, as at a cone (§5).
                const Vec2 corner = (d[i % 3] - centroid(d)) / longestSide(d);
                const Eigen::Matrix2d A = l.A;
                l.b = -A * corner;
                l.c = 0.5 * corner.dot(A * corner);
            }
            const std::string e = checkForm(fromLocal(l, d), d, k, g, st);
            QVERIFY2(e.empty(), (std::to_string(i) + ": " + e).c_str());
        }
        qInfo("%s: %s", toString(k), summary(st).c_str());
        if (k == ConicKind::Empty) {
            QCOMPARE(st.segments, 0);
            return;
        }
        QVERIFY(st.withSegments > 1000);
        QVERIFY(st.chordsWithCrossings > 1000);
        // A line meets the convex domain in one piece; a conic branch in up to three.
        if (k == ConicKind::Ellipse || k == ConicKind::Hyperbola || k == ConicKind::Parabola)
            QVERIFY(st.piecesPerBranch[2] > 0);
        if (k == ConicKind::Ellipse)
            QVERIFY(st.insideEllipses > 20);
    }

    void randomBezierPatches() {
        // Generic patches give ellipses and hyperbolas. Never a definite form
        // without zeros: the projection r -> (p(r) . tau_1, p(r) . tau_2) is a
        // quadratic map whose Jacobian is tau . n; a definite quadratic part
        // makes it of degree 2 at infinity, so it cannot be a local
        // diffeomorphism of the plane and tau . n vanishes somewhere.
        std::mt19937 g(7);
        Stats st;
        std::map<ConicKind, int> kinds;
        for (int i = 0; i < 3000; ++i) {
            const Domain d = randomDomain(g);
            ConicKind kind = ConicKind::Empty;
            const std::string e =
                checkPatch(randomPatch(g, d), randomUnit(g), ConicKind::Empty, g, st, &kind);
            QVERIFY2(e.empty(), (std::to_string(i) + ": " + e).c_str());
            ++kinds[kind];
        }
        qInfo("random patches: %d ellipse, %d hyperbola, %d empty; %s", kinds[ConicKind::Ellipse],
              kinds[ConicKind::Hyperbola], kinds[ConicKind::Empty], summary(st).c_str());
        QVERIFY(kinds[ConicKind::Ellipse] > 100);
        QVERIFY(kinds[ConicKind::Hyperbola] > 100);
        QCOMPARE(kinds[ConicKind::Empty], 0);
        QVERIFY(st.withSegments > 300);
    }

    void conePatches() {
        // Zero gradient at corner 0 (b01 = b20 = b0, §5.2): n = 0 there, c^ = 0,
        // the contour is a pair of lines through the corner (or empty).
        std::mt19937 g(8);
        Stats st;
        int lines = 0, empty = 0;
        for (int i = 0; i < 2000; ++i) {
            const Domain d = randomDomain(g);
            QuadraticBezier<Vec3> patch = randomPatch(g, d);
            patch.control[3] = patch.control[5] = patch.control[0];
            const Vec3 tau = randomUnit(g);
            ConicKind kind = ConicKind::Empty;
            const std::string e = checkPatch(patch, tau, ConicKind::Empty, g, st, &kind);
            QVERIFY2(e.empty(), (std::to_string(i) + ": " + e).c_str());
            QVERIFY2(kind == ConicKind::IntersectingLines || kind == ConicKind::Empty,
                     toString(kind));
            (kind == ConicKind::Empty ? empty : lines) += 1;
            for (const ContourSegment& s : patchContours(patch, 0, tau)) {
                // One end at the corner, the other on the opposite side.
                const double h = longestSide(d);
                const double a = (s.curve.at(s.t0) - d[0]).norm() / h;
                const double b = (s.curve.at(s.t1) - d[0]).norm() / h;
                QVERIFY(std::min(a, b) < 1e-9);
                QCOMPARE(a < b ? s.endSide : s.startSide, 1);
            }
        }
        qInfo("cone patches: %d intersecting lines, %d empty; %s", lines, empty,
              summary(st).c_str());
        QVERIFY(lines > 500);
        QVERIFY(empty > 100);
    }

    void cylinderLikePatches() {
        // Ruled and developable patches whose tau . n has a singular Hessian:
        // (u + a v^2, v, h(u, v)) with h_uu = 0 gives a parabola;
        // (u (1 + b v), y(v), z(v)) parallel lines; (x(u), y(u), v), whose
        // n is linear, a line (the parabola with sigma_1 = 0). All rotated.
        std::mt19937 g(9);
        Stats st;
        for (int i = 0; i < 3000; ++i) {
            const Domain d = randomDomain(g);
            const Vec2 o = centroid(d);
            const double h = longestSide(d);
            const Eigen::Matrix3d rot = randomRotation(g);
            std::array<double, 8> k{};
            for (double& x : k)
                x = uniform(g, -1, 1);
            Vec3 tauLocal = randomUnit(g);
            std::function<Vec3(const Vec2&)> p;
            ConicKind kind;
            if (i % 3 == 0) {
                kind = ConicKind::Parabola;
                while (std::abs(tauLocal.y()) < 0.2)
                    tauLocal = randomUnit(g);
                p = [=](const Vec2& r) {
                    const Vec2 s = (r - o) / h;
                    return Vec3(s.x() + k[0] * s.y() * s.y(), s.y(),
                                k[1] * s.x() + k[2] * s.y() + k[3] * s.x() * s.y() +
                                    k[4] * s.y() * s.y());
                };
                if (std::abs(k[0] * k[3]) < 0.05)
                    continue;
            } else if (i % 3 == 1) {
                kind = ConicKind::ParallelLines;
                const double beta = (k[0] < 0 ? -1 : 1) / uniform(g, 0.2, 1.0);
                p = [=](const Vec2& r) {
                    const Vec2 s = (r - o) / h;
                    return Vec3(s.x() * (1 + beta * s.y()), k[1] * s.y() + k[2] * s.y() * s.y(),
                                k[3] * s.y() + k[4] * s.y() * s.y());
                };
                // tau . n = (1 + beta v) (linear in v): two distinct roots.
                const Vec3 t = tauLocal;
                const double l0 = -t.y() * k[3] + t.z() * k[1],
                             l1 = 2 * (-t.y() * k[4] + t.z() * k[2]);
                if (std::abs(l1) < 0.1 || std::abs(-l0 / l1 + 1 / beta) < 0.05)
                    continue;
            } else {
                kind = ConicKind::Parabola;
                p = [=](const Vec2& r) {
                    const Vec2 s = (r - o) / h;
                    return Vec3(s.x() + k[0] * s.x() * s.x(), k[1] * s.x() + k[2] * s.x() * s.x(),
                                s.y());
                };
                if (std::abs(tauLocal.z()) > 0.9)
                    continue;
            }
            const auto rotated = [&](const Vec2& r) -> Vec3 {
                return rot * p(r);
            };
            const std::string e = checkPatch(bezierOf(rotated, d), rot * tauLocal, kind, g, st);
            QVERIFY2(e.empty(), (std::to_string(i) + ": " + e).c_str());
        }
        qInfo("cylinder-like patches: %s", summary(st).c_str());
        QVERIFY(st.withSegments > 500);
    }

    void nearSingularForms() {
        // A nearly singular A (cylinder-like, §4.1) on both sides of the
        // tolerance: below it the parabola (its dropped 1/2 sigma_2 z_2^2 is
        // below eps over the domain), above it an ellipse or hyperbola whose
        // center is ~|b| / sigma_2 away, and (sigma_2 >= 1e-6) intersecting
        // lines through a center ~1 / sqrt(sigma_2) away. All must pass the
        // same checks as the other cases. Not covered: c^ = 0 with a smaller
        // sigma_2 (PatchContour.h, limits).
        std::mt19937 g(17);
        for (double s2 : {1e-11, 1e-9, 1e-8, 1e-7, 1e-6, 1e-4}) {
            Stats st;
            std::map<ConicKind, int> kinds;
            for (int i = 0; i < 600; ++i) {
                const Domain d = randomDomain(g);
                const double angle = uniform(g, 0, 2 * kPi);
                const Vec2 e1(std::cos(angle), std::sin(angle)), e2(-e1.y(), e1.x());
                Local l;
                const double s1 = uniform(g, 0.5, 2);
                l.A = s1 * outer(e1) + (i % 2 ? 1 : -1) * s2 * outer(e2);
                l.b = uniform(g, -1, 1) * e1 + uniform(g, 0.2, 1) * e2;
                l.c = uniform(g, -0.3, 0.3);
                if (i % 3 == 2 && s2 >= 1e-6) {
                    // c^ = 0: intersecting lines through a center ~1/sqrt(sigma_2)
                    // away that cross the domain.
                    l.A = s1 * outer(e1) - s2 * outer(e2);
                    const Vec2 center =
                        uniform(g, -0.3, 0.3) * e1 + uniform(g, 0.1, 0.5) * std::sqrt(s1 / s2) * e2;
                    l.b = -l.A * center;
                    l.c = 0.5 * center.dot(l.A * center);
                }
                const QuadraticForm2 f = fromLocal(l, d);
                const ConicKind kind = classifyConic(f, d);
                ++kinds[kind];
                QVERIFY2(s2 < 1e-10
                             ? kind == ConicKind::Parabola
                             : kind != ConicKind::Parabola && kind != ConicKind::ParallelLines,
                         toString(kind));
                const auto segs = conicContours(f, d, 7);
                std::string e = checkSegments(f, d, segs, kind, 7, st);
                if (e.empty())
                    e = checkChords(f, f, d, segs, g, 4, st);
                QVERIFY2(e.empty(), (std::to_string(i) + ": " + e).c_str());
            }
            qInfo("sigma_2 = %.0e: %d ellipse, %d hyperbola, %d lines, %d parabola; %s", s2,
                  kinds[ConicKind::Ellipse], kinds[ConicKind::Hyperbola],
                  kinds[ConicKind::IntersectingLines], kinds[ConicKind::Parabola],
                  summary(st).c_str());
            QVERIFY(st.withSegments > 200);
        }
    }

    void segmentAlongASideBelongsToOnePatch() {
        // f vanishing on side 0 of a domain: exactly one of the two domains
        // sharing that side reports the segment, with its ends at the corners.
        std::mt19937 g(12);
        for (int i = 0; i < 200; ++i) {
            const Domain d = randomDomain(g);
            const Vec2 e = d[1] - d[0];
            const Vec2 n = Vec2(-e.y(), e.x()).normalized();
            const Domain other = {d[1], d[0], 0.5 * (d[0] + d[1]) - uniform(g, 0.2, 1) * n};
            QuadraticForm2 f; // f = (n . (r - d0)) (1 + m . r): a line and another one
            const Vec2 m(uniform(g, -0.1, 0.1), uniform(g, -0.1, 0.1));
            if (i % 2) {
                f.b = n;
                f.c = -n.dot(d[0]);
            } else {
                f.A = n * m.transpose() + m * n.transpose();
                f.b = n - n.dot(d[0]) * m;
                f.c = -n.dot(d[0]);
            }
            const auto mine = conicContours(f, d, 0), theirs = conicContours(f, other, 1);
            int along = 0;
            for (const auto* segs : {&mine, &theirs})
                for (const ContourSegment& s : *segs) {
                    const Domain& dom = segs == &mine ? d : other;
                    const double h = longestSide(dom);
                    if (distanceToSide(dom, 0, s.curve.at(0.5 * (s.t0 + s.t1))) < 1e-9 * h) {
                        ++along;
                        QVERIFY(segs == &mine); // grad f points into d
                        const double a = std::min((s.curve.at(s.t0) - d[0]).norm(),
                                                  (s.curve.at(s.t0) - d[1]).norm());
                        const double b = std::min((s.curve.at(s.t1) - d[0]).norm(),
                                                  (s.curve.at(s.t1) - d[1]).norm());
                        QVERIFY(a < 1e-9 * h && b < 1e-9 * h);
                    }
                    QVERIFY(s.t1 > s.t0);
                }
            QCOMPARE(along, 1);
        }
    }

    void curveThroughACorner() {
        // A line through corner 1 and the midpoint of side 2: one segment,
        // no zero-length piece at the corner.
        std::mt19937 g(13);
        for (int i = 0; i < 200; ++i) {
            const Domain d = randomDomain(g);
            const Vec2 a = d[1], b = 0.5 * (d[2] + d[0]);
            const Vec2 n = Vec2(-(b - a).y(), (b - a).x());
            QuadraticForm2 f;
            f.b = n;
            f.c = -n.dot(a);
            const auto segs = conicContours(f, d, 0);
            QCOMPARE(segs.size(), std::size_t(1));
            const ContourSegment& s = segs[0];
            const double h = longestSide(d);
            const Vec2 p = s.curve.at(s.t0), q = s.curve.at(s.t1);
            QVERIFY(std::min((p - a).norm(), (q - a).norm()) < 1e-12 * h);
            QVERIFY(std::min((p - b).norm(), (q - b).norm()) < 1e-12 * h);
            QCOMPARE((p - a).norm() < (q - a).norm() ? s.endSide : s.startSide, 2);
        }
    }

    void fittedSphere() {
        // Random views of the fitted sphere: every patch's segments pass the
        // checks against its own tau . (p_u x p_v); cone patches give lines
        // through the cone or nothing; every end on a side meets an end of
        // another patch at the same 3D point (the contour is closed, A.8 #8).
        std::mt19937 g(14);
        Stats st;
        int coneLines = 0;
        for (int view = 0; view < 6; ++view) {
            const Vec3 tau = randomUnit(g);
            std::vector<Vec3> ends;
            std::vector<Index> endPatch;
            for (Index id = 0; id < Index(sphere_.patches.size()); ++id) {
                const QuadraticBezier<Vec3>& patch = sphere_.patches[id];
                const QuadraticForm2 form = contourFunction(patch, tau);
                const ConicKind kind = classifyConic(form, patch.domain);
                const auto segs = patchContours(patch, id, tau);
                std::string e = checkSegments(form, patch.domain, segs, kind, id, st);
                if (e.empty())
                    e = checkChords(
                        form, [&](const Vec2& r) { return direct(patch, tau, r); }, patch.domain,
                        segs, g, 3, st);
                QVERIFY2(e.empty(), (std::to_string(id) + ": " + e).c_str());
                if (sphere_.conePatch[id]) {
                    QVERIFY2(kind == ConicKind::IntersectingLines || kind == ConicKind::Empty,
                             toString(kind));
                    coneLines += kind == ConicKind::IntersectingLines;
                }
                for (const ContourSegment& s : segs)
                    for (const auto& [side, t] :
                         {std::pair{s.startSide, s.t0}, std::pair{s.endSide, s.t1}})
                        if (side >= 0) {
                            ends.push_back(
                                sphere_.position(id, barycentricOf(patch.domain, s.curve.at(t))));
                            endPatch.push_back(id);
                        }
            }
            QVERIFY(ends.size() > 20);
            double worst = 0;
            for (std::size_t i = 0; i < ends.size(); ++i) {
                double best = std::numeric_limits<double>::infinity();
                for (std::size_t j = 0; j < ends.size(); ++j)
                    if (endPatch[j] != endPatch[i])
                        best = std::min(best, (ends[i] - ends[j]).norm());
                worst = std::max(worst, best);
            }
            qInfo("view %d: %zu segment ends, farthest from a partner %.2e", view, ends.size(),
                  worst);
            QVERIFY(worst < 1e-9);
        }
        qInfo("fitted sphere, %zu patches: %s; %d cone patches with lines", sphere_.patches.size(),
              summary(st).c_str(), coneLines);
        QVERIFY(coneLines > 0);
    }

    void timing() {
        // Not asserted: ~100k patches of the fitted sphere under random views.
        std::mt19937 g(15);
        const Index n = Index(sphere_.patches.size());
        const int views = std::max(1, int(100000 / n));
        std::vector<Vec3> taus;
        for (int v = 0; v < views; ++v)
            taus.push_back(randomUnit(g));
        std::size_t segments = 0;
        QElapsedTimer timer;
        timer.start();
        for (const Vec3& tau : taus)
            for (Index id = 0; id < n; ++id)
                segments += patchContours(sphere_.patches[id], id, tau).size();
        const double all = double(timer.nsecsElapsed());
        std::vector<QuadraticForm2> forms;
        for (const Vec3& tau : taus)
            for (Index id = 0; id < n; ++id)
                forms.push_back(contourFunction(sphere_.patches[id], tau));
        timer.restart();
        std::size_t conicSegments = 0;
        for (std::size_t i = 0; i < forms.size(); ++i)
            conicSegments += conicContours(forms[i], sphere_.patches[i % n].domain, 0).size();
        const double trim = double(timer.nsecsElapsed());
        const double count = double(forms.size());
        qInfo("timing over %.0f patches: patchContours %.0f ns per patch (form, classification, "
              "trimming); conicContours on a given form %.0f ns per patch; %zu segments",
              count, all / count, trim / count, segments);
        QCOMPARE(segments, conicSegments);
        // Random patches over random domains, most with segments.
        std::vector<QuadraticBezier<Vec3>> patches;
        for (int i = 0; i < 100000; ++i)
            patches.push_back(randomPatch(g, randomDomain(g)));
        const Vec3 tau = randomUnit(g);
        std::size_t randomSegments = 0;
        timer.restart();
        for (const QuadraticBezier<Vec3>& p : patches)
            randomSegments += patchContours(p, 0, tau).size();
        qInfo("timing over %zu random patches: patchContours %.0f ns per patch; %zu segments",
              patches.size(), double(timer.nsecsElapsed()) / double(patches.size()),
              randomSegments);
    }

    void badInput() {
        std::mt19937 g(16);
        const Domain d = randomDomain(g);
        QuadraticBezier<Vec3> patch = randomPatch(g, d);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, patchContours(patch, 0, Vec3::Zero()));
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            patchContours(patch, 0, Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 1)));
        PatchContourOptions negative;
        negative.zeroTolerance = -1;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 patchContours(patch, 0, Vec3(0, 0, 1), negative));
        QuadraticBezier<Vec3> clockwise = patch;
        std::swap(clockwise.domain[1], clockwise.domain[2]);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, patchContours(clockwise, 0, Vec3(0, 0, 1)));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, contourFunction(clockwise, Vec3(0, 0, 1)));
        QuadraticBezier<Vec3> broken = patch;
        broken.control[4].x() = std::numeric_limits<double>::infinity();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, patchContours(broken, 0, Vec3(0, 0, 1)));
        QuadraticForm2 f;
        f.c = std::numeric_limits<double>::quiet_NaN();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, conicContours(f, d, 0));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, classifyConic(f, d));
        // The zero form (a plane seen edge-on) has no stable contour.
        QCOMPARE(conicContours(QuadraticForm2{}, d, 0).size(), std::size_t(0));
        QVERIFY(classifyConic(QuadraticForm2{}, d) == ConicKind::Empty);
    }
};

QTEST_GUILESS_MAIN(TestPsPatchContour)
#include "test_ps_patch_contour.moc"
