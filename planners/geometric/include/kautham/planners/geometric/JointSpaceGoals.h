#pragma once

#include <functional>
#include <vector>

#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/util/RandomNumbers.h>

#include "kautham/physics/InverseKinematics.h"
#include "kautham/physics/SceneChecker.h"
#include "kautham/physics/WorkspaceGoal.h"

namespace kautham::planners::geometric {

/// Extra condition on a goal configuration (coordinates): the scene around it, for instance.
using ConfigurationTest = std::function<bool(const double* c)>;

/// A pose of the goal link as a goal over JointSpace coordinates: satisfied within the target's
/// tolerances (and `accept`, when given); sampled by inverse kinematics from random seeds, so
/// bidirectional planners can grow a tree from it.
class PoseGoal : public ompl::base::GoalSampleableRegion {
 public:
  PoseGoal(const ompl::base::SpaceInformationPtr& si, const physics::InverseKinematics& ik,
           physics::PoseTarget target, ConfigurationTest accept = nullptr);

  double distanceGoal(const ompl::base::State* state) const override;
  bool isSatisfied(const ompl::base::State* state, double* distance) const override;
  /// A valid configuration on the target found by IK, or (after many failed tries) a random one
  /// that the planner will find invalid or unsatisfying and skip.
  void sampleGoal(ompl::base::State* state) const override;
  unsigned maxSampleCount() const override { return 1000000; }
  /// Seeds IK near these coordinates first (where the arm is): the goal configurations found
  /// are then near the arm's posture, and the paths to them short, instead of swinging the
  /// arm to whichever of its many solutions a random seed falls into.
  void seedNear(std::vector<double> coordinates) { near_ = std::move(coordinates); }

 private:
  const physics::InverseKinematics* ik_;
  std::vector<double> near_;
  physics::PoseTarget target_;
  ConfigurationTest accept_;
  mutable ompl::RNG rng_;
  mutable std::vector<std::vector<double>> found_;  ///< goal configurations IK found so far
};

/// Kautham's configuration goal: normalized joint values within a Euclidean tolerance.
class ConfigurationGoal : public ompl::base::GoalSampleableRegion {
 public:
  ConfigurationGoal(const ompl::base::SpaceInformationPtr& si, const physics::JointSpace& joints,
                    const physics::GoalSpec& spec);
  double distanceGoal(const ompl::base::State* state) const override;
  void sampleGoal(ompl::base::State* state) const override;
  unsigned maxSampleCount() const override { return 1; }

 private:
  const physics::JointSpace* joints_;
  physics::GoalSpec spec_;
  std::vector<double> goal_;  ///< coordinates of the goal configuration
};

}  // namespace kautham::planners::geometric
