#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "kautham/physics/Replay.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"

namespace kautham::planners {

/// What a verification found: how many of the sampled executions it ran succeeded.
struct VerificationResult {
  unsigned runs = 0;       ///< executions run (fewer than asked when it stopped early)
  unsigned successes = 0;  ///< of those, valid all along and ending in the goal
  bool passed = false;     ///< the success rate reaches the threshold over all the runs asked
  bool cutShort = false;   ///< the deadline passed before the count was decided
  /// Per control of the plan: the runs that began it, and of those the runs that got through
  /// it without breaking a rule (through the last control: that ended in the goal).
  std::vector<unsigned> entered;
  std::vector<unsigned> gotThrough;
  double rate() const { return runs == 0 ? 0.0 : static_cast<double>(successes) / runs; }
  /// Adds one run of a plan of entered.size() controls to the counts.
  void add(const ExecutionOutcome& run);
};

/// Executes a whole plan open loop in worlds sampled from the problem's uncertainty, as
/// `kautham validate` does (physics::execute), before p-KPIECE lets it end the search (not in
/// the paper). The particles judge one motion at a time from a fitted spread of where their
/// parent's particles ended; an execution carries everything that happened before, so its
/// success rate is the estimate the plan is judged by.
///
/// Runs go in batches over the evaluator's processes (MotionEvaluator::runExecutions), and are
/// counted in order, as if one after another: the result, and the streams the next
/// verification draws, do not depend on how many processes run them. Each verification draws
/// fresh random streams (a counter over `seedBase`), never those of `kautham validate --seed N`
/// for a small N.
class PlanVerifier {
 public:
  using Clock = std::chrono::steady_clock;

  PlanVerifier(MotionEvaluator& evaluator, std::uint64_t seedBase);

  /// From now on a count stops between two batches once `deadline` has passed (cutShort): a
  /// verification so cut does not pass, a measurement gives the rate of the runs it made.
  /// std::nullopt: no deadline.
  void stopAt(std::optional<Clock::time_point> deadline) { deadline_ = deadline; }
  /// `call` runs before each batch of runs: it may change how many processes the evaluator
  /// runs them over (cores lent to a tree's process, parallel_trees), which changes no result.
  void beforeEachBatch(std::function<void()> call) { beforeEachBatch_ = std::move(call); }
  /// Runs counted from now on draw from streams derived from `seedBase`, from its first on (a
  /// tree of its own, parallel_trees).
  void reseed(std::uint64_t seedBase) { resume({seedBase, 0}); }
  /// Where the runs' streams stand: the runs counted next draw from `nextRun` on, over
  /// `seedBase`.
  struct Streams {
    std::uint64_t seedBase = 0;
    std::uint64_t nextRun = 0;
  };
  Streams streams() const { return {seedBase_, nextRun_}; }
  /// Runs counted from now on draw from `at` on: another verifier's runs go on here exactly as
  /// they would have there (a tree's plan measured by the planner's process, parallel_trees).
  void resume(const Streams& at) {
    seedBase_ = at.seedBase;
    nextRun_ = at.nextRun;
  }

  /// Runs up to `runs` executions of `controls`; stops as soon as the rate over all `runs`
  /// is sure to reach `threshold` (enough have succeeded) or sure not to (too many have
  /// failed): the verdict is the one all the runs would give, for fewer runs. Cut short by
  /// the deadline, it has not passed.
  VerificationResult verify(const std::vector<physics::ControlStep>& controls, unsigned runs,
                            double threshold);
  /// Runs all `runs` executions of `controls` (fewer when the deadline cuts it short): the
  /// success rate they measure.
  VerificationResult measure(const std::vector<physics::ControlStep>& controls, unsigned runs);

 private:
  /// Runs up to `runs` executions; stops once `needed` have succeeded or more than
  /// `allowed` have failed.
  VerificationResult count(const std::vector<physics::ControlStep>& controls, unsigned runs,
                           unsigned needed, unsigned allowed);

  MotionEvaluator& evaluator_;
  std::uint64_t seedBase_;
  std::uint64_t nextRun_ = 0;  ///< runs counted so far: every counted run has its own stream
  std::optional<Clock::time_point> deadline_;
  std::function<void()> beforeEachBatch_;
};

}  // namespace kautham::planners
