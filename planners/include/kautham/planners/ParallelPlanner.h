#pragma once

namespace kautham::planners {

/// A planner that can spread its work over several cores: solve() hands it the common
/// `threads` parameter before planning. p-KPIECE is one (its particle motions run in worker
/// processes, see ParticleWorkers); planners that are not ignore the parameter. A plan must
/// not depend on the number of threads.
class ParallelPlanner {
 public:
  virtual ~ParallelPlanner() = default;
  /// Called once the planning context exists and before solve(); 1 means in this process only.
  virtual void setThreads(unsigned threads) = 0;
};

}  // namespace kautham::planners
