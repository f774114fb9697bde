#pragma once

#include <limits>
#include <memory>

#include <ompl/base/goals/GoalRegion.h>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// A pre-grasp region: the goal link's origin within a tolerance of a point in the workspace.
class WorkspaceGoal : public ompl::base::GoalRegion {
 public:
  WorkspaceGoal(const ompl::base::SpaceInformationPtr& si,
                std::shared_ptr<const WorldLayout> layout, const Eigen::Vector3d& position,
                double tolerance);

  /// Distance of the goal link to the goal point; also tracks the best seen, for progress.
  double distanceGoal(const ompl::base::State* state) const override;
  double distance(const double* state) const;
  const Eigen::Vector3d& position() const { return position_; }

  /// Smallest distanceGoal() since the last reset: how close the search has come.
  double bestDistance() const { return best_; }
  void resetBestDistance() { best_ = std::numeric_limits<double>::infinity(); }

 private:
  std::shared_ptr<const WorldLayout> layout_;
  Eigen::Vector3d position_;
  mutable double best_ = std::numeric_limits<double>::infinity();
};

}  // namespace kautham::physics
