#pragma once

#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "kautham/physics/UncertaintySampler.h"
#include "kautham/physics/WorldLayout.h"
#include "kautham/planners/pkpiece/GaussianMixture.h"

namespace kautham::planners {

/// What a p-KPIECE motion knows about where the objects are at its end (the paper's U_rgn):
/// per movable object and target, a Gaussian mixture over its planar pose, or nothing for an
/// object whose pose is certain. It starts as the initial uncertainty U_init, one Gaussian
/// per object; after an interaction the displaced objects get the mixture fitted by EM to the
/// particles' outcomes. Immutable once built: motions share it until an interaction changes it.
class ObjectPoseBelief {
 public:
  /// U_init: each uncertain object's Gaussian around its pose in `start`.
  static std::shared_ptr<const ObjectPoseBelief> initial(const physics::WorldLayout& layout,
                                                         const physics::UncertaintySampler& sampler,
                                                         const double* start);

  /// Replaces the uncertain objects' poses in `state` by a draw from their distribution.
  void samplePoses(double* state, std::mt19937_64& rng) const;

  /// The belief after a motion: objects that the motion moved (more than a millimetre), in
  /// the nominal run or in a particle, get the mixture fitted to the outcomes (the nominal end
  /// state and every particle's end state); the others keep their distribution from `this`.
  /// A particle's move is measured from its own start (`particleStarts[p]`, where its poses
  /// were sampled), not from the nominal start: an object no particle touched keeps its
  /// distribution exactly. Throws std::invalid_argument if the two lists differ in length.
  std::shared_ptr<const ObjectPoseBelief> afterMotion(
      const std::vector<std::size_t>& objectBodies, const double* nominalStart,
      const double* nominalEnd, const std::vector<std::vector<double>>& particleStarts,
      const std::vector<std::vector<double>>& particleEnds, std::mt19937_64& rng) const;

  /// The distribution of a body's planar pose; nullptr if its pose is certain.
  const GaussianMixture* distribution(std::size_t body) const;

  /// Components of the mixture of each object body (0: certain).
  std::vector<std::size_t> componentCounts() const;

 private:
  std::vector<std::optional<GaussianMixture>> perBody_;  ///< indexed by body; empty: certain
};

}  // namespace kautham::planners
