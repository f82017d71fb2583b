#include "contours/Methods.h"

namespace contour {

const std::vector<Method>& contourMethods() {
    static const std::vector<Method> methods{
        makeMeshContourMethod(), makeInterpolatedContourMethod(), makeConsistentContourMethod(),
        makePowellSabinMethod(), makeTracedContourMethod()};
    return methods;
}

const Method* findMethod(const std::string& name) {
    for (const Method& m : contourMethods())
        if (m.name == name)
            return &m;
    return nullptr;
}

const std::vector<PlannedMethod>& plannedMethods() {
    static const std::vector<PlannedMethod> planned{};
    return planned;
}

const PlannedMethod* findPlannedMethod(const std::string& name) {
    for (const PlannedMethod& m : plannedMethods())
        if (m.name == name)
            return &m;
    return nullptr;
}

} // namespace contour
