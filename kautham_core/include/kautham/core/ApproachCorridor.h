#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/Problem.h"

namespace kautham::core {

/// The movable objects that stand, at their home poses, on a side pre-grasp or in the straight
/// corridor before it: the strip the open gripper sweeps moving along the approach direction
/// (its horizontal part) at grasp height, `approachCorridor` metres up to the goal and on
/// through the goal's free space. The strip is as wide as the free space across the fingers
/// (along the level axis). An object counts when its footprint (the horizontal bounding box of
/// its collision shapes) overlaps the strip. Empty when the goal has no corridor.
std::vector<std::string> approachBlockers(const Problem& problem, const GoalRegion& goal);

/// An interval along one axis of the table plane.
struct Interval {
  double lo, hi;
  bool overlaps(const Interval& other) const { return lo < other.hi && other.lo < hi; }
};

/// The interval a footprint (a world-aligned box, seen from above) covers along a horizontal
/// unit `direction`, measured from `origin`.
Interval projectFootprint(const Eigen::AlignedBox3d& box, const Eigen::Vector2d& origin,
                          const Eigen::Vector2d& direction);

}  // namespace kautham::core
