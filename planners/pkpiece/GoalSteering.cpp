#include "kautham/planners/pkpiece/GoalSteering.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace kautham::planners {

namespace {
constexpr double kProbe = 0.5;     // control of a probe step (controls lie in [-1, 1])
constexpr double kDamping = 1e-3;  // m per step: keeps the least squares tame near singularities
// Makes a turn comparable to a move for the least squares, as the goal's distance does:
// turning the gripper by 0.1 rad counts like moving it 1 cm.
constexpr double kMetresPerRadian = 0.1;
// The longest straight move a clearing motion aims for: the Jacobian is a linearisation, and
// the tree steers again from where a shorter move ends.
constexpr double kMaxStride = 0.1;  // m
// The link counts as on the approach line behind the goal point within this of it: about
// the control noise's drift over a move, well inside the goal's tolerance.
constexpr double kOnApproachLine = 0.01;  // m
// The link counts as over the line-up point, to be lowered onto it, within this (a lowering
// drifts by about a centimetre).
constexpr double kOverLineUp = 0.03;  // m
// This far above the travel height the link is high above the cans, not near them after a push.
constexpr double kHighAbove = 0.05;  // m
// A gripper pointing further down than the approach by more than this (after a steep push)
// turns only once above the cans: turned low, where a push ends, its fingertips dipped below the
// workspace's floor (yumi_clutter_30, from a push pitched 1.2 rad).
constexpr double kLargeTurn = 0.5;  // rad
// An approach less steep than this (the sine of its angle below horizontal) comes in from the
// side, between the objects on the table.
constexpr double kSideApproach = 0.5;

/// The rotation vector (axis times angle) of a rotation matrix.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd turn(rotation);
  return turn.angle() * turn.axis();
}
}  // namespace

Eigen::Matrix3d GoalSteering::pitchedApproach(const physics::PlanningContext& context,
                                              double pitch) {
  const Eigen::Matrix3d& nominal = context.goal().nominalGoalPose().linear();
  const physics::GoalSpec& spec = context.goal().spec();
  if (!spec.approach || pitch == 0.0) return nominal;
  const Eigen::Vector3d across = spec.approach->cross(Eigen::Vector3d::UnitZ());
  if (across.norm() < 1e-9) return nominal;  // a vertical approach
  return Eigen::AngleAxisd(-pitch, across.normalized()) * nominal;
}

GoalSteering::GoalSteering(const physics::PlanningContext& context, MotionEvaluator& evaluator,
                           bool clearing, const PushSettings& push, bool kinematic,
                           const ApproachSettings& approach)
    : context_(context),
      approachTurn_(pitchedApproach(context, approach.pitch)),
      evaluator_(evaluator),
      end_(context, pitchedApproach(context, approach.pitch), approach.shift),
      clearing_(context, push, &end_),
      clearingOn_(clearing),
      pushSpeed_(push.speed),
      finalApproach_(approach.lineUp),
      approachSpeed_(approach.speed),
      moveSpeed_(approach.moveSpeed) {
  if (kinematic) kinematic_.emplace(context);
}

double GoalSteering::rankDistance(const double* state) const {
  if (clearingOn_)
    if (std::optional<ClearingPush::Step> step = clearing_.next(state))
      return kBlockedRank + step->remaining;
  return context_.goal().searchDistance(state);
}

double GoalSteering::learningRank(const double* state) const {
  if (clearingOn_)
    if (const std::optional<double> left = clearing_.clearingLeft(state))
      return kBlockedRank + *left;
  return context_.goal().searchDistance(state);
}

std::optional<NominalMotion> GoalSteering::towardsGoal(const double* start) const {
  if (context_.goal().spec().joints.size() > 0) return std::nullopt;
  // While an object fills the goal's free space, the straight move at the goal point only
  // shoves it on towards the target: steer the clearing push instead, or (without it) keep
  // the random candidates.
  if (clearingOn_)
    if (const std::optional<ClearingPush::Step> step = clearing_.next(start))
      return steer(start, step->waypoint, step->orientation,
                   step->pushing ? pushSpeed_ : moveSpeed_);
  const std::optional<GoalEnd::Pose> end = end_.clearPose(start);
  if (!end) return std::nullopt;
  if (const std::optional<Aim> lineUp = lineUpAim(start, *end))
    return steer(start, lineUp->position, lineUp->orientation, moveSpeed_);
  if (const std::optional<Aim> up = riseAim(start))
    return steer(start, up->position, up->orientation, moveSpeed_);
  return steer(start, end->point, end->turn, approachSpeed_, Strides::Even);
}

