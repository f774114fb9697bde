#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/InputError.h"
#include "kautham/core/KinematicModel.h"
#include "kautham/core/Pose.h"

namespace kautham::core {

/// How the planner may treat an object (the paper's fixed, movable and target classes).
enum class ObjectRole { Fixed, Movable, Target };
const char* toString(ObjectRole role);

/// Standard deviations of an object's planar pose: metres for x and y, radians for yaw.
struct PoseUncertainty {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

/// A URDF model placed in the scene.
struct ModelInstance {
  std::string name;
  std::filesystem::path urdf;
  KinematicModel model;
  Pose home;
  SourceLocation where;
};

struct RobotInstance : ModelInstance {
  /// Initial values of the movable joints, in the order of KinematicModel::movableJoints().
  std::vector<double> initialJoints;
};

/// Where an object made by <Environment octomap=".."> came from (see OctomapEnvironment.h).
struct EnvironmentSource {
  std::filesystem::path octree;
  double resolution = 0.0;  ///< metres
  std::size_t leaves = 0;   ///< occupied leaves of the octree
  std::size_t boxes = 0;    ///< boxes they were merged into: the object's collision shapes
};

struct ObjectInstance : ModelInstance {
  ObjectRole role = ObjectRole::Fixed;
  PoseUncertainty uncertainty;
  std::optional<EnvironmentSource> environment;  ///< set for sensed environments only
};

/// The <Physics> block: the ODE world and its contact model.
struct PhysicsSettings {
  double stepSize = 0.01;  ///< seconds per physics step
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  int maxContacts = 8;  ///< contact points per pair; fewer than 8 lets resting cylinders creep
  int solverIterations = 20;  ///< iterations of ODE's QuickStep solver
  double friction = 0.6;      ///< Coulomb friction coefficient mu
  double erp = 0.2;           ///< contact error reduction parameter
  double cfm = 1e-5;          ///< contact constraint force mixing
  SourceLocation where;
};

/// The <Interaction> block: what pushing may do to the scene (the paper's interaction constraints).
struct InteractionConstraints {
  double maxObjectSpeed = 1.0;     ///< m/s, any movable object
  double maxDisplacement = 0.3;    ///< m, the paper's d: one motion may not move an object further
  double maxTilt = 0.35;           ///< rad, how far a movable object may tip
  double targetTolerance = 0.005;  ///< m, how far the target may drift before it counts as moved
  std::string supportObject;       ///< fixed object whose top face objects must stay on
  SourceLocation where;
};

/// A pre-grasp region: a robot link's origin within `tolerance` of a point given in the frame
/// of `relativeTo` (an object's home pose; the world when empty).
struct GoalRegion {
  std::string link;
  std::string relativeTo;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double tolerance = 0.02;
  SourceLocation where;
};

struct Query {
  std::string name;
  /// Normalized initial joint values in [0,1] (Kautham controls); empty: every joint at 0,
  /// clamped into its limits.
  std::vector<double> init;
  GoalRegion goal;
  SourceLocation where;
};

/// One <Parameter> of the <Planner> block, kept as text until the planner's registry types it.
struct PlannerParameter {
  std::string name;
  std::string value;
  SourceLocation where;
};

struct PlannerSpec {
  std::string name;
  std::vector<PlannerParameter> parameters;
  SourceLocation where;
};

/// A loaded and checked problem file.
struct Problem {
  std::string name;
  std::filesystem::path file;
  RobotInstance robot;
  std::vector<ObjectInstance> objects;
  PhysicsSettings physics;
  InteractionConstraints interaction;
  Eigen::AlignedBox3d workspace;  ///< where the robot's goal link may go
  PlannerSpec planner;
  std::vector<Query> queries;

  const ObjectInstance& target() const;
  std::optional<int> findObject(const std::string& objectName) const;
  /// World position of the goal region's centre.
  Eigen::Vector3d goalPosition(const GoalRegion& goal) const;
  /// Joint values of the robot at the start of a query.
  std::vector<double> initialJointValues(const Query& query) const;
  /// The fixed object that movable objects must stay on: the one named by <Interaction
  /// support>, else the highest fixed object under the target; none if nothing is under it.
  std::optional<int> supportObject() const;
};

/// Every collision shape of a model at its home pose (joints at zero), placed in the world.
std::vector<CollisionShape> shapesAtHome(const ModelInstance& instance);

/// World-aligned bounding box of an object's collision geometry at its home pose.
Eigen::AlignedBox3d boundsAtHome(const ModelInstance& instance);

}  // namespace kautham::core
