#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/Geometry.h"

namespace kautham::core {

enum class JointType { Fixed, Revolute, Continuous, Prismatic };

struct Inertial {
  double mass = 0.0;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< centre of mass frame in the link
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         ///< about the centre of mass frame
  /// Line of the URDF's <mass> element; 0 when the link has no <inertial>. It tells a mass the
  /// file gives as zero (to be fixed there) from one it does not give at all.
  int massLine = 0;
};

struct Link {
  std::string name;
  Inertial inertial;
  std::vector<CollisionShape> collisions;
  std::vector<VisualShape> visuals;  ///< for pictures only; empty when the URDF gives none
  int parentJoint = -1;              ///< index into KinematicModel::joints, -1 for the root
  std::vector<int> childJoints;
};

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parentLink = -1;
  int childLink = -1;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< child frame in the parent frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();           ///< unit axis in the child frame
  double lower = 0.0;
  double upper = 0.0;
  double maxVelocity = 0.0;
  double maxEffort = 0.0;
  /// URDF <mimic>: this joint follows `joint` as value = multiplier * leader + offset. The
  /// loader couples it to its leader's controls (ControlSet), so it is no degree of freedom of
  /// its own for the planner.
  struct Mimic {
    std::string joint;
    double multiplier = 1.0;
    double offset = 0.0;
  };
  std::optional<Mimic> mimic;

  bool isMovable() const { return type != JointType::Fixed; }
};

/// A tree of links and joints, as a URDF describes a robot or an object.
/// Geometry-only: it knows nothing of the physics engine that will simulate it.
class KinematicModel {
 public:
  std::string name;
  std::vector<Link> links;
  std::vector<Joint> joints;
  int rootLink = 0;

  std::optional<int> findLink(const std::string& linkName) const;
  /// The top of the links that `link` is joined to by fixed joints (the root, or a link whose
  /// parent joint moves): they move as one rigid group, one body in the physics.
  int rigidGroupTop(int link) const;
  /// Joints that move (not fixed), in the order of `joints`: the model's degrees of freedom.
  std::vector<int> movableJoints() const;
  /// World pose of every link for the given values of the movable joints.
  std::vector<Eigen::Isometry3d> linkPoses(const Eigen::Isometry3d& base,
                                           const std::vector<double>& jointValues) const;
  /// Transform that a joint adds at the given value (rotation about, or translation along, its
  /// axis).
  static Eigen::Isometry3d jointMotion(const Joint& joint, double value);
};

}  // namespace kautham::core
