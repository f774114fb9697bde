#include "BenchPreflight.h"

#include <stdexcept>

#include <fmt/format.h>

#include "KauthamPlanners.h"
#include "ParameterOverrides.h"
#include "PlannerFromFile.h"
#include "StartCheck.h"
#include "kautham/core/PhysicsOverrides.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"
#include "kautham/planners/Solve.h"

namespace kautham::apps {

namespace {

double checkConfig(const BenchSpec& spec, core::Problem problem, const BenchConfig& config,
                   const std::vector<std::filesystem::path>& modelDirs) {
  // A Kautham benchmark's entry: its file's planner, mapped as `plan --planner-from` maps it.
  std::optional<std::string> planner = config.planner;
  if (config.plannerFile) {
    problem = withPlannerOf(std::move(problem), *config.plannerFile, modelDirs);
    planner = plannerToUse(problem, std::nullopt, /*lenient=*/false);
  }
  try {
    core::applyPhysicsOverrides(problem.physics, config.physics);
    const planners::PlanRequest request = planners::makeRequest(
        problem, planner, parameterOverrides(config.sets, spec.time, spec.threads), spec.seed);
    // Builds the world and checks the start state; then the planner, whose own checks of its
    // settings together (p-KPIECE's parallel_trees with plans > 1, ...) come when it is made.
    const auto context = makeCheckedContext(problem, 0, request);
    planners::makePlanner(*context, request);
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
      limits.push_back(checkConfig(spec, problem, config, modelDirs));
  }
  return result;
}

}  // namespace kautham::apps
