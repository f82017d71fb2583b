// Contour refinement: not in the paper. Bénard 2014 §6 places contour
// vertices only where g changes sign along the initial edges (§6.2 e), so a
// contour edge is a chord of the smooth contour between two roots: where the
// contour bends it strays from the curve (up to 2.4 px on spot_control, and
// the dense ground truth then sees the curve cross a domain face the chord
// misses). This phase splits such an edge at a root of g near its middle, the
// way §6.2 (e) splits an FB edge (Fig. 16c), and keeps the split only when the
// four new faces are no less consistent than the two they replace (§6.4's
// acceptance rule, not strictly better: the move is for accuracy). It runs
// after the last optimization so that no move of §6.4 has to work around the
// new vertices.
#include "contours/consistent/edits/CuspEndRetriangulation.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/ContourCuspSearch.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"

#include <algorithm>
#include <deque>
#include <optional>

namespace contour::consistent {

namespace {

struct RefinementStats {
    long long measured = 0, farther = 0, split = 0, rejected = 0, missed = 0, depthLimited = 0;
    double largestBefore = 0.0, largestAfter = 0.0;
};

// Pixel distance from p to the image segment a-b.
double pixelDistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

// A contour-generator edge (§8.1): both ends C, one face F-VBO, the other
// B-VBO. Returns {c, d}, the corners opposite a-b in a-b-c and b-a-d.
std::optional<std::array<Index, 2>> contourEdgeCorners(const ConsistentMesh& m, Index a, Index b) {
    if (m.vertex(a).label != VertexLabel::Contour || m.vertex(b).label != VertexLabel::Contour)
        return std::nullopt;
    const Index f = m.faceOfHalfedge(a, b), h = m.faceOfHalfedge(b, a);
    if (f == kInvalidIndex || h == kInvalidIndex)
        return std::nullopt;
    const Vbo vf = faceVbo(m, f), vh = faceVbo(m, h);
    if (vf == Vbo::Undefined || vh == Vbo::Undefined || vf == vh)
        return std::nullopt;
    const auto [c, d] = m.oppositeVertices(a, b);
    if (c == kInvalidIndex || d == kInvalidIndex)
        return std::nullopt;
    return std::array<Index, 2>{c, d};
}

// The contour point beside the chord's middle S(1/2) (appendix B
// interpolation of u_a and u_b): the root of g on the line from the opposite
// corner whose g has the other sign than g(S(1/2)) — contourPointOnFan of the
// cusp search (ContourCuspSearch.h), which does exactly that root search.
std::optional<MeshVertex> contourPointBeside(const ConsistentMesh& m, Index a, Index b, Index c,
                                             Index d, const ContourCuspOptions& options,
                                             RefinementStats& st) {
    ContourCuspStats stats;
    std::optional<ContourPoint> point = contourPointOnFan(m, c, a, b, 0.5, options, stats);
    if (!point)
        point = contourPointOnFan(m, d, b, a, 0.5, options, stats);
    if (!point || !point->converged) {
        ++st.missed; // no common chart, no sign change towards either corner, or unconverged
        return std::nullopt;
    }
    return m.evaluate(point->preimage);
}

struct ContourRefinementOptions {
    double pixels = 0.5; // contour-refinement-pixels (0: off)
    int maxDepth = 3;    // contour-refinement-depth
    double rootTolerance = 0.0;
    int rootIterations = 100;
};

// The root search's settings are contour insertion's (§6.2 e), read through
// its own options, the bound its post-condition checks.
ContourRefinementOptions contourRefinementOptions(const ParameterSet& p) {
    const ContourRootOptions roots = ContourRootOptions::read(p);
    return {p.getDouble("contour-refinement-pixels"), p.getInt("contour-refinement-depth"),
            roots.tolerance, roots.maxIterations};
}

void runContourRefinement(const PhaseContext& ctx, Snapshot& s) {
    const ContourRefinementOptions o = contourRefinementOptions(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const double pixels = o.pixels;
    const int maxDepth = o.maxDepth;
    // As contour insertion (§6.2 e): half the checked |g| bound, which is
    // relative to the diagonal after the phase.
    const double tol = 0.5 * o.rootTolerance * sceneScale(m);
    ContourCuspOptions options;
    options.gTolerance = tol;
    options.maxRootIterations = o.rootIterations;
    RefinementStats st;
    const Camera& camera = m.camera();
    struct Item {
        Index a, b;
        int depth;
    };
    std::deque<Item> work;
    for (const auto& [a, b] : m.edges())
        if (contourEdgeCorners(m, a, b))
            work.push_back({a, b, 0});
    LocalEdit before(m), after(m);
    while (pixels > 0.0 && !work.empty()) {
        ctx.checkCancelled();
        const Item item = work.front();
        work.pop_front();
        const auto corners = contourEdgeCorners(m, item.a, item.b);
        if (!corners)
            continue;
        const auto [c, d] = *corners;
        std::optional<MeshVertex> root = contourPointBeside(m, item.a, item.b, c, d, options, st);
        if (!root)
            continue;
        ++st.measured;
        const double distance = pixelDistanceToSegment(
            camera.project(root->position).pixel, camera.project(m.vertex(item.a).position).pixel,
            camera.project(m.vertex(item.b).position).pixel);
        if (item.depth == 0)
            st.largestBefore = std::max(st.largestBefore, distance);
        const auto keep = [&] {
            st.largestAfter = std::max(st.largestAfter, distance);
        };
        if (distance <= pixels) {
            keep();
            continue;
        }
        st.farther += item.depth == 0;
        if (item.depth >= maxDepth) {
            ++st.depthLimited;
            keep();
            continue;
        }
        root->label = VertexLabel::Contour;
        root->provenance = Provenance::Inserted;
        root->phase = phase;
        before.clear();
        before.addFaces({m.faceOfHalfedge(item.a, item.b), m.faceOfHalfedge(item.b, item.a)});
        after.clear();
        const Index r = after.addVertex(*root);
        after.addFace({item.a, r, c});
        after.addFace({r, item.b, c});
        after.addFace({item.b, r, d});
        after.addFace({r, item.a, d});
        if (after.inconsistent() > before.inconsistent() || !after.labelsValid() ||
            !after.parameterValid() || after.turnedOver() > before.turnedOver()) {
            ++st.rejected;
            keep();
            continue;
        }
        const Index v = m.splitEdge(item.a, item.b, *root, phase);
        ++st.split;
        work.push_back({item.a, v, item.depth + 1});
        work.push_back({v, item.b, item.depth + 1});
    }
    // The C vertices added give the discs at a cusp's radial end new
    // outlines: the next phase (contour-refinement-retriangulation)
    // searches them again.
    publish(s, m);
    s.setCounter(counters::kContourEdgesMeasured, static_cast<double>(st.measured));
    s.setCounter(counters::kContourEdgesFarther, static_cast<double>(st.farther));
    s.setCounter(counters::kContourEdgesSplit, static_cast<double>(st.split));
    s.setCounter(counters::kContourSplitsRejected, static_cast<double>(st.rejected));
    s.setCounter(counters::kEdgesLeftAtDepth, static_cast<double>(st.depthLimited));
    s.setCounter(counters::kEdgesWithoutContourPoint, static_cast<double>(st.missed));
    s.setCounter(counters::kLargestChordDistanceBefore, st.largestBefore);
    s.setCounter(counters::kLargestChordDistanceAfter, st.largestAfter);
    if (pixels > 0.0 && st.largestAfter > pixels)
        s.notes.push_back("contour refinement: some contour edges still stray up to " +
                          std::to_string(st.largestAfter) +
                          " px from the contour (their split was rejected or hit "
                          "contour-refinement-depth)");
}

std::vector<InvariantCheck> checkContourRefinement(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, false);
}

} // namespace

void addContourRefinementPhase(Method& m) {
    m.parameters.push_back(
        {"contour-refinement-pixels",
         "Contour refinement: pixels",
         "Not in the paper: a contour edge whose chord passes farther than this many "
         "pixels from the contour beside its middle is split at a root of g there (as "
         "§6.2 e splits FB edges), when the new faces are no less consistent and nothing "
         "folds. 0: off.",
         ParameterType::Double,
         0.5,
         0.0,
         1000.0,
         {}});
    m.parameters.push_back(
        {"contour-refinement-depth",
         "Contour refinement: depth",
         "With contour-refinement-pixels above 0 (not in the paper): how many times a "
         "contour edge may be halved.",
         ParameterType::Int,
         3,
         0,
         20,
         {}});
    m.addPhase(
        {"contour-refinement",
         "Not in the paper: contour edges that stray more than contour-refinement-pixels from "
         "the smooth contour are split at a root of g beside their middle (as §6.2 e splits an "
         "FB edge), up to contour-refinement-depth times, each split kept only when it makes "
         "no face inconsistent, folds nothing and keeps every VBO defined.",
         runContourRefinement, checkContourRefinement});
}

} // namespace contour::consistent
