#include "FinalLinkGoal.h"

namespace kautham::core {

namespace {

/// Kautham's goal region for its physics planners is satisfied within this distance (m).
constexpr double kKauthamGoalThreshold = 0.05;

}  // namespace

std::string chainEndLink(const KinematicModel& model) {
  int link = model.rootLink;
  for (;;) {
    const std::vector<int>& children = model.links[static_cast<std::size_t>(link)].childJoints;
    if (children.size() != 1) break;
    link = model.joints[static_cast<std::size_t>(children.front())].childLink;
  }
  return model.links[static_cast<std::size_t>(link)].name;
}

GoalRegion finalLinkGoal(const Problem& problem, const GoalRegion& configuration) {
  GoalRegion goal;
  goal.link = chainEndLink(problem.robot.model);
  goal.where = configuration.where;
  const std::vector<Eigen::Isometry3d> poses = problem.robot.model.linkPoses(
      problem.robot.home.isometry(), problem.jointValuesFromControls(configuration.controls));
  goal.offset =
      poses.at(static_cast<std::size_t>(*problem.robot.model.findLink(goal.link))).translation();
  goal.tolerance = kKauthamGoalThreshold;
  return goal;
}

}  // namespace kautham::core
