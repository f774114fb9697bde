#include "BenchPreflight.h"

#include <stdexcept>

#include <fmt/format.h>

#include "StartCheck.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/planners/PlanRequest.h"

namespace kautham::apps {

namespace {

/// The overrides `kautham plan` will apply for this configuration (bench passes the same
/// --set, --time and --threads to it).
std::vector<planners::ParameterOverride> overridesOf(const BenchSpec& spec,
                                                     const BenchConfig& config) {
  std::vector<planners::ParameterOverride> overrides;
  for (const std::string& text : config.sets) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0)
      throw std::invalid_argument("--set expects NAME=VALUE, got '" + text + "'");
    overrides.emplace_back(text.substr(0, equals), text.substr(equals + 1));
  }
  if (spec.time) overrides.emplace_back("time_limit", fmt::format("{}", *spec.time));
  if (spec.threads) overrides.emplace_back("threads", fmt::format("{}", *spec.threads));
  return overrides;
}

double checkConfig(const BenchSpec& spec, const core::Problem& problem, const BenchConfig& config) {
  try {
    const planners::PlanRequest request =
        planners::makeRequest(problem, config.planner, overridesOf(spec, config), spec.seed);
    makeCheckedContext(problem, 0, request);  // builds the world and checks the start state
    return request.timeLimit();
  } catch (const std::invalid_argument& e) {  // the command line's part: planner, --set
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
