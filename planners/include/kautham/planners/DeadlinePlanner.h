#pragma once

#include <chrono>

namespace kautham::planners {

/// A planner with steps that run long between two looks at the termination condition
/// (p-KPIECE verifies a plan by executing it up to twice verify_runs times): solve() tells it
/// when the time limit ends, before each solve, so such a step stops there rather than run past
/// the limit and report a plan found after it. The termination condition itself is not asked
/// inside those steps: how often it is asked must not depend on how the work is split (tests
/// stop planners by counting its checks).
class DeadlinePlanner {
 public:
  using Clock = std::chrono::steady_clock;
  virtual ~DeadlinePlanner() = default;
  virtual void setDeadline(Clock::time_point deadline) = 0;
};

}  // namespace kautham::planners
