// Vertex wiggling in parameter space (Bénard 2014 §6.4).
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/numerics/Bisection.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "contours/consistent/phases/OptimizationPhaseSupport.h"
#include "contours/consistent/phases/RadialEdgeInsertion.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/RadialTriangles.h"
#include "contours/consistent/predicates/Shiftability.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vector>

namespace contour::consistent {

namespace {

// "Each face in the vertex one-ring is regularly sampled at 100 locations":
// the interior points of the regular triangular lattice of step 1/n, n the
// smallest with at least `samples` of them ((n-1)(n-2)/2: 100 -> n = 16,
// 105 points). Face v-a-b is walked by rows parallel to a-b: row L (2 <= L
// < n) joins A = v + (L/n)(a - v) to B = v + (L/n)(b - v) and holds the L - 1
// points A + (j/L)(B - A), so every point costs one interpolation.
struct Lattice {
    int n = 0;
    int points() const { return (n - 1) * (n - 2) / 2; }
};

Lattice lattice(int samples) {
    Lattice l{3};
    while (l.points() < samples)
        ++l.n;
    return l;
}

bool onTaggedEdge(const ConsistentMesh& m, Index v) {
    for (Index w : m.neighbours(v))
        if (m.edgeTag(v, w) != kNoTag)
            return true;
    return false;
}

// The C vertex p when v's only tagged edge is one radial edge p-v: v may
// then move along p's radial plane (it stays the far end of a radial edge,
// §6.3 g), else kInvalidIndex.
Index radialPartner(const ConsistentMesh& m, Index v) {
    Index p = kInvalidIndex;
    for (Index w : m.neighbours(v)) {
        const int tag = m.edgeTag(v, w);
        if (tag == kNoTag)
            continue;
        if (tag != kRadialEdge || p != kInvalidIndex || m.vertex(w).label != VertexLabel::Contour)
            return kInvalidIndex;
        p = w;
    }
    return p;
}

// The C vertex at the other end of each radial edge at v (v is their far
// end), or nullopt when v also has a tag that is not radial.
std::optional<std::vector<Index>> radialPartners(const ConsistentMesh& m, Index v) {
    std::vector<Index> out;
    for (Index w : m.neighbours(v)) {
        const int tag = m.edgeTag(v, w);
        if (tag == kNoTag)
            continue;
        if (tag != kRadialEdge || m.vertex(w).label != VertexLabel::Contour)
            return std::nullopt;
        out.push_back(w);
    }
    return out;
}

struct WiggleStats {
    long long skipped = 0, cancelledSamples = 0, rejected = 0, radialMoved = 0,
              radialUnconverged = 0, radialFreed = 0, radialTagsDropped = 0;
};

// The zero of h_p on the parameter segment a-b (h_p(a), h_p(b) of opposite
// signs), by the Illinois variant of regula falsi, to `tolerance` (a
// distance); nullopt when a chart is missing or it does not converge.
std::optional<MeshVertex> radialRoot(const ConsistentMesh& m, const MeshVertex& p,
                                     const Preimage& a, double ha, const Preimage& b, double hb,
                                     double tolerance, int maxIterations) {
    BisectionOptions search;
    search.step = BisectionStep::FalsePosition;
    search.sign = BisectionSign::Negative;
    search.maxIterations = maxIterations;
    search.tolerance = tolerance;
    BisectionResult<MeshVertex> r = bisect(
        [&](double along) -> std::optional<MeshVertex> {
            const std::optional<Preimage> u = m.interpolate(a, b, along);
            if (!u)
                return std::nullopt;
            // The radial curvature of the chosen sample is evaluated by wiggle().
            return m.evaluateWithoutCurvature(*u);
        },
        [&](const MeshVertex& x) { return radialPlaneDistance(m.camera(), p, x.position); },
        {0.0, 1.0, ha, hb}, search);
    if (r.outcome != BisectionOutcome::Converged)
        return std::nullopt;
    return std::move(r.last);
}

struct WiggleSettings {
    Lattice grid;
    double radialTolerance = 0.0;
    int radialIterations = 100;
    bool freeRadialEnds = false; // wiggle-radial-ends
};

// The radial edges p-v that v at `position` no longer ends (|h_p| above the
// tolerance): they lose their tag when v moves there.
std::vector<Index> droppedRadialEdges(const ConsistentMesh& m, const std::vector<Index>& partners,
                                      const Vec3& position, double tolerance) {
    std::vector<Index> out;
    for (Index p : partners)
        if (!(std::abs(radialPlaneDistance(m.camera(), m.vertex(p), position)) <= tolerance))
            out.push_back(p);
    return out;
}

// Dropping those tags keeps the post-condition of Fig. 18d-e: a cusp that
// loses a radial edge keeps another one (or has valence 4 again).
bool cuspsKeepRadialEdge(const ConsistentMesh& m, Index v, const std::vector<Index>& dropped) {
    for (Index p : dropped) {
        if (!m.vertex(p).cusp)
            continue;
        bool other = false;
        for (Index w : m.neighbours(p))
            other = other || (w != v && (m.edgeTag(p, w) & kRadialEdge) &&
                              std::find(dropped.begin(), dropped.end(), w) == dropped.end());
        if (!other && m.neighbours(p).size() != 4)
            return false;
    }
    return true;
}

// Moves v to the sample of its one-ring that leaves the fewest inconsistent
// faces around it (strictly fewer than now), ties to the largest minimum
// Bank-Smith quality of the ring. C vertices stay (they sit on g = 0, and
// the simplest way to keep them there is not to move them), as do
// boundary vertices and endpoints of cusp edges or of several radial
// edges. The far end r of one radial edge p-r moves only along p's radial
// plane (§6.3: r stays on it; not in the paper, whose §6.4 wiggle does not
// say how radial edges are kept): its candidates are the zeros of h_p on
// the lattice rows, and it keeps its label. Candidates must keep every VBO
// defined, make no degenerate CC edge, turn no face over in 3D and satisfy
// appendix C (shiftable(): no parameter fold, no CCC, no "X", interpolation
// possible).
//
// `freeRadial` (wiggle-radial-ends, not in the paper): v is the far end of
// one or more radial edges and its constrained move above found nothing; it
// now samples its whole one-ring like any F or B vertex, and the radial
// edges whose plane it leaves lose their tag (those faces are no longer
// radial triangles; a cusp keeps at least one radial edge or valence 4).
bool wiggle(ConsistentMesh& m, Index v, const WiggleSettings& set, int phase, WiggleStats& st,
            bool freeRadial = false) {
    const MeshVertex current = m.vertex(v);
    std::vector<Index> partners;
    if (freeRadial) {
        const std::optional<std::vector<Index>> found = radialPartners(m, v);
        if (!found || found->empty() || current.label == VertexLabel::Contour || current.cusp ||
            m.isBoundaryVertex(v))
            return false;
        partners = *found;
    }
    const Index partner = freeRadial ? kInvalidIndex : radialPartner(m, v);
    if (current.label == VertexLabel::Contour || current.cusp || m.isBoundaryVertex(v) ||
        (!freeRadial && onTaggedEdge(m, v) && partner == kInvalidIndex)) {
        ++st.skipped;
        return false;
    }
    const std::vector<Index> star = m.vertexFaces(v);
    LocalEdit edit(m);
    edit.addFaces(star);
    const LocalScore now = edit.score();
    if (now.inconsistent == 0)
        return false;
    std::vector<char> turned(star.size());
    for (size_t i = 0; i < star.size(); ++i)
        turned[i] = edit.turnedOver(edit.faces()[i]);
    const std::vector<Index> ring = m.neighbours(v);
    std::optional<MeshVertex> best;
    LocalScore bestScore;
    // A sample's score depends on the sample alone (computed in parallel
    // for the lattice, each task with its own LocalEdit); the choice below
    // takes them in order, so it is the serial one.
    struct Scored {
        bool eligible = false;
        int count = 0;        // inconsistent faces around v after the move
        double quality = 0.0; // their minimum quality, when count improves
    };
    auto scoreOf = [&](LocalEdit& e, const MeshVertex& x) {
        Scored r;
        if (x.label == VertexLabel::Contour)
            return r;
        if (partner != kInvalidIndex && x.label != current.label)
            return r;
        // An FB edge would make its faces' VBO undefined.
        if (std::any_of(ring.begin(), ring.end(), [&](Index w) {
                return static_cast<int>(m.vertex(w).label) * static_cast<int>(x.label) < 0;
            }))
            return r;
        e.moveVertex(v, x);
        r.eligible = true;
        r.count = e.inconsistent();
        if (r.count < now.inconsistent)
            r.quality = e.minQuality();
        return r;
    };
    auto decide = [&](MeshVertex x, const Scored& r) {
        if (!r.eligible)
            return;
        const int count = r.count;
        if (count >= now.inconsistent || (best && count > bestScore.inconsistent))
            return;
        const LocalScore trial{count, r.quality};
        if (best && !betterScore(trial, bestScore))
            return;
        x.provenance = Provenance::Wiggled;
        x.phase = phase;
        edit.moveVertex(v, x);
        bool ok = edit.labelsValid();
        for (size_t i = 0; ok && i < star.size(); ++i)
            ok = turned[i] || !edit.turnedOver(edit.faces()[i]);
        ok = ok && shiftable(m, v, x.preimage, x.label);
        ok = ok && (!freeRadial ||
                    cuspsKeepRadialEdge(
                        m, v, droppedRadialEdges(m, partners, x.position, set.radialTolerance)));
        if (!ok) {
            ++st.rejected;
            return;
        }
        best = x;
        bestScore = trial;
    };
    auto consider = [&](const MeshVertex& x) {
        decide(x, scoreOf(edit, x));
    };
    const MeshVertex* p = partner != kInvalidIndex ? &m.vertex(partner) : nullptr;
    const Lattice& grid = set.grid;
    // Lattice samples in their fixed order (face, row, position in the row):
    // preimages first, one chart search per row; then evaluated in parallel
    // without the radial curvature (only f, n and g decide); then considered
    // one by one in that order, so the choice does not depend on the thread
    // count.
    std::vector<Preimage> samples;
    std::vector<double> rowT, levels;
    std::vector<std::optional<Preimage>> endsA, endsB;
    std::vector<std::optional<Preimage>> rowU;
    for (const Triangle& face : edit.faces()) {
        int k = 0;
        while (face[k] != v)
            ++k;
        const Preimage pv = current.preimage, pa = m.vertex(face[(k + 1) % 3]).preimage,
                       pb = m.vertex(face[(k + 2) % 3]).preimage;
        // The rows' ends on v-a and v-b, one chart search per edge.
        levels.resize(static_cast<size_t>(std::max(grid.n - 2, 0)));
        for (int row = 2; row < grid.n; ++row)
            levels[static_cast<size_t>(row - 2)] = static_cast<double>(row) / grid.n;
        endsA.resize(levels.size());
        endsB.resize(levels.size());
        m.interpolate(pv, pa, levels, endsA);
        m.interpolate(pv, pb, levels, endsB);
        for (int row = 2; row < grid.n; ++row) {
            const std::optional<Preimage>& ra = endsA[static_cast<size_t>(row - 2)];
            const std::optional<Preimage>& rb = endsB[static_cast<size_t>(row - 2)];
            if (p) {
                // The radial curve crosses this row where h_p changes sign.
                if (!ra || !rb) {
                    ++st.cancelledSamples;
                    continue;
                }
                const double ha =
                    radialPlaneDistance(m.camera(), *p, m.evaluateWithoutCurvature(*ra).position);
                const double hb =
                    radialPlaneDistance(m.camera(), *p, m.evaluateWithoutCurvature(*rb).position);
                if (!((ha < 0.0 && hb > 0.0) || (ha > 0.0 && hb < 0.0)))
                    continue;
                const std::optional<MeshVertex> x =
                    radialRoot(m, *p, *ra, ha, *rb, hb, set.radialTolerance, set.radialIterations);
                if (!x) {
                    ++st.radialUnconverged;
                    continue;
                }
                consider(*x);
                continue;
            }
            // Appendix B charts; a missing chart drops the sample.
            if (!ra || !rb) {
                st.cancelledSamples += row - 1;
                continue;
            }
            rowT.resize(static_cast<size_t>(row - 1));
            rowU.resize(rowT.size());
            for (int j = 1; j < row; ++j)
                rowT[static_cast<size_t>(j - 1)] = static_cast<double>(j) / row;
            m.interpolate(*ra, *rb, rowT, rowU);
            for (const std::optional<Preimage>& u : rowU) {
                if (u)
                    samples.push_back(*u);
                else
                    ++st.cancelledSamples;
            }
        }
    }
    if (!samples.empty()) {
        std::vector<MeshVertex> evaluated(samples.size());
        std::vector<Scored> scored(samples.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 16),
                          [&](const tbb::blocked_range<size_t>& range) {
                              LocalEdit local(m);
                              local.addFaces(star);
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  evaluated[i] = m.evaluateWithoutCurvature(samples[i]);
                                  scored[i] = scoreOf(local, evaluated[i]);
                              }
                          });
        for (size_t i = 0; i < samples.size(); ++i)
            decide(evaluated[i], scored[i]);
    }
    if (!best)
        return false;
    // The chosen sample's full record (with its radial curvature).
    MeshVertex chosen = m.evaluate(best->preimage);
    chosen.provenance = Provenance::Wiggled;
    chosen.phase = phase;
    if (freeRadial) {
        for (Index q : droppedRadialEdges(m, partners, chosen.position, set.radialTolerance)) {
            m.setEdgeTag(v, q, m.edgeTag(v, q) & ~kRadialEdge);
            ++st.radialTagsDropped;
        }
        ++st.radialFreed;
    }
    m.setVertex(v, chosen, phase);
    st.radialMoved += p != nullptr;
    return true;
}