std::optional<GoalSteering::Aim> GoalSteering::lineUpAim(const double* state,
                                                         const GoalEnd::Pose& end) const {
  const physics::GoalSpec& spec = context_.goal().spec();
  if (finalApproach_ <= 0.0 || !spec.approach) return std::nullopt;
  const Eigen::Vector3d& approach = end.approach;
  const Eigen::Vector3d& goal = end.point;
  const Eigen::Vector3d link = context_.layout().goalLinkPosition(state);
  const Eigen::Vector3d fromGoal = link - goal;
  const double along = fromGoal.dot(approach);  // negative behind the goal point
  const double offLine = (fromGoal - along * approach).norm();
  // On the line, behind the goal point and no further back than the line-up point (give or
  // take the same margin): straight in from here.
  if (offLine <= kOnApproachLine && along <= kOnApproachLine &&
      along >= -finalApproach_ - kOnApproachLine)
    return std::nullopt;
  const Eigen::Matrix3d& turn = end.turn;
  const Eigen::Vector3d lineUp = goal - finalApproach_ * approach;
  // A side approach among the cans, from a push that ended low: up first, still turned as the
  // push left it, to the travel height above the cans; turned on the way, the fingers swung into
  // the cans and the target. Then over the line-up point, turned, and down onto it (straight
  // from the travel height to the line-up point, kuka_clutter_20 solved 5 of 10 seeds, against
  // 8). From high above the cans (the arm's start), straight at the goal point as before: the
  // arm at the line-up point pressed its forearm on kuka_clutter_5's can3, 26 cm behind the
  // pre-grasp, and tipped it.
  const bool side = std::abs(approach.z()) < kSideApproach;
  if (!side) return Aim{lineUp, turn};
  const double travel = std::max(lineUp.z(), clearing_.travelHeight());
  if (link.z() > travel + kHighAbove) return std::nullopt;
  const Transfer transfer = transferOver(link, lineUp, travel, kOverLineUp, kOnApproachLine);
  if (transfer.leg == Transfer::Leg::Up)
    return Aim{transfer.waypoint, context_.layout().goalLinkOrientation(state)};
  return Aim{transfer.waypoint, turn};
}

std::optional<GoalSteering::Aim> GoalSteering::riseAim(const double* state) const {
  const physics::GoalSpec& spec = context_.goal().spec();
  if (!clearingOn_ || !spec.approach || std::abs(spec.approach->normalized().z()) >= kSideApproach)
    return std::nullopt;
  const Eigen::Matrix3d turn = context_.layout().goalLinkOrientation(state);
  // How much further down the gripper points than the approach asks.
  if (pitchBelowLevel(turn) - pitchBelowLevel(approachTurn_) <= kLargeTurn) return std::nullopt;
  const Eigen::Vector3d link = context_.layout().goalLinkPosition(state);
  const double travel = clearing_.travelHeight();
  // Up first, turned as it is; there, turned in place (turned on the way down, its fingers
  // swung into yumi_clutter_30's target).
  if (link.z() < travel - kOnApproachLine)
    return Aim{Eigen::Vector3d(link.x(), link.y(), travel), turn};
  return Aim{link, approachTurn_};
}

std::optional<Eigen::MatrixXd> GoalSteering::probedJacobian(const double* start) const {
  const auto& si = context_.spaceInformation();
  const auto dimension = static_cast<Eigen::Index>(si->getControlSpace()->getDimension());
  std::vector<NominalMotion> probes(static_cast<std::size_t>(dimension) + 1);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    probes[i].control.assign(static_cast<std::size_t>(dimension), 0.0);
    if (i > 0) probes[i].control[i - 1] = kProbe;
    probes[i].steps = 1;
  }
  const std::vector<NominalRun> runs = evaluator_.runNominals(start, probes, false);
  for (const NominalRun& run : runs)
    if (run.steps == 0) return std::nullopt;
  const physics::WorldLayout& layout = context_.layout();
  const Eigen::Vector3d drift = layout.goalLinkPosition(runs[0].end.data());
  const Eigen::Matrix3d driftTurn = layout.goalLinkOrientation(runs[0].end.data());
  Eigen::MatrixXd jacobian(6, dimension);
  for (Eigen::Index i = 0; i < dimension; ++i) {
    const double* probed = runs[static_cast<std::size_t>(i) + 1].end.data();
    jacobian.col(i).head<3>() = (layout.goalLinkPosition(probed) - drift) / kProbe;
    jacobian.col(i).tail<3>() =
        rotationVector(layout.goalLinkOrientation(probed) * driftTurn.transpose()) / kProbe;
  }
  return jacobian;
}

