#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "kautham/physics/WorldLayout.h"

namespace kautham::planners {

/// Where the robot may really be at the end of a p-KPIECE motion: the robot part of the
/// states its particle motions reached (the states of the robot's link bodies and its joint
/// positions and rates), and the whole state (pose, tilt, velocities) of the objects the path
/// has moved. The particles of a motion grown from it start from these, particle i from
/// sample i (cycling when fewer survived), so control noise accumulates along a path as it
/// does when the plan runs open loop, and a can that tilts or slides at the end of one
/// motion goes on doing so in the next. Immutable once built.
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

  /// The robot part of each of `states`, and the body states of `objects` (body indices);
  /// null when there are no states.
  static std::shared_ptr<const RobotSpread> fromStates(
      std::shared_ptr<const Part> part, const std::vector<const std::vector<double>*>& states,
      std::vector<std::size_t> objects = {});

  std::size_t size() const { return samples_; }
  /// The objects whose states it carries (body indices, ascending).
  const std::vector<std::size_t>& objects() const { return objects_; }
  /// Writes sample `i % size()` into `state`: the robot part and the carried objects; the
  /// other objects stay as they are.
  void apply(std::size_t i, double* state) const;
  /// The robot part of sample `i % size()`, in Part::indices() order.
  const double* sample(std::size_t i) const;

 private:
  RobotSpread(std::shared_ptr<const Part> part, std::size_t samples,
              std::vector<std::size_t> objects);
  std::size_t rowSize() const;
  std::shared_ptr<const Part> part_;
  std::size_t samples_;
  std::vector<std::size_t> objects_;
  /// samples_ rows: part_->indices().size() robot numbers, then 13 per carried object
  std::vector<double> values_;
};

}  // namespace kautham::planners
