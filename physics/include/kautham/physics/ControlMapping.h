#pragma once

#include <vector>

#include <Eigen/Core>

#include "kautham/core/ControlSet.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// Turns the planner's controls into joint velocity targets for the motors.
///
/// Each control u_i lies in [-1, 1]. Joint j turns at v_j = vmax_j (K u)_j, clipped to
/// [-vmax_j, vmax_j], where K is the control set's matrix (docs/planners.md): without a .cntr
/// file K = I and u_j is joint j's speed as a fraction of its URDF velocity limit. A joint that
/// no control moves gets velocity 0, so its motor holds it where it is (a gripper held open).
class ControlMapping {
 public:
  ControlMapping(const core::ControlSet& controls, const std::vector<JointInfo>& joints);

  std::size_t size() const { return static_cast<std::size_t>(matrix_.cols()); }
  /// Writes one velocity per joint into `velocities`.
  void jointVelocities(const double* controls, double* velocities) const;
  /// The control that asks for `velocities` (exact when K = I and no velocity is clipped).
  std::vector<double> controlsFor(const std::vector<double>& velocities) const;

 private:
  Eigen::MatrixXd matrix_;       ///< K, one row per joint
  Eigen::VectorXd maxVelocity_;  ///< per joint
};

}  // namespace kautham::physics
