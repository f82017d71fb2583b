// The "simplification" phase: Bénard, Hertzmann & Kass 2014 §9 on the
// visibility phase's view graph. A stylistic step, off by default. It works
// on a copy of the graph, so the previous snapshot keeps the unsimplified
// one (reversible), and it only sets ViewChain::simplifiedAway.
#include "visibility/SimplificationPhase.h"

#include "visibility/TopologicalSimplification.h"

#include <cmath>
#include <memory>
#include <sstream>

namespace contour {

namespace {

constexpr const char* kSimplify = "simplify";
constexpr const char* kThreshold = "simplify-threshold";

// The phase's parameters, read once per run (and by its post-conditions).
struct SimplificationOptions {
    bool enabled = false;   // simplify
    double threshold = 0.0; // simplify-threshold, pixels
    static SimplificationOptions read(const ParameterSet& p) {
        SimplificationOptions o;
        o.enabled = p.getBool(kSimplify);
        o.threshold = p.getDouble(kThreshold);
        return o;
    }
};

void runSimplification(const PhaseContext& ctx, Snapshot& s) {
    const SimplificationOptions options = SimplificationOptions::read(ctx.parameters);
    if (!s.viewGraph) {
        s.notes.push_back("simplification: no view graph (the visibility phase is off or "
                          "missing); nothing to simplify");
        return;
    }
    if (!options.enabled) {
        s.notes.push_back("simplification is off (--simplify to turn it on): the view graph "
                          "is passed through unchanged");
        s.setCounter(counters::kChainsHiddenBySimplification, 0.0);
        return;
    }
    const double threshold = options.threshold;
    auto graph = std::make_shared<ViewGraph>(*s.viewGraph);
    const double before = graph->visibleLengthPixels();
    const SimplificationResult result = simplifyViewGraph(*graph, threshold);
    const double after = graph->visibleLengthPixels();
    s.setCounter(counters::kChainsHiddenBySimplification, result.chainsHidden);
    s.setCounter(counters::kSimplificationIterations, result.iterations);
    s.setCounter(counters::kVisibleLengthBeforeSimplificationPx, before);
    s.setCounter(counters::kVisibleLengthAfterSimplificationPx, after);
    std::ostringstream note;
    note << "simplification (Bénard 2014 §9, threshold " << threshold << " px) hid "
         << result.chainsHidden << " chains (" << before - after << " px of " << before
         << " px visible) in " << result.iterations << " passes";
    s.notes.push_back(note.str());
    s.viewGraph = std::move(graph);
}

std::vector<InvariantCheck> checkSimplification(const PhaseContext& ctx, const Snapshot& s) {
    InvariantCheck longHidden{"no chain longer than the threshold is simplified away", 0, {}};
    InvariantCheck fixedPoint{
        "simplification is at its fixed point (a second run hides nothing)", 0, {}};
    const SimplificationOptions options = SimplificationOptions::read(ctx.parameters);
    if (!s.viewGraph || !options.enabled)
        return {longHidden, fixedPoint};
    const double threshold = options.threshold;
    const ViewGraph& g = *s.viewGraph;
    for (size_t c = 0; c < g.chains.size(); ++c)
        if (g.chains[c].simplifiedAway && !(g.chains[c].lengthPixels < threshold)) {
            if (longHidden.violations++ == 0)
                longHidden.firstExample = "chain " + std::to_string(c);
        }
    ViewGraph again = g;
    const SimplificationResult second = simplifyViewGraph(again, threshold);
    fixedPoint.violations = second.chainsHidden;
    if (second.chainsHidden > 0)
        fixedPoint.firstExample =
            std::to_string(second.chainsHidden) + " more chains hidden by a second run";
    return {longHidden, fixedPoint};
}

} // namespace

void addSimplificationPhase(Method& m) {
    m.parameters.push_back({kSimplify,
                            "Simplify topology",
                            "Hide small visible chains that clutter the drawing: spurs ending in "
                            "a dead-end, specks, small loops and chains drawn over by another "
                            "(Bénard 2014 §9, Fig. 24). A stylistic step; the unsimplified graph "
                            "stays in the visibility snapshot.",
                            ParameterType::Bool,
                            false,
                            0,
                            0,
                            {}});
    m.parameters.push_back({kThreshold,
                            "Simplification threshold (px)",
                            "Only runs of visible chains shorter than this image length are "
                            "candidates for simplification (Bénard 2014 §9; the paper used "
                            "10–20 px).",
                            ParameterType::Double,
                            15.0,
                            0.0,
                            1000.0,
                            {}});
    m.addPhase({"simplification",
                "Topological simplification of the view graph (Bénard 2014 §9): "
                "candidate runs of visible chains below the threshold are hidden when "
                "they join a junction to a dead-end, two dead-ends, a node to itself, or "
                "are overlapped in 2D by another chain; repeated to a fixed point.",
                runSimplification, checkSimplification});
}

} // namespace contour
