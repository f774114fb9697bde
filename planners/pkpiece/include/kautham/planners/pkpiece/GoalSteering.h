#pragma once

#include <optional>

#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"

namespace kautham::planners {

/// A control that drives the goal link straight at the goal region's centre, for p-KPIECE's
/// goal-biased expansions (not in the paper: uniform random joint velocities enter a 3 cm
/// region with the right approach about once in a thousand candidates).
///
/// Estimated from the physics itself, so it needs no kinematic model: one propagation step
/// with no control and one per control dimension give the link's displacement per unit of
/// control (a numerical Jacobian); damped least squares turns the displacement still to go,
/// spread over the fewest steps the control limits allow, into a control.
///
/// None while an object fills the goal's free space (WorkspaceGoal::freeSpaceBlocker): the
/// straight move would push that object on to the target.
class GoalSteering {
 public:
  GoalSteering(const physics::PlanningContext& context, MotionEvaluator& evaluator);

  /// The steering motion from `start`; none when a probe step is invalid, the goal is a
  /// configuration, or the goal's free space is blocked.
  std::optional<NominalMotion> towardsGoal(const double* start) const;

 private:
  const physics::PlanningContext& context_;
  MotionEvaluator& evaluator_;
};

}  // namespace kautham::planners
