#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/physics/JointSpace.h"

namespace kautham::physics {

/// Where the goal link should be: its origin at a point and, when given, its +z axis (the
/// gripper's approach) along a world direction and a link axis (the fingers' opening axis)
/// level.
struct PoseTarget {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> approach;   ///< unit, world frame
  std::optional<Eigen::Vector3d> levelAxis;  ///< unit, link frame
  double tolerance = 0.005;                  ///< m
  double angleTolerance = 0.05;              ///< rad
};

/// Inverse kinematics by numerical optimisation: Levenberg-Marquardt (Eigen's) on the position
/// and axis errors over JointSpace coordinates, from a seed; coordinates stay in [0, 1].
/// Used as a goal sampler by the geometric planners and by the task planner's grasps.
class InverseKinematics {
 public:
  InverseKinematics(const JointSpace& joints, int link) : joints_(&joints), link_(link) {}

  /// Coordinates near `seed` that put the link on the target within its tolerances, or none.
  std::optional<std::vector<double>> solve(const PoseTarget& target,
                                           const std::vector<double>& seed) const;
  /// How many times solve() has run: a measure of work that does not depend on the clock.
  std::uint64_t solves() const { return solves_; }
  /// Position error (m) and the larger axis error (rad) at coordinates `c`.
  std::pair<double, double> errors(const PoseTarget& target, const std::vector<double>& c) const;

 private:
  const JointSpace* joints_;
  int link_;
  mutable std::atomic<std::uint64_t> solves_{0};
};

}  // namespace kautham::physics
