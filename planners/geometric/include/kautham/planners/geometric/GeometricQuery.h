#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>

#include "kautham/physics/InverseKinematics.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/SceneChecker.h"

namespace kautham::planners::geometric {

/// A path over JointSpace coordinates, one vector per waypoint, start first.
using CoordinatePath = std::vector<std::vector<double>>;

/// Geometric planning in one query's world: the robot's JointSpace as an OMPL state space
/// (coordinates in [0, 1]), validity by collision checks of the frozen scene (SceneChecker),
/// inverse kinematics for pose goals. The scene and what the gripper holds can change between
/// plans (the task planner moves objects).
class GeometricQuery {
 public:
  explicit GeometricQuery(physics::PlanningContext& context);

  const physics::JointSpace& joints() const { return *joints_; }
  physics::SceneChecker& checker() { return *checker_; }
  const physics::SceneChecker& checker() const { return *checker_; }
  const physics::InverseKinematics& ik() const { return *ik_; }
  const ompl::base::SpaceInformationPtr& spaceInformation() const { return si_; }
  /// The model index of the goal link (the gripper).
  int gripperLink() const { return gripperLink_; }

  /// The margin the robot keeps from obstacles (SceneChecker::setClearance, with the directions
  /// free at the query's start), and the resolution of collision checks along motions: no
  /// point of the robot moves more than the margin (at least 2 mm) between two checks.
  void setClearance(double metres);

  /// The query's own goal over coordinates. A pre-grasp region is aimed at with half its
  /// tolerances, so the plan ends inside it with margin, and it also needs the goal's free
  /// space clear in the scene; a configuration goal is Kautham's.
  /// Without `freeSpaceClear`, a pre-grasp pose counts whatever fills the goal's free space
  /// (where the task planner asks how it would reach the goal if nothing were in the way).
  /// Pose goals seed their IK near `near` (the query's start when empty).
  ompl::base::GoalPtr problemGoal(bool freeSpaceClear = true, std::vector<double> near = {});

  /// Plans from `start` to `goal` with `planner` (cleared first) until it solves or `ptc`;
  /// simplifies the path (shortcutting, at most a second) when asked. None if not solved.
  std::optional<CoordinatePath> plan(const std::vector<double>& start,
                                     const ompl::base::GoalPtr& goal, ompl::base::Planner& planner,
                                     const ompl::base::PlannerTerminationCondition& ptc,
                                     bool simplify);
  /// Joint values at each waypoint.
  std::vector<std::vector<double>> jointValues(const CoordinatePath& path) const;

 private:
  physics::PlanningContext* context_;
  std::shared_ptr<physics::JointSpace> joints_;
  ompl::base::SpaceInformationPtr si_;
  std::shared_ptr<physics::SceneChecker> checker_;
  int gripperLink_ = -1;
  std::shared_ptr<physics::InverseKinematics> ik_;
};

}  // namespace kautham::planners::geometric
