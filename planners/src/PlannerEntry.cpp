#include "kautham/planners/PlannerEntry.h"

#include <cstdio>
#include <stdexcept>

#include <ompl/util/Console.h>

namespace kautham::planners {

namespace {

constexpr const char* kCellSize = "cell_size";

/// The value as text that reads back as the same double (17 significant digits).
std::string exactText(const core::ParameterSpec& spec, double value) {
  if (spec.type == core::ParameterType::Boolean) return value != 0.0 ? "1" : "0";
  if (spec.type == core::ParameterType::Integer)
    return std::to_string(static_cast<long long>(value));
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

/// OMPL's range suggestion: "min:max" for numbers, "0,1" for a flag.
std::string rangeSuggestion(const core::ParameterSpec& spec) {
  if (spec.type == core::ParameterType::Boolean) return "0,1";
  return exactText(spec, spec.min) + ":" + exactText(spec, spec.max);
}

bool isFrameworkParameter(const std::string& name) { return name == kCellSize; }

template <typename T>
void declareReadOnly(ompl::base::ParamSet& params, const std::string& name, T value) {
  params.declareParam<T>(
      name,
      [name](T) {
        OMPL_WARN(
            "kautham: parameter '%s' is fixed when the planner is made; set it with "
            "--set or the problem file",
            name.c_str());
      },
      [value] { return value; });
}

}  // namespace

core::Parameter goalBiasParameter(double byDefault) {
  return core::Parameter::real("goal_bias")
      .byDefault(byDefault)
      .range(0.0, 1.0)
      .describe(
          "probability of expanding towards the goal (from a motion near it) instead of "
          "exploring")
      .alias("Goal Bias")
      .alias("goalBias");
}

core::Parameter cellSizeParameter() {
  return core::Parameter::real(kCellSize)
      .byDefault(0.05)
      .range(0.001, 1.0)
      .describe("projection cell side, as a fraction of the workspace side")
      .alias("Cell Size");
}

void applyFrameworkParameters(const core::ParameterSet& values, physics::PlanningContext& context) {
  if (values.has(kCellSize)) context.projection().setCellFraction(values.real(kCellSize));
}

void setOmplParameters(ompl::base::Planner& planner, const core::ParameterSet& values) {
  ompl::base::ParamSet& params = planner.params();
  for (const core::ParameterSpec& spec : values.specs()) {
    if (params.hasParam(spec.name)) {
      if (!params.setParam(spec.name, exactText(spec, values.real(spec.name))))
        throw std::logic_error("OMPL's " + planner.getName() + " refused parameter '" + spec.name +
                               "'");
    } else if (!isFrameworkParameter(spec.name)) {
      throw std::logic_error(planner.getName() + " has no OMPL parameter '" + spec.name +
                             "' (OMPL declares: " +
                             [&] {
                               std::vector<std::string> names;
                               params.getParamNames(names);
                               std::string list;
                               for (const std::string& n : names)
                                 list += (list.empty() ? "" : ", ") + n;
                               return list;
                             }() +
                             ")");
    }
  }
}

void declareOmplParameters(ompl::base::Planner& planner, const core::ParameterSet& values) {
  ompl::base::ParamSet& params = planner.params();
  for (const core::ParameterSpec& spec : values.specs()) {
    if (params.hasParam(spec.name)) continue;  // the planner's own (set by setOmplParameters)
    const double value = values.real(spec.name);
    switch (spec.type) {
      case core::ParameterType::Real:
        declareReadOnly<double>(params, spec.name, value);
        break;
      case core::ParameterType::Integer:
        declareReadOnly<int>(params, spec.name, static_cast<int>(value));
        break;
      case core::ParameterType::Boolean:
        declareReadOnly<bool>(params, spec.name, value != 0.0);
        break;
    }
    params[spec.name].setRangeSuggestion(rangeSuggestion(spec));
  }
}

}  // namespace kautham::planners
