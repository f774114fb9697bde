#include "kautham/planners/geometric/GoalPoseOverlaps.h"

#include <algorithm>
#include <map>
#include <random>

#include "kautham/planners/geometric/GeometricQuery.h"

namespace kautham::planners::geometric {

GoalPoseOverlaps goalPoseOverlaps(physics::PlanningContext& context, int attempts,
                                  std::uint32_t seed) {
  GoalPoseOverlaps result;
  const physics::GoalSpec& goal = context.goal().spec();
  if (!goal.joints.empty() || !goal.approach) return result;
  GeometricQuery query(context);
  physics::PoseTarget target;
  target.position = goal.position;
  target.approach = goal.approach;
  target.levelAxis = goal.levelAxis;
  target.tolerance = 0.005;
  target.angleTolerance = 0.05;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::map<std::string, int> touched;
  const auto& bodies = context.layout().bodies;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    // The first pose is the one nearest the start; the others show the arm's alternatives.
    std::vector<double> from = query.joints().start();
    if (attempt > 0)
      for (double& c : from) c = uniform(random);
    const std::optional<std::vector<double>> pose = query.ik().solve(target, from);
    if (!pose) continue;
    ++result.poses;
    const physics::RobotTouches touches = query.checker().touchesAt(pose->data());
    if (!touches.any()) ++result.touchFree;
    if (touches.fixed) ++touched["(fixed)"];
    for (int b : touches.bodies) ++touched[bodies.at(static_cast<std::size_t>(b)).name];
  }
  result.objects.assign(touched.begin(), touched.end());
  std::stable_sort(result.objects.begin(), result.objects.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return result;
}

}  // namespace kautham::planners::geometric
