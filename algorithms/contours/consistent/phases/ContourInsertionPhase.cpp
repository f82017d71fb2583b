// Contour vertex insertion (Bénard 2014 §6.2 e-f, Fig. 15d-f).
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/ContourInsertion.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FoldTest.h"
#include "contours/consistent/predicates/Shiftability.h"

#include <cmath>

namespace contour::consistent {

namespace {

bool touchesCuspEdge(const ConsistentMesh& m, Index v) {
    for (Index w : m.neighbours(v))
        if (m.edgeTag(v, w) & kCuspEdge)
            return true;
    return false;
}

// Snapping w onto the root joins the root to all of w's neighbours. When one
// of w's faces would need a regular-corner chart (appendix B, one-ring of a
// domain vertex) the new edges cut across that corner: straight contour
// edges that span two domain faces diagonally and stray from the true
// contour (1-1.5 px on the bumpy torus). Splitting the FB edge instead keeps
// the contour as fine as without corner charts; the charts still serve the
// later moves.
bool snapStaysInEdgeCharts(const ConsistentMesh& m, Index w, const Preimage& root) {
    for (Index f : m.vertexFaces(w)) {
        const Triangle t = rotatedTo(m.face(f), w);
        if (!m.withinEdgeCharts({root, m.vertex(t[1]).preimage, m.vertex(t[2]).preimage}))
            return false;
    }
    return true;
}

// The phase's parameters, read once per run.
struct ContourInsertionOptions {
    ContourRootOptions root;
    double snapFraction = 0.0; // snap-fraction
    bool snapAcrossCorners = true;
    static ContourInsertionOptions read(const ParameterSet& p) {
        ContourInsertionOptions o;
        o.root = ContourRootOptions::read(p);
        o.snapFraction = p.getDouble("snap-fraction");
        // Without corner charts every shiftable snap stays in edge charts.
        o.snapAcrossCorners =
            !ChartOptions::read(p).vertexRings || p.getBool("snap-across-corners");
        return o;
    }
};

// §6.2 (e): bisection of g along every FB edge, snap to a
// shiftable endpoint within `snap-fraction` of the edge length, otherwise
// insert a C vertex splitting both faces (Fig. 16c); repeat until no FB edge
// remains. §6.2 (f), Fig. 18c-d: the FB edges tagged by cusp detection are
// saved for last and always split, never snapped, so the cusp vertex gets
// valence 4; endpoints of cusp edges are never snapped either (the cusp
// edge would lose its sign change).
void runContourInsertion(const PhaseContext& ctx, Snapshot& s) {
    const ContourInsertionOptions options = ContourInsertionOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    // The post-condition checks |g| <= root-tolerance times the diagonal of
    // the mesh *after* the phase, which snapping can shrink (bob_controlmesh
    // view 10: 2.5473 -> 2.5451, and a root at 1.0004 times the checked
    // bound): bisect to half of it.
    const double tol = 0.5 * options.root.tolerance * sceneScale(m);
    const int maxIterations = options.root.maxIterations;
    const double snap = options.snapFraction;
    const bool snapAcrossCorners = options.snapAcrossCorners;
    long long inserted = 0, snapped = 0, cancelled = 0, unconverged = 0, cusps = 0;
    long long snappedAgainstFolds = 0, rootsInAnotherChart = 0, foldingSplits = 0;
    for (const bool cuspStage : {false, true})
        for (bool progress = true; progress;) {
            progress = false;
            for (const auto& [e0, e1] : m.edges()) {
                ctx.checkCancelled();
                if (static_cast<int>(m.vertex(e0).label) * static_cast<int>(m.vertex(e1).label) >=
                        0 ||
                    (m.faceOfHalfedge(e0, e1) == kInvalidIndex &&
                     m.faceOfHalfedge(e1, e0) == kInvalidIndex))
                    continue;
                const bool cuspEdge = (m.edgeTag(e0, e1) & kCuspEdge) != 0;
                if (cuspEdge != cuspStage)
                    continue;
                // x is the F end, y the B end: g(x) > 0 > g(y) along the edge.
                const Index x = m.vertex(e0).label == VertexLabel::Front ? e0 : e1;
                const Index y = x == e0 ? e1 : e0;
                const Preimage px = m.vertex(x).preimage, py = m.vertex(y).preimage;
                // g decides; the radial curvature is evaluated for the root
                // kept, below. g > 0 at x (the bracket's lower end), < 0 at y (its upper end).
                BisectionOptions search;
                search.step = BisectionStep::Midpoint;
                search.sign = BisectionSign::Positive;
                search.best = BisectionBest::FromFirst;
                search.maxIterations = maxIterations;
                search.tolerance = tol;
                const auto rootAlong = [&](const ConsistentMesh::Segment& xy) {
                    return bisect(
                        [&](double along) -> std::optional<MeshVertex> {
                            const std::optional<Preimage> p = xy.at(along);
                            if (!p)
                                return std::nullopt;
                            return m.evaluateWithoutCurvature(*p);
                        },
                        [](const MeshVertex& v) { return v.g; }, {0.0, 1.0, 1.0, -1.0}, search);
                };
                BisectionResult<MeshVertex> r = rootAlong(m.segment(px, py));
                std::optional<MeshVertex> root = r.best;
                bool converged = r.outcome == BisectionOutcome::Converged;
                if (r.outcome == BisectionOutcome::Failed || !root) {
                    ++cancelled; // appendix B: no common chart, insertion cancelled
                    continue;
                }
                unconverged += !converged;
                progress = true;
                // The C vertex a root becomes (the radial curvature included).
                const auto contourVertex = [&](const Preimage& p) {
                    MeshVertex v = m.evaluate(p);
                    v.label = VertexLabel::Contour;
                    v.provenance = Provenance::Inserted;
                    return v;
                };
                root = contourVertex(root->preimage);
                // Snap rule: shift an endpoint onto the root when it is within
                // snap-fraction of the edge length and shiftable (appendix C).
                const double length = (m.vertex(x).position - m.vertex(y).position).norm();
                const auto snapOnto = [&](double fraction) {
                    const double dx = (root->position - m.vertex(x).position).norm();
                    const double dy = (root->position - m.vertex(y).position).norm();
                    for (Index w : dx <= dy ? std::array{x, y} : std::array{y, x}) {
                        const double d = w == x ? dx : dy;
                        if (!cuspEdge && d < fraction * length && !touchesCuspEdge(m, w) &&
                            (snapAcrossCorners || snapStaysInEdgeCharts(m, w, root->preimage)) &&
                            shiftable(m, w, root->preimage, VertexLabel::Contour)) {
                            m.shiftVertex(w, root->preimage, VertexLabel::Contour, phase);
                            ++snapped;
                            return true;
                        }
                    }
                    return false;
                };
                if (snapOnto(snap))
                    continue;
                // Near a domain vertex of valence 3 the root, interpolated
                // in one chart, can lie on the other side of a new edge in
                // the chart the new face is read in (appendix B): a fold.
                // Then the root along the straight segment of another
                // common chart of x and y, if its split folds nothing; else
                // an endpoint shifted onto the root, which keeps every face
                // unfolded (appendix C rule 1) whatever its distance.
                bool keeps = splitKeepsParameterOrientation(m, x, y, root->preimage);
                for (int chart = 0, charts = keeps ? 0 : m.interpolationCharts(px, py);
                     chart < charts && !keeps; ++chart) {
                    const BisectionResult<MeshVertex> other =
                        rootAlong(m.segmentInChart(px, py, chart));
                    if (other.outcome == BisectionOutcome::Failed || !other.best ||
                        !splitKeepsParameterOrientation(m, x, y, other.best->preimage))
                        continue;
                    keeps = true;
                    ++rootsInAnotherChart;
                    unconverged -= !converged;
                    converged = other.outcome == BisectionOutcome::Converged;
                    unconverged += !converged;
                    root = contourVertex(other.best->preimage);
                }
                if (!keeps && snapOnto(1.0)) {
                    ++snappedAgainstFolds;
                    continue;
                }
                foldingSplits += !keeps;
                root->cusp = cuspEdge;
                m.splitEdge(x, y, *root, phase);
                ++(cuspEdge ? cusps : inserted);
            }
        }
    publish(s, m);
    s.setCounter(counters::kInsertedContourVertices, static_cast<double>(inserted));
    s.setCounter(counters::kInsertedCuspVertices, static_cast<double>(cusps));
    s.setCounter(counters::kSnappedVertices, static_cast<double>(snapped));
    s.setCounter(counters::kCancelledInsertions, static_cast<double>(cancelled));
    s.setCounter(counters::kUnconvergedRoots, static_cast<double>(unconverged));
    s.setCounter(counters::kSnapsAgainstFolds, static_cast<double>(snappedAgainstFolds));
    s.setCounter(counters::kRootsInAnotherChart, static_cast<double>(rootsInAnotherChart));
    s.setCounter(counters::kFoldingSplits, static_cast<double>(foldingSplits));
    if (foldingSplits > 0)
        s.notes.push_back(std::to_string(foldingSplits) +
                          " C vertices split an FB edge although a new face is folded in "
                          "parameter space or has no common chart (appendix B), in every "
                          "common chart of the edge's ends, and neither endpoint could be "
                          "shifted onto the root");
    if (unconverged > 0)
        s.notes.push_back(std::to_string(unconverged) +
                          " roots did not reach |g| <= root-tolerance within root-max-iterations "
                          "bisection steps (g jumps along the edge there: a crease); the "
                          "post-condition checks that g changes sign within the tolerance of "
                          "their C vertices");
    if (cancelled > 0)
        s.notes.push_back(std::to_string(cancelled) +
                          " FB edges kept: their endpoints' preimages have no common chart, "
                          "so the insertion was cancelled (appendix B)");
}

std::vector<InvariantCheck> checkContourInsertion(const PhaseContext& ctx, const Snapshot& s) {
    const ConsistentMesh m = reload(ctx, s);
    std::vector<InvariantCheck> out = phaseChecks(ctx, s, m, true);
    return out;
}

} // namespace

ContourRootOptions ContourRootOptions::read(const ParameterSet& p) {
    ContourRootOptions o;
    o.tolerance = p.getDouble("root-tolerance");
    o.maxIterations = p.getInt("root-max-iterations");
    return o;
}

void addContourInsertionPhase(Method& m) {
    m.parameters.push_back(
        {"root-tolerance",
         "Root tolerance",
         "Bisection on FB edges (§6.2 e) stops when |g| is below this times the "
         "bounding-box diagonal; also the bound checked at C vertices. The paper gives "
         "no tolerance.",
         ParameterType::Double,
         1e-10,
         1e-16,
         1e-2,
         {}});
    m.parameters.push_back(
        {"root-max-iterations",
         "Root iterations",
         "Maximum bisection steps per FB edge (§6.2 e; the paper gives no value).",
         ParameterType::Int,
         100,
         1,
         1000,
         {}});
    m.parameters.push_back(
        {"snap-fraction",
         "Snap fraction",
         "A root closer than this fraction of the edge length to an endpoint shifts that "
         "endpoint onto it when shiftable (appendix C) instead of inserting a vertex "
         "(§6.2 e; paper: 0.2).",
         ParameterType::Double,
         0.2,
         0.0,
         0.5,
         {}});
    m.parameters.push_back(
        {"snap-across-corners",
         "Snap across corners",
         "With chart-vertex-rings: may the snap rule (§6.2 e) shift a vertex whose faces "
         "then need a corner chart (appendix B)? On: as the paper allows. Off (default): "
         "the root is inserted by an edge split instead, which keeps the contour closer "
         "to the true one.",
         ParameterType::Bool,
         false,
         0,
         0,
         {}});
    m.addPhase(
        {"contour-insertion",
         "§6.2 e (Fig. 15d-f): bisection root of g on every FB edge; shift a shiftable endpoint "
         "within snap-fraction of the edge length onto it (appendix C), otherwise insert a C "
         "vertex splitting both faces; until no FB edge remains. §6.2 f (Fig. 18c-d): the cusp "
         "edges come last and are always split, giving each cusp a C vertex of valence 4.",
         runContourInsertion, checkContourInsertion});
}

} // namespace contour::consistent
