#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kautham::planners {

/// How many of the motions a planner ran in sampled worlds failed for one reason, and on which
/// object ("" when the robot broke the rule).
struct FailureCount {
  std::string reason;  ///< physics::toString of the violation, or "moved more than d"
  std::string object;
  std::uint64_t count = 0;
};

/// A planner that judges motions by running them in sampled worlds (p-KPIECE's particles) and
/// can say why those runs failed: what keeps a search from trusting the motions it needs.
class FailureReporter {
 public:
  virtual ~FailureReporter() = default;
  /// Most frequent first.
  virtual std::vector<FailureCount> sampledFailures() const = 0;
  /// Why candidate motions, run once as planned (nominally), stopped at a broken rule: what
  /// cuts the tree's growth short. Most frequent first; empty if the planner does not say.
  virtual std::vector<FailureCount> candidateFailures() const { return {}; }
  /// Of those, the candidates the planner aimed at the goal (its goal steering).
  virtual std::vector<FailureCount> steeredFailures() const { return {}; }
};

}  // namespace kautham::planners
