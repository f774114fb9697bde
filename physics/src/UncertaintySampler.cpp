#include "kautham/physics/UncertaintySampler.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "kautham/core/Random.h"

namespace kautham::physics {

namespace {

const core::PoseUncertainty kNoUncertainty{};

double gaussian(double mean, double sd, std::mt19937_64& rng) {
  return mean + sd * core::standardNormal(rng);
}

}  // namespace

UncertaintySampler::UncertaintySampler(const core::Problem& problem, const WorldLayout& layout)
    : layout_(layout),
      contact_(problem.uncertainty),
      mean_{problem.physics.friction, problem.physics.erp, problem.physics.cfm},
      poses_(layout.bodies.size()) {
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const BodyInfo& body = layout.bodies[b];
    if (body.role == BodyRole::Robot || body.objectIndex < 0) continue;
    poses_[b] = problem.objects.at(static_cast<std::size_t>(body.objectIndex)).uncertainty;
  }
}

ContactParameters UncertaintySampler::sampleContact(std::mt19937_64& rng) const {
  // Always three draws (six raw numbers), whatever the standard deviations, so that what is
  // drawn after does not depend on which of them are zero.
  ContactParameters p;
  p.friction = std::max(0.0, gaussian(mean_.friction, contact_.friction, rng));
  p.erp = std::clamp(gaussian(mean_.erp, contact_.erp, rng), 0.0, 1.0);
  p.cfm = std::max(0.0, gaussian(mean_.cfm, contact_.cfm, rng));
  return p;
}

void UncertaintySampler::perturbControl(const double* control, double* noisy, std::size_t size,
                                        std::mt19937_64& rng) const {
  for (std::size_t i = 0; i < size; ++i)
    noisy[i] = std::clamp(gaussian(control[i], contact_.control, rng), -1.0, 1.0);
}

void UncertaintySampler::sampleInitialPoses(double* state, std::mt19937_64& rng) const {
  for (std::size_t b = 0; b < layout_.bodies.size(); ++b) {
    if (layout_.bodies[b].role == BodyRole::Robot) continue;
    const core::PoseUncertainty& sd = poses_[b];
    // Three draws per object, zero standard deviations included (see sampleContact).
    const Eigen::Vector3d noise(sd.x * core::standardNormal(rng), sd.y * core::standardNormal(rng),
                                sd.yaw * core::standardNormal(rng));
    if (sd.isZero()) continue;  // leave the state bit for bit as it was
    setPlanarPose(state, b, planarPose(state, b) + noise);
  }
}

const core::PoseUncertainty& UncertaintySampler::initialUncertainty(std::size_t body) const {
  return body < poses_.size() ? poses_[body] : kNoUncertainty;
}

bool UncertaintySampler::hasUncertainty() const {
  if (contact_.friction > 0.0 || contact_.erp > 0.0 || contact_.cfm > 0.0 || contact_.control > 0.0)
    return true;
  return std::any_of(poses_.begin(), poses_.end(),
                     [](const core::PoseUncertainty& p) { return !p.isZero(); });
}

Eigen::Vector3d planarPose(const double* state, std::size_t body) {
  const Eigen::Vector3d position = WorldLayout::position(state, body);
  const Eigen::Matrix3d rotation = WorldLayout::orientation(state, body).toRotationMatrix();
  // Yaw of the body's x axis seen from above (the z of a z-y-x Euler decomposition).
  return {position.x(), position.y(), std::atan2(rotation(1, 0), rotation(0, 0))};
}

void setPlanarPose(double* state, std::size_t body, const Eigen::Vector3d& pose) {
  double* values = state + body * WorldLayout::kBodyStateSize;
  const double turn = pose.z() - planarPose(state, body).z();
  // A turn about the world's z axis, applied before the body's rotation: the tilt (the
  // rotation about horizontal axes) stays as it was.
  const Eigen::Quaterniond rotated =
      (Eigen::Quaterniond(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ())) *
       WorldLayout::orientation(state, body))
          .normalized();
  values[WorldLayout::kPosition + 0] = pose.x();
  values[WorldLayout::kPosition + 1] = pose.y();
  values[WorldLayout::kOrientation + 0] = rotated.w();
  values[WorldLayout::kOrientation + 1] = rotated.x();
  values[WorldLayout::kOrientation + 2] = rotated.y();
  values[WorldLayout::kOrientation + 3] = rotated.z();
}

}  // namespace kautham::physics
