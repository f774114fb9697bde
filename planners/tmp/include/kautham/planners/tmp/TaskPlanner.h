#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>

#include "kautham/core/Parameter.h"
#include "kautham/physics/PathTracking.h"
#include "kautham/planners/ControlReporter.h"
#include "kautham/planners/geometric/GeometricQuery.h"
#include "kautham/planners/tmp/Placement.h"

namespace kautham::planners::tmp {

/// About 2 s of RRTConnect on the development machine (13,000 to 18,000 checks a second).
constexpr int kDefaultSubQueryWork = 25000;

struct TaskSettings {
  bool uncertainty = false;  ///< TMP-U: movable objects inflated by their pose uncertainty
  double sigmas = 3.0;       ///< k: the inflation is k standard deviations of x and y
  /// Work each geometric sub-query may take, in collision checks (IK solves count 10)
  int subQueryWork = kDefaultSubQueryWork;
  int maxMoves = 20;         ///< objects moved at most, before giving up
  double speed = 0.5;        ///< joint speed along paths, a fraction of the limits
  double clearance = 0.002;  ///< m kept from every obstacle while planning
  double graspGap = 0.01;    ///< m between the object's top and the gripper's origin

  static core::SettingsParameters<TaskSettings> parameters(bool withUncertainty);
};

/// The task-and-motion-planning baseline (after Srivastava et al. 2014; with uncertainty,
/// Hadfield-Menell et al. 2015), docs/planners.md "TMP". While no collision-free path reaches
/// the pre-grasp, it asks where the arm would go if movable objects were not there, takes
/// the first object that path runs into (or that fills the goal's free space), grasps it from
/// above, carries it to a free place on the table off that path, and releases it; then it
/// tries again. Every motion is a geometric plan (RRTConnect over JointSpace) driven through
/// the physics; a grasp fixes the object to the gripper. Its planning time includes every
/// sub-query.
class TaskPlanner : public ompl::base::Planner, public ControlReporter {
 public:
  TaskPlanner(physics::PlanningContext& context, const std::string& name, TaskSettings settings);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  std::vector<physics::ControlStep> solutionControls() const override { return plan_.controls; }

 private:
  using Ptc = ompl::base::PlannerTerminationCondition;

  /// The world state the plan has reached, as the scene of the next geometric query.
  const std::vector<double>& now() const { return plan_.states.back(); }
  std::vector<double> coordinatesNow() const;
  /// The gripper at `target`, IK seeded near where the arm is now.
  ompl::base::GoalPtr poseGoal(const physics::PoseTarget& target) const;
  /// Whether IK finds a valid configuration for a pose goal in the scene as it is now.
  bool reachable(const ompl::base::Goal& goal);
  /// Whether IK puts the gripper on `target` at all, obstacles aside.
  bool withinReach(const physics::PoseTarget& target);
  /// A geometric plan from where the arm is now, within `share` of a sub-query's work.
  std::optional<geometric::CoordinatePath> planTo(const ompl::base::GoalPtr& goal, const Ptc& ptc,
                                                  double share = 1.0);
  /// Drives the path through the physics from now(); the first control carries `action`.
  bool execute(const geometric::CoordinatePath& path, physics::GripperAction action, int object);
  bool holdStill(physics::GripperAction action, unsigned steps);
  /// Holds the arm still until the held `object` is at rest (or a short while has passed).
  bool stopHolding(std::size_t object);

  /// The object to move next, and the gripper's path to the pre-grasp if nothing blocked it.
  std::optional<std::size_t> obstruction(const Ptc& ptc);
  bool moveAway(std::size_t object, const Ptc& ptc);
  bool grasp(std::size_t object, const Ptc& ptc);
  /// The gripper's pose to grasp `object` from above, if the arm reaches one.
  std::optional<physics::PoseTarget> graspFromAbove(std::size_t object);
  bool lift(std::size_t object);
  bool carryAway(std::size_t object, const Ptc& ptc);
  /// Carries the held object to the first of `places` the arm reaches and a path leads to
  /// that the physics can follow; false if there is none.
  bool carryTo(std::size_t object, const std::vector<Eigen::Vector2d>& places, const Ptc& ptc);

  Footprint footprint(std::size_t body) const;
  PlacementRules placementRules(std::size_t moved) const;
  /// Free places for `object` within the arm's reach, farthest from the pre-grasp first; off
  /// every corridor found so far, or only off the latest (when the others leave no room).
  std::vector<Eigen::Vector2d> placesFor(std::size_t object, bool latestCorridorOnly);
  void setObjectMargin();

  physics::PlanningContext& context_;
  TaskSettings settings_;
  geometric::GeometricQuery query_;
  ompl::base::PlannerPtr motionPlanner_;
  physics::TrackedPath plan_;
  /// Where the gripper would sweep to the pre-grasp, one polyline per obstruction query.
  std::vector<std::vector<Eigen::Vector2d>> corridors_;
  /// Set by obstruction() when the path it found runs into nothing: the way to the goal.
  std::optional<geometric::CoordinatePath> clearPath_;
  std::set<std::size_t> unmovable_;   ///< objects whose move failed since the last that did not
  std::set<std::size_t> placed_;      ///< objects this planner has put down somewhere
  std::set<std::size_t> outOfReach_;  ///< objects the gripper cannot reach from above
  ompl::RNG rng_;
  int moves_ = 0;
  int subQueries_ = 0;
};

}  // namespace kautham::planners::tmp
