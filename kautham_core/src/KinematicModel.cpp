#include "kautham/core/KinematicModel.h"

#include <stdexcept>

namespace kautham::core {

std::optional<int> KinematicModel::findLink(const std::string& linkName) const {
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == linkName) return static_cast<int>(i);
  return std::nullopt;
}

int KinematicModel::rigidGroupTop(int link) const {
  while (links[link].parentJoint >= 0 && !joints[links[link].parentJoint].isMovable())
    link = joints[links[link].parentJoint].parentLink;
  return link;
}

std::vector<int> KinematicModel::movableJoints() const {
  std::vector<int> movable;
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].isMovable()) movable.push_back(static_cast<int>(i));
  return movable;
}

Eigen::Isometry3d KinematicModel::jointMotion(const Joint& joint, double value) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::Prismatic)
    motion.translation() = joint.axis * value;
  else if (joint.type != JointType::Fixed)
    motion.linear() = Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  return motion;
}

std::vector<Eigen::Isometry3d> KinematicModel::linkPoses(
    const Eigen::Isometry3d& base, const std::vector<double>& jointValues) const {
  const std::vector<int> movable = movableJoints();
  if (jointValues.size() != movable.size())
    throw std::invalid_argument("linkPoses: expected " + std::to_string(movable.size()) +
                                " joint values, got " + std::to_string(jointValues.size()));
  std::vector<double> valueOfJoint(joints.size(), 0.0);
  for (std::size_t i = 0; i < movable.size(); ++i) valueOfJoint[movable[i]] = jointValues[i];

  std::vector<Eigen::Isometry3d> poses(links.size(), Eigen::Isometry3d::Identity());
  poses[rootLink] = base;
  // Links are visited parents first: walk down from the root with an explicit stack.
  std::vector<int> pending{rootLink};
  while (!pending.empty()) {
    const int link = pending.back();
    pending.pop_back();
    for (int j : links[link].childJoints) {
      const Joint& joint = joints[j];
      poses[joint.childLink] = poses[link] * joint.origin * jointMotion(joint, valueOfJoint[j]);
      pending.push_back(joint.childLink);
    }
  }
  return poses;
}

}  // namespace kautham::core
