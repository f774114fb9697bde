#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/KinematicModel.h"

namespace kautham::core {

/// What each movable joint's motor has to accelerate at joint values `q` (in the order of
/// KinematicModel::movableJoints()): for a prismatic joint the mass of every link beyond it (kg),
/// for a revolute one their moment of inertia about its axis (kg m^2). A motor's effort over it
/// is the fastest the joint can speed up or slow down with the rest of the robot still.
std::vector<double> jointInertias(const KinematicModel& model, const Eigen::Isometry3d& base,
                                  const std::vector<double>& q);

}  // namespace kautham::core
