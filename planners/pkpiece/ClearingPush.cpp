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
// How far the gripper reaches back from the goal link (fingers, palm, wrist), held level: the
// room a stand-off needs lies along this footprint (shorter as the gripper points down).
constexpr double kFootprint = 0.12;  // m
// A stand-off whose footprint passes nearer than this to another object's centre has no room:
// a can's radius (3.3 cm) and a margin.
constexpr double kCrowdedRoom = 0.06;  // m
// A gripper lowered to slide into a crowded stand-off lands where no object's centre is nearer
// than this to it (its whole width over the table): a can's radius (3.3 cm) and a margin.
constexpr double kLandingClear = 0.04;  // m
// Margin above the workspace floor (the goal link may not leave the workspace).
constexpr double kFloorMargin = 0.012;  // m
// What a push still to come after the current one adds to the remaining length: more than
// any single push's own length, so a state with one push done ranks before any state still
// on the one before.
constexpr double kLaterPush = 0.5;  // m
}  // namespace

ClearingPush::ClearingPush(const physics::PlanningContext& context, const PushSettings& settings,
                           const GoalEnd* end)
    : context_(context),
      behind_(settings.behind),
      belowCentre_(settings.belowCentre),
      slide_(settings.crowdedSlide),
      end_(end),
      angles_(
          {settings.angleSpread, settings.angleAfter, settings.angleGeneration, settings.angleSeed},
          context.layout().bodies.size()) {
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
  push_ = posture(pitch);
  corridor_ = posture(std::max(pitch, settings.corridorPitch));
  crowded_ = posture(settings.crowdedPitch);
}

