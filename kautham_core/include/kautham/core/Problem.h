#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/ControlSet.h"
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

  bool isZero() const { return x == 0.0 && y == 0.0 && yaw == 0.0; }
};

/// The top-level <Uncertainty> element's contact and control parts (the paper's U_D and
/// U_epsilon): standard deviations of ODE's contact parameters around <Physics>'s values, and
/// of the Gaussian noise added to each control dimension (controls lie in [-1, 1]).
struct ContactUncertainty {
  double friction = 0.0;
  double erp = 0.0;
  double cfm = 0.0;
  double control = 0.0;
  SourceLocation where;
};

/// A URDF model placed in the scene.
struct ModelInstance {
  std::string name;
  std::filesystem::path urdf;
  KinematicModel model;
  Pose home;
  SourceLocation where;
  SourceLocation homeWhere;  ///< its <Home> element (`where` when it has none), for messages
};

/// Kautham's <Limits name="X|Y|Z" min max>: the robot's base slides along an axis of its
/// <Home> frame (a prismatic joint added in front of the URDF's root link).
struct BaseAxisLimits {
  std::string axis;  ///< "X", "Y" or "Z"
  double min = 0.0;
  double max = 0.0;
  double velocity = 0.5;  ///< m/s (an addition of this project; Kautham has none)
  double effort = 100.0;  ///< N
  SourceLocation where;
};

struct RobotInstance : ModelInstance {
  /// Joint values when a query gives no <Init>, in the order of movableJoints().
  std::vector<double> initialJoints;
  std::vector<BaseAxisLimits> baseAxes;  ///< mobile-base joints added to `model`, if any
  /// How the planner's controls move the joints (from <Controls>, or one per joint).
  ControlSet controls;
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
  /// The effective initial pose uncertainty: the object's own <Uncertainty>, else the problem's
  /// default (top-level <Uncertainty x y yaw>); always zero for fixed objects.
  PoseUncertainty uncertainty;
  std::optional<EnvironmentSource> environment;  ///< set for sensed environments only
};

/// The <Physics> block: the ODE world and its contact model.
struct PhysicsSettings {
  double stepSize = 0.01;  ///< seconds per physics step
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  int maxContacts = 8;  ///< contact points per pair; fewer than 8 lets resting cylinders creep
  int solverIterations = 20;  ///< iterations of ODE's QuickStep solver
  /// QuickStep's successive over-relaxation factor (ODE's default 1.3): above 1 each
  /// iteration overshoots its correction, so fewer iterations reach the same accuracy
  /// (docs/physics.md, "Over-relaxation").
  double overRelaxation = 1.3;
  double friction = 0.6;  ///< Coulomb friction coefficient mu
  double erp = 0.2;       ///< contact error reduction parameter
  double cfm = 1e-5;      ///< contact constraint force mixing
  /// Objects at rest sleep until something awake touches them (docs/physics.md, "Sleeping
  /// objects"): a resting object costs no contacts and no solver work.
  bool sleep = true;
  double sleepSpeed = 0.01;  ///< m/s and rad/s below which an object counts as idle
  int sleepSteps = 10;       ///< idle steps after which an object falls asleep
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

/// The <Kinodynamics> block: how far the robot's own motion may go (DESIGN.md section 4).
struct KinodynamicLimits {
  double jointLimitTolerance = 0.02;  ///< rad or m a joint may pass its URDF limit (ODE stops give)
  double jointSpeedFactor = 1.2;  ///< a joint faster than this times its URDF velocity is invalid
  double maxLinkSpeed = 2.0;      ///< m/s, any robot link's centre of mass
  SourceLocation where;
};

/// The goal of a query. Either a pre-grasp region: a robot link's origin within `tolerance`
/// of a point given in the frame of `relativeTo` (an object's home pose; the world when empty),
/// optionally with the link's +z axis within `approachTolerance` of the `approach` direction;
/// or (Kautham's <Goal>) a configuration: normalized controls, reached when the normalized
/// joint values are within `jointTolerance` (Euclidean) of it.
struct GoalRegion {
  std::string link;  ///< for a configuration goal: the robot's tip link (projection, pictures)
  std::string relativeTo;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double tolerance = 0.02;
  std::optional<Eigen::Vector3d> approach;  ///< unit vector, in the frame of `relativeTo`
  double approachTolerance = 0.35;          ///< rad
  /// An axis of the goal link (in its own frame) that must lie level, within
  /// `approachTolerance` of horizontal: for a side grasp, the axis the fingers open along.
  std::optional<Eigen::Vector3d> levelAxis;
  /// A box in the goal link's frame that no movable object may occupy in a goal state:
  /// the space between the open fingers and on the final approach to the grasp.
  struct FreeSpace {
    Eigen::Vector3d size = Eigen::Vector3d::Zero();    ///< full side lengths, m
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< in the goal link's frame
  };
  std::optional<FreeSpace> freeSpace;
  /// Length (m) of the straight corridor before the pre-grasp, along the approach, that the
  /// gripper sweeps on a side approach; `kautham check` counts the objects standing in it.
  double approachCorridor = 0.0;
  std::vector<double> controls;  ///< configuration goal (normalized controls)
  double jointTolerance = 0.05;
  SourceLocation where;

