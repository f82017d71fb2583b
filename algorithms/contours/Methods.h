#pragma once
// The registry of contour methods. The GUI's method selector, the CLI's
// --method and the JSON report list methods from here.
#include "pipeline/Method.h"

#include <string>
#include <vector>

namespace contour {

// Methods that run today: "mesh", "interpolated", "consistent" (every
// sub-phase of Bénard 2014 §6; some inconsistent faces remain, see its
// description), "powell-sabin" (the fitted spline) and "traced" (the contour
// traced on the limit surface, Summers 2016).
const std::vector<Method>& contourMethods();
const Method* findMethod(const std::string& name);

// Methods the workbench will offer but that are not implemented yet. Callers
// must say so to the user (GUI: disabled entry with this reason; CLI: error).
struct PlannedMethod {
    std::string name;
    std::string label;
    std::string reason;
};
const std::vector<PlannedMethod>& plannedMethods();
const PlannedMethod* findPlannedMethod(const std::string& name);

Method makeMeshContourMethod();
Method makeInterpolatedContourMethod();
Method makeConsistentContourMethod();
// The fitted Powell-Sabin spline (Capouellez et al. 2023 §5) and its contour
// conics, chains and cusps (§4); its visibility is not computed yet.
Method makePowellSabinMethod();
// The contour generator traced on the Catmull-Clark or Loop limit surface
// (Summers 2016), with cusps and the common view graph.
Method makeTracedContourMethod();

} // namespace contour
