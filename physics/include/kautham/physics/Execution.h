#pragma once

#include <cstddef>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kautham/physics/ContactParameters.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/Replay.h"

namespace kautham::physics {

/// Stands for the fixed obstacles among ExecutionResult::touchedOffThePose.
inline constexpr const char* kFixedObstacle = "a fixed obstacle";

/// One open-loop execution of a plan in a sampled world (one particle of the whole plan).
struct ExecutionResult {
  bool reachedGoal = false;  ///< valid all along and ends inside the goal region
  Violation firstViolation = Violation::None;
  double finalGoalDistance = 0.0;
  double time = 0.0;               ///< seconds of motion executed (up to the violation)
  std::vector<double> startState;  ///< the sampled start (the context's when not sampling)
  std::vector<double> finalState;  ///< the state at the end (or at the violation)
  /// The object that broke the rule (a layout body), when an object did
  std::optional<std::size_t> offendingObject;
  /// The control during which the run broke a rule (an index into the plan's controls), when it
  /// did: which move of a plan is fragile (a push that tips a can, a descent onto one).
  std::optional<std::size_t> brokenInControl;
  /// A valid run that ended with the gripper where the goal asks, turned as it asks, but missed
  /// it: the movable objects in the free space between its fingers (WorkspaceGoal::poseReached;
  /// the pre-grasp is not clear).
  std::vector<std::string> leftInFreeSpace;
  /// A valid run that ended off the goal pose: what it missed (for a region's goal).
  WorkspaceGoal::PoseMiss poseMissed;
  /// And what the robot touches there (the objects' names, and kFixedObstacle): what may have
  /// stopped it short. Empty: nothing holds it there; it was put off its course earlier.
  std::vector<std::string> touchedOffThePose;
  /// Where the goal link was at the end of each control run in full (compared with the nominal
  /// execution's, which control put a run off its course).
  std::vector<Eigen::Vector3d> linkAfterControl;
  /// What the robot touched during each control (layout bodies, robot bodies excluded), up to
  /// the one that broke a rule: what may have put it off its course there.
  std::vector<std::vector<int>> touchedInControl;
  ContactParameters contact;       ///< the contact parameters of the run
  std::size_t rejectedStarts = 0;  ///< sampled starts redrawn because things interpenetrated
};

/// Executes a plan's controls open loop from the context's start state, one propagation step
/// at a time through the context's propagator (as physics::replay does), and stops at the
/// first invalid state.
///
/// With `sampleUncertainty` (the paper's section III-C, with UncertaintySampler's draws in this
/// order): the movable objects' and the target's initial poses are drawn (U_init), redrawn (at
/// most 100 times) while two things interpenetrate by more than 2 mm or the start is invalid;
/// then the contact parameters for the whole run (U_D); then, for each control of the plan,
/// one noisy control (U_epsilon), held for all its steps. The target-moved check and a goal
/// region given relative to an object follow that object's sampled start pose.
/// Without it, nothing is drawn and the result is exactly physics::replay's.
///
/// The world's contact parameters are restored afterwards, so the context can be reused.
ExecutionResult execute(PlanningContext& context, const std::vector<ControlStep>& controls,
                        std::mt19937_64& rng, bool sampleUncertainty);

}  // namespace kautham::physics
