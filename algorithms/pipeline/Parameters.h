#pragma once
// A method's parameter schema and the values chosen for it. The GUI form, the
// CLI flags and the JSON report are all generated from the schema.
// Parameters are grouped by the phase that reads them (Method::addPhase), and
// a method names presets: complete value sets such as "default" and "paper".
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <variant>
#include <vector>

namespace contour {

using ParameterValue = std::variant<bool, int, double, std::string>;

enum class ParameterType { Bool, Int, Double, Choice };

struct ParameterSpec {
    std::string name;  // kebab-case, also the CLI flag: --name
    std::string label; // for the GUI form
    std::string help;  // tooltip and --help text; cite the paper
    ParameterType type = ParameterType::Double;
    ParameterValue defaultValue;
    double minimum = 0.0; // Int and Double only
    double maximum = 0.0;
    std::vector<std::string> choices; // Choice only
    // The group the GUI form and the CLI list it under. Empty in a
    // declaration: Method::addPhase gives it the name of the phase declared
    // after it. Set only for parameters read by more than one phase
    // (method-wide ones such as "surface") or by no phase of their own.
    std::string group{};
};

// A named set of values for a method's schema: the schema's defaults with
// `values` replacing some of them.
struct ParameterPreset {
    std::string name; // also the CLI's --preset value: "default", "paper"
    std::string description;
    std::map<std::string, ParameterValue> values;
};

// The preset of the schema's defaults, which every method offers.
ParameterPreset defaultPreset();

class ParameterSet {
public:
    ParameterSet() = default;
    static ParameterSet defaults(const std::vector<ParameterSpec>& schema);

    bool has(const std::string& name) const { return values_.count(name) != 0; }
    const ParameterValue& value(const std::string& name) const;
    void set(const std::string& name, ParameterValue value) { values_[name] = std::move(value); }

    bool getBool(const std::string& name) const { return std::get<bool>(value(name)); }
    int getInt(const std::string& name) const { return std::get<int>(value(name)); }
    double getDouble(const std::string& name) const;
    const std::string& getChoice(const std::string& name) const {
        return std::get<std::string>(value(name));
    }
    const std::map<std::string, ParameterValue>& values() const { return values_; }

    nlohmann::json toJson() const;

private:
    std::map<std::string, ParameterValue> values_;
};

// Parses text ("true", "3", "0.25", "area") into a value of the spec's type
// and checks its range or choices. Throws std::invalid_argument with a message
// naming the parameter, the text and the allowed range.
ParameterValue parseParameter(const ParameterSpec& spec, const std::string& text);

// Checks every value against the schema; returns one message per problem.
std::vector<std::string> validateParameters(const std::vector<ParameterSpec>& schema,
                                            const ParameterSet& values);

// The schema's defaults with the preset's values applied.
ParameterSet presetValues(const std::vector<ParameterSpec>& schema, const ParameterPreset& preset);

// The values of `values` that differ from the preset's (presetValues): what
// was changed after starting from it. Numbers compare by value (an int 2
// equals a double 2.0); parameters the schema or `values` lacks are left out.
ParameterSet changedFromPreset(const std::vector<ParameterSpec>& schema,
                               const ParameterPreset& preset, const ParameterSet& values);

std::string toString(const ParameterValue& value);

} // namespace contour
