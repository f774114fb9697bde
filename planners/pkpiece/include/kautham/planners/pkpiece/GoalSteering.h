#pragma once

#include <cstdint>
#include <optional>

#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/pkpiece/ClearingPush.h"
#include "kautham/planners/pkpiece/GoalEnd.h"
#include "kautham/planners/pkpiece/JointSpaceSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/PKpieceSettings.h"

namespace kautham::planners {

/// How the goal steering makes its approach to the goal point: p-KPIECE's final_approach,
/// approach_pitch and approach_speed parameters.
struct ApproachSettings {
  double lineUp = 0.0;  ///< m behind the goal point the straight last move starts (0: none)
  double pitch = 0.0;   ///< rad the approach points the gripper down
  /// m/s the last move goes at most (0: as fast as the joints allow, which the arm lags).
  double speed = 0.0;
  /// m from the goal point the gripper may end instead, where an object reaches into the free
  /// space at the goal point (GoalEnd; 0: the goal point only).
  double shift = 0.0;
  /// m/s the link goes on its other moves: to and up from a push, and to the line-up point.
  double moveSpeed = 0.3;
};

/// The clearing push as p-KPIECE's parameters set it, for a search with `seed` (OMPL's: what
/// `kautham plan --seed` sets), which draws the trees' push angles.
inline PushSettings pushSettingsOf(const PKpieceSettings& s, std::uint64_t seed) {
  return {s.pushPitch,
          s.clearBehind,
          s.corridorPitch,
          s.pushBelowCentre,
          s.pushSpeed,
          s.crowdedPitch,
          s.crowdedSlide,
          s.pushAngleSpread,
          s.pushAngleAfter,
          s.pushAngleGeneration,
          seed};
}
/// The approach as p-KPIECE's parameters set it.
inline ApproachSettings approachSettingsOf(const PKpieceSettings& s) {
  return {s.finalApproach, s.approachPitch, s.approachSpeed, s.goalShift, s.moveSpeed};
}

/// A control that drives the goal link to the goal region's centre, for p-KPIECE's
/// goal-biased expansions (not in the paper: uniform random joint velocities enter a 3 cm
/// region with the right approach about once in a thousand candidates).
///
/// Aimed by inverse kinematics and a straight line in joint space (JointSpaceSteering), or
/// (`kinematic` off, and where inverse kinematics finds no pose) by a numerical Jacobian from
/// the physics itself: one propagation step with no control and one per control dimension give
/// the link's displacement per unit of control; damped least squares turns the displacement
/// still to go, spread over the fewest steps the control limits allow, into a control.
///
/// While an object fills the goal's free space (WorkspaceGoal::freeSpaceBlocker) the straight
/// move would push that object on to the target: it steers the ClearingPush instead (or,
/// with `clearing` off, not at all); with `clearBehind`, also while an object stands in the
/// corridor behind the goal, where the arm will be.
///
/// With a speed cap (`ApproachSettings::speed`) the last move to the goal point goes in the fewest
/// equal strides: a full stride first could end inside the goal region, short of its centre,
/// where the search stops (yumi_clutter_5: 1.1 cm off).
///
/// With a line-up distance (`ApproachSettings::lineUp`), a link that is not yet on the approach
/// line behind the goal point is first steered to a point that far behind it, turned as the goal
/// asks, and from there straight in. Steered straight at the goal point from beside it, the gripper
/// turned and swept its fingers past the target on the way (kuka_clutter_10: the target touched in
/// up to 33 of 100 executions).
class GoalSteering {
 public:
  /// Blocked states rank behind every clear one by at least this much (m).
  static constexpr double kBlockedRank = 0.5;

  /// `push`: how the clearing push is done (its pitch, the corridor it clears behind the goal
  /// point, its height and speed). `kinematic`: aim by inverse kinematics and a line in joint
  /// space (JointSpaceSteering), with the Jacobian only where inverse kinematics finds no pose.
  /// `approach`: the straight last move's length, the gripper's pitch on the approach and the
  /// last move's speed.
  GoalSteering(const physics::PlanningContext& context, MotionEvaluator& evaluator, bool clearing,
               const PushSettings& push, bool kinematic, const ApproachSettings& approach = {});
  // Its clearing push keeps a pointer to its GoalEnd: not copied, not moved.
  GoalSteering(const GoalSteering&) = delete;
  GoalSteering& operator=(const GoalSteering&) = delete;

