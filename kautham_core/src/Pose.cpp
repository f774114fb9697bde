#include "kautham/core/Pose.h"

#include <algorithm>
#include <cmath>

namespace kautham::core {

Eigen::Isometry3d Pose::isometry() const {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = orientation.normalized().toRotationMatrix();
  transform.translation() = position;
  return transform;
}

Pose Pose::fromIsometry(const Eigen::Isometry3d& transform) {
  return {transform.translation(), Eigen::Quaterniond(transform.linear()).normalized()};
}

Pose Pose::fromAxisAngle(const Eigen::Vector3d& position, const Eigen::Vector3d& axis,
                         double angle) {
  const double norm = axis.norm();
  // Kautham writes "0 0 1 0" for no rotation, but also "0 0 0 0": both mean identity.
  if (norm < 1e-12 || angle == 0.0) return {position, Eigen::Quaterniond::Identity()};
  return {position, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis / norm))};
}

double tiltAngle(const Eigen::Quaterniond& orientation) {
  const Eigen::Vector3d up = orientation * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up.z() / up.norm(), -1.0, 1.0));
}

}  // namespace kautham::core