// The phase's parameters, read once per run.
struct ParameterWiggleOptions {
    int samples = 0;             // wiggle-samples
    bool freeRadialEnds = false; // wiggle-radial-ends
    int maxSweeps = 0;           // wiggle-max-sweeps
    RadialEdgeOptions radial;
    static ParameterWiggleOptions read(const ParameterSet& p) {
        ParameterWiggleOptions o;
        o.samples = p.getInt("wiggle-samples");
        o.freeRadialEnds = p.getBool("wiggle-radial-ends");
        o.maxSweeps = p.getInt("wiggle-max-sweeps");
        o.radial = RadialEdgeOptions::read(p);
        return o;
    }
};

void runParameterWiggle(const PhaseContext& ctx, Snapshot& s) {
    const ParameterWiggleOptions options = ParameterWiggleOptions::read(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    WiggleSettings set;
    set.grid = lattice(options.samples);
    set.radialTolerance = options.radial.rootTolerance * sceneScale(m);
    set.radialIterations = options.radial.rootMaxIterations;
    set.freeRadialEnds = options.freeRadialEnds;
    const int maxSweeps = options.maxSweeps;
    OptimizationTally tally;
    WiggleStats st;
    sweepInconsistent(ctx, m, maxSweeps, true, tally, [&](Index v) {
        return wiggle(m, v, set, phase, st) ||
               (set.freeRadialEnds && wiggle(m, v, set, phase, st, true));
    });
    publish(s, m);
    publishTally(s, tally, counters::kVerticesTried, counters::kVerticesAccepted,
                 "wiggle-max-sweeps");
    s.setCounter(counters::kSamplesPerFace, static_cast<double>(set.grid.points()));
    s.setCounter(counters::kRadialEdgeEndsMovedAlongTheirRadialPlane,
                 static_cast<double>(st.radialMoved));
    s.setCounter(counters::kRadialPlaneRootsWithoutAChartOrUnconverged,
                 static_cast<double>(st.radialUnconverged));
    s.setCounter(counters::kVerticesSkippedCBoundaryCuspEdgeTwoRadialEdges,
                 static_cast<double>(st.skipped));
    s.setCounter(counters::kSamplesRejectedFoldAppendixCDegenerateEdge,
                 static_cast<double>(st.rejected));
    s.setCounter(counters::kSamplesWithoutAChart, static_cast<double>(st.cancelledSamples));
    s.setCounter(counters::kRadialEdgeEndsMovedOffTheirRadialPlaneWiggleRadialEnds,
                 static_cast<double>(st.radialFreed));
    s.setCounter(counters::kRadialEdgeTagsDroppedWiggleRadialEnds,
                 static_cast<double>(st.radialTagsDropped));
}

std::vector<InvariantCheck> checkParameterWiggle(const PhaseContext& ctx, const Snapshot& s) {
    return optimizationChecks(ctx, s, true);
}

} // namespace

