#include "kautham/planners/pkpiece/PlanVerifier.h"

#include <cmath>
#include <random>

#include "kautham/core/Random.h"
#include "kautham/physics/Execution.h"

namespace kautham::planners {

PlanVerifier::PlanVerifier(physics::PlanningContext& context, std::uint64_t seedBase)
    : context_(context), seedBase_(seedBase) {}

VerificationResult PlanVerifier::verify(const std::vector<physics::ControlStep>& controls,
                                        unsigned runs, double threshold) {
  VerificationResult result;
  // The most failures that still leave `threshold` reachable over all the runs.
  const double allowed = std::floor(runs * (1.0 - threshold) + 1e-9);
  unsigned failures = 0;
  while (result.runs < runs) {
    std::mt19937_64 rng(core::runSeed(seedBase_, nextRun_++));
    const physics::ExecutionResult run = physics::execute(context_, controls, rng, true);
    ++result.runs;
    if (run.reachedGoal)
      ++result.successes;
    else if (++failures > allowed)
      return result;
  }
  result.passed = result.rate() >= threshold;
  return result;
}

}  // namespace kautham::planners
