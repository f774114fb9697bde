#include "kautham/physics/Replay.h"

#include <ompl/control/spaces/RealVectorControlSpace.h>

namespace kautham::physics {

namespace {

/// How far (m) from the object's bounding box the gripper's origin may be for a grasp to hold.
constexpr double kGraspReach = 0.02;

}  // namespace

const char* toString(GripperAction action) {
  switch (action) {
    case GripperAction::Grasp:
      return "grasp";
    case GripperAction::Release:
      return "release";
    default:
      return "";
  }
}

void applyGripperAction(World& world, const ControlStep& step, const double* state) {
  if (step.action == GripperAction::Release) world.release();
  const auto body = static_cast<std::size_t>(step.object);
  if (step.action != GripperAction::Grasp || step.object < 0 ||
      body >= world.layout().bodies.size() || world.layout().bodies[body].role == BodyRole::Robot)
    return;                 // nothing there to hold (a plan file is checked for it when read)
  world.writeState(state);  // attach where the bodies are now
  world.attach(body, kGraspReach);
}

void addFinalContacts(World& world, double* state) {
  const WorldLayout& layout = world.layout();
  // The robot's links alone, as a step's contact events judge them: a held object resting on
  // the table is not the robot touching it.
  const RobotTouches touches = world.robotTouches(-1);
  unsigned flags = layout.flags(state);
  if (touches.fixed) flags |= kRobotTouchedFixed;
  if (touches.target) flags |= kRobotTouchedTarget;
  state[layout.flagsIndex()] = flags;
}

ReplayResult replay(PlanningContext& context, const std::vector<ControlStep>& controls) {
  const auto& si = context.spaceInformation();
  const double stepSize = si->getPropagationStepSize();
  ompl::base::State* current = si->allocState();
  ompl::base::State* next = si->allocState();
  double* values = WorldStateSpace::values(current);
  std::copy(context.startState().begin(), context.startState().end(),
            WorldStateSpace::values(current));
  ompl::control::Control* control = si->allocControl();
  auto* velocities = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;

  ReplayResult result;
  result.frames.push_back({0.0, context.startState(), Violation::None, {}});
  double time = 0.0;
  World& world = context.world();
  const WorldValidityChecker& checker = context.validityChecker();
  world.release();
  for (const ControlStep& step : controls) {
    if (result.firstViolation != Violation::None) break;
    applyGripperAction(world, step, values);
    std::copy(step.values.begin(), step.values.end(), velocities);
    for (unsigned i = 0; i < step.steps && result.firstViolation == Violation::None; ++i) {
      world.takeTouchedBodies();
      context.propagator().propagate(current, control, stepSize, next);
      si->copyState(current, next);
      time += stepSize;
      const Violation violation = checker.check(values, checker.targetStart(), world.held());
      result.frames.push_back({time, std::vector<double>(values, values + si->getStateDimension()),
                               violation, world.takeTouchedBodies()});
      result.firstViolation = violation;
    }
  }
  if (result.firstViolation == Violation::None && result.frames.size() > 1) {
    ReplayFrame& last = result.frames.back();
    addFinalContacts(world, last.state.data());
    last.violation = checker.check(last.state.data(), checker.targetStart(), world.held());
    result.firstViolation = last.violation;
  }
  world.release();
  si->freeControl(control);
  si->freeState(current);
  si->freeState(next);
  result.finalGoalDistance = context.goal().distance(result.finalState().data());
  result.reachedGoal = result.firstViolation == Violation::None &&
                       context.goal().reached(result.finalState().data());
  return result;
}

std::vector<ObjectDisplacement> movedObjects(const WorldLayout& layout, const ReplayResult& replay,
                                             double threshold) {
  std::vector<ObjectDisplacement> moved;
  const double* first = replay.frames.front().state.data();
  const double* last = replay.frames.back().state.data();
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role != BodyRole::Movable) continue;
    const double d = (WorldLayout::position(last, b) - WorldLayout::position(first, b)).norm();
    if (d > threshold) moved.push_back({layout.bodies[b].name, d});
  }
  return moved;
}

}  // namespace kautham::physics