void addParameterWigglePhase(Method& m) {
    m.parameters.push_back({"wiggle-samples",
                            "Wiggle: samples per face",
                            "Samples of every one-ring face in parameter space when wiggling a "
                            "vertex (§6.4: 100): the interior points of the smallest regular "
                            "triangular lattice with at least this many.",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.parameters.push_back(
        {"wiggle-max-sweeps",
         "Wiggle: sweeps",
         "Largest number of sweeps over the vertices of inconsistent faces (§6.4: "
         "\"until no further improvements can be made\").",
         ParameterType::Int,
         100,
         1,
         10000,
         {}});
    m.parameters.push_back(
        {"wiggle-radial-ends",
         "Wiggle: free radial ends",
         "§6.4 does not say how the wiggle treats radial edges. Off: a single radial "
         "edge's far end stays on its radial plane, the end of two never moves. On (not "
         "in the paper): failing that, the end samples its whole one-ring and the radial "
         "edges it leaves lose their tag.",
         ParameterType::Bool,
         false,
         0,
         0,
         {}});
    m.addPhase(
        {"parameter-wiggle",
         "§6.4 Vertex Wiggling in Parameter Space: every F or B vertex of an inconsistent "
         "face moves to the sample of its one-ring faces (wiggle-samples each) that leaves the "
         "fewest inconsistent faces around it, ties to the best minimum Bank-Smith quality; no "
         "fold, appendix C respected; sweeps until nothing improves. The far end of a single "
         "radial edge p-r moves only to the zeros of h_p on the sample rows (stays on p's "
         "radial plane and on its side; not in the paper).",
         runParameterWiggle, checkParameterWiggle});
}

} // namespace contour::consistent
