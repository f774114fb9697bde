#include "MobileBase.h"

#include <algorithm>

namespace kautham::core {

namespace {

// Carriages between the base joints carry no geometry; ODE still needs a mass for each moving
// body, so they get a small one (robot bodies have no gravity: it loads only the motors).
constexpr double kCarriageMass = 0.5;
constexpr double kCarriageInertia = 0.005;

Eigen::Vector3d axisVector(const std::string& axis) {
  if (axis == "X") return Eigen::Vector3d::UnitX();
  if (axis == "Y") return Eigen::Vector3d::UnitY();
  return Eigen::Vector3d::UnitZ();
}

/// Renumbers every index of `model` as if `count` links and joints were inserted in front.
void shiftIndices(KinematicModel& model, int count) {
  for (Link& link : model.links) {
    if (link.parentJoint >= 0) link.parentJoint += count;
    for (int& j : link.childJoints) j += count;
  }
  for (Joint& joint : model.joints) {
    joint.parentLink += count;
    joint.childLink += count;
  }
  model.rootLink += count;
}

}  // namespace

void addMobileBase(KinematicModel& model, const std::vector<BaseAxisLimits>& axes) {
  if (axes.empty()) return;
  std::vector<BaseAxisLimits> ordered = axes;
  std::sort(ordered.begin(), ordered.end(),
            [](const BaseAxisLimits& a, const BaseAxisLimits& b) { return a.axis < b.axis; });
  const int count = static_cast<int>(ordered.size());
  shiftIndices(model, count);

  // Links 0..count-1: the static mount, then one carriage per axis but the last, whose child is
  // the URDF's root. Joints 0..count-1 link them in that order.
  std::vector<Link> links(static_cast<std::size_t>(count));
  std::vector<Joint> joints(static_cast<std::size_t>(count));
  links[0].name = "mobile_base_mount";
  for (int i = 0; i < count; ++i) {
    const BaseAxisLimits& limits = ordered[static_cast<std::size_t>(i)];
    Joint& joint = joints[static_cast<std::size_t>(i)];
    joint.name = "base_" + limits.axis;
    joint.type = JointType::Prismatic;
    joint.parentLink = i;
    joint.childLink = i + 1 < count ? i + 1 : model.rootLink;
    joint.axis = axisVector(limits.axis);
    joint.lower = limits.min;
    joint.upper = limits.max;
    joint.maxVelocity = limits.velocity;
    joint.maxEffort = limits.effort;
    links[static_cast<std::size_t>(i)].childJoints.push_back(i);
    if (i > 0) {
      Link& carriage = links[static_cast<std::size_t>(i)];
      carriage.name = "mobile_base_" + ordered[static_cast<std::size_t>(i) - 1].axis;
      carriage.parentJoint = i - 1;
      carriage.inertial.mass = kCarriageMass;
      carriage.inertial.inertia = Eigen::Matrix3d::Identity() * kCarriageInertia;
    }
  }
  model.links[static_cast<std::size_t>(model.rootLink - count)].parentJoint = count - 1;
  model.links.insert(model.links.begin(), links.begin(), links.end());
  model.joints.insert(model.joints.begin(), joints.begin(), joints.end());
  model.rootLink = 0;
}

}  // namespace kautham::core
