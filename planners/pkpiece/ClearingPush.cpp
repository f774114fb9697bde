#include "kautham/planners/pkpiece/ClearingPush.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "kautham/core/ApproachCorridor.h"
#include "kautham/core/SegmentDistance.h"

namespace kautham::planners {

namespace {
// Beyond the free space's half width, how far beside the object's centre the push starts:
// the object's radius, a finger's thickness and a margin, so the gripper lands clear of it.
constexpr double kStandOff = 0.05;  // m
// How far ahead of the object's centre the push aims: the waypoint stays ahead of the
// object while it moves, so the push goes on until the free space is clear.
constexpr double kPushThrough = 0.03;  // m
// The gripper counts as at the stand-off, or on the line of the push, within this.
constexpr double kOnLine = 0.03;  // m
// The stand-off is reached from this high above the push: lowered onto it, the gripper
// does not sweep through the objects beside it.
constexpr double kAbove = 0.10;  // m
// Between pushes the gripper travels this high above the tallest movable object's top: its
// fingertips, the lowest point of a gripper pointing down, pass over the cans.
constexpr double kOverTops = 0.04;  // m
// The goal link is at the fingertips; the fingers' middle, which should meet the object,
// lies this far back along the approach.
constexpr double kFingerMiddle = 0.025;  // m
// How far the gripper reaches back from the goal link (fingers, palm, wrist): the room a
// stand-off needs lies along this footprint.
constexpr double kFootprint = 0.12;  // m
// Margin above the workspace floor (the goal link may not leave the workspace).
constexpr double kFloorMargin = 0.012;  // m
// What a push still to come after the current one adds to the remaining length: more than
// any single push's own length, so a state with one push done ranks before any state still
// on the one before.
constexpr double kLaterPush = 0.5;  // m
}  // namespace

ClearingPush::ClearingPush(const physics::PlanningContext& context, const PushSettings& settings)
    : context_(context), behind_(settings.behind), belowCentre_(settings.belowCentre) {
  const double pitch = settings.pitch;
  const physics::WorldLayout& layout = context.layout();
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const physics::BodyInfo& body = layout.bodies[b];
    if (body.role != physics::BodyRole::Movable || body.objectIndex < 0) continue;
    const Eigen::AlignedBox3d bounds = core::boundsAtHome(
        context.problem().objects.at(static_cast<std::size_t>(body.objectIndex)));
    footprints_.push_back(
        {b, physics::WorldLayout::position(context.startState().data(), b), bounds});
    travelHeight_ = std::max(travelHeight_, bounds.max().z() + kOverTops);
  }
  travelHeight_ = std::min(travelHeight_, context.problem().workspace.max().z() - kFloorMargin);
  const physics::GoalSpec& spec = context.goal().spec();
  if (!spec.freeSpace || !spec.approach || !spec.levelAxis) return;
  back_ = -*spec.approach;
  back_.z() = 0.0;
  across_ = spec.approach->cross(Eigen::Vector3d::UnitZ());
  if (back_.norm() < 1e-9 || across_.norm() < 1e-9) return;  // a vertical approach
  back_.normalize();
  across_.normalize();
  halfWidth_ = 0.5 * spec.freeSpace->size.dot(spec.levelAxis->normalized().cwiseAbs());
  lowest_ = context.problem().workspace.min().z() + kFloorMargin;
  const Eigen::AngleAxisd pitchDown(-pitch, across_);
  orientation_ = pitchDown * context.goal().nominalGoalPose().linear();
  fingers_ = pitchDown * Eigen::Vector3d(-back_);
  const Eigen::AngleAxisd steepDown(-std::max(pitch, settings.corridorPitch), across_);
  steepOrientation_ = steepDown * context.goal().nominalGoalPose().linear();
  steepFingers_ = steepDown * Eigen::Vector3d(-back_);
}

std::optional<std::size_t> ClearingPush::corridorBlocker(const double* state) const {
  if (halfWidth_ <= 0.0 || behind_ <= 0.0) return std::nullopt;
  const Eigen::Vector2d goal = context_.goal().position().head<2>();
  const Eigen::Vector2d along = -back_.head<2>();
  const Eigen::Vector2d across = across_.head<2>();
  std::optional<std::size_t> furthest;
  double furthestBack = 0.0;
  // Behind the goal point (the free space in front is the free space's business).
  const core::Interval strip{-behind_, 0.0};
  const core::Interval width{-halfWidth_, halfWidth_};
  for (const Footprint& f : footprints_) {
    // The footprint where the body is now.
    const Eigen::AlignedBox3d now =
        f.bounds.translated(physics::WorldLayout::position(state, f.body) - f.start);
    const core::Interval alongIt = core::projectFootprint(now, goal, along);
    const bool inStrip = alongIt.overlaps(strip) && 0.5 * (alongIt.lo + alongIt.hi) < 0.0 &&
                         core::projectFootprint(now, goal, across).overlaps(width);
    if (inStrip && -alongIt.hi >= furthestBack) {
      furthestBack = -alongIt.hi;
      furthest = f.body;
    }
  }
  return furthest;
}

