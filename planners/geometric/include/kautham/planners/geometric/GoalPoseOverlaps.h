#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "kautham/physics/PlanningContext.h"

namespace kautham::planners::geometric {

/// What the robot overlaps at a pre-grasp pose in the start scene: inverse kinematics finds arm
/// poses for the goal (from the start's joints, then from random seeds), and the frozen scene
/// says what each touches. An object that every pose touches must be moved by any plan: how
/// much a scene asks of a pushing planner beyond clearing the free space.
struct GoalPoseOverlaps {
  int poses = 0;      ///< arm poses found for the goal
  int touchFree = 0;  ///< of those, touching nothing
  /// Per object touched (fixed obstacles as "(fixed)", the target by its name): how many of
  /// the poses touch it, most first.
  std::vector<std::pair<std::string, int>> objects;
};

/// Tries `attempts` inverse kinematics solutions for the query's pre-grasp (its position,
/// approach and level axis, within 5 mm and 0.05 rad) with a fixed random seed, so the answer
/// is the same every time. Empty (no poses) for a configuration goal or a goal without an
/// approach direction.
GoalPoseOverlaps goalPoseOverlaps(physics::PlanningContext& context, int attempts = 40,
                                  std::uint32_t seed = 7);

}  // namespace kautham::planners::geometric
