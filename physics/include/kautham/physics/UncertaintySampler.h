#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>

#include "kautham/core/Problem.h"
#include "kautham/physics/ContactParameters.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// Draws the uncertain parts of a run (the paper's section III-C): object poses around their
/// measured values, contact parameters around their approximations, control disturbances.
/// Every draw uses only the given std::mt19937_64's raw output (no std distributions), so a
/// seed gives the same numbers with any standard library.
class UncertaintySampler {
 public:
  UncertaintySampler(const core::Problem& problem, const WorldLayout& layout);

  /// Contact parameters N(mean, sd) from <Physics> and <Uncertainty>, clipped to valid values
  /// (friction >= 0, erp in [0, 1], cfm >= 0).
  ContactParameters sampleContact(std::mt19937_64& rng) const;
  /// The control plus N(0, sd^2) noise per dimension (sd from <Uncertainty control>), clipped to
  /// [-1, 1]. `size` numbers are read from `control` and written to `noisy`.
  void perturbControl(const double* control, double* noisy, std::size_t size,
                      std::mt19937_64& rng) const;
  /// Moves every movable object and the target of `state` by a draw from its initial pose
  /// uncertainty (x, y, yaw): the paper's U_init. Velocities are left as they are.
  void sampleInitialPoses(double* state, std::mt19937_64& rng) const;

  /// Standard deviations of a body's initial pose uncertainty (zero for robot bodies).
  const core::PoseUncertainty& initialUncertainty(std::size_t body) const;
  bool hasUncertainty() const;  ///< false when every standard deviation is zero

 private:
  const WorldLayout& layout_;
  core::ContactUncertainty contact_;
  ContactParameters mean_;
  std::vector<core::PoseUncertainty> poses_;  ///< per body
};

/// An object's planar pose in a state: x, y of its centre and yaw (rotation about world z).
Eigen::Vector3d planarPose(const double* state, std::size_t body);
/// Sets an object's x, y and yaw in a state, keeping its height and its tilt (the rotation
/// about horizontal axes) as they were.
void setPlanarPose(double* state, std::size_t body, const Eigen::Vector3d& pose);

}  // namespace kautham::physics