std::optional<ClearingPush::Step> ClearingPush::next(const double* state) const {
  if (halfWidth_ <= 0.0) return std::nullopt;
  const std::optional<std::size_t> inFreeSpace = context_.goal().freeSpaceBlocker(state);
  // The corridor first; after it, the free space (a push of its own, counted as kLaterPush).
  if (const std::optional<std::size_t> inCorridor = corridorBlocker(state))
    return pushStep(state, *inCorridor,
                    inFreeSpace && *inFreeSpace != *inCorridor ? kLaterPush : 0.0, true);
  if (inFreeSpace) return pushStep(state, *inFreeSpace, 0.0, false);
  return std::nullopt;
}

ClearingPush::Step ClearingPush::pushStep(const double* state, std::size_t blocker, double later,
                                          bool steep) const {
  const physics::WorkspaceGoal& goal = context_.goal();
  const Eigen::Matrix3d& turn = steep ? steepOrientation_ : orientation_;
  const Eigen::Vector3d& fingers = steep ? steepFingers_ : fingers_;
  // The goal link aims where the fingers' middle meets the object below its centre.
  Eigen::Vector3d object = physics::WorldLayout::position(state, blocker);
  object.z() -= belowCentre_;
  object += kFingerMiddle * fingers;
  object.z() = std::max(object.z(), lowest_);
  // Push away from the side with more room: the stand-off lies on the other side.
  const double standOff = halfWidth_ + kStandOff;
  const Eigen::Vector3d plus = object + standOff * across_;
  const Eigen::Vector3d minus = object - standOff * across_;
  const bool fromPlus = room(state, plus, blocker) >= room(state, minus, blocker);
  const Eigen::Vector3d direction = fromPlus ? Eigen::Vector3d(-across_) : across_;
  const Eigen::Vector3d start = fromPlus ? plus : minus;
  const Eigen::Vector3d end = object + kPushThrough * direction;
  const double endToGoal = later + (goal.position() - end).norm();

  const Eigen::Vector3d link = context_.layout().goalLinkPosition(state);
  const Eigen::Vector3d fromObject = link - object;
  const double along = fromObject.dot(direction);
  const double offLine = (fromObject - along * direction).norm();
  if (along <= 0.0 && offLine <= kOnLine)
    return Step{end, turn, (end - link).norm() + endToGoal, true};
  // To the stand-off over the cans, from above it (high enough to pass over them); from a push
  // that ended low, up first: a straight move from there to the next stand-off sweeps through
  // the tops of the cans between (it tipped can1 on kuka_clutter_20, on the way from can3's
  // push to can1's).
  const Transfer transfer =
      transferOver(link, start, std::max(start.z() + kAbove, travelHeight_), kOnLine, kOnLine);
  return Step{transfer.waypoint, turn, transfer.length + (end - start).norm() + endToGoal, false};
}

Transfer transferOver(const Eigen::Vector3d& link, const Eigen::Vector3d& target, double height,
                      double over, double below) {
  if (std::hypot(link.x() - target.x(), link.y() - target.y()) <= over)
    return {Transfer::Leg::Down, target, (target - link).norm()};
  const Eigen::Vector3d above(target.x(), target.y(), height);
  const double descent = height - target.z();
  if (link.z() < height - below) {
    const Eigen::Vector3d lifted(link.x(), link.y(), height);
    return {Transfer::Leg::Up, lifted, (lifted - link).norm() + (above - lifted).norm() + descent};
  }
  return {Transfer::Leg::Across, above, (above - link).norm() + descent};
}

double ClearingPush::room(const double* state, const Eigen::Vector3d& point,
                          std::size_t blocker) const {
  double nearest = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d wrist = point + kFootprint * back_;
  const auto& bodies = context_.layout().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (b == blocker || bodies[b].role == physics::BodyRole::Robot) continue;
    // Horizontal distances: the objects stand on the table, the gripper above it.
    const Eigen::Vector2d object = physics::WorldLayout::position(state, b).head<2>();
    nearest = std::min(nearest, core::distanceToSegment<Eigen::Vector2d>(object, point.head<2>(),
                                                                         wrist.head<2>()));
  }
  return nearest;
}

}  // namespace kautham::planners
