#include "kautham/core/JointInertia.h"

namespace kautham::core {

std::vector<double> jointInertias(const KinematicModel& model, const Eigen::Isometry3d& base,
                                  const std::vector<double>& q) {
  const std::vector<Eigen::Isometry3d> poses = model.linkPoses(base, q);
  std::vector<double> inertias;
  for (int j : model.movableJoints()) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    const Eigen::Isometry3d& frame = poses[static_cast<std::size_t>(joint.childLink)];
    const Eigen::Vector3d axis = frame.linear() * joint.axis;  // the child frame's origin is on it
    double inertia = 0.0;
    std::vector<int> pending{joint.childLink};
    while (!pending.empty()) {
      const Link& link = model.links[static_cast<std::size_t>(pending.back())];
      const Eigen::Isometry3d com =
          poses[static_cast<std::size_t>(pending.back())] * link.inertial.origin;
      pending.pop_back();
      for (int child : link.childJoints)
        pending.push_back(model.joints[static_cast<std::size_t>(child)].childLink);
      if (joint.type == JointType::Prismatic) {
        inertia += link.inertial.mass;
        continue;
      }
      const Eigen::Vector3d arm = com.translation() - frame.translation();
      const Eigen::Vector3d lever = arm - arm.dot(axis) * axis;
      const Eigen::Matrix3d rotated =
          com.linear() * link.inertial.inertia * com.linear().transpose();
      inertia += axis.dot(rotated * axis) + link.inertial.mass * lever.squaredNorm();
    }
    inertias.push_back(inertia);
  }
  return inertias;
}

}  // namespace kautham::core
