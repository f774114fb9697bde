#include "kautham/physics/WorkspaceGoal.h"

#include <algorithm>
#include <cmath>

#include "kautham/physics/JointDistance.h"
#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

namespace {
// Makes an approach error comparable to a position error for the search's distance: turning
// the gripper by 0.1 rad counts like moving it 1 cm.
constexpr double kMetresPerRadian = 0.1;
// Makes a filled free space comparable to a position error: a can standing in the dense
// suite's box fills about a fifth of it, which counts like being 20 cm away, so a state with
// the gripper at the goal and the can still between its fingers ranks behind one where the
// can is pushed out and the gripper is 10 cm away.
constexpr double kMetresPerOccupiedBox = 1.0;

/// The goal link's orientation at the goal: its +z along the approach, and its level axis
/// horizontal (the side of the approach; a free space symmetric about the approach does not
/// care which).
Eigen::Matrix3d nominalOrientation(const Eigen::Vector3d& approach, const Eigen::Vector3d& level) {
  const Eigen::Vector3d linkZ = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d linkLevel = level - level.dot(linkZ) * linkZ;
  Eigen::Vector3d worldLevel = approach.cross(Eigen::Vector3d::UnitZ());
  if (linkLevel.norm() < 1e-9 || worldLevel.norm() < 1e-9) return Eigen::Matrix3d::Identity();
  linkLevel.normalize();
  worldLevel.normalize();
  Eigen::Matrix3d link;
  link << linkZ, linkLevel, linkZ.cross(linkLevel);
  Eigen::Matrix3d world;
  const Eigen::Vector3d a = approach.normalized();
  world << a, worldLevel, a.cross(worldLevel);
  return world * link.transpose();
}
}  // namespace

WorkspaceGoal::WorkspaceGoal(const ompl::base::SpaceInformationPtr& si,
                             std::shared_ptr<const WorldLayout> layout, GoalSpec spec)
    : GoalRegion(si), layout_(std::move(layout)), spec_(std::move(spec)) {
  setThreshold(spec_.joints.empty() ? spec_.tolerance : spec_.jointTolerance);
  if (spec_.freeSpace) freeSpace_.emplace(layout_, spec_.freeSpace->size, spec_.freeSpace->center);
  nominalGoalPose_.translation() = spec_.position;
  if (spec_.approach && spec_.levelAxis)
    nominalGoalPose_.linear() = nominalOrientation(*spec_.approach, *spec_.levelAxis);
}

double WorkspaceGoal::distanceGoal(const ompl::base::State* state) const {
  const double d = searchDistance(WorldStateSpace::values(state));
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

double WorkspaceGoal::searchDistance(const double* state) const {
  const double d = distance(state);
  if (!freeSpace_) return d;
  return d + kMetresPerOccupiedBox * freeSpace_->occupancy(state, nominalGoalPose_).fraction;
}

std::optional<std::size_t> WorkspaceGoal::freeSpaceBlocker(const double* state) const {
  if (!freeSpace_) return std::nullopt;
  return freeSpace_->occupancy(state, nominalGoalPose_).largest;
}

double WorkspaceGoal::freeSpaceFilledAt(const double* state,
                                        const Eigen::Isometry3d& goalLink) const {
  return freeSpace_ ? freeSpace_->occupancy(state, goalLink).fraction : 0.0;
}

bool WorkspaceGoal::reached(const double* state) const {
  if (!spec_.joints.empty()) return jointError(state) <= spec_.jointTolerance;
  // The free space is looked at last: it is the only costly test.
  return poseReached(state) && freeSpaceOccupants(state).empty();
}

bool WorkspaceGoal::poseReached(const double* state) const {
  if (!spec_.joints.empty()) return jointError(state) <= spec_.jointTolerance;
  // poseMiss()'s three conditions, the cheapest first, stopping at the first missed: the search
  // asks at every state it reaches.
  return positionError(state) <= spec_.tolerance &&
         approachError(state) <= spec_.approachTolerance &&
         levelError(state) <= spec_.approachTolerance;
}

WorkspaceGoal::PoseMiss WorkspaceGoal::poseMiss(const double* state) const {
  if (!spec_.joints.empty()) return {};
  return {positionError(state) > spec_.tolerance, approachError(state) > spec_.approachTolerance,
          levelError(state) > spec_.approachTolerance};
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
  return jointDistance(layout_->joints, state + layout_->jointPositionIndex(), spec_.joints.data(),
                       spec_.jointRanges);
}

}  // namespace kautham::physics
