#include "kautham/physics/WorkspaceGoal.h"

#include <algorithm>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

WorkspaceGoal::WorkspaceGoal(const ompl::base::SpaceInformationPtr& si,
                             std::shared_ptr<const WorldLayout> layout,
                             const Eigen::Vector3d& position, double tolerance)
    : GoalRegion(si), layout_(std::move(layout)), position_(position) {
  setThreshold(tolerance);
}

double WorkspaceGoal::distanceGoal(const ompl::base::State* state) const {
  const double d = distance(WorldStateSpace::values(state));
  best_ = std::min(best_, d);
  return d;
}

double WorkspaceGoal::distance(const double* state) const {
  return (layout_->goalLinkPosition(state) - position_).norm();
}

}  // namespace kautham::physics
