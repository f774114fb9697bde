#include "kautham/planners/pkpiece/GoalEnd.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace kautham::planners {

namespace {
// The grid of points tried beside the goal point.
constexpr double kSpacing = 0.0025;  // m
// The turns about the vertical tried at each point, nearest first.
constexpr std::array<double, 7> kYaws{0.0, 0.05, -0.05, 0.1, -0.1, 0.15, -0.15};  // rad
// A turned end keeps this much of the approach tolerance: the arm ends near it, not on it.
constexpr double kToleranceKept = 0.05;  // rad
// A free space filled more than this at the goal point is not cleared by ending within a
// centimetre, turned a little (a can reaching 1 cm into its far end fills 3 %): no pose beside
// the goal point is tried. The search asks at every state while a can is pushed out, and trying
// the 200 poses costs about 200 free-space tests.
constexpr double kMostFilled = 0.05;
// The room a pose beside the goal point leaves around its free space at least: the arm ends
// within a few millimetres of where it is steered, and an end on the edge of a clear pose would
// not do.
constexpr double kRoom = 0.002;  // m
// Of the poses with room, the steering takes one with the most, counted in these steps up to
// kMostRoom: the objects' poses are uncertain (on the dense suite, 5 mm standard deviation each
// way, about 7 mm between two objects), and on kuka_clutter_30 the nearest pose with 2 mm of room
// had can20 or can23 in its free space in about half the executions that reached it
// (docs/planners.md, session 33).
constexpr double kRoomStep = 0.001;  // m
constexpr double kMostRoom = 0.012;  // m

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}
}  // namespace

GoalEnd::GoalEnd(const physics::PlanningContext& context, const Eigen::Matrix3d& turn, double shift)
    : context_(context) {
  const physics::GoalSpec& spec = context.goal().spec();
  const Eigen::Vector3d approach =
      spec.approach ? spec.approach->normalized() : Eigen::Vector3d(turn.col(2));
  poses_.push_back({spec.position, turn, approach});
  if (shift <= 0.0) return;
  struct Tried {
    double distance;
    double yaw;
    Pose pose;
  };
  std::vector<Tried> tried;
  const int reach = static_cast<int>(std::floor(shift / kSpacing + 1e-9));
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j) {
      const Eigen::Vector3d offset(i * kSpacing, j * kSpacing, 0.0);
      if (offset.norm() > shift + 1e-9) continue;
      for (const double yaw : kYaws) {
        if (i == 0 && j == 0 && yaw == 0.0) continue;
        const Eigen::Matrix3d turned = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * turn;
        if (spec.approach &&
            angleBetween(turned.col(2), approach) > spec.approachTolerance - kToleranceKept)
          continue;
        tried.push_back({offset.norm(),
                         std::abs(yaw),
                         {spec.position + offset, turned,
                          Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * approach}});
      }
    }
  std::stable_sort(tried.begin(), tried.end(), [](const Tried& a, const Tried& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.yaw < b.yaw;
  });
  for (const Tried& t : tried) poses_.push_back(t.pose);
  if (!spec.freeSpace) return;
  const int levels = static_cast<int>(std::lround((kMostRoom - kRoom) / kRoomStep)) + 1;
  for (int level = 0; level < levels; ++level) {
    const double room = kRoom + level * kRoomStep;
    roomier_.emplace_back(context.sharedLayout(),
                          spec.freeSpace->size + Eigen::Vector3d::Constant(2.0 * room),
                          spec.freeSpace->center);
  }
}

Eigen::Isometry3d GoalEnd::linkAt(const Pose& pose) {
  Eigen::Isometry3d link = Eigen::Isometry3d::Identity();
  link.linear() = pose.turn;
  link.translation() = pose.point;
  return link;
}

std::optional<std::size_t> GoalEnd::nearestClear(const double* state) const {
  const double filled = context_.goal().freeSpaceFilledAt(state, linkAt(poses_.front()));
  if (filled == 0.0) return 0;
  if (filled > kMostFilled || roomier_.empty()) return std::nullopt;
  for (std::size_t i = 1; i < poses_.size(); ++i)
    if (roomier_.front().isFree(state, linkAt(poses_[i]))) return i;
  return std::nullopt;
}

bool GoalEnd::anyClearPose(const double* state) const {
  if (!shifts()) return !context_.goal().freeSpaceBlocker(state);
  return nearestClear(state).has_value();
}

std::size_t GoalEnd::climb(const double* state, const Eigen::Isometry3d& link,
                           std::size_t level) const {
  while (level < roomier_.size() && roomier_[level].isFree(state, link)) ++level;
  return level - 1;
}

bool GoalEnd::clearThrough(const double* state, const Eigen::Isometry3d& link,
                           std::size_t level) const {
  for (std::size_t l = 0; l <= level; ++l)
    if (!roomier_[l].isFree(state, link)) return false;
  return true;
}

std::optional<GoalEnd::Pose> GoalEnd::clearPose(const double* state) const {
  if (!shifts()) {
    // As before there were shifts: the free space judged at the goal's nominal pose.
    if (context_.goal().freeSpaceBlocker(state)) return std::nullopt;
    return poses_.front();
  }
  const std::optional<std::size_t> first = nearestClear(state);
  if (!first) return std::nullopt;
  if (*first == 0) return poses_.front();  // the goal point's free space is clear
  // One pass, nearest first. A farther pose replaces the best only with more room, so it is
  // asked first about the level above the best's: one free-space test rules most poses out.
  // A pose's room is the last level of an unbroken run from the first: the free spaces are
  // judged on sample points that move as they grow, so clear at one level need not mean clear
  // at every level below it.
  std::size_t best = *first;
  std::size_t bestLevel = climb(state, linkAt(poses_[best]), 1);
  for (std::size_t i = best + 1; i < poses_.size() && bestLevel + 1 < roomier_.size(); ++i) {
    const Eigen::Isometry3d link = linkAt(poses_[i]);
    if (!roomier_[bestLevel + 1].isFree(state, link) || !clearThrough(state, link, bestLevel))
      continue;
    best = i;
    bestLevel = climb(state, link, bestLevel + 2);
  }
  return poses_[best];
}

}  // namespace kautham::planners
