// Vertex wiggling in parameter space (Bénard 2014 §6.4; notes §2.4.3).
#include "contours/consistent/ConsistentPhaseSupport.h"
#include "contours/consistent/ConsistentPhases.h"
#include "contours/consistent/LocalEdit.h"
#include "contours/consistent/OptimizationPhaseSupport.h"
#include "contours/consistent/Shiftability.h"

#include <algorithm>

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

struct WiggleStats {
    long long skipped = 0, cancelledSamples = 0, rejected = 0;
};

// Moves v to the sample of its one-ring that leaves the fewest inconsistent
// faces around it (strictly fewer than now), ties to the largest minimum
// Bank-Smith quality of the ring. C vertices stay (they sit on g = 0, and
// the simplest way to keep them there is not to move them), as do
// boundary vertices and endpoints of radial or cusp edges (moving them would
// take them off the radial plane the edge was built on, §6.3). Candidates
// must keep every VBO defined, make no degenerate CC edge, turn no face over
// in 3D and satisfy appendix C (shiftable(): no parameter fold, no CCC, no
// "X", interpolation possible).
bool wiggle(ConsistentMesh& m, Index v, const Lattice& grid, int phase, WiggleStats& st) {
    const MeshVertex current = m.vertex(v);
    if (current.label == VertexLabel::Contour || current.cusp || m.isBoundaryVertex(v) ||
        onTaggedEdge(m, v)) {
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
    for (const Triangle& face : edit.faces()) {
        int k = 0;
        while (face[k] != v)
            ++k;
        const Preimage pv = current.preimage, pa = m.vertex(face[(k + 1) % 3]).preimage,
                       pb = m.vertex(face[(k + 2) % 3]).preimage;
        for (int row = 2; row < grid.n; ++row) {
            const double level = static_cast<double>(row) / grid.n;
            const std::optional<Preimage> ra = m.interpolate(pv, pa, level);
            const std::optional<Preimage> rb = m.interpolate(pv, pb, level);
            for (int j = 1; j < row; ++j) {
                // Appendix B charts; a missing chart drops the sample.
                const std::optional<Preimage> p =
                    ra && rb ? m.interpolate(*ra, *rb, static_cast<double>(j) / row)
                             : std::optional<Preimage>();
                if (!p) {
                    ++st.cancelledSamples;
                    continue;
                }
                MeshVertex x = m.evaluate(*p);
                if (x.label == VertexLabel::Contour)
                    continue;
                // An FB edge would make its faces' VBO undefined.
                if (std::any_of(ring.begin(), ring.end(), [&](Index w) {
                        return static_cast<int>(m.vertex(w).label) * static_cast<int>(x.label) < 0;
                    }))
                    continue;
                x.provenance = Provenance::Wiggled;
                x.phase = phase;
                edit.moveVertex(v, x);
                const int count = edit.inconsistent();
                if (count >= now.inconsistent || (best && count > bestScore.inconsistent))
                    continue;
                const LocalScore trial{count, edit.minQuality()};
                if (best && !betterScore(trial, bestScore))
                    continue;
                bool ok = edit.labelsValid();
                for (size_t i = 0; ok && i < star.size(); ++i)
                    ok = turned[i] || !edit.turnedOver(edit.faces()[i]);
                ok = ok && shiftable(m, v, x.preimage, x.label);
                if (!ok) {
                    ++st.rejected;
                    continue;
                }
                best = x;
                bestScore = trial;
            }
        }
    }
    if (!best)
        return false;
    m.setVertex(v, *best, phase);
    return true;
}

void runParameterWiggle(const PhaseContext& ctx, Snapshot& s) {
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const Lattice grid = lattice(ctx.parameters.getInt("wiggle-samples"));
    const int maxSweeps = ctx.parameters.getInt("wiggle-max-sweeps");
    OptimizationTally tally;
    WiggleStats st;
    std::vector<Index> faces = inconsistentFaces(m);
    tally.before = static_cast<long long>(faces.size());
    for (; tally.sweeps < maxSweeps && !faces.empty();) {
        ++tally.sweeps;
        long long accepted = 0;
        for (Index v : verticesOf(m, faces)) {
            ctx.checkCancelled();
            ++tally.tried;
            accepted += wiggle(m, v, grid, phase, st);
        }
        tally.accepted += accepted;
        if (accepted == 0)
            break;
        faces = inconsistentFaces(m);
        tally.sweepLimitHit = tally.sweeps == maxSweeps && !faces.empty();
    }
    publish(s, m);
    publishTally(s, tally, "vertices", "wiggle-max-sweeps");
    s.setCounter("samples per face", static_cast<double>(grid.points()));
    s.setCounter("vertices skipped (C, boundary, radial or cusp edge)",
                 static_cast<double>(st.skipped));
    s.setCounter("samples rejected (fold, appendix C, degenerate edge)",
                 static_cast<double>(st.rejected));
    s.setCounter("samples without a chart", static_cast<double>(st.cancelledSamples));
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
    m.parameters.push_back({"wiggle-max-sweeps",
                            "Wiggle: sweeps",
                            "Largest number of sweeps over the vertices of inconsistent faces "
                            "(§6.4: \"until no further improvements can be made\").",
                            ParameterType::Int,
                            100,
                            1,
                            10000,
                            {}});
    m.phases.push_back(
        {"parameter-wiggle",
         "§6.4 Vertex Wiggling in Parameter Space: every F or B vertex of an inconsistent "
         "face moves to the sample of its one-ring faces (wiggle-samples each) that leaves the "
         "fewest inconsistent faces around it, ties to the best minimum Bank-Smith quality; no "
         "fold, appendix C respected; sweeps until nothing improves.",
         runParameterWiggle, checkParameterWiggle});
}

} // namespace contour::consistent
