#pragma once

#include <cstdint>
#include <vector>

#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/Replay.h"

namespace kautham::planners {

/// What a verification found: how many of the sampled executions it ran succeeded.
struct VerificationResult {
  unsigned runs = 0;       ///< executions run (fewer than asked when it stopped early)
  unsigned successes = 0;  ///< of those, valid all along and ending in the goal
  bool passed = false;     ///< the success rate reached the threshold over all the runs asked
  double rate() const { return runs == 0 ? 0.0 : static_cast<double>(successes) / runs; }
};

/// Executes a whole plan open loop in worlds sampled from the problem's uncertainty, as
/// `kautham validate` does (physics::execute), before p-KPIECE lets it end the search (not in
/// the paper). The particles judge one motion at a time from a fitted spread of where their
/// parent's particles ended; an execution carries everything that happened before, so its
/// success rate is the estimate the plan is judged by.
///
/// Runs go in the calling process, one after another, so the result does not depend on how
/// many processes the particles use. Each verification draws fresh random streams (a counter
/// over `seedBase`), never those of `kautham validate --seed N` for a small N.
class PlanVerifier {
 public:
  PlanVerifier(physics::PlanningContext& context, std::uint64_t seedBase);

  /// Runs up to `runs` executions of `controls`; stops as soon as too many have failed for
  /// the rate over all `runs` to reach `threshold` (a rejected plan costs less).
  VerificationResult verify(const std::vector<physics::ControlStep>& controls, unsigned runs,
                            double threshold);

 private:
  physics::PlanningContext& context_;
  std::uint64_t seedBase_;
  std::uint64_t nextRun_ = 0;  ///< runs drawn so far: every run has its own stream
};

}  // namespace kautham::planners