ClearingPush::Posture ClearingPush::posture(double pitch) const {
  const Eigen::AngleAxisd pitchDown(-pitch, across_);
  return {pitch, pitchDown * context_.goal().nominalGoalPose().linear(),
          pitchDown * Eigen::Vector3d(-back_), kFootprint * std::cos(pitch)};
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

ClearingPush::Blockers ClearingPush::blockers(const double* state) const {
  Blockers found;
  if (halfWidth_ <= 0.0) return found;
  // An object reaching into the free space only where a nearby end leaves it clear needs no
  // push: the gripper ends there.
  found.freeSpace = context_.goal().freeSpaceBlocker(state);
  if (found.freeSpace && end_ && end_->shifts() && end_->anyClearPose(state))
    found.freeSpace.reset();
  found.corridor = corridorBlocker(state);
  // The corridor first; after it, the free space (a push of its own, counted as kLaterPush).
  if (found.corridor && found.freeSpace && *found.freeSpace != *found.corridor)
    found.later = kLaterPush;
  return found;
}

std::optional<ClearingPush::Step> ClearingPush::next(const double* state) const {
  const Blockers found = blockers(state);
  if (found.corridor) return pushStep(state, *found.corridor, found.later, corridor_);
  if (found.freeSpace) return pushStep(state, *found.freeSpace, 0.0, push_);
  return std::nullopt;
}

std::optional<double> ClearingPush::clearingLeft(const double* state) const {
  // The blockers next() pushes, measured across the approach only, so that a push turned towards
  // the target is not nearer for its angle alone.
  const Blockers found = blockers(state);
  if (found.corridor) return reachAcross(state, *found.corridor) + found.later;
  if (found.freeSpace) return reachAcross(state, *found.freeSpace);
  return std::nullopt;
}

double ClearingPush::reachAcross(const double* state, std::size_t body) const {
  const auto footprint = std::find_if(footprints_.begin(), footprints_.end(),
                                      [body](const Footprint& f) { return f.body == body; });
  if (footprint == footprints_.end()) return 0.0;
  const Eigen::AlignedBox3d now =
      footprint->bounds.translated(physics::WorldLayout::position(state, body) - footprint->start);
  const core::Interval across = core::projectFootprint(now, context_.goal().position().head<2>(),
                                                       across_.head<2>().normalized());
  return std::max(0.0, std::min(across.hi + halfWidth_, halfWidth_ - across.lo));
}

const ClearingPush::Posture& ClearingPush::choosePosture(const double* state, std::size_t blocker,
                                                         const Posture& own) const {
  if (crowded_.pitch <= own.pitch) return own;
  const Eigen::Vector3d link = context_.layout().goalLinkPosition(state);
  const Eigen::Vector3d centre = physics::WorldLayout::position(state, blocker);
  const Eigen::Vector3d fromPlus = pushDirection(1.0, blocker);
  const Eigen::Vector3d fromMinus = pushDirection(-1.0, blocker);
  if (onLine(link, aimAt(centre, own), fromPlus) || onLine(link, aimAt(centre, own), fromMinus) ||
      onLine(link, aimAt(centre, crowded_), fromPlus) ||
      onLine(link, aimAt(centre, crowded_), fromMinus)) {
    // A push under way keeps the posture the gripper is nearest: the pitch it has now.
    return nearer(pitchNow(state), own, crowded_);
  }
  const double ownRoom = widerRoom(state, centre, blocker, own);
  if (ownRoom >= kCrowdedRoom) return own;
  return widerRoom(state, centre, blocker, crowded_) > ownRoom ? crowded_ : own;
}

double ClearingPush::widerRoom(const double* state, const Eigen::Vector3d& centre,
                               std::size_t blocker, const Posture& posture) const {
  return std::max(room(state, standOff(centre, posture, 1.0, blocker), blocker, posture.reach),
                  room(state, standOff(centre, posture, -1.0, blocker), blocker, posture.reach));
}

double pitchBelowLevel(const Eigen::Matrix3d& turn) {
  return -std::asin(std::clamp(turn.col(2).z(), -1.0, 1.0));
}

double ClearingPush::pitchNow(const double* state) const {
  return pitchBelowLevel(context_.layout().goalLinkOrientation(state));
}

const ClearingPush::Posture& ClearingPush::nearer(double pitch, const Posture& a,
                                                  const Posture& b) {
  return std::abs(pitch - b.pitch) < std::abs(pitch - a.pitch) ? b : a;
}

double ClearingPush::pushAngle(std::size_t blocker) const { return angles_.angle(blocker); }

Eigen::Vector3d ClearingPush::pushDirection(double side, std::size_t blocker) const {
  // Across the approach, turned towards the target (+) or away from it by the push's angle.
  const double angle = pushAngle(blocker);
  return -side * std::cos(angle) * across_ - std::sin(angle) * back_;
}

bool ClearingPush::onLine(const Eigen::Vector3d& link, const Eigen::Vector3d& aim,
                          const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d fromAim = link - aim;
  return (fromAim - fromAim.dot(direction) * direction).norm() <= kOnLine;
}

Eigen::Vector3d ClearingPush::aimAt(const Eigen::Vector3d& centre, const Posture& posture) const {
  // The goal link aims where the fingers' middle meets the object below its centre.
  Eigen::Vector3d aim = centre;
  aim.z() -= belowCentre_;
  aim += kFingerMiddle * posture.fingers;
  aim.z() = std::max(aim.z(), lowest_);
  return aim;
}

Eigen::Vector3d ClearingPush::standOff(const Eigen::Vector3d& centre, const Posture& posture,
                                       double side, std::size_t blocker) const {
  return aimAt(centre, posture) - (halfWidth_ + kStandOff) * pushDirection(side, blocker);
}

ClearingPush::Step ClearingPush::pushStep(const double* state, std::size_t blocker, double later,
                                          const Posture& own) const {
  const physics::WorkspaceGoal& goal = context_.goal();
  const Posture& posture = choosePosture(state, blocker, own);
  const Eigen::Vector3d centre = physics::WorldLayout::position(state, blocker);
  const Eigen::Vector3d object = aimAt(centre, posture);
  const Eigen::Vector3d plus = standOff(centre, posture, 1.0, blocker);
  const Eigen::Vector3d minus = standOff(centre, posture, -1.0, blocker);
  // Push away from the side with more room: the stand-off lies on the other side.
  const bool fromPlus =
      room(state, plus, blocker, posture.reach) >= room(state, minus, blocker, posture.reach);
  const Eigen::Vector3d direction = pushDirection(fromPlus ? 1.0 : -1.0, blocker);
  const Eigen::Vector3d start = fromPlus ? plus : minus;
  const Eigen::Vector3d end = object + kPushThrough * direction;
  const double endToGoal = later + (goal.position() - end).norm();

  const Eigen::Vector3d link = context_.layout().goalLinkPosition(state);
  const double along = (link - object).dot(direction);
  const double pushLength = (end - start).norm();
  if (along <= 0.0 && onLine(link, object, direction))
    return Step{end, posture.orientation, (end - link).norm() + endToGoal, true};
  // Low behind the stand-off (within slide_): slide in at the push's speed, the objects in the
  // way slide. Judged on the whole slide_, not on the landing: the landing moves as the slide
  // pushes the cans aside, and a slide cut short by the room it made would rise and start over.
  if (sliding(link, start))
    return Step{start, posture.orientation, (start - link).norm() + pushLength + endToGoal, true};
  const Eigen::Vector3d lowered = slide_ > 0.0 ? landing(state, start, blocker, posture) : start;
  const double slideLength = (start - lowered).norm();
  // To the stand-off (or the landing behind it) over the cans, from above it (high enough to
  // pass over them); from a push
  // that ended low, up first: a straight move from there to the next stand-off sweeps through
  // the tops of the cans between (it tipped can1 on kuka_clutter_20, on the way from can3's
  // push to can1's).
  const Transfer transfer =
      transferOver(link, lowered, std::max(start.z() + kAbove, travelHeight_), kOnLine, kOnLine);
  // On the way up from a push the gripper keeps the posture it pushed with: turned low, next to
  // the cans it had pushed, the gripper swept one (yumi_clutter_30, can3, turning from the
  // corridor's steep push to the free space's level one).
  const Posture* held = &posture;
  if (transfer.leg == Transfer::Leg::Up) {
    const double pitch = pitchNow(state);
    held = &nearer(pitch, nearer(pitch, push_, corridor_), crowded_);
  }
  return Step{transfer.waypoint, held->orientation,
              transfer.length + slideLength + pushLength + endToGoal, false};
}

Eigen::Vector3d ClearingPush::landing(const double* state, const Eigen::Vector3d& start,
                                      std::size_t blocker, const Posture& posture) const {
  constexpr double kStep = 0.01;  // m
  Eigen::Vector3d roomiest = start;
  double most = -std::numeric_limits<double>::infinity();
  for (double back = 0.0; back <= slide_ + 1e-9; back += kStep) {
    const Eigen::Vector3d point = start + back * back_;
    const double here = landingRoom(state, point, blocker, posture.reach);
    if (here >= kLandingClear) return point;
    if (here > most) {
      most = here;
      roomiest = point;
    }
  }
  return roomiest;
}

double ClearingPush::landingRoom(const double* state, const Eigen::Vector3d& point,
                                 std::size_t blocker, double reach) const {
  double nearest = std::numeric_limits<double>::infinity();
  const auto& bodies = context_.layout().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (b == blocker || bodies[b].role == physics::BodyRole::Robot) continue;
    const Eigen::Vector3d from = physics::WorldLayout::position(state, b) - point;
    // Outside the gripper's rectangle over the table: across it, and before or behind it.
    const double across = std::max(std::abs(from.dot(across_)) - halfWidth_, 0.0);
    const double along = std::max({-from.dot(back_), 0.0, from.dot(back_) - reach});
    nearest = std::min(nearest, std::hypot(across, along));
  }
  return nearest;
}

bool ClearingPush::sliding(const Eigen::Vector3d& link, const Eigen::Vector3d& start) const {
  if (slide_ <= 0.0 || link.z() > start.z() + kOnLine) return false;
  const Eigen::Vector2d from = start.head<2>() + slide_ * back_.head<2>();
  return core::distanceToSegment<Eigen::Vector2d>(link.head<2>(), from, start.head<2>()) <=
             kOnLine &&
         (link - start).dot(back_) > kOnLine;
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

double ClearingPush::room(const double* state, const Eigen::Vector3d& point, std::size_t blocker,
                          double reach) const {
  double nearest = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d wrist = point + reach * back_;
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
