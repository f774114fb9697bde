#pragma once

#include <memory>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// OMPL state space of the whole world: every dynamic body's pose and velocity, plus the
/// contact events of the step that produced the state (see WorldLayout).
/// Distances are between end-effector positions: that is what "closer to the goal" means to
/// the planners, and the objects' states are consequences, not choices.
class WorldStateSpace : public ompl::base::RealVectorStateSpace {
 public:
  WorldStateSpace(std::shared_ptr<const WorldLayout> layout, const Eigen::AlignedBox3d& region);

  double distance(const ompl::base::State* a, const ompl::base::State* b) const override;

  const WorldLayout& layout() const { return *layout_; }
  static const double* values(const ompl::base::State* state);
  static double* values(ompl::base::State* state);

 private:
  std::shared_ptr<const WorldLayout> layout_;
};

}  // namespace kautham::physics
