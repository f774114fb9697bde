#include "kautham/planners/pkpiece/ObjectPoseBelief.h"

#include <stdexcept>
#include <string>

namespace kautham::planners {

namespace {
// An object that moved less than this in every outcome kept its pose: its distribution stays.
constexpr double kMovedThreshold = 0.001;  // m
}  // namespace

std::shared_ptr<const ObjectPoseBelief> ObjectPoseBelief::initial(
    const physics::WorldLayout& layout, const physics::UncertaintySampler& sampler,
    const double* start) {
  auto belief = std::make_shared<ObjectPoseBelief>();
  belief->perBody_.resize(layout.bodies.size());
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].role == physics::BodyRole::Robot) continue;
    const core::PoseUncertainty& u = sampler.initialUncertainty(b);
    if (u.x <= 0.0 && u.y <= 0.0 && u.yaw <= 0.0) continue;
    // A zero deviation on one axis becomes the mixture's floor: a thousandth of a unit.
    const Eigen::Vector3d sd(std::max(u.x, 1e-4), std::max(u.y, 1e-4), std::max(u.yaw, 1e-4));
    belief->perBody_[b] = GaussianMixture::single(physics::planarPose(start, b), sd);
  }
  return belief;
}

void ObjectPoseBelief::samplePoses(double* state, std::mt19937_64& rng) const {
  for (std::size_t b = 0; b < perBody_.size(); ++b)
    if (perBody_[b]) physics::setPlanarPose(state, b, perBody_[b]->sample(rng));
}

std::shared_ptr<const ObjectPoseBelief> ObjectPoseBelief::afterMotion(
    const std::vector<std::size_t>& objectBodies, const double* nominalStart,
    const double* nominalEnd, const std::vector<std::vector<double>>& particleStarts,
    const std::vector<std::vector<double>>& particleEnds, std::mt19937_64& rng) const {
  if (particleStarts.size() != particleEnds.size())
    throw std::invalid_argument(
        "ObjectPoseBelief::afterMotion: " + std::to_string(particleStarts.size()) +
        " particle starts for " + std::to_string(particleEnds.size()) + " particle ends");
  // Its particles start where their poses were drawn, up to centimetres from the nominal
  // start: measured from there, every object would count as moved and be refitted from a
  // handful of draws of its own distribution (a noisier copy, and most of the fitting time).
  const auto movedBetween = [](const double* from, const double* to, std::size_t body) {
    return (physics::WorldLayout::position(to, body) - physics::WorldLayout::position(from, body))
               .head<2>()
               .norm() > kMovedThreshold;
  };
  auto next = std::make_shared<ObjectPoseBelief>(*this);
  for (std::size_t b : objectBodies) {
    bool moved = movedBetween(nominalStart, nominalEnd, b);
    for (std::size_t p = 0; p < particleEnds.size() && !moved; ++p)
      moved = movedBetween(particleStarts[p].data(), particleEnds[p].data(), b);
    if (!moved) continue;
    std::vector<PlanarPose> outcomes{physics::planarPose(nominalEnd, b)};
    for (const std::vector<double>& end : particleEnds)
      outcomes.push_back(physics::planarPose(end.data(), b));
    if (next->perBody_.size() <= b) next->perBody_.resize(b + 1);  // a belief made certain
    if (outcomes.size() < 2) {
      // No particles (planning without uncertainty): the object is where the motion put it.
      next->perBody_[b].reset();
      continue;
    }
    next->perBody_[b] = GaussianMixture::fit(outcomes, rng);
  }
  return next;
}

const GaussianMixture* ObjectPoseBelief::distribution(std::size_t body) const {
  return body < perBody_.size() && perBody_[body] ? &*perBody_[body] : nullptr;
}

std::vector<std::size_t> ObjectPoseBelief::componentCounts() const {
  std::vector<std::size_t> counts;
  for (const auto& mixture : perBody_) counts.push_back(mixture ? mixture->components().size() : 0);
  return counts;
}

}  // namespace kautham::planners
