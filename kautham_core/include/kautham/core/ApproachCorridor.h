#pragma once

#include <string>
#include <vector>

#include "kautham/core/Problem.h"

namespace kautham::core {

/// The movable objects that stand, at their home poses, on a side pre-grasp or in the straight
/// corridor before it: the strip the open gripper sweeps moving along the approach direction
/// (its horizontal part) at grasp height, `approachCorridor` metres up to the goal and on
/// through the goal's free space. The strip is as wide as the free space across the fingers
/// (along the level axis). An object counts when its footprint (the horizontal bounding box of
/// its collision shapes) overlaps the strip. Empty when the goal has no corridor.
std::vector<std::string> approachBlockers(const Problem& problem, const GoalRegion& goal);

}  // namespace kautham::core
