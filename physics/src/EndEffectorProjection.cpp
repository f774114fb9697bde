#include "kautham/physics/EndEffectorProjection.h"

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

namespace {
// A workspace thinner than this (a planar robot's) is projected on x and y only.
constexpr double kFlatWorkspace = 0.05;
constexpr double kDefaultCellFraction = 0.05;
}  // namespace

EndEffectorProjection::EndEffectorProjection(const ompl::base::StateSpace* space,
                                             std::shared_ptr<const WorldLayout> layout,
                                             const Eigen::AlignedBox3d& workspace)
    : ProjectionEvaluator(space),
      layout_(std::move(layout)),
      workspace_(workspace),
      dimension_(workspace.sizes().z() < kFlatWorkspace ? 2u : 3u) {}

void EndEffectorProjection::defaultCellSizes() { setCellFraction(kDefaultCellFraction); }

void EndEffectorProjection::setCellFraction(double fraction) {
  std::vector<double> sizes(dimension_);
  for (unsigned k = 0; k < dimension_; ++k) sizes[k] = fraction * workspace_.sizes()[k];
  setCellSizes(sizes);
}

void EndEffectorProjection::project(const ompl::base::State* state,
                                    Eigen::Ref<Eigen::VectorXd> projection) const {
  const Eigen::Vector3d p = layout_->goalLinkPosition(WorldStateSpace::values(state));
  projection = p.head(dimension_);
}

}  // namespace kautham::physics
