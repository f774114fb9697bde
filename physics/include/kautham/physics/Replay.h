#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "kautham/physics/PlanningContext.h"

namespace kautham::physics {

/// What the gripper does at the start of a control (the task planner's plans carry objects).
enum class GripperAction { None, Grasp, Release };
const char* toString(GripperAction action);  ///< "", "grasp" or "release"

/// One control of a plan: joint velocity targets held for `steps` propagation steps, after the
/// gripper's action, if any.
struct ControlStep {
  std::vector<double> values;  ///< the normalized control, one number per control in [-1, 1]
  unsigned steps = 0;
  GripperAction action = GripperAction::None;
  int object = -1;  ///< the body a Grasp takes hold of (index into the layout's bodies)
};

/// Applies a control's gripper action to the world (in `state`, before the control): a grasp
/// holds the object only if it is within the gripper's reach (World::attach), else nothing
/// is held and the plan runs on without it, as a real gripper that closes on air.
void applyGripperAction(World& world, const ControlStep& step, const double* state);

/// Adds to `state`'s contact flags whether the robot touches a fixed obstacle or the target
/// where a run ends (the world in that state). A step records the contacts it starts from, so
/// the last state's would be judged only by a step that never comes: a run that ends with a
/// finger on the target has touched it.
void addFinalContacts(World& world, double* state);

/// The world after each propagation step of a replay (frame 0 is the start state).
struct ReplayFrame {
  double time = 0.0;
  std::vector<double> state;
  Violation violation = Violation::None;
  std::vector<int> touched;  ///< bodies the robot touched during the step to this frame
};

struct ReplayResult {
  std::vector<ReplayFrame> frames;
  Violation firstViolation = Violation::None;
  double finalGoalDistance = 0.0;
  bool reachedGoal = false;  ///< valid all along and ends inside the goal region

  const std::vector<double>& finalState() const { return frames.back().state; }
};

/// How far a movable object ended up from where it started.
struct ObjectDisplacement {
  std::string name;
  double distance = 0.0;  ///< metres
};

/// Movable objects that moved more than `threshold` metres between the first and last frame.
std::vector<ObjectDisplacement> movedObjects(const WorldLayout& layout, const ReplayResult& replay,
                                             double threshold = 0.005);

/// Re-propagates a plan's controls from the context's start state, one propagation step at
/// a time as the planners do, and stops at the first invalid state.
ReplayResult replay(PlanningContext& context, const std::vector<ControlStep>& controls);

}  // namespace kautham::physics
