#pragma once

#include <vector>

namespace kautham::planners {

/// A planner that knows how robust each motion of its solution is (p-KPIECE's beliefs).
class BeliefReporter {
 public:
  virtual ~BeliefReporter() = default;
  /// One belief in [0, 1] per control of the last solution, in order; empty without one.
  virtual std::vector<double> solutionBeliefs() const = 0;
};

}  // namespace kautham::planners
