#include "pipeline/Method.h"

namespace contour {

const ParameterSpec* Method::parameter(const std::string& parameterName) const {
    for (const ParameterSpec& p : parameters)
        if (p.name == parameterName)
            return &p;
    return nullptr;
}

int Method::phaseIndex(const std::string& phaseName) const {
    for (size_t i = 0; i < phases.size(); ++i)
        if (phases[i].name == phaseName)
            return static_cast<int>(i);
    return -1;
}

} // namespace contour
