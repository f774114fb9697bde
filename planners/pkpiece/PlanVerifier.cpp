#include "kautham/planners/pkpiece/PlanVerifier.h"

#include <algorithm>
#include <cmath>

#include "kautham/core/Random.h"

namespace kautham::planners {

namespace {
// Runs handed out at once per process: enough to keep every process busy between two
// looks at the count, few enough that an early stop wastes little.
constexpr unsigned kRunsPerProcess = 4;
}  // namespace

PlanVerifier::PlanVerifier(MotionEvaluator& evaluator, std::uint64_t seedBase)
    : evaluator_(evaluator), seedBase_(seedBase) {}

VerificationResult PlanVerifier::verify(const std::vector<physics::ControlStep>& controls,
                                        unsigned runs, double threshold) {
  VerificationResult result;
  // The most failures that still leave `threshold` reachable over all the runs.
  const double allowed = std::floor(runs * (1.0 - threshold) + 1e-9);
  // One process: one run at a time, so a rejected plan costs no run beyond the deciding one.
  const unsigned processes = evaluator_.threads();
  const unsigned batch = processes > 1 ? kRunsPerProcess * processes : 1;
  unsigned failures = 0;
  while (result.runs < runs) {
    std::vector<std::uint64_t> seeds(std::min(batch, runs - result.runs));
    for (std::size_t i = 0; i < seeds.size(); ++i)
      seeds[i] = core::runSeed(seedBase_, nextRun_ + i);
    // Counted in order up to the deciding failure; runs past it are not counted, and their
    // streams are drawn again by the next verification, as a serial run would.
    for (const bool reached : evaluator_.runExecutions(controls, seeds)) {
      ++nextRun_;
      ++result.runs;
      if (reached)
        ++result.successes;
      else if (++failures > allowed)
        return result;
    }
  }
  result.passed = result.rate() >= threshold;
  return result;
}

}  // namespace kautham::planners
