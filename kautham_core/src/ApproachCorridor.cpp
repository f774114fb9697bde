#include "kautham/core/ApproachCorridor.h"

#include <algorithm>
#include <cmath>

namespace kautham::core {

Interval projectFootprint(const Eigen::AlignedBox3d& box, const Eigen::Vector2d& origin,
                          const Eigen::Vector2d& direction) {
  Interval out{INFINITY, -INFINITY};
  for (double x : {box.min().x(), box.max().x()})
    for (double y : {box.min().y(), box.max().y()}) {
      const double t = (Eigen::Vector2d(x, y) - origin).dot(direction);
      out = {std::min(out.lo, t), std::max(out.hi, t)};
    }
  return out;
}

std::vector<std::string> approachBlockers(const Problem& problem, const GoalRegion& goal) {
  const std::optional<Eigen::Vector3d> approach = problem.goalApproach(goal);
  if (goal.approachCorridor <= 0.0 || !goal.freeSpace || !goal.levelAxis || !approach) return {};
  Eigen::Vector2d along = approach->head<2>();
  if (along.norm() < 1e-6) return {};  // a top-down approach has no corridor on the table
  along.normalize();
  const Eigen::Vector2d across(-along.y(), along.x());

  const GoalRegion::FreeSpace& free = *goal.freeSpace;
  const double halfWidth = 0.5 * goal.levelAxis->cwiseAbs().dot(free.size);
  const double front = free.center.z() + 0.5 * free.size.z();  // the goal link's +z: approach
  const Interval strip{-goal.approachCorridor, front};
  // The free space may sit off the goal link's axis across the fingers.
  const double offset = goal.levelAxis->dot(free.center);
  const Interval width{offset - halfWidth, offset + halfWidth};
  const Eigen::Vector2d origin = problem.goalPosition(goal).head<2>();

  std::vector<std::string> names;
  for (const ObjectInstance& object : problem.objects) {
    if (object.role != ObjectRole::Movable) continue;
    const Eigen::AlignedBox3d footprint = boundsAtHome(object);
    if (projectFootprint(footprint, origin, along).overlaps(strip) &&
        projectFootprint(footprint, origin, across).overlaps(width))
      names.push_back(object.name);
  }
  return names;
}

}  // namespace kautham::core
