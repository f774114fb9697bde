#include "kautham/physics/WorldStateSpace.h"

#include <algorithm>
#include <cmath>

#include "kautham/physics/EndEffectorProjection.h"
#include "kautham/physics/JointDistance.h"

namespace kautham::physics {

WorldStateSpace::WorldStateSpace(std::shared_ptr<const WorldLayout> layout,
                                 const Eigen::AlignedBox3d& workspace)
    : RealVectorStateSpace(static_cast<unsigned>(layout->stateSize())),
      layout_(std::move(layout)),
      workspace_(workspace) {
  setName("World" + getName());
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(1.0);
  const Eigen::AlignedBox3d region(workspace.min() - margin, workspace.max() + margin);
  // Bounds only serve OMPL's uniform sampling (RRT-like planners sample end-effector targets);
  // validity is decided by WorldValidityChecker, not by these boxes.
  constexpr double kMaxSpeed = 10.0;
  ompl::base::RealVectorBounds bounds(getDimension());
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b) {
    const std::size_t base = b * WorldLayout::kBodyStateSize;
    for (int k = 0; k < 3; ++k) {
      bounds.setLow(base + WorldLayout::kPosition + k, region.min()[k]);
      bounds.setHigh(base + WorldLayout::kPosition + k, region.max()[k]);
      bounds.setLow(base + WorldLayout::kLinearVelocity + k, -kMaxSpeed);
      bounds.setHigh(base + WorldLayout::kLinearVelocity + k, kMaxSpeed);
      bounds.setLow(base + WorldLayout::kAngularVelocity + k, -kMaxSpeed);
      bounds.setHigh(base + WorldLayout::kAngularVelocity + k, kMaxSpeed);
    }
    for (int k = 0; k < 4; ++k) {
      bounds.setLow(base + WorldLayout::kOrientation + k, -1.0);
      bounds.setHigh(base + WorldLayout::kOrientation + k, 1.0);
    }
  }
  for (std::size_t j = 0; j < layout_->joints.size(); ++j) {
    const JointInfo& joint = layout_->joints[j];
    const double lower = joint.limited ? joint.lower : -M_PI;
    const double upper = joint.limited ? joint.upper : M_PI;
    bounds.setLow(layout_->jointPositionIndex() + j, lower);
    bounds.setHigh(layout_->jointPositionIndex() + j, std::max(upper, lower + 1e-9));
    bounds.setLow(layout_->jointVelocityIndex() + j, -joint.maxVelocity);
    bounds.setHigh(layout_->jointVelocityIndex() + j, std::max(joint.maxVelocity, 1e-9));
  }
  bounds.setLow(layout_->flagsIndex(), 0.0);
  bounds.setHigh(layout_->flagsIndex(), 0.0);
  setBounds(bounds);
}

const double* WorldStateSpace::values(const ompl::base::State* state) {
  return state->as<StateType>()->values;
}

double* WorldStateSpace::values(ompl::base::State* state) { return state->as<StateType>()->values; }

void WorldStateSpace::registerProjections() {
  registerDefaultProjection(std::make_shared<EndEffectorProjection>(this, layout_, workspace_));
}

double WorldStateSpace::distance(const ompl::base::State* a, const ompl::base::State* b) const {
  if (jointRanges_.empty())
    return (layout_->goalLinkPosition(values(a)) - layout_->goalLinkPosition(values(b))).norm();
  const std::size_t joints = layout_->jointPositionIndex();
  return jointDistance(layout_->joints, values(a) + joints, values(b) + joints, jointRanges_);
}

}  // namespace kautham::physics
