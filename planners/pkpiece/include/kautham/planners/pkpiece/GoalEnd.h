#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "kautham/physics/GoalFreeSpace.h"
#include "kautham/physics/PlanningContext.h"

namespace kautham::planners {

/// Where in the goal region p-KPIECE's goal steering makes the gripper end (ours, not in the
/// paper).
///
/// At the goal point, turned as the steering's approach asks (`turn`), while the goal's free
/// space is clear there. With `shift` > 0, where an object reaches a little way into the free
/// space at the goal point, a pose nearby (within `shift` of the goal point, horizontally,
/// on a 2.5 mm grid; then turned by up to 0.15 rad about the vertical, within the goal's
/// approach tolerance) whose free space is clear with 2 mm to spare on every side (the arm ends
/// within a few millimetres of where it is steered): of those, the one with the most room, in
/// 1 mm steps up to 12 mm (each judged on the free space's sample points, up to 1 cm apart),
/// and the nearest of equals. The objects' poses are uncertain (on the dense suite, 5 mm
/// standard deviation each way), and an end with 2 mm of room found one of them in its free
/// space in about half the executions that reached it (kuka_clutter_30). The goal region allows it:
/// the gripper may end anywhere within the tolerance, turned within the approach tolerance, and the
/// free space moves with it. On kuka_clutter_30 a can behind the target reaches 6 mm into the free
/// space's far end, where no push can get at it without touching the target; 7.5 mm short of
/// the goal point, the free space is clear.
class GoalEnd {
 public:
  struct Pose {
    Eigen::Vector3d point;     ///< where the goal link ends
    Eigen::Matrix3d turn;      ///< how it is turned there
    Eigen::Vector3d approach;  ///< the goal's approach direction, turned with it
  };

  GoalEnd(const physics::PlanningContext& context, const Eigen::Matrix3d& turn, double shift);

  /// The pose to end at in `state`; none while every pose tried has an object in its free
  /// space.
  std::optional<Pose> clearPose(const double* state) const;
  /// Whether clearPose() finds a pose (cheaper: stops at the nearest).
  bool anyClearPose(const double* state) const;
  /// Whether poses beside the goal point are tried (`shift` > 0).
  bool shifts() const { return poses_.size() > 1; }

 private:
  const physics::PlanningContext& context_;
  /// The goal point turned as asked first, then the others, nearest first.
  std::vector<Pose> poses_;
  /// The goal's free space grown by the room a pose beside the goal point must leave, then by
  /// each room step more (none without shifts or a free space).
  std::vector<physics::GoalFreeSpace> roomier_;

  static Eigen::Isometry3d linkAt(const Pose& pose);
  /// The index in poses_ of the goal point (0) if its free space is clear, else of the nearest
  /// pose with kRoom; none if there is none, or the free space at the goal point is
  /// too full for a pose nearby to be clear.
  std::optional<std::size_t> nearestClear(const double* state) const;
  /// The last room level (index in roomier_) clear at `link`, climbing from `level`, the levels
  /// below it known clear.
  std::size_t climb(const double* state, const Eigen::Isometry3d& link, std::size_t level) const;
  /// Whether the free space at `link` is clear at every room level up to `level`.
  bool clearThrough(const double* state, const Eigen::Isometry3d& link, std::size_t level) const;
};

}  // namespace kautham::planners
