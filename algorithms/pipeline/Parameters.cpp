#include "pipeline/Parameters.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace contour {

ParameterSet ParameterSet::defaults(const std::vector<ParameterSpec>& schema) {
    ParameterSet set;
    for (const ParameterSpec& spec : schema)
        set.set(spec.name, spec.defaultValue);
    return set;
}

ParameterPreset defaultPreset() {
    return {"default", "The defaults of every parameter.", {}};
}

ParameterSet presetValues(const std::vector<ParameterSpec>& schema, const ParameterPreset& preset) {
    ParameterSet set = ParameterSet::defaults(schema);
    for (const auto& [name, value] : preset.values)
        set.set(name, value);
    return set;
}

namespace {

bool sameValue(const ParameterValue& a, const ParameterValue& b) {
    const auto number = [](const ParameterValue& v) -> std::optional<double> {
        if (const int* i = std::get_if<int>(&v))
            return *i;
        if (const double* d = std::get_if<double>(&v))
            return *d;
        return std::nullopt;
    };
    if (const std::optional<double> x = number(a), y = number(b); x && y)
        return *x == *y;
    return a == b;
}

} // namespace

ParameterSet changedFromPreset(const std::vector<ParameterSpec>& schema,
                               const ParameterPreset& preset, const ParameterSet& values) {
    const ParameterSet start = presetValues(schema, preset);
    ParameterSet changed;
    for (const ParameterSpec& spec : schema)
        if (values.has(spec.name) && !sameValue(values.value(spec.name), start.value(spec.name)))
            changed.set(spec.name, values.value(spec.name));
    return changed;
}

const ParameterValue& ParameterSet::value(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end())
        throw std::out_of_range("no parameter named \"" + name + "\"");
    return it->second;
}

double ParameterSet::getDouble(const std::string& name) const {
    const ParameterValue& v = value(name);
    if (const int* i = std::get_if<int>(&v))
        return *i;
    return std::get<double>(v);
}

nlohmann::json ParameterSet::toJson() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, v] : values_)
        std::visit([&](const auto& x) { j[name] = x; }, v);
    return j;
}

std::string toString(const ParameterValue& value) {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, bool>)
                return x ? "true" : "false";
            else if constexpr (std::is_same_v<T, std::string>)
                return x;
            else {
                std::ostringstream s;
                s << x;
                return s.str();
            }
        },
        value);
}

namespace {
std::string rangeText(const ParameterSpec& spec) {
    std::ostringstream s;
    s << "[" << spec.minimum << ", " << spec.maximum << "]";
    return s.str();
}

std::string problemWith(const ParameterSpec& spec, const ParameterValue& v) {
    switch (spec.type) {
    case ParameterType::Bool:
        return std::holds_alternative<bool>(v) ? "" : "must be true or false";
    case ParameterType::Int:
        if (!std::holds_alternative<int>(v))
            return "must be an integer";
        if (std::get<int>(v) < spec.minimum || std::get<int>(v) > spec.maximum)
            return "must be in " + rangeText(spec);
        return "";
    case ParameterType::Double: {
        double d;
        if (const int* i = std::get_if<int>(&v))
            d = *i;
        else if (const double* x = std::get_if<double>(&v))
            d = *x;
        else
            return "must be a number";
        if (!std::isfinite(d) || d < spec.minimum || d > spec.maximum)
            return "must be in " + rangeText(spec);
        return "";
    }
    case ParameterType::Choice: {
        const std::string* s = std::get_if<std::string>(&v);
        if (s && std::find(spec.choices.begin(), spec.choices.end(), *s) != spec.choices.end())
            return "";
        std::string list;
        for (const std::string& c : spec.choices)
            list += (list.empty() ? "" : ", ") + c;
        return "must be one of: " + list;
    }
    }
    return "has an unknown type";
}
} // namespace

ParameterValue parseParameter(const ParameterSpec& spec, const std::string& text) {
    ParameterValue v;
    const auto fail = [&](const std::string& why) {
        throw std::invalid_argument("parameter " + spec.name + ": \"" + text + "\" " + why);
    };
    switch (spec.type) {
    case ParameterType::Bool:
        if (text == "true" || text == "1" || text == "on" || text == "yes")
            v = true;
        else if (text == "false" || text == "0" || text == "off" || text == "no")
            v = false;
        else
            fail("is not a boolean (true/false)");
        break;
    case ParameterType::Int: {
        int x = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (ec != std::errc() || end != text.data() + text.size())
            fail("is not an integer");
        v = x;
        break;
    }
    case ParameterType::Double: {
        size_t used = 0;
        double x = 0;
        try {
            x = std::stod(text, &used);
        } catch (const std::exception&) {
            fail("is not a number");
        }
        if (used != text.size())
            fail("is not a number");
        v = x;
        break;
    }
    case ParameterType::Choice:
        v = text;
        break;
    }
    if (const std::string p = problemWith(spec, v); !p.empty())
        fail(p);
    return v;
}

std::vector<std::string> validateParameters(const std::vector<ParameterSpec>& schema,
                                            const ParameterSet& values) {
    std::vector<std::string> problems;
    for (const ParameterSpec& spec : schema) {
        if (!values.has(spec.name)) {
            problems.push_back("parameter " + spec.name + " is missing");
            continue;
        }
        if (const std::string p = problemWith(spec, values.value(spec.name)); !p.empty())
            problems.push_back("parameter " + spec.name + " " + p);
    }
    for (const auto& [name, v] : values.values()) {
        (void)v;
        if (std::none_of(schema.begin(), schema.end(),
                         [&](const ParameterSpec& s) { return s.name == name; }))
            problems.push_back("parameter " + name + " is not a parameter of this method");
    }
    return problems;
}

} // namespace contour