  bool isConfiguration() const { return !controls.empty(); }
};

struct Query {
  std::string name;
  /// Normalized initial controls in [0,1] (Kautham's <Init>, one per control); empty: every
  /// joint at 0, clamped into its limits.
  std::vector<double> init;
  /// <Init><Joint name value/>...</Init>: the start given joint by joint (radians, metres), in
  /// the order of movableJoints(); when set it replaces `init`.
  std::vector<double> initJoints;
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
  SourceLocation nameWhere;  ///< the <Name> element
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
  /// Top-level <Uncertainty x y yaw>: the default initial pose uncertainty of every movable
  /// object and the target (already applied to ObjectInstance::uncertainty).
  PoseUncertainty defaultPoseUncertainty;
  /// Top-level <Uncertainty friction erp cfm control>.
  ContactUncertainty uncertainty;
  InteractionConstraints interaction;
  KinodynamicLimits kinodynamics;
  Eigen::AlignedBox3d workspace;  ///< where the robot's goal link may go
  /// Kautham's ODE environment has an implicit ground: a plane z = height that objects rest on
  /// and the robot passes through. Set for files in Kautham's own form (no roles) planned with
  /// physics; empty for this project's scenes, which stand on a table.
  std::optional<double> groundHeight;
  PlannerSpec planner;
  std::vector<Query> queries;

  const ObjectInstance& target() const;
  std::optional<int> findObject(const std::string& objectName) const;
  /// World position of the goal region's centre (of the goal link, for a configuration goal).
  Eigen::Vector3d goalPosition(const GoalRegion& goal) const;
  /// World direction the goal link's +z axis must point along, if the goal constrains it.
  std::optional<Eigen::Vector3d> goalApproach(const GoalRegion& goal) const;
  /// Joint values of the robot at the start of a query.
  std::vector<double> initialJointValues(const Query& query) const;
  /// Joint values reached by normalized controls (Kautham's mapping through the control set).
  std::vector<double> jointValuesFromControls(const std::vector<double>& controls) const;
  bool hasTarget() const;
  /// The fixed object that movable objects must stay on: the one named by <Interaction
  /// support>, else the highest fixed object under the target; none if nothing is under it
  /// (or there is no target).
  std::optional<int> supportObject() const;
};

/// Every collision shape of a model at its home pose (joints at zero), placed in the world.
std::vector<CollisionShape> shapesAtHome(const ModelInstance& instance);

/// World-aligned bounding box of an object's collision geometry at its home pose.
Eigen::AlignedBox3d boundsAtHome(const ModelInstance& instance);

}  // namespace kautham::core
