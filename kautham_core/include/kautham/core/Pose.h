#pragma once

#include <Eigen/Geometry>

namespace kautham::core {

/// A rigid placement: position plus unit quaternion orientation.
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();

  Eigen::Isometry3d isometry() const;
  static Pose fromIsometry(const Eigen::Isometry3d& transform);
  /// Kautham's <Home X Y Z WX WY WZ TH>: a position and a rotation of TH radians about (WX,WY,WZ).
  static Pose fromAxisAngle(const Eigen::Vector3d& position, const Eigen::Vector3d& axis,
                            double angle);
};

/// Angle (radians) between the body's z axis and the world's z axis: how far it is tipped over.
double tiltAngle(const Eigen::Quaterniond& orientation);

}  // namespace kautham::core
