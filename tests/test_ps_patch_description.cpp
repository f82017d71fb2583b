// What the inspector shows about a patch of the fitted Powell-Sabin spline
// (contours/powell_sabin/PatchDescription.h; Capouellez et al. 2023 §4.1,
// §5.2), on spot run to the cusps phase: the rows name the patch's macro-
// patch and sub-triangle and give its control points and domain; the
// printed coefficients of eq. 2 reproduce tau . (p_u x p_v) evaluated from
// the patch's derivatives; every segment of a patch is listed with its
// interval and a rational form that stays on the printed conic; the conic
// case is the segments' (or "no contour"); every cusp is claimed by a patch
// at its uv; the cone corners agree with the fit's cone patches.
#include "ContourTestSupport.h"
#include "contours/powell_sabin/PatchDescription.h"

#include <QtTest>
#include <regex>

using namespace contour;
using namespace contour::testing;
using namespace contour::powell_sabin;

namespace {

// The value of row `name`, or "" (QVERIFY on it in the caller).
std::string row(const DescriptionRows& rows, const std::string& name) {
    for (const auto& [property, value] : rows)
        if (property == name)
            return value;
    return {};
}

int countRowsStartingWith(const DescriptionRows& rows, const std::string& prefix) {
    int n = 0;
    for (const auto& r : rows)
        n += r.first.rfind(prefix, 0) == 0;
    return n;
}

// The decimal numbers in `text`, in order.
std::vector<double> numbers(const std::string& text) {
    static const std::regex pattern(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
    std::vector<double> out;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
         it != std::sregex_iterator(); ++it)
        out.push_back(std::stod(it->str()));
    return out;
}

bool close(double a, double b, double scale) {
    return std::abs(a - b) <= 1e-8 * std::max({std::abs(a), std::abs(b), scale});
}

// f(r) = 1/2 r^T A r + b^T r + c from the three printed rows.
struct PrintedForm {
    double a11 = 0, a12 = 0, a21 = 0, a22 = 0, b1 = 0, b2 = 0, c = 0;
    double operator()(const Vec2& r) const {
        return 0.5 * (a11 * r.x() * r.x() + (a12 + a21) * r.x() * r.y() + a22 * r.y() * r.y()) +
               b1 * r.x() + b2 * r.y() + c;
    }
    double scale() const {
        return std::abs(a11) + std::abs(a12) + std::abs(a22) + std::abs(b1) + std::abs(b2) +
               std::abs(c);
    }
};

bool parseForm(const DescriptionRows& rows, PrintedForm& f) {
    const std::vector<double> a = numbers(row(rows, "τ·n: A"));
    const std::vector<double> b = numbers(row(rows, "τ·n: b"));
    const std::vector<double> c = numbers(row(rows, "τ·n: c"));
    if (a.size() != 4 || b.size() != 2 || c.size() != 1)
        return false;
    f = {a[0], a[1], a[2], a[3], b[0], b[1], c[0]};
    return true;
}

} // namespace

class TestPsPatchDescription : public QObject {
    Q_OBJECT

private:
    MethodRun run_;
    const PowellSabinState* state_ = nullptr; // after the cusps phase
    std::vector<Index> withContour_;          // patches with a segment, ascending

private slots:
    void initTestCase() {
        const auto spot = sampleOrShape("spot", 0);
        Camera camera =
            Camera::framing(spot->boundingBox(), Vec3(1.0, 0.3, 0.5), Viewport{800, 600});
        run_ = run("powell-sabin", spot, camera, {}, "cusps");
        state_ = powellSabinState(run_.last());
        QVERIFY(state_ && state_->spline && state_->segments && state_->chaining && state_->cusps);
        for (const ContourSegment& s : *state_->segments)
            if (withContour_.empty() || withContour_.back() != s.patch)
                withContour_.push_back(s.patch);
        std::sort(withContour_.begin(), withContour_.end());
        withContour_.erase(std::unique(withContour_.begin(), withContour_.end()),
                           withContour_.end());
        qInfo("spot: %zu patches, %zu with a contour, %zu segments, %zu interior cusps",
              state_->spline->patches.size(), withContour_.size(), state_->segments->size(),
              state_->cusps->size());
        QVERIFY(withContour_.size() > 10);
        QVERIFY(!state_->cusps->empty());
    }

