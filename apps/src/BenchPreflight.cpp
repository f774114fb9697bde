#include "BenchPreflight.h"

#include <stdexcept>

#include <fmt/format.h>

#include "ParameterOverrides.h"
#include "StartCheck.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"

namespace kautham::apps {

namespace {

double checkConfig(const BenchSpec& spec, core::Problem problem, const BenchConfig& config) {
  try {
    core::applyPhysicsOverrides(problem.physics, config.physics);
    const planners::PlanRequest request =
        planners::makeRequest(problem, config.planner,
                              parameterOverrides(config.sets, spec.time, spec.threads), spec.seed);
    makeCheckedContext(problem, 0, request);  // builds the world and checks the start state
    return request.timeLimit();
  } catch (const std::invalid_argument& e) {  // the command line's part: planner, --set, physics
    throw std::invalid_argument(fmt::format("{}, configuration {} (planner {}): {}",
                                            problem.file.string(), config.name, config.planner,
                                            e.what()));
  }
}

}  // namespace

Preflight preflight(const BenchSpec& spec) {
  const std::vector<std::filesystem::path> modelDirs(spec.modelDirs.begin(), spec.modelDirs.end());
  Preflight result;
  for (const std::filesystem::path& file : spec.problems) {
    const core::Problem problem = core::loadProblem(file, modelDirs);
    if (problem.queries.empty())
      throw core::InputError({file, 0}, "the problem has no query to plan");
    std::vector<double>& limits = result.timeLimits.emplace_back();
    for (const BenchConfig& config : spec.configs)
      limits.push_back(checkConfig(spec, problem, config));
  }
  return result;
}

}  // namespace kautham::apps
