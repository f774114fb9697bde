#pragma once

#include <memory>

#include <ompl/base/ProjectionEvaluator.h>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// KPIECE's projection: the end effector's position in the workspace (x and y, plus z when
/// the workspace has height). Cells are `cellFraction` of the workspace side on each axis.
class EndEffectorProjection : public ompl::base::ProjectionEvaluator {
 public:
  EndEffectorProjection(const ompl::base::StateSpace* space,
                        std::shared_ptr<const WorldLayout> layout,
                        const Eigen::AlignedBox3d& workspace);

  unsigned int getDimension() const override { return dimension_; }
  void defaultCellSizes() override;
  void project(const ompl::base::State* state,
               Eigen::Ref<Eigen::VectorXd> projection) const override;

  /// Sets the cell size to `fraction` of the workspace side on every projected axis.
  void setCellFraction(double fraction);

 private:
  std::shared_ptr<const WorldLayout> layout_;
  Eigen::AlignedBox3d workspace_;
  unsigned int dimension_;
};

}  // namespace kautham::physics
