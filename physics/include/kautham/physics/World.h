#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ode/ode.h>

#include "kautham/core/Problem.h"
#include "kautham/physics/ContactParameters.h"
#include "kautham/physics/OdeLibrary.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

struct GeomTag;      // what an ODE geometry belongs to (private to the physics library)
struct OdeMeshData;  // arrays that ODE's convex and trimesh geometries point into (private)

/// Two things that interpenetrate deeper than a resting contact does.
struct Overlap {
  std::string first;
  std::string second;
  double depth = 0.0;  ///< metres
};

/// What the robot's moving links, and an object it holds, touch at the current poses.
struct RobotTouches {
  bool fixed = false;       ///< a fixed obstacle (or, for a held object, the robot's base)
  bool target = false;      ///< the target object
  std::vector<int> bodies;  ///< objects touched, movable or target (indices into the layout)
  bool any() const { return fixed || target || !bodies.empty(); }
};

/// A robot joint driven by a velocity motor: one control of the planner.
struct Actuator {
  std::string name;
  dJointID joint = nullptr;  ///< none for a joint built into the static base (heldAt)
  core::JointType type = core::JointType::Revolute;
  double maxVelocity = 0.0;
  double heldAt = 0.0;  ///< the value of a joint built into the static base
};

/// The ODE world built from a problem: a flat collision space, fixed obstacles as static
/// geometry, the robot as bodies joined by motorised joints (without gravity, so it holds
/// itself), objects as free bodies. Owns every ODE object it makes.
///
/// Stepping is reproducible: QuickStep reorders constraints with ODE's process-wide random
/// seed, so `resetSolverSeed()` must be called before a run of steps that must repeat.
/// One World belongs to one thread.
class World {
 public:
  World(const core::Problem& problem, const core::Query& query);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const WorldLayout& layout() const { return layout_; }
  const std::vector<Actuator>& actuators() const { return actuators_; }
  const core::PhysicsSettings& settings() const { return settings_; }

  /// The friction, ERP and CFM of every contact made from the next step on (a particle's
  /// sampled D). Initially <Physics>'s values. Not part of the state: whoever changes them for
  /// a run restores them afterwards (see physics::execute).
  void setContactParameters(const ContactParameters& parameters);
  const ContactParameters& contactParameters() const { return contact_; }

  void readState(double* state) const;
  /// Also decides which objects sleep: exactly those whose velocities in `state` are all
  /// zero, which is how ODE leaves an object it puts to sleep. So sleep is part of the state,
  /// and a run from a written state repeats whatever ran before.
  void writeState(const double* state);

  /// Sets every motor's target velocity (one value per actuator, clamped to its limit).
  void setJointVelocities(const double* velocities);
  /// Current position of each actuated joint (radians or metres), read from ODE.
  std::vector<double> jointPositions() const;
  /// Current rate of each actuated joint (rad/s or m/s), read from ODE.
  std::vector<double> jointVelocities() const;

  void resetSolverSeed() const;
  /// Detects contacts, advances the simulation by one step, and records contact events.
  void step();
  /// Detects contacts without stepping (to check a start state): records contact events and
  /// returns every pair that interpenetrates deeper than `depth` metres.
  std::vector<Overlap> probeContacts(double depth);
  /// Collision query without stepping, for geometric planning: what the robot's moving links
  /// and the body `heldBody` (an object carried by the gripper; -1 for none) touch, among the
  /// things that move with neither. Makes no contact joints and records no events.
  RobotTouches robotTouches(int heldBody = -1);
  /// robotTouches(heldBody), remembering every pair of a moving geometry and another whose
  /// bounding boxes are at most `margin` apart on each axis, and where the moving bodies are:
  /// the only pairs that can touch once they are shifted by up to `margin` (a bounding box
  /// moves with its body), for robotTouchesShifted().
  RobotTouches robotTouchesNear(int heldBody, double margin);
  /// What robotTouches() finds with the moving bodies of the last robotTouchesNear() moved by
  /// `offset` (no component above its margin), testing only the remembered pairs. Moving a body
  /// makes ODE recompute its bounding boxes at the next space-wide test, which for convex hulls
  /// of a thousand vertices was most of a geometric planner's time; this path needs none,
  /// except where a triangle mesh is near (ODE picks its triangles by the other box).
  /// Leaves the moving bodies moved: write a state before anything else.
  RobotTouches robotTouchesShifted(const Eigen::Vector3d& offset);
  /// Fixes the object `body` to the gripper (the goal link's body) where it is now, with an
  /// ODE fixed joint: the task planner's grasp. While held it has no gravity, as the arm's
  /// links have none (a gravity-compensated payload). Returns false, holding nothing, if the object
  /// is not within `reach` metres of the goal link's origin (measured to the object's
  /// bounding box). Holding is not part of the state: replays and executions start with
  /// release().
  bool attach(std::size_t body, double reach);
  /// Lets go of whatever the gripper holds.
  void release();
  std::optional<std::size_t> held() const { return held_; }
  /// Events (ContactEvent flags) recorded since the last call, which clears them.
  unsigned takeEvents();

