#pragma once

#include "kautham/core/Problem.h"

namespace kautham::core {

/// Kautham's physics planners with `only final link position?` 1 reach a goal when the chain's
/// final link lies within 5 cm of where it is at the goal configuration (its goal region
/// compares positions, not joint values). That link is where the robot's chain ends or first
/// branches: the gripper of Kautham's planar chain, whose fingers branch from it.
std::string chainEndLink(const KinematicModel& model);

/// The configuration goal as such a position goal: the chain's end link at the goal
/// configuration, within Kautham's threshold, in the world frame.
GoalRegion finalLinkGoal(const Problem& problem, const GoalRegion& configuration);

}  // namespace kautham::core
