#include "kautham/planners/PlanRequest.h"

#include <set>
#include <stdexcept>

#include "kautham/core/Log.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

std::vector<core::ParameterSpec> commonParameters() {
  using core::Parameter;
  return {
      Parameter::real("time_limit")
          .byDefault(30.0)
          .range(0.01, 86400.0)
          .describe("seconds of planning before giving up")
          .alias("_Max Planning Time")
          .alias("Max Planning Time")
          .alias("timeLimit"),
      Parameter::real("propagation_step_size")
          .byDefault(0.05)
          .range(0.0001, 10.0)
          .describe("seconds per propagation step (a whole number of physics steps)")
          .alias("PropagationStepSize"),
      Parameter::integer("min_control_steps")
          .byDefault(2)
          .range(1, 100000)
          .describe("fewest propagation steps a control is held")
          .alias("Min Control Steps"),
      Parameter::integer("max_control_steps")
          .byDefault(20)
          .range(1, 100000)
          .describe("most propagation steps a control is held")
          .alias("Max Control Steps"),
      Parameter::integer("threads")
          .byDefault(1)
          .range(1, 64)
          .describe("worker processes for p-KPIECE's particles and whole-plan verification "
                    "(the plan does not depend on it); the other planners run in one thread")
          .alias("Threads"),
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

/// Parameters of Kautham's geometric planners that change how Kautham plans but have no
/// counterpart in OMPL's planners here (Kautham's own PRM connection rules and samplers): a
/// file that sets them loads, with a warning that they are ignored.
bool isUnmatchedKauthamParameter(const std::string& name) {
  static const std::set<std::string> unmatched{"DistanceThreshold", "BounceDistanceThreshold",
                                               "MinGrowTime", "MinExpandTime",
                                               "Sampler 0(r) 1(h) 2(sdk) 3(g)"};
  return unmatched.count(name) > 0;
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
      if (setParameter(request, p.name, p.value) || p.name.front() == '_' || otherPlanner ||
          isIgnoredKauthamParameter(p.name))
        continue;
      if (!isUnmatchedKauthamParameter(p.name))
        throw std::invalid_argument(unknownParameter(request, p.name));
      core::warning(p.where.str() + ": Kautham's parameter '" + p.name +
                    "' has no counterpart in " + request.planner + " here; ignored");
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
