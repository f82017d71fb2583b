// Consistent contours (Bénard, Hertzmann & Kass 2014): a per-view triangle
// mesh of the smooth surface whose mesh contour generator should be
// topologically equivalent to the smooth one. The method's parameters and
// phases come from the sub-phase files, in the paper's order (§6).
#include "contours/Methods.h"
#include "contours/common/SurfacePhase.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/phases/ConsistentPhases.h"
#include "visibility/SimplificationPhase.h"
#include "visibility/VisibilityPhase.h"

#include <string>

namespace contour {

Method makeConsistentContourMethod() {
    using namespace consistent;
    Method m;
    m.name = "consistent";
    m.label = "Consistent contours (Bénard et al. 2014)";
    m.description =
        "A per-view triangulation of the smooth surface whose contour generator is meant to be "
        "topologically equivalent to the smooth one (Bénard, Hertzmann & Kass 2014), built by "
        "the sub-phases of §6 in the paper's order, then the contour generator (edges between "
        "F-VBO and B-VBO faces) chained. Inconsistent faces can remain (0-0.005 % of the "
        "faces per view on average on ConTesse's meshes, at most 0.015 % on any of their 26 "
        "views; 0 on a sphere, ellipsoid, torus and bumpy torus); every phase counts them and "
        "the Overlays toolbar outlines them. Against a dense ground truth, contour loops match "
        "in 36 of 36 views on every test shape and cusp counts in 34-36.";
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
          toString(SurfaceKind::VertexNormalPatches)}},
        {"chart-tolerance",
         "Chart tolerance",
         "How close (in domain parameters) a preimage must be to a domain edge to also belong "
         "to the neighbouring face, and how far outside a face an interpolated preimage may "
         "land (appendix B; not in the paper).",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-3,
         {}},
        {"chart-vertex-rings",
         "Charts around regular corners",
         "Appendix B interpolates in the chart of a domain vertex's one-ring. Off: only a "
         "domain face and its edge neighbours share a chart. On: also two faces meeting at a "
         "regular corner (four quads), so moves next to domain vertices are no longer "
         "cancelled for want of a chart; contour insertion still snaps only within edge charts "
         "(snap-across-corners), so the contour matches the dense ground truth exactly as with "
         "the option off. Off by default: over 26 views (patch-search off) it takes the torus "
         "(resolution 12) from 12 inconsistent faces to 0, the bumpy torus from 14 to 12, "
         "spot_control from 73 to 68 and bob_controlmesh from 72 to 70 (torus 16: 46, "
         "unchanged), but 6 of those 130 views end 1 face worse, and over 8 views bigguy, "
         "spot_quad and fertility drop (117 -> 103, 31 -> 28, 65 -> 63) while bob_quad and "
         "killeroo rise (67 -> 72, 331 -> 333): the mesh reaching the final normal wiggle has "
         "fewer inconsistent faces, but the wiggle fixes fewer of them (bob_quad view 4: 33 -> "
         "20 against 32 -> 16).",
         ParameterType::Bool,
         false,
         0,
         0,
         {}},
        {"embedding-tolerance",
         "Embedding tolerance",
         "Post-condition pos = f(u) (notes §6.1 item 2) holds within this times the "
         "bounding-box diagonal.",
         ParameterType::Double,
         1e-9,
         0.0,
         1e-2,
         {}},
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
    addContourRefinementPhase(m);
    addCuspRetryPhase(m); // reruns the phases above: keep it after them
    addChainingPhase(m);
    addVisibilityPhase(m, VisibilityFlavor::Consistent);
    addSimplificationPhase(m);
    return m;
}

} // namespace contour