    void rowsNameThePatchItsControlPointsAndDomain() {
        const PowellSabinSpline& spline = *state_->spline;
        for (const Index p : {withContour_.front(), withContour_.back(), Index(0),
                              static_cast<Index>(spline.patches.size() - 1)}) {
            const DescriptionRows rows = describePatch(*state_, p);
            QCOMPARE(rows.front().first, std::string("patch"));
            QCOMPARE(numbers(rows.front().second), std::vector<double>{double(p)});
            const std::vector<double> face = numbers(row(rows, "layout face"));
            QVERIFY(face.size() == 4);
            QCOMPARE(face[0], double(p / kPs12Patches));
            const Triangle& t = state_->layout->mesh.triangle(p / kPs12Patches);
            QCOMPARE(face[1], double(t[0]));
            QCOMPARE(numbers(row(rows, "sub-triangle")).front(), double(p % kPs12Patches));
            const QuadraticBezier<Vec3>& patch = spline.patches[static_cast<size_t>(p)];
            const std::array<const char*, 6> names{"b0", "b1", "b2", "b01", "b12", "b20"};
            for (size_t c = 0; c < names.size(); ++c) {
                const std::vector<double> x = numbers(row(rows, names[c]));
                QVERIFY2(x.size() == 3, names[c]);
                for (int k = 0; k < 3; ++k)
                    QVERIFY2(close(x[static_cast<size_t>(k)], patch.control[c][k],
                                   patch.control[c].norm()),
                             names[c]);
            }
            const std::vector<double> uv = numbers(row(rows, "uv domain"));
            QCOMPARE(uv.size(), size_t(6));
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 2; ++k)
                    QVERIFY(close(uv[static_cast<size_t>(2 * c + k)], patch.domain[c][k], 1.0));
        }
    }

    // eq. 2 against the normal from the patch's own uv derivatives.
    void coefficientsReproduceTauDotN() {
        const PowellSabinSpline& spline = *state_->spline;
        int checked = 0;
        for (size_t i = 0; i < withContour_.size(); i += 7) {
            const Index p = withContour_[i];
            const DescriptionRows rows = describePatch(*state_, p);
            PrintedForm f;
            QVERIFY(parseForm(rows, f));
            const QuadraticBezier<Vec3>& patch = spline.patches[static_cast<size_t>(p)];
            for (const Vec3& b : {Vec3(1.0, 0.0, 0.0), Vec3(0.2, 0.5, 0.3), Vec3(0.1, 0.1, 0.8),
                                  Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)}) {
                const Vec2 r =
                    b[0] * patch.domain[0] + b[1] * patch.domain[1] + b[2] * patch.domain[2];
                const double tauDotN = spline.normal(p, b).z();
                // Relative to the form's size over the domain.
                const double scale = f.scale() * (1.0 + r.squaredNorm());
                QVERIFY2(
                    std::abs(f(r) - tauDotN) <= 1e-7 * scale,
                    qPrintable(
                        QString("patch %1: printed %2, tau.n %3").arg(p).arg(f(r)).arg(tauDotN)));
            }
            ++checked;
        }
        QVERIFY(checked > 1);
    }

    void intervalsAreTheSegments() {
        const std::vector<ContourSegment>& segments = *state_->segments;
        for (const Index p : withContour_) {
            const DescriptionRows rows = describePatch(*state_, p);
            std::vector<size_t> mine;
            for (size_t i = 0; i < segments.size(); ++i)
                if (segments[i].patch == p)
                    mine.push_back(i);
            QCOMPARE(countRowsStartingWith(rows, "contour interval "),
                     static_cast<int>(mine.size()));
            QCOMPARE(countRowsStartingWith(rows, "rational form "), static_cast<int>(mine.size()));
            QCOMPARE(row(rows, "conic case"), std::string(toString(segments[mine[0]].kind)));
            PrintedForm f;
            QVERIFY(parseForm(rows, f));
            for (size_t k = 0; k < mine.size(); ++k) {
                const ContourSegment& s = segments[mine[k]];
                const std::string index = std::to_string(k + 1);
                const std::vector<double> interval =
                    numbers(row(rows, "contour interval " + index));
                QVERIFY(interval.size() >= 3);
                QCOMPARE(interval[0], double(mine[k]));
                QVERIFY(close(interval[1], s.t0, 1.0) && close(interval[2], s.t1, 1.0));
                // The printed X, Y, W stay on the printed conic over [t0, t1].
                const std::vector<double> q = numbers(row(rows, "rational form " + index));
                QCOMPARE(q.size(), size_t(9));
                for (int j = 0; j <= 4; ++j) {
                    const double t = s.t0 + 0.25 * j * (s.t1 - s.t0);
                    const auto at = [&](size_t r0) {
                        return q[r0] + q[r0 + 1] * t + q[r0 + 2] * t * t;
                    };
                    const Vec2 r(at(0) / at(6), at(3) / at(6));
                    QVERIFY2(std::abs(f(r)) <= 1e-6 * f.scale() * (1.0 + r.squaredNorm()),
                             qPrintable(QString("patch %1 segment %2 at t %3: f %4")
                                            .arg(p)
                                            .arg(mine[k])
                                            .arg(t)
                                            .arg(f(r))));
                    QVERIFY((r - s.curve.at(t)).norm() <= 1e-6 * (1.0 + r.norm()));
                }
            }
        }
        // A patch without a segment says so, and still gives its form's case.
        int without = 0;
        for (Index p = 0; p < static_cast<Index>(state_->spline->patches.size()) && without < 20;
             p += 97) {
            if (std::binary_search(withContour_.begin(), withContour_.end(), p))
                continue;
            const DescriptionRows rows = describePatch(*state_, p);
            QVERIFY(row(rows, "conic case").rfind("no contour (the form: ", 0) == 0);
            QCOMPARE(countRowsStartingWith(rows, "contour interval "), 0);
            ++without;
        }
        QVERIFY(without > 0);
    }

    void everyCuspIsClaimedAtItsUv() {
        std::vector<int> claimed(state_->cusps->size(), 0);
        for (const Index p : withContour_) {
            const std::string text = row(describePatch(*state_, p), "interior cusp");
            QVERIFY(!text.empty());
            if (text == "no")
                continue;
            const std::vector<double> uv = numbers(text);
            QVERIFY(uv.size() >= 2 && uv.size() % 2 == 0);
            for (size_t k = 0; k + 1 < uv.size(); k += 2)
                for (size_t c = 0; c < claimed.size(); ++c)
                    claimed[c] += close(uv[k], (*state_->cusps)[c].uv.x(), 1.0) &&
                                  close(uv[k + 1], (*state_->cusps)[c].uv.y(), 1.0);
        }
        for (size_t c = 0; c < claimed.size(); ++c)
            QVERIFY2(claimed[c] >= 1, qPrintable(QString("cusp %1").arg(c)));
    }

    // The fit marks cone patches from the uv of the split (ThinPlateFit).
    void coneCornersAreTheFitsConePatches() {
        const PowellSabinSpline& spline = *state_->spline;
        int cones = 0, others = 0;
        for (Index p = 0; p < static_cast<Index>(spline.patches.size()); ++p) {
            const bool cone = spline.conePatch[static_cast<size_t>(p)] != 0;
            if (!cone && p % 53 != 0)
                continue;
            const std::string text = row(describePatch(*state_, p), "cone corner");
            QCOMPARE(text == "no", !cone);
            if (cone) {
                // Corners 0 of the sub-triangles are the layout's vertices.
                QVERIFY2(text.rfind("corner 0 (layout vertex ", 0) == 0, text.c_str());
                const Index v = static_cast<Index>(numbers(text)[1]);
                QVERIFY(state_->layout->isCone[static_cast<size_t>(v)] != 0);
            }
            (cone ? cones : others) += 1;
        }
        // 8 cones, each a corner of 2 patches per incident face (at least 3).
        QVERIFY(cones >= 8 * 2 * 3);
        QVERIFY(others > 0);
    }

    void earlierPhasesSayWhatIsMissing() {
        const PowellSabinState* fit = powellSabinState(run_.phase("fit"));
        QVERIFY(fit && fit->spline && !fit->segments);
        const DescriptionRows rows = describePatch(*fit, withContour_.front());
        QVERIFY(row(rows, "conic case").find("from patch-contours on") != std::string::npos);
        QCOMPARE(countRowsStartingWith(rows, "contour interval "), 0);
        QVERIFY(row(rows, "interior cusp").find("cusps phase") != std::string::npos);
        // Out of range, and a state before the fit.
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, describePatch(*state_, -1));
        QVERIFY_THROWS_EXCEPTION(
            std::out_of_range,
            describePatch(*state_, static_cast<Index>(state_->spline->patches.size())));
        const PowellSabinState* layout = powellSabinState(run_.phase("layout"));
        QVERIFY(layout);
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, describePatch(*layout, 0));
    }

    void chainPatchesInOrderOnce() {
        ViewChain chain;
        chain.segmentElement = {12, 12, 40, 12, 7, kInvalidIndex, 40, 9};
        QCOMPARE(chainPatches(chain), (std::vector<Index>{12, 40, 7, 9}));
        QCOMPARE(describeChainPatches(chain, 2), std::string("4 patches: 12, 40, …"));
        QCOMPARE(describeChainPatches(chain, 4), std::string("4 patches: 12, 40, 7, 9"));
        chain.segmentElement = {};
        QCOMPARE(describeChainPatches(chain), std::string("0 patches"));
    }
};

QTEST_GUILESS_MAIN(TestPsPatchDescription)
#include "test_ps_patch_description.moc"
