#pragma once

#include <vector>

#include "kautham/physics/Replay.h"

namespace kautham::planners {

/// A planner whose plan holds more than OMPL's control path can say: the task planner's
/// grasps and releases. solve() takes the controls from it instead of from the path.
class ControlReporter {
 public:
  virtual ~ControlReporter() = default;
  /// The plan's controls, with their gripper actions.
  virtual std::vector<physics::ControlStep> solutionControls() const = 0;
};

}  // namespace kautham::planners
