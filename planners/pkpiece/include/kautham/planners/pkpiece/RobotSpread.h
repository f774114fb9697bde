#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "kautham/physics/WorldLayout.h"

namespace kautham::planners {

/// Where the robot may really be at the end of a p-KPIECE motion: the robot part of the
/// states its particle motions reached (the states of the robot's link bodies and its joint
/// positions and rates). The particles of a motion grown from it start from these, particle i
/// from sample i (cycling when fewer survived), so control noise accumulates along a path as
/// it does when the plan runs open loop. Immutable once built.
class RobotSpread {
 public:
  /// Which numbers of a state describe the robot, for one layout.
  class Part {
   public:
    explicit Part(const physics::WorldLayout& layout);
    const std::vector<std::size_t>& indices() const { return indices_; }

   private:
    std::vector<std::size_t> indices_;
  };

  /// The robot part of each of `states`; null when there are none.
  static std::shared_ptr<const RobotSpread> fromStates(
      std::shared_ptr<const Part> part, const std::vector<const std::vector<double>*>& states);

  std::size_t size() const { return samples_; }
  /// Writes the robot part of sample `i % size()` into `state`, leaving the objects as they are.
  void apply(std::size_t i, double* state) const;
  /// The robot part of sample `i % size()`, in Part::indices() order.
  const double* sample(std::size_t i) const;

 private:
  RobotSpread(std::shared_ptr<const Part> part, std::size_t samples);
  std::shared_ptr<const Part> part_;
  std::size_t samples_;
  std::vector<double> values_;  ///< samples_ rows of part_->indices().size() numbers
};

}  // namespace kautham::planners