  /// The steering motion from `start`; none when no aim is found (a probe step is invalid), the
  /// goal is a configuration, or the goal's free space is blocked and there is no clearing push.
  std::optional<NominalMotion> towardsGoal(const double* start) const;
  /// How far `state` is from the goal, for choosing what the goal bias grows: the search
  /// distance, or while the free space is blocked (and clearing is on) kBlockedRank plus
  /// what remains of the clearing push.
  double rankDistance(const double* state) const;
  /// How near `state` is to the goal by a measure that does not depend on the trees' push
  /// angles, for PushAngles to learn from: the search distance, or while the free space is
  /// blocked (and clearing is on) kBlockedRank plus ClearingPush::clearingLeft(). rankDistance()
  /// would do for neither: the length of a push still to go shrinks as it turns towards the
  /// target (docs/planners.md, "Learned from the trees before").
  double learningRank(const double* state) const;
  /// Motions aimed by the Jacobian (inverse kinematics found no pose, or `kinematic` is off)
  /// since construction or resetCount().
  std::uint64_t jacobianAims() const { return jacobianAims_; }
  void resetCount() { jacobianAims_ = 0; }
  /// Which of p-KPIECE's trees it steers for (ClearingPush::setTree).
  void setTree(std::uint64_t tree) { clearing_.setTree(tree); }
  /// The angles the trees push at, which learn from how near each tree got (PushAngles).
  PushAngles& pushAngles() { return clearing_.angles(); }
  /// Adds aims made elsewhere (a tree grown in a process of its own).
  void addJacobianAims(std::uint64_t aims) { jacobianAims_ += aims; }

 private:
  /// The goal's nominal orientation pitched down by `pitch` about the horizontal across the
  /// approach (unchanged without a side approach).
  static Eigen::Matrix3d pitchedApproach(const physics::PlanningContext& context, double pitch);
  /// Where the goal link heads next, and turned how.
  struct Aim {
    Eigen::Vector3d position;
    Eigen::Matrix3d orientation;
  };
  /// Where the link heads to line up for the straight last move, when it is not on that line
  /// yet: the line-up point on the approach line, the line-up distance behind the goal point,
  /// turned as the goal asks. For a side approach near the cans: up to
  /// ClearingPush::travelHeight() first (as it is turned), over the line-up point, and down
  /// onto it; from high above them, none (straight at `end`, where the gripper ends). None
  /// without an approach.
  std::optional<Aim> lineUpAim(const double* state, const GoalEnd::Pose& end) const;
  /// Without a line-up, for a side approach with the clearing push: from below the travel
  /// height with the gripper pointing much further down than the approach (after a steep
  /// push), straight up to that height, turned as it is; there, turned in place to the
  /// approach's posture.
  std::optional<Aim> riseAim(const double* state) const;
  /// How a move longer than a stride is cut: a longest stride first (the tree steers again
  /// from its end), or into the fewest equal strides, so that the last ends on the target.
  enum class Strides { Longest, Even };
  /// A control that drives the goal link straight at `target` and turns it towards
  /// `orientation` (as far as the goal cares about turns); with `maxSpeed` > 0 (m/s) no
  /// faster than that and at most a stride far, cut as `strides` says.
  std::optional<NominalMotion> steer(const double* start, const Eigen::Vector3d& target,
                                     const Eigen::Matrix3d& orientation, double maxSpeed,
                                     Strides strides = Strides::Longest) const;
  /// How far the next stride goes of `distance` still to go, at most `longest`.
  static double strideOf(double distance, double longest, Strides strides);
  /// The longest straight move aimed for at `maxSpeed` (m/s; 0: no limit): kMaxStride, or
  /// less where a motion of the longest control duration would have to go faster.
  double strideAt(double maxSpeed) const;
  /// The link's displacement and turn (world rotation vector) per step and unit of each control,
  /// from one physics step per control (and one without); none when a probe step is invalid.
  std::optional<Eigen::MatrixXd> probedJacobian(const double* start) const;
  /// What of a turn (world rotation vector) the goal cares about: all of it with a level
  /// axis, none without an approach, the part that tilts the approach axis otherwise.
  Eigen::Matrix3d turnProjection(const Eigen::Matrix3d& turn) const;
  /// The rotation vector (world frame) from the goal link's orientation `turn` to
  /// `orientation` (with a level axis; otherwise to the goal's approach).
  Eigen::Vector3d turnTo(const Eigen::Matrix3d& turn, const Eigen::Matrix3d& orientation) const;

  const physics::PlanningContext& context_;
  /// How the approach turns the goal link: the goal's nominal orientation pitched down by
  /// the approach's pitch about the horizontal across the approach.
  Eigen::Matrix3d approachTurn_;
  MotionEvaluator& evaluator_;
  GoalEnd end_;  ///< where the gripper ends (before clearing_, which asks it)
  ClearingPush clearing_;
  bool clearingOn_;
  double pushSpeed_;      ///< m/s
  double finalApproach_;  ///< m, the line-up distance
  double approachSpeed_;  ///< m/s; 0: no limit
  double moveSpeed_;      ///< m/s
  std::optional<JointSpaceSteering> kinematic_;
  mutable std::uint64_t jacobianAims_ = 0;
};

}  // namespace kautham::planners
