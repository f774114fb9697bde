#pragma once

#include <vector>

#include <Eigen/Core>

#include "kautham/physics/ContactParameters.h"

namespace kautham::planners {

/// Whether a motion watches the goal region, and what it does there.
enum class GoalStop : unsigned {
  Ignore = 0,    ///< a particle: the goal is judged afterwards, from its recorded states
  Entering = 1,  ///< stop at the first state in the goal
  Leaving = 2,   ///< go on while inside; stop at the last state before leaving
};

/// One motion (a particle, or a candidate's nominal run), self-contained: everything random about
/// it was drawn beforehand (by MotionEvaluator, in the planner's process), so any process with a
/// copy of the planning context runs it to the same result, bit for bit.
struct ParticleJob {
  std::vector<double> start;                                  ///< the sampled start state
  std::vector<double> control;                                ///< the noisy control
  unsigned steps = 0;                                         ///< propagation steps
  physics::ContactParameters contact;                         ///< the sampled D
  Eigen::Vector3d targetReference = Eigen::Vector3d::Zero();  ///< where the target must stay
  /// Step counts (ascending, at most `steps`) after which the state is kept in the result.
  std::vector<unsigned> recordAfter;
  GoalStop goalStop = GoalStop::Ignore;
  /// A tighter limit than the scene's maxTilt for the movable objects (rad; 0: the scene's
  /// alone): a state where one tilts further is invalid (tilt_margin, nominal runs only).
  double tiltLimit = 0.0;
  /// A tighter limit than the scene's targetTolerance for the target's drift from
  /// targetReference (m; 0: the scene's alone): a state where it drifts further is invalid
  /// (target_margin, nominal runs only).
  double targetDriftLimit = 0.0;
};

/// What a particle motion gave.
struct ParticleResult {
  bool valid = true;        ///< every state of the motion was valid
  std::vector<double> end;  ///< the last state (the first invalid one if it stopped early)
  /// The valid states after the job's recordAfter steps, as far as the motion stayed valid.
  std::vector<std::vector<double>> recorded;
  /// Steps after which it was first in the goal (0: never, or the job ignored the goal).
  unsigned goalFrom = 0;
};

/// What one execution of a whole plan gave (PlanVerifier): how far through the plan it got.
struct ExecutionOutcome {
  bool reached = false;  ///< valid all along and ended in the goal
  /// The plan's controls it ran without breaking a rule: the index of the control during which
  /// it broke one, or all of them (reached, or valid to the end and short of the goal).
  unsigned controlsPassed = 0;
};

}  // namespace kautham::planners
