#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "kautham/physics/WorldLayout.h"
#include "kautham/physics/WorldValidityChecker.h"
#include "kautham/planners/FailureReporter.h"

namespace kautham::planners {

/// Why motions failed, tallied by reason and object: the first rule a motion's first invalid
/// state broke (and the object that broke it), or that an object moved more than d. p-KPIECE
/// keeps one for its particles and one for its candidates' nominal runs. A diagnosis only:
/// nothing in the search reads it, so it changes no plan.
class FailureTally {
 public:
  /// A motion stopped at an invalid state: the rule it broke and the body that broke it.
  void addViolation(physics::Violation violation, std::optional<std::size_t> body);
  /// A valid motion moved `body` more than the interaction limit d.
  void addDisplacement(std::size_t body);
  /// One kind of failure and how often: what entries() lists and add() takes back (a tally
  /// moved between processes).
  struct Entry {
    physics::Violation violation = physics::Violation::None;  ///< None: moved more than d
    std::optional<std::size_t> body;
    std::uint64_t count = 0;
  };
  std::vector<Entry> entries() const;
  void add(const Entry& entry);
  std::uint64_t total() const { return total_; }
  /// Most frequent first, bodies named by the layout.
  std::vector<FailureCount> counts(const physics::WorldLayout& layout) const;

 private:
  /// Violation::None stands for "moved more than d"; no body for the robot.
  using Key = std::pair<physics::Violation, std::optional<std::size_t>>;
  std::map<Key, std::uint64_t> counts_;
  std::uint64_t total_ = 0;
};

}  // namespace kautham::planners
