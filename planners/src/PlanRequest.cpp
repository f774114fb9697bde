#include "kautham/planners/PlanRequest.h"

#include <set>
#include <stdexcept>

#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

std::vector<core::ParameterSpec> commonParameters() {
  using core::ParameterType;
  return {
      {"time_limit",
       ParameterType::Real,
       30.0,
       0.01,
       86400.0,
       "seconds of planning before giving up",
       {"_Max Planning Time", "Max Planning Time", "timeLimit"}},
      {"propagation_step_size",
       ParameterType::Real,
       0.05,
       0.0001,
       10.0,
       "seconds per propagation step (a whole number of physics steps)",
       {"PropagationStepSize"}},
      {"min_control_steps",
       ParameterType::Integer,
       2,
       1,
       100000,
       "fewest propagation steps a control is held",
       {"Min Control Steps"}},
      {"max_control_steps",
       ParameterType::Integer,
       20,
       1,
       100000,
       "most propagation steps a control is held",
       {"Max Control Steps"}},
      {"threads",
       ParameterType::Integer,
       1,
       1,
       64,
       "processes for p-KPIECE's particles (the plan does not depend on it); others ignore it",
       {"Threads"}},
  };
}

physics::PropagationSettings PlanRequest::propagation() const {
  return {common.real("propagation_step_size"),
          static_cast<unsigned>(common.integer("min_control_steps")),
          static_cast<unsigned>(common.integer("max_control_steps"))};
}

namespace {

/// Sets a parameter in whichever set knows it. Returns false if neither does.
bool setParameter(PlanRequest& request, const std::string& name, const std::string& value) {
  if (request.common.has(name))
    request.common.set(name, value);
  else if (request.parameters.has(name))
    request.parameters.set(name, value);
  else
    return false;
  return true;
}

/// Parameters of Kautham's physics planners that this framework has no use for: a Kautham file
/// that sets them still loads (docs/problem-format.md says why each is not needed).
bool isIgnoredKauthamParameter(const std::string& name) {
  static const std::set<std::string> ignored{"Control Dimensions", "Max Speed", "Speed Factor",
                                             "only final link position?", "kinematic chain"};
  return ignored.count(name) > 0;
}

std::string unknownParameter(const PlanRequest& request, const std::string& name) {
  std::string known;
  for (const auto* set : {&request.common, &request.parameters})
    for (const core::ParameterSpec& s : set->specs()) known += (known.empty() ? "" : ", ") + s.name;
  return "unknown parameter '" + name + "' for planner " + request.planner + "; known: " + known;
}

}  // namespace

PlanRequest makeRequest(const core::Problem& problem,
                        const std::optional<std::string>& plannerOverride,
                        const std::vector<ParameterOverride>& overrides, std::uint32_t seed) {
  PlanRequest request;
  request.planner = plannerOverride.value_or(problem.planner.name);
  const PlannerRegistry& registry = plannerRegistry();
  if (!plannerOverride && !registry.find(request.planner)) {
    try {
      registry.at(request.planner);
    } catch (const std::invalid_argument& e) {
      throw core::InputError(problem.planner.where, e.what());
    }
  }
  request.parameters = registry.defaults(request.planner);  // throws for an unknown override
  request.common = core::ParameterSet(commonParameters());
  request.seed = seed;

  const bool otherPlanner = plannerOverride && *plannerOverride != problem.planner.name;
  for (const core::PlannerParameter& p : problem.planner.parameters) {
    try {
      // Kautham's generic parameters start with '_'; those we do not use are skipped, and so
      // are the file planner's own parameters when the command line picks another planner.
      if (!setParameter(request, p.name, p.value) && p.name.front() != '_' && !otherPlanner &&
          !isIgnoredKauthamParameter(p.name))
        throw std::invalid_argument(unknownParameter(request, p.name));
    } catch (const std::invalid_argument& e) {
      throw core::InputError(p.where, e.what());
    }
  }
  for (const auto& [name, value] : overrides)
    if (!setParameter(request, name, value))
      throw std::invalid_argument(unknownParameter(request, name));
  return request;
}

}  // namespace kautham::planners
