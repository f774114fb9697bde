#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/Problem.h"

namespace kautham::physics {

/// What a dynamic body stands for.
enum class BodyRole { Robot, Movable, Target };
const char* toString(BodyRole role);  ///< "robot", "movable" or "target"

/// One dynamic body of the world: a robot link (with the links fixed to it) or an object.
struct BodyInfo {
  std::string name;
  BodyRole role = BodyRole::Robot;
  int objectIndex = -1;  ///< index into Problem::objects, -1 for robot bodies
  /// Pose of the body's main link in the body frame (ODE bodies sit at the centre of mass).
  Eigen::Isometry3d linkInBody = Eigen::Isometry3d::Identity();
};

/// A collision shape of the world, for pictures and replays: on a body (placed in the body
/// frame) or static (placed in the world).
struct ShapeInfo {
  core::Shape shape;
  int body = -1;  ///< index into WorldLayout::bodies; -1: static geometry
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string owner;  ///< object name, or robot/link
  std::string role;   ///< "robot", "fixed", "movable" or "target"
};

/// Where a robot link is: on a dynamic body, or built into the static base (the base itself,
/// the links fixed to it, and the held joints' links that hang from it).
struct RobotLinkPlacement {
  int body = -1;  ///< index into WorldLayout::bodies; -1: static, `pose` is in the world
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the body frame, or the world
};

/// A robot joint as the state records it: its position and rate are part of every state, so
/// validity can check joint limits and speeds without the physics engine.
struct JointInfo {
  std::string name;
  double lower = 0.0;  ///< radians or metres (both 0 for continuous joints: no limits)
  double upper = 0.0;
  double maxVelocity = 0.0;  ///< URDF velocity limit, rad/s or m/s
  bool limited = true;       ///< false for continuous joints
  /// No control moves it: locked at its start value (its rate is only solver jitter, which
  /// the speed check ignores), or built into the static base if it hangs from it.
  bool held = false;
};

/// Reasons why a propagation step produced an invalid state; stored as bit flags in the state.
enum ContactEvent : unsigned {
  kNoEvent = 0,
  kRobotTouchedFixed = 1u << 0,
  kRobotTouchedTarget = 1u << 1,
  kSimulationDiverged = 1u << 2,
};

/// The layout of a world state: every dynamic body's 13 numbers (position, unit quaternion
/// w-x-y-z, linear and angular velocity), the position of every robot joint, the rate of every
/// robot joint, then one number holding ContactEvent flags. Joint values are read back from the
/// bodies: writing a state sets the bodies only.
/// Planners, validity checks and replays read states through this description only.
class WorldLayout {
 public:
  static constexpr std::size_t kBodyStateSize = 13;
  static constexpr std::size_t kPosition = 0;
  static constexpr std::size_t kOrientation = 3;
  static constexpr std::size_t kLinearVelocity = 7;
  static constexpr std::size_t kAngularVelocity = 10;

  std::vector<BodyInfo> bodies;
  std::vector<ShapeInfo> shapes;
  std::vector<JointInfo> joints;  ///< the robot's movable joints, in KinematicModel order
  std::vector<RobotLinkPlacement> robotLinks;  ///< every robot link, in KinematicModel order
  int goalBody = -1;                           ///< the body that carries the goal link
  Eigen::Isometry3d goalLinkInBody = Eigen::Isometry3d::Identity();

  std::size_t stateSize() const { return flagsIndex() + 1; }
  std::size_t jointPositionIndex() const { return bodies.size() * kBodyStateSize; }
  std::size_t jointVelocityIndex() const { return jointPositionIndex() + joints.size(); }
  std::size_t flagsIndex() const { return jointVelocityIndex() + joints.size(); }

  static Eigen::Vector3d position(const double* state, std::size_t body);
  static Eigen::Quaterniond orientation(const double* state, std::size_t body);
  static Eigen::Vector3d linearVelocity(const double* state, std::size_t body);
  static Eigen::Vector3d angularVelocity(const double* state, std::size_t body);
  unsigned flags(const double* state) const;

  /// World position of the goal link's origin (the end effector).
  Eigen::Vector3d goalLinkPosition(const double* state) const;
  /// World orientation of the goal link (its +z axis is the gripper's approach direction).
  Eigen::Matrix3d goalLinkOrientation(const double* state) const;
  /// World pose of a body's main link.
  Eigen::Isometry3d linkPose(const double* state, std::size_t body) const;
  /// World-aligned bounding box of a body's collision shapes in `state` (without `state`: in
  /// the body's own frame).
  Eigen::AlignedBox3d bounds(std::size_t body, const double* state = nullptr) const;
  /// Puts a body where its main link is at `link` (world pose), at rest.
  void placeBody(double* state, std::size_t body, const Eigen::Isometry3d& link) const;
};

}  // namespace kautham::physics
