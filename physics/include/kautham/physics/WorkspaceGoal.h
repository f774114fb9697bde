#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <ompl/base/goals/GoalRegion.h>

#include "kautham/physics/GoalFreeSpace.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// What a WorkspaceGoal asks for, in world terms (built from core::GoalRegion).
struct GoalSpec {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< where the goal link's origin goes
  double tolerance = 0.02;                             ///< m
  std::optional<Eigen::Vector3d> approach;  ///< world direction for the goal link's +z axis
  double approachTolerance = 0.35;          ///< rad
  /// A goal-link axis (link frame) that must be level within approachTolerance.
  std::optional<Eigen::Vector3d> levelAxis;
  std::optional<core::GoalRegion::FreeSpace> freeSpace;  ///< must hold no movable object
  std::vector<double> joints;       ///< a configuration goal's joint values (else empty)
  std::vector<double> jointRanges;  ///< per joint: what a normalized unit is
  double jointTolerance = 0.05;     ///< normalized Euclidean distance
};

/// The goal of a query. A pre-grasp region: the goal link's origin within a tolerance of a
/// point, and its +z axis (the approach direction of the gripper) within an angle of a
/// direction when the goal gives one; a level axis (the fingers' opening axis) within the same
/// angle of horizontal; and no movable object in the free space between the fingers. Or, for
/// Kautham's <Goal>, a configuration.
class WorkspaceGoal : public ompl::base::GoalRegion {
 public:
  WorkspaceGoal(const ompl::base::SpaceInformationPtr& si,
                std::shared_ptr<const WorldLayout> layout, GoalSpec spec);

  /// searchDistance(); also tracks the best seen, for progress.
  double distanceGoal(const ompl::base::State* state) const override;
  /// Position and approach tolerances must both hold (the distance alone would trade them).
  bool isSatisfied(const ompl::base::State* state, double* distance) const override;
  /// How far the gripper is from the goal: metres for a region (an approach or level error
  /// beyond its tolerance adds 0.1 m per radian), normalized joint units for a configuration.
  /// What plan, replay and validate report.
  double distance(const double* state) const;
  /// distance() plus what still fills the free space at the goal pose (1 m for a box full
  /// of objects): what planners search by, so that clearing a blocker counts as progress.
  double searchDistance(const double* state) const;
  /// The movable object that fills most of the free space at the goal pose (none when the
  /// goal has no free space or it is clear).
  std::optional<std::size_t> freeSpaceBlocker(const double* state) const;
  /// The share of the free space that movable objects fill with the goal link at `goalLink`
  /// (0: clear, and 0 without a free space).
  double freeSpaceFilledAt(const double* state, const Eigen::Isometry3d& goalLink) const;
  /// The goal link at the goal point, turned as the approach and level axis ask.
  const Eigen::Isometry3d& nominalGoalPose() const { return nominalGoalPose_; }
  bool reached(const double* state) const;
  /// reached() but for the free space: the gripper is where the goal asks, turned as it asks.
  bool poseReached(const double* state) const;
  /// Which of poseReached()'s conditions a region's goal link misses (none for a configuration).
  struct PoseMiss {
    bool position = false;  ///< further from the goal point than the tolerance
    bool approach = false;  ///< its +z turned further from the approach than its tolerance
    bool level = false;     ///< its level axis tilted further than the approach tolerance
    bool any() const { return position || approach || level; }
  };
  PoseMiss poseMiss(const double* state) const;
  /// Angle between the goal link's +z axis and the approach direction (0 without one).
  double approachError(const double* state) const;
  /// Angle between the level axis and the horizontal plane (0 without one).
  double levelError(const double* state) const;
  /// Movable objects in the goal's free space at this state (empty without one).
  std::vector<std::string> freeSpaceOccupants(const double* state) const;

  const Eigen::Vector3d& position() const { return spec_.position; }
  const GoalSpec& spec() const { return spec_; }
  /// Smallest distanceGoal() since the last reset: how close the search has come.
  double bestDistance() const { return best_; }
  void resetBestDistance() { best_ = std::numeric_limits<double>::infinity(); }

 private:
  double positionError(const double* state) const;
  double jointError(const double* state) const;

  std::shared_ptr<const WorldLayout> layout_;
  GoalSpec spec_;
  std::optional<GoalFreeSpace> freeSpace_;
  /// The goal link at the goal point, turned as the approach and level axis ask (identity
  /// turn without them): where the free space must be clear in the end.
  Eigen::Isometry3d nominalGoalPose_ = Eigen::Isometry3d::Identity();
  mutable double best_ = std::numeric_limits<double>::infinity();
};

}  // namespace kautham::physics
