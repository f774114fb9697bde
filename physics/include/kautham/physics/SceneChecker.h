#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <set>
#include <vector>

#include <ompl/base/StateValidityChecker.h>

#include "kautham/physics/JointSpace.h"
#include "kautham/physics/World.h"
#include "kautham/physics/WorldValidityChecker.h"

namespace kautham::physics {

/// An object carried by the gripper: it moves with the goal link, rigidly.
struct HeldObject {
  std::size_t body = 0;                                         ///< index into the layout's bodies
  Eigen::Isometry3d inGripper = Eigen::Isometry3d::Identity();  ///< its link in the goal link
};

/// Which objects a geometric query treats as obstacles.
enum class Obstacles {
  Everything,  ///< fixed obstacles, the target and every movable object (geometric planning)
  FixedOnly,   ///< fixed obstacles and the target: where would the arm go if nothing blocked?
};

/// Geometric validity over a JointSpace (states are its coordinates, RealVectorStateSpace):
/// the robot at those coordinates, every object frozen where the scene state has it, and no
/// contact between the robot (or what it holds) and anything else. Safe to call from several
/// threads (they take turns with the world). Nothing is simulated: each
/// check writes the poses into the world and asks ODE's collision detection.
class SceneChecker : public ompl::base::StateValidityChecker {
 public:
  /// `rules` also judges every configuration's world state (the robot's workspace and joint
  /// limits: what replays will judge the executed path by), when given.
  SceneChecker(const ompl::base::SpaceInformationPtr& si, World& world, const JointSpace& joints,
               int gripperLink, const double* scene, const WorldValidityChecker* rules = nullptr);

  bool isValid(const ompl::base::State* state) const override;
  /// What the robot touches at coordinates `c` (obstacles as set by setObstacles).
  RobotTouches touchesAt(const double* c) const;
  /// The world state with the robot at coordinates `c` and the held object in its gripper.
  std::vector<double> stateAt(const double* c) const;

  void setScene(const double* scene);
  const std::vector<double>& scene() const { return scene_; }
  void hold(std::optional<HeldObject> object) { held_ = object; }
  const std::optional<HeldObject>& held() const { return held_; }
  /// `solid`: movable objects that stay obstacles under Obstacles::FixedOnly (ones the task
  /// planner found it cannot move).
  void setObstacles(Obstacles obstacles, std::set<std::size_t> solid = {}) {
    obstacles_ = obstacles;
    solid_ = std::move(solid);
  }
  /// A margin (m) the robot keeps from obstacles: a configuration is valid only if the robot
  /// (with what it holds) also touches nothing when shifted by it along each world axis, both
  /// ways, except along the directions in which it already touches something at `start`
  /// (coordinates; a base resting on the floor). Physics does not track a path exactly, so a
  /// path that grazes an obstacle fails when executed.
  void setClearance(double metres, const double* start);
  double clearance() const { return clearance_; }
  /// A margin (m) kept from movable objects only, horizontally (on top of the clearance): the
  /// objects inflated by their pose uncertainty (the task planner with uncertainty).
  void setObjectMargin(double metres) { objectMargin_ = metres; }
  /// Where the goal link must stay (the problem's workspace shrunk by a margin, so the
  /// physics, tracking the path closely, does not leave the real one).
  void setWorkspace(const Eigen::AlignedBox3d& box) { workspace_ = box; }
  std::uint64_t checks() const { return checks_; }

 private:
  World* world_;
  /// One world for every thread a planner runs (OMPL's PRM samples goals in a second thread).
  mutable std::mutex worldMutex_;
  const WorldValidityChecker* rules_;
  const JointSpace* joints_;
  int gripperLink_;
  std::vector<double> scene_;
  /// What the robot touches in `state` (a stateAt() result), with the clearance and margins.
  RobotTouches touchesOf(const std::vector<double>& state) const;
  /// Touches of the robot placed as in `state` shifted by `offset`.
  RobotTouches touchesShifted(std::vector<double> state, const Eigen::Vector3d& offset) const;
  /// `touches` without the movable objects that are no obstacles (setObstacles).
  RobotTouches obstaclesOnly(RobotTouches touches) const;
  int heldBody() const { return held_ ? static_cast<int>(held_->body) : -1; }

  std::optional<HeldObject> held_;
  double clearance_ = 0.0;
  double objectMargin_ = 0.0;
  std::optional<Eigen::AlignedBox3d> workspace_;
  std::vector<Eigen::Vector3d> shifts_;  ///< the clearance's directions in use
  Obstacles obstacles_ = Obstacles::Everything;
  std::set<std::size_t> solid_;
  mutable std::atomic<std::uint64_t> checks_{0};
};

}  // namespace kautham::physics
