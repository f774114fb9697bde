#include "kautham/planners/pkpiece/PlanVerifier.h"

#include <algorithm>
#include <cmath>

#include "kautham/core/Random.h"

namespace kautham::planners {

namespace {
// Runs handed out at once per process, at most: enough to keep every process busy between
// two looks at the count.
constexpr unsigned kRunsPerProcess = 4;
}  // namespace

void VerificationResult::add(const ExecutionOutcome& run) {
  ++runs;
  if (run.reached) ++successes;
  const std::size_t controls = entered.size();
  for (std::size_t c = 0; c < controls && c <= run.controlsPassed; ++c) {
    ++entered[c];
    const bool last = c + 1 == controls;
    if (c < run.controlsPassed && (!last || run.reached)) ++gotThrough[c];
  }
}

PlanVerifier::PlanVerifier(MotionEvaluator& evaluator, std::uint64_t seedBase)
    : evaluator_(evaluator), seedBase_(seedBase) {}

VerificationResult PlanVerifier::verify(const std::vector<physics::ControlStep>& controls,
                                        unsigned runs, double threshold) {
  // The fewest successes that reach `threshold` over all the runs; more failures than the
  // rest put it out of reach. The count is decided as soon as either happens.
  const auto needed = static_cast<unsigned>(std::ceil(runs * threshold - 1e-9));
  VerificationResult result = count(controls, runs, needed, runs - needed);
  result.passed = !result.cutShort && result.successes >= needed;
  return result;
}

VerificationResult PlanVerifier::measure(const std::vector<physics::ControlStep>& controls,
                                         unsigned runs) {
  // Neither more successes than runs nor more failures than runs: nothing decides early.
  VerificationResult result = count(controls, runs, runs + 1, runs);
  result.passed = !result.cutShort;
  return result;
}

VerificationResult PlanVerifier::count(const std::vector<physics::ControlStep>& controls,
                                       unsigned runs, unsigned needed, unsigned allowed) {
  VerificationResult result;
  result.entered.assign(controls.size(), 0);
  result.gotThrough.assign(controls.size(), 0);
  unsigned failures = 0;
  while (result.runs < runs && result.successes < needed && failures <= allowed) {
    if (deadline_ && Clock::now() >= *deadline_) {
      result.cutShort = true;
      break;
    }
    if (beforeEachBatch_) beforeEachBatch_();
    const unsigned processes = evaluator_.threads();
    const unsigned batch = processes > 1 ? kRunsPerProcess * processes : 1;
    // No batch goes past the earliest run that could decide the count: every run handed out
    // is counted, so the work and the streams drawn do not depend on how many processes ran
    // them, and an early stop wastes no run.
    const unsigned decidable = std::min(needed - result.successes, allowed + 1 - failures);
    std::vector<std::uint64_t> seeds(std::min({batch, runs - result.runs, decidable}));
    for (std::size_t i = 0; i < seeds.size(); ++i)
      seeds[i] = core::runSeed(seedBase_, nextRun_ + i);
    for (const ExecutionOutcome& run : evaluator_.runExecutions(controls, seeds)) {
      ++nextRun_;
      result.add(run);
      if (!run.reached) ++failures;
    }
  }
  return result;
}

}  // namespace kautham::planners
