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
// the 200 poses costs as much as 200 free-space tests.
constexpr double kMostFilled = 0.05;
// The room a pose beside the goal point leaves around its free space at least: the arm ends
// within a few millimetres of where it is steered, and an end on the edge of a clear pose would
// not do.
constexpr double kRoom = 0.002;  // m
// Of the poses with room, the steering takes one with the most, counted in these steps up to
// kMostRoom: the objects stand where the scene says only to its pose noise (5 mm on the dense
// suite), and on kuka_clutter_30 the nearest pose with 2 mm of room had can20 or can23 in its
// free space in about half the executions that reached it (docs/planners.md, session 33).
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
  for (double room = kRoom; room <= kMostRoom + 1e-9; room += kRoomStep)
    roomier_.emplace_back(context.sharedLayout(),
                          spec.freeSpace->size + Eigen::Vector3d::Constant(2.0 * room),
                          spec.freeSpace->center);
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

std::optional<GoalEnd::Pose> GoalEnd::clearPose(const double* state) const {
  if (!shifts()) {
    // As before there were shifts: the free space judged at the goal's nominal pose.
    if (context_.goal().freeSpaceBlocker(state)) return std::nullopt;
    return poses_.front();
  }
  const std::optional<std::size_t> first = nearestClear(state);
  if (!first) return std::nullopt;
  if (*first == 0) return poses_.front();  // the goal point's free space is clear
  // The poses with kRoom, nearest first; then, room step by room step, those that keep it.
  std::vector<std::size_t> roomiest{*first};
  for (std::size_t i = *first + 1; i < poses_.size(); ++i)
    if (roomier_.front().isFree(state, linkAt(poses_[i]))) roomiest.push_back(i);
  for (std::size_t level = 1; level < roomier_.size(); ++level) {
    std::vector<std::size_t> kept;
    for (const std::size_t i : roomiest)
      if (roomier_[level].isFree(state, linkAt(poses_[i]))) kept.push_back(i);
    if (kept.empty()) break;
    roomiest.swap(kept);
  }
  return poses_[roomiest.front()];
}

}  // namespace kautham::planners
