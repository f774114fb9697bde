#include "kautham/physics/WorkspaceGoal.h"

#include <algorithm>
#include <cmath>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

namespace {
// Makes an approach error comparable to a position error for the search's distance: turning
// the gripper by 0.1 rad counts like moving it 1 cm.
constexpr double kMetresPerRadian = 0.1;
}  // namespace

WorkspaceGoal::WorkspaceGoal(const ompl::base::SpaceInformationPtr& si,
                             std::shared_ptr<const WorldLayout> layout, GoalSpec spec)
    : GoalRegion(si), layout_(std::move(layout)), spec_(std::move(spec)) {
  setThreshold(spec_.joints.empty() ? spec_.tolerance : spec_.jointTolerance);
  if (spec_.freeSpace) freeSpace_.emplace(layout_, spec_.freeSpace->size, spec_.freeSpace->center);
}

double WorkspaceGoal::distanceGoal(const ompl::base::State* state) const {
  const double d = distance(WorldStateSpace::values(state));
  best_ = std::min(best_, d);
  return d;
}

bool WorkspaceGoal::isSatisfied(const ompl::base::State* state, double* distance) const {
  const double d = distanceGoal(state);
  if (distance) *distance = d;
  return reached(WorldStateSpace::values(state));
}

double WorkspaceGoal::distance(const double* state) const {
  if (!spec_.joints.empty()) return jointError(state);
  const double excess = std::max(0.0, approachError(state) - spec_.approachTolerance) +
                        std::max(0.0, levelError(state) - spec_.approachTolerance);
  return positionError(state) + kMetresPerRadian * excess;
}

bool WorkspaceGoal::reached(const double* state) const {
  if (!spec_.joints.empty()) return jointError(state) <= spec_.jointTolerance;
  // The free space is looked at last: it is the only costly test.
  return positionError(state) <= spec_.tolerance &&
         approachError(state) <= spec_.approachTolerance &&
         levelError(state) <= spec_.approachTolerance && freeSpaceOccupants(state).empty();
}

double WorkspaceGoal::levelError(const double* state) const {
  if (!spec_.levelAxis) return 0.0;
  const Eigen::Vector3d axis = layout_->goalLinkOrientation(state) * *spec_.levelAxis;
  return std::asin(std::clamp(std::abs(axis.z()), 0.0, 1.0));
}

std::vector<std::string> WorkspaceGoal::freeSpaceOccupants(const double* state) const {
  if (!freeSpace_) return {};
  Eigen::Isometry3d goalLink = Eigen::Isometry3d::Identity();
  goalLink.linear() = layout_->goalLinkOrientation(state);
  goalLink.translation() = layout_->goalLinkPosition(state);
  return freeSpace_->occupants(state, goalLink);
}

double WorkspaceGoal::positionError(const double* state) const {
  return (layout_->goalLinkPosition(state) - spec_.position).norm();
}

double WorkspaceGoal::approachError(const double* state) const {
  if (!spec_.approach) return 0.0;
  const Eigen::Vector3d axis = layout_->goalLinkOrientation(state) * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(axis.dot(*spec_.approach), -1.0, 1.0));
}

double WorkspaceGoal::jointError(const double* state) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < spec_.joints.size(); ++j) {
    const double d = (state[layout_->jointPositionIndex() + j] - spec_.joints[j]) /
                     std::max(spec_.jointRanges[j], 1e-9);
    sum += d * d;
  }
  return std::sqrt(sum);
}

}  // namespace kautham::physics
