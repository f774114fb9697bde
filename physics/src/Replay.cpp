#include "kautham/physics/Replay.h"

#include <ompl/control/spaces/RealVectorControlSpace.h>

namespace kautham::physics {

ReplayResult replay(PlanningContext& context, const std::vector<ControlStep>& controls) {
  const auto& si = context.spaceInformation();
  const double stepSize = si->getPropagationStepSize();
  ompl::base::State* current = si->allocState();
  ompl::base::State* next = si->allocState();
  const double* values = WorldStateSpace::values(current);
  std::copy(context.startState().begin(), context.startState().end(),
            WorldStateSpace::values(current));
  ompl::control::Control* control = si->allocControl();
  auto* velocities = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;

  ReplayResult result;
  result.frames.push_back({0.0, context.startState(), Violation::None, {}});
  double time = 0.0;
  for (const ControlStep& step : controls) {
    std::copy(step.values.begin(), step.values.end(), velocities);
    for (unsigned i = 0; i < step.steps && result.firstViolation == Violation::None; ++i) {
      context.world().takeTouchedBodies();
      context.propagator().propagate(current, control, stepSize, next);
      si->copyState(current, next);
      time += stepSize;
      const Violation violation = context.validityChecker().check(values);
      result.frames.push_back({time, std::vector<double>(values, values + si->getStateDimension()),
                               violation, context.world().takeTouchedBodies()});
      result.firstViolation = violation;
    }
  }
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
