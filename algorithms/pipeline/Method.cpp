#include "pipeline/Method.h"

#include <algorithm>
#include <stdexcept>

namespace contour {

void Method::addPhase(Phase phase) {
    std::vector<std::string> waiting;
    for (const ParameterSpec& p : parameters)
        if (p.group.empty())
            waiting.push_back(p.name);
    if (!waiting.empty() && phases.size() != phasesAdded_)
        throw std::logic_error("method " + name + ": parameter " + waiting.front() +
                               " has no group and a phase was appended without Method::addPhase "
                               "before phase " +
                               phase.name);
    for (ParameterSpec& p : parameters)
        if (p.group.empty())
            p.group = phase.name;
    phases.push_back(std::move(phase));
    phasesAdded_ = phases.size();
}

std::vector<std::string> Method::parameterGroups() const {
    std::vector<std::string> groups;
    for (const ParameterSpec& p : parameters)
        if (std::find(groups.begin(), groups.end(), p.group) == groups.end())
            groups.push_back(p.group);
    return groups;
}

const ParameterPreset* Method::preset(const std::string& presetName) const {
    for (const ParameterPreset& p : presets)
        if (p.name == presetName)
            return &p;
    // Every method offers the schema's defaults, listed or not.
    static const ParameterPreset defaults = defaultPreset();
    return presetName == defaults.name ? &defaults : nullptr;
}

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