std::optional<NominalMotion> GoalSteering::steer(const double* start, const Eigen::Vector3d& target,
                                                 const Eigen::Matrix3d& orientation,
                                                 double maxSpeed, Strides strides) const {
  const auto& si = context_.spaceInformation();
  const physics::WorldLayout& layout = context_.layout();
  const double longest = strideAt(maxSpeed);
  if (kinematic_) {
    Eigen::Vector3d aim = target;
    const Eigen::Vector3d from = layout.goalLinkPosition(start);
    const double distance = (target - from).norm();
    if (maxSpeed > 0.0 && distance > longest)
      aim = from + strideOf(distance, longest, strides) * (target - from).normalized();
    if (std::optional<NominalMotion> motion =
            kinematic_->towards(start, aim, orientation, maxSpeed))
      return motion;
  }
  ++jacobianAims_;
  const std::optional<Eigen::MatrixXd> perControl = probedJacobian(start);
  if (!perControl) return std::nullopt;
  // Per step and unit of control: the link's displacement, and its turn in metres
  // (kMetresPerRadian), with what the goal does not care about projected out.
  const Eigen::Matrix3d startTurn = layout.goalLinkOrientation(start);
  const Eigen::Matrix3d turnRows = turnProjection(startTurn);
  Eigen::MatrixXd jacobian(6, perControl->cols());
  jacobian.topRows<3>() = perControl->topRows<3>();
  jacobian.bottomRows<3>() = kMetresPerRadian * turnRows * perControl->bottomRows<3>();
  Eigen::Matrix<double, 6, 1> toGo;
  toGo.head<3>() = target - layout.goalLinkPosition(start);
  toGo.tail<3>() = kMetresPerRadian * turnRows * turnTo(startTurn, orientation);
  const double toGoLength = toGo.norm();
  if (maxSpeed > 0.0 && toGoLength > longest)
    toGo *= strideOf(toGoLength, longest, strides) / toGoLength;
  const Eigen::Matrix<double, 6, 6> damped =
      jacobian * jacobian.transpose() +
      kDamping * kDamping * Eigen::Matrix<double, 6, 6>::Identity();
  const Eigen::VectorXd perStep = jacobian.transpose() * damped.ldlt().solve(toGo);
  // The fewest steps whose control stays within the limits (and the link below maxSpeed).
  return pacedMotion(*si, std::vector<double>(perStep.data(), perStep.data() + perStep.size()),
                     perStep.cwiseAbs().maxCoeff(), toGo.head<3>().norm(), maxSpeed);
}

double GoalSteering::strideOf(double distance, double longest, Strides strides) {
  if (distance <= longest) return distance;
  if (strides == Strides::Longest) return longest;
  // The fewest equal strides: the last one ends on the target, not a full stride in from
  // wherever the one before ended (inside the goal region, short of its centre).
  return distance / std::ceil(distance / longest);
}

double GoalSteering::strideAt(double maxSpeed) const {
  if (maxSpeed <= 0.0) return kMaxStride;
  // A motion lasts at most the longest control duration: a longer stride would go faster.
  const auto& si = *context_.spaceInformation();
  const double longest = maxSpeed * si.getPropagationStepSize() * si.getMaxControlDuration();
  return std::min(kMaxStride, longest);
}

Eigen::Matrix3d GoalSteering::turnProjection(const Eigen::Matrix3d& turn) const {
  const physics::GoalSpec& spec = context_.goal().spec();
  if (!spec.approach) return Eigen::Matrix3d::Zero();
  if (spec.levelAxis) return Eigen::Matrix3d::Identity();
  // Only the approach is asked for: a turn about the link's own +z changes nothing.
  const Eigen::Vector3d axis = turn.col(2);
  return Eigen::Matrix3d::Identity() - axis * axis.transpose();
}

Eigen::Vector3d GoalSteering::turnTo(const Eigen::Matrix3d& turn,
                                     const Eigen::Matrix3d& orientation) const {
  const physics::GoalSpec& spec = context_.goal().spec();
  if (!spec.approach) return Eigen::Vector3d::Zero();
  if (!spec.levelAxis) {
    const Eigen::Vector3d axis = turn.col(2);
    const Eigen::Vector3d approach = spec.approach->normalized();
    const Eigen::Vector3d normal = axis.cross(approach);
    const double angle = std::atan2(normal.norm(), axis.dot(approach));
    return normal.norm() > 1e-12 ? Eigen::Vector3d(angle * normal.normalized())
                                 : Eigen::Vector3d::Zero();
  }
  // A two-finger gripper is symmetric about its approach (the link's +z): of the two turns
  // to `orientation`, aim at the nearer.
  const Eigen::Matrix3d flipped = orientation * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d toGoal = rotationVector(orientation * turn.transpose());
  const Eigen::Vector3d toFlipped = rotationVector(flipped * turn.transpose());
  return toGoal.norm() <= toFlipped.norm() ? toGoal : toFlipped;
}

}  // namespace kautham::planners
