#pragma once

#include <memory>
#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// OMPL state space of the whole world: every dynamic body's pose and velocity, plus the
/// contact events of the step that produced the state (see WorldLayout).
/// Distances are between end-effector positions: that is what "closer to the goal" means to
/// the planners, and the objects' states are consequences, not choices. For a configuration
/// goal they are between joint values instead (measureJoints).
class WorldStateSpace : public ompl::base::RealVectorStateSpace {
 public:
  /// `workspace` is where the end effector may go: it bounds the sampled end-effector
  /// positions (with a margin) and sizes the projection's cells.
  WorldStateSpace(std::shared_ptr<const WorldLayout> layout, const Eigen::AlignedBox3d& workspace);

  double distance(const ompl::base::State* a, const ompl::base::State* b) const override;
  /// Measures distances between joint configurations instead (metres and radians, continuous
  /// joints the short way round), for a configuration goal, so that tree planners grow towards
  /// what the goal asks. A mobile base's goal has a heading, which end-effector positions do not
  /// see: Kautham's Tiago RRT grew 78000 states in 10 s and stopped beside a table, its heading
  /// wrong wherever it came near the goal.
  void measureJoints() { jointRanges_.assign(layout_->joints.size(), 1.0); }
  /// Registers the end-effector projection as the default one. (RealVectorStateSpace's own
  /// would project the first state numbers, the robot's carriage, and OMPL calls this from
  /// setup(), replacing any projection registered before.)
  void registerProjections() override;

  const WorldLayout& layout() const { return *layout_; }
  static const double* values(const ompl::base::State* state);
  static double* values(ompl::base::State* state);

 private:
  std::shared_ptr<const WorldLayout> layout_;
  Eigen::AlignedBox3d workspace_;
  std::vector<double> jointRanges_;  ///< per joint: its unit; empty: end-effector distances
};

}  // namespace kautham::physics
