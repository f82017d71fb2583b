#include "pipeline/Method.h"

namespace contour {

const ParameterSpec* Method::parameter(const std::string& parameterName) const {
    for (const ParameterSpec& p : parameters)
        if (p.name == parameterName)
            return &p;
    return nullptr;
}

} // namespace contour
