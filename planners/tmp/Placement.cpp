#include "kautham/planners/tmp/Placement.h"

#include <algorithm>

#include "kautham/core/SegmentDistance.h"

namespace kautham::planners::tmp {

bool isFreePlacement(const PlacementRules& rules, const Eigen::Vector2d& centre, double radius) {
  if (!rules.area.contains(centre)) return false;
  for (const Footprint& other : rules.occupied)
    if ((other.centre - centre).norm() < other.radius + radius + rules.gap) return false;
  const double clear = rules.corridorHalfWidth + radius;
  for (const std::vector<Eigen::Vector2d>& corridor : rules.corridors)
    for (std::size_t i = 0; i < corridor.size(); ++i) {
      const Eigen::Vector2d& a = corridor[i];
      const Eigen::Vector2d& b = corridor[std::min(i + 1, corridor.size() - 1)];
      if (core::distanceToSegment(centre, a, b) < clear) return false;
    }
  return true;
}

std::vector<Eigen::Vector2d> samplePlacements(const PlacementRules& rules, double radius, int tries,
                                              ompl::RNG& rng) {
  std::vector<Eigen::Vector2d> free;
  if (rules.area.isEmpty()) return free;
  for (int i = 0; i < tries; ++i) {
    const Eigen::Vector2d centre(rng.uniformReal(rules.area.min().x(), rules.area.max().x()),
                                 rng.uniformReal(rules.area.min().y(), rules.area.max().y()));
    if (isFreePlacement(rules, centre, radius)) free.push_back(centre);
  }
  return free;
}

}  // namespace kautham::planners::tmp
