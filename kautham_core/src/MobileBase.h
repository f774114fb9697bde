#pragma once

#include <vector>

#include "kautham/core/KinematicModel.h"
#include "kautham/core/Problem.h"

namespace kautham::core {

/// Puts a model on Kautham's mobile base: one prismatic joint per <Limits> axis (X, then Y,
/// then Z, along the axes of the <Home> frame) between a new static root and the URDF's root.
/// The new joints come first in movableJoints(), so a control set's DOF order starts with them.
void addMobileBase(KinematicModel& model, const std::vector<BaseAxisLimits>& axes);

}  // namespace kautham::core
