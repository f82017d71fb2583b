#include "contours/Methods.h"

namespace contour {

const std::vector<Method>& contourMethods() {
    static const std::vector<Method> methods{
        makeMeshContourMethod(), makeInterpolatedContourMethod(), makeConsistentContourMethod()};
    return methods;
}

const Method* findMethod(const std::string& name) {
    for (const Method& m : contourMethods())
        if (m.name == name)
            return &m;
    return nullptr;
}

const std::vector<PlannedMethod>& plannedMethods() {
    static const std::vector<PlannedMethod> planned{
        {"powell-sabin", "Powell-Sabin contours (Capouellez et al. 2023)",
         "not implemented yet: Powell-Sabin contours are planned after the consistent method"},
        // Summers 2016 traces the contour generator on the limit surface itself
        // instead of extracting it from a tessellation.
        {"traced", "Traced curves (Summers 2016)",
         "not implemented yet: the contour generator traced on the limit surface"},
    };
    return planned;
}

const PlannedMethod* findPlannedMethod(const std::string& name) {
    for (const PlannedMethod& m : plannedMethods())
        if (m.name == name)
            return &m;
    return nullptr;
}

} // namespace contour
