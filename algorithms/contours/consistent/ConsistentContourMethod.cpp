// Consistent contours (Bénard, Hertzmann & Kass 2014): a per-view triangle
// mesh of the smooth surface whose mesh contour generator should be
// topologically equivalent to the smooth one. The method's parameters and
// phases come from the sub-phase files, in the paper's order (§6).
#include "contours/Methods.h"
#include "contours/common/SurfacePhase.h"
#include "contours/consistent/ConsistentOutputs.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "visibility/SimplificationPhase.h"
#include "visibility/VisibilityPhase.h"

#include <string>

namespace contour {

namespace {

// The parameters every phase reads: the surface and its tolerances.
constexpr const char* kSurfaceGroup = "surface";

} // namespace

Method makeConsistentContourMethod() {
    using namespace consistent;
    Method m;
    m.name = "consistent";
    m.label = "Consistent contours (Bénard et al. 2014)";
    m.description =
        "A per-view triangulation of the smooth surface whose contour generator is meant to be "
        "topologically equivalent to the smooth one (Bénard, Hertzmann & Kass 2014), built by "
        "the sub-phases of §6 in the paper's order, then the contour generator (edges between "
        "F-VBO and B-VBO faces) chained (§8). Inconsistent faces can remain: every phase "
        "counts them and the Overlays toolbar outlines them.";
    m.parameters = {
        {"surface",
         "Smooth surface",
         "The smooth surface whose domain is triangulated (§6.1): Catmull-Clark (the cage "
         "subdivided once), Loop or vertex-normal patches. auto: Catmull-Clark, or Loop for an "
         "all-triangle cage.",
         ParameterType::Choice,
         std::string("auto"),
         0,
         0,
         {"auto", toString(SurfaceKind::CatmullClark), toString(SurfaceKind::Loop),
          toString(SurfaceKind::VertexNormalPatches)},
         kSurfaceGroup},
        {"chart-tolerance",
         "Chart tolerance",
         "How close (in domain parameters) a preimage must be to a domain edge to also "
         "belong to the neighbouring face, and how far outside a face an interpolated "
         "preimage may land (appendix B; the paper gives no value).",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-3,
         {},
         kSurfaceGroup},
        {"chart-vertex-rings",
         "Charts around regular corners",
         "Charts for preimage interpolation (appendix B). On: a domain vertex's "
         "one-ring, as in the paper, so two faces meeting at a regular corner share a "
         "chart. Off (default): only a face and its edge neighbours share one; moves "
         "that need a corner chart are cancelled.",
         ParameterType::Bool,
         false,
         0,
         0,
         {},
         kSurfaceGroup},
        {"embedding-tolerance",
         "Embedding tolerance",
         "Tolerance of the post-condition pos = f(u) (§6.1), times the bounding-box "
         "diagonal.",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-2,
         {},
         kSurfaceGroup},
    };
    addInitializationPhase(m);
    addCuspDetectionPhase(m);
    addCuspRefinementPhase(m);
    addContourInsertionPhase(m);
    addRadialEdgeInsertionPhase(m);
    addRadialFlipPhase(m);
    addRadialExtensionPhase(m);
    addOptimizationFlipPhase(m);
    addParameterWigglePhase(m);
    addEdgeSplitPhase(m);
    addVertexRemovalPhase(m);
    addPatchSearchPhase(m);
    addNormalWigglePhase(m);
    addCuspEndPushPhase(m);
    addCuspEndRetriangulationPhase(m);
    addContourRefinementPhase(m);
    addContourRefinementRetriangulationPhase(m);
    // Decided after the last phase so far, re-runs from cusp-refinement.
    addCuspRetryBranch(m);
    addChainingPhase(m);
    addVisibilityPhase(m, VisibilityFlavor::Consistent);
    addSimplificationPhase(m);
    // Bénard 2014 as written: every parameter whose help says "not in the
    // paper" at its off value, and the paper's numbers where it gives one;
    // the parameters it gives no value for keep their defaults.
    m.presets = {
        defaultPreset(),
        {"paper",
         "Bénard 2014 as written: every extension off, the paper's values where it gives one "
         "(§6.1-§6.4, appendices B and C, footnote 3), the defaults elsewhere.",
         {
             // Appendix B: charts of a domain vertex's one-ring; appendix C
             // allows any shift that keeps interpolation possible.
             {"chart-vertex-rings", true},
             {"snap-across-corners", true},
             // §6.1: one pass, 10 samples per edge, the first crossing.
             {"crossing-samples", 10},
             {"crossing-search-rounds", 1},
             {"crossing-split-deepest", false},
             // §6.2 d: the corner test, area 1e-20.
             {"cusp-area-threshold", 1e-20},
             {"cusp-search-subdivision", 0},
             {"cusp-contour-samples", 0},
             {"cusp-double-crossing-split", false},
             {"cusp-refinement", false},
             // §6.2 e: snap within 20 % of the edge length.
             {"snap-fraction", 0.2},
             // §6.3 g-h.
             {"radial-joint-min-barycentric", 0.0},
             {"radial-keep-consistency", false},
             {"radial-cusp-inside-pixels", 0.0},
             {"radial-cusp-pair-pixels", 0.0},
             {"radial-cusp-opposite-edge", false},
             {"radial-cusp-both-sides", false},
             {"radial-fold-fallback", true},
             {"radial-fan-sequences", false},
             // §6.4: one-face extension, single flips, 100 wiggle samples,
             // 10 split samples, 100 normal offsets up to the one-ring
             // distance.
             {"extension-cusp-push-depth", 0},
             {"extension-cusp-push-final", false},
             {"extension-push-every-end-final", false},
             {"optimization-cusp-edits", true},
             {"optimization-flip-pairs", false},
             {"wiggle-samples", 100},
             {"wiggle-radial-ends", false},
             {"split-samples", 10},
             {"split-wiggle-samples", 0},
             {"vertex-removal", false},
             {"patch-search", false},
             {"normal-wiggle-samples", 100},
             {"normal-wiggle-max-offset", 1.0},
             {"normal-wiggle-fine-offsets", 0},
             {"normal-wiggle-pair-offsets", 0},
             {"normal-wiggle-ring-pairs", false},
             {"cusp-end-retriangulation-faces", 0},
             {"contour-refinement-pixels", 0.0},
             {"cusp-retry", false},
             // §8: boundaries and surface intersections are curves;
             // footnote 3's near-face threshold.
             {"include-boundaries", true},
             {"surface-intersections", true},
             {"near-face-epsilon", 1.0},
             {"curtain-folds-from-cusps", false},
             {"visibility-keep-clean-propagation", false},
             {"t-junction-min-loop", 0.0},
         }},
    };
    m.outputs = consistentOutputs();
    return m;
}

} // namespace contour