  /// Bodies the robot touched since the last call (indices into layout().bodies, robot bodies
  /// excluded), which clears the record.
  std::vector<int> takeTouchedBodies();

 private:
  class Builder;
  friend class Builder;

  static void nearCallback(void* data, dGeomID a, dGeomID b);
  static void touchCallback(void* data, dGeomID a, dGeomID b);
  void recordTouch(dGeomID a, dGeomID b);
  void collide(dGeomID a, dGeomID b);
  bool diverged() const;
  static bool isAwake(dBodyID body);  ///< a body that steps (not asleep, not static geometry)
  void destroy();
  void restoreGeomOrder();
  /// Writes each actuated joint's position and rate (the state's joint part; no allocation:
  /// it runs on every propagation).
  void readJoints(double* positions, double* rates) const;
  void recordOverlap(const GeomTag& a, const GeomTag& b, int contacts);
  /// Moves the first `count` contacts of the buffer that are usable to its front; their number.
  int usableContacts(int count);

  std::shared_ptr<OdeLibrary> ode_;
  core::PhysicsSettings settings_;
  ContactParameters contact_;  ///< used by collide(); settings_'s values until changed
  WorldLayout layout_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contactGroup_ = nullptr;
  std::vector<dBodyID> bodies_;        ///< parallel to layout_.bodies
  std::vector<dGeomID> dynamicGeoms_;  ///< geometries on bodies, in creation order
  std::vector<dBodyID> sleepers_;      ///< objects that may sleep (<Physics sleep>)
  std::vector<Actuator> actuators_;
  std::vector<std::unique_ptr<GeomTag>> tags_;
  /// Mesh arrays referenced (not copied) by ODE's geometries: they live as long as the world.
  std::vector<std::shared_ptr<OdeMeshData>> meshData_;
  std::vector<dContact> contactBuffer_;
  unsigned events_ = kNoEvent;
  std::vector<char> touched_;  ///< per body: touched by the robot since takeTouchedBodies()
  std::vector<Overlap>* overlaps_ = nullptr;  ///< set while probeContacts runs
  double overlapDepth_ = 0.0;
  RobotTouches* touches_ = nullptr;  ///< set while robotTouches runs
  dJointID grip_ = nullptr;          ///< the fixed joint of attach()
  std::optional<std::size_t> held_;
  int heldBody_ = -1;
  /// robotTouchesNear()'s pairs (moving geometry first) and its moving bodies' positions.
  std::vector<std::pair<dGeomID, dGeomID>> nearPairs_;
  std::vector<std::pair<dBodyID, Eigen::Vector3d>> nearBodies_;
  int nearHeldBody_ = -1;
  /// robotTouchesShifted() moved bodies without bringing their bounding boxes up to date.
  bool shiftedAside_ = false;
  /// Some of nearPairs_ pair a moving geometry with a triangle mesh or a heightfield.
  bool nearTriangles_ = false;
};

}  // namespace kautham::physics
