#include "contours/powell_sabin/PatchDescription.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>

namespace contour::powell_sabin {

namespace {

// After the projective transform the view is along +z (§3).
const Vec3 kTau(0.0, 0.0, 1.0);

// Appends the parts (std::string or text): GCC 12 warns (-Wrestrict, a
// false positive) on text + std::string temporaries.
template <typename... Parts> std::string cat(const Parts&... parts) {
    std::string out;
    ((out += parts), ...);
    return out;
}

std::string number(double v) {
    std::array<char, 32> text{};
    std::snprintf(text.data(), text.size(), "%.9g", v);
    return text.data();
}

std::string point(const Vec2& p) {
    return cat("(", number(p.x()), ", ", number(p.y()), ")");
}

std::string point(const Vec3& p) {
    return cat("(", number(p.x()), ", ", number(p.y()), ", ", number(p.z()), ")");
}

// a + b t + c t² of one row of a rational quadratic's coefficients.
std::string quadratic(const Eigen::Matrix3d& coefficients, int row) {
    return cat(number(coefficients(row, 0)), " + ", number(coefficients(row, 1)), " t + ",
               number(coefficients(row, 2)), " t²");
}

// The split points of Ps12Patch.h by name: V_i, M_s, Q_i, C.
std::string splitPointName(int point) {
    if (point < 3)
        return cat("V", std::to_string(point));
    if (point < 6)
        return cat("M", std::to_string(point - 3));
    if (point < 9)
        return cat("Q", std::to_string(point - 6));
    return "C";
}

std::string sideName(int side) {
    return side < 0 ? std::string("inside") : cat("side ", std::to_string(side));
}

// The chain of the chaining that holds `segment`, or kInvalidIndex.
Index chainOf(const ContourChaining& chaining, Index segment) {
    for (size_t c = 0; c < chaining.chains.size(); ++c)
        for (const ChainLink& link : chaining.chains[c].links)
            if (link.segment == segment)
                return static_cast<Index>(c);
    return kInvalidIndex;
}

// Whether `cusp` lies on `patch`: its uv in the domain and its point the
// patch's point there (face uv alone is ambiguous across components, and a
// cusp on a shared side belongs to both patches).
bool cuspInPatch(const PatchCusp& cusp, const QuadraticBezier<Vec3>& patch) {
    const Vec3 b = barycentricOf(patch.domain, cusp.uv);
    if (!(b.minCoeff() >= -1e-9))
        return false;
    double size = 0.0;
    for (const Vec3& p : patch.control)
        size = std::max(size, (p - patch.control[0]).norm());
    return (evaluate(patch, b) - cusp.position).norm() <= 1e-9 * std::max(size, 1e-300);
}

} // namespace

DescriptionRows describePatch(const PowellSabinState& state, Index patch) {
    if (!state.spline || !state.layout)
        throw std::out_of_range("describePatch: the state has no fitted spline yet");
    const PowellSabinSpline& spline = *state.spline;
    if (patch < 0 || patch >= static_cast<Index>(spline.patches.size()))
        throw std::out_of_range(cat("describePatch: patch ", std::to_string(patch), " of ",
                                    std::to_string(spline.patches.size())));
    const QuadraticBezier<Vec3>& bezier = spline.patches[static_cast<size_t>(patch)];
    const Index face = patch / kPs12Patches;
    const int sub = static_cast<int>(patch % kPs12Patches);
    const ConeLayout& layout = *state.layout;
    const Triangle& corners = layout.mesh.triangle(face);
    const std::array<int, 3>& split = ps12SubTriangleCorners[static_cast<size_t>(sub)];

    DescriptionRows rows;
    rows.emplace_back("patch", std::to_string(patch));
    rows.emplace_back("layout face",
                      cat(std::to_string(face), " (the macro-patch; vertices ",
                          std::to_string(corners[0]), ", ", std::to_string(corners[1]), ", ",
                          std::to_string(corners[2]), ")"));
    rows.emplace_back("sub-triangle",
                      cat(std::to_string(sub), " of 12 (", splitPointName(split[0]), ", ",
                          splitPointName(split[1]), ", ", splitPointName(split[2]), ")"));
    static constexpr std::array<const char*, 6> kControlNames{"b0",  "b1",  "b2",
                                                              "b01", "b12", "b20"};
    for (size_t c = 0; c < kControlNames.size(); ++c)
        rows.emplace_back(kControlNames[c], point(bezier.control[c]));
    rows.emplace_back("uv domain", cat(point(bezier.domain[0]), ", ", point(bezier.domain[1]), ", ",
                                       point(bezier.domain[2])));

    // eq. 2: the contour generator is the zero set of this form (§4.1).
    const QuadraticForm2 form = contourFunction(bezier, kTau);
    rows.emplace_back("τ·n: A", cat("[[", number(form.A(0, 0)), ", ", number(form.A(0, 1)), "], [",
                                    number(form.A(1, 0)), ", ", number(form.A(1, 1)), "]]"));
    rows.emplace_back("τ·n: b", point(form.b));
    rows.emplace_back("τ·n: c", number(form.c));

    // Table 1's case: what the segments were computed with, else the form's.
    std::vector<Index> mine;
    if (state.segments)
        for (size_t i = 0; i < state.segments->size(); ++i)
            if ((*state.segments)[i].patch == patch)
                mine.push_back(static_cast<Index>(i));
    const ConicKind formKind = classifyConic(form, bezier.domain);
    if (!state.segments) {
        rows.emplace_back("conic case", cat(toString(formKind),
                                            " (of the form; segments from patch-contours on)"));
    } else if (mine.empty()) {
        rows.emplace_back("conic case", cat("no contour (the form: ", toString(formKind), ")"));
    } else {
        std::vector<ConicKind> kinds;
        for (const Index i : mine)
            if (std::find(kinds.begin(), kinds.end(), (*state.segments)[i].kind) == kinds.end())
                kinds.push_back((*state.segments)[i].kind);
        std::string text;
        for (const ConicKind k : kinds)
            text += cat(text.empty() ? "" : ", ", toString(k));
        rows.emplace_back("conic case", text);
    }
    for (size_t k = 0; k < mine.size(); ++k) {
        const ContourSegment& s = (*state.segments)[static_cast<size_t>(mine[k])];
        std::string interval =
            cat("segment ", std::to_string(mine[k]), ": t in [", number(s.t0), ", ", number(s.t1),
                "], from ", sideName(s.startSide), " to ", sideName(s.endSide));
        if (state.chaining) {
            const Index chain = chainOf(*state.chaining, mine[k]);
            interval += chain == kInvalidIndex ? std::string(", in no chain")
                                               : cat(", contour chain ", std::to_string(chain));
        }
        const std::string index = std::to_string(k + 1);
        rows.emplace_back(cat("contour interval ", index), interval);
        rows.emplace_back(cat("rational form ", index),
                          cat("X = ", quadratic(s.curve.coefficients, 0),
                              "; Y = ", quadratic(s.curve.coefficients, 1),
                              "; W = ", quadratic(s.curve.coefficients, 2)));
    }

    if (!state.cusps) {
        rows.emplace_back("interior cusp", "not computed before the cusps phase");
    } else {
        std::string text;
        for (const PatchCusp& cusp : *state.cusps)
            if (cuspInPatch(cusp, bezier))
                text += cat(text.empty() ? "yes, at uv " : ", ", point(cusp.uv));
        rows.emplace_back("interior cusp", text.empty() ? std::string("no") : text);
    }

    // A patch corner is a cone only at a layout vertex V_i (§5.1).
    std::string cones;
    for (int c = 0; c < 3; ++c) {
        const int p = split[static_cast<size_t>(c)];
        if (p < 3 && layout.isCone[static_cast<size_t>(corners[p])])
            cones += cat(cones.empty() ? "" : "; ", "corner ", std::to_string(c),
                         " (layout vertex ", std::to_string(corners[p]), ")");
    }
    rows.emplace_back("cone corner", cones.empty() ? std::string("no") : cones);
    return rows;
}

std::vector<Index> chainPatches(const ViewChain& chain) {
    std::vector<Index> patches;
    for (const Index p : chain.segmentElement)
        if (p != kInvalidIndex && std::find(patches.begin(), patches.end(), p) == patches.end())
            patches.push_back(p);
    return patches;
}

std::string describeChainPatches(const ViewChain& chain, std::size_t shown) {
    const std::vector<Index> patches = chainPatches(chain);
    std::string text =
        cat(std::to_string(patches.size()), patches.size() == 1 ? " patch" : " patches",
            patches.empty() ? "" : ": ");
    for (size_t i = 0; i < std::min(shown, patches.size()); ++i)
        text += cat(i == 0 ? "" : ", ", std::to_string(patches[i]));
    if (patches.size() > shown)
        text += ", …";
    return text;
}

} // namespace contour::powell_sabin
