#include "kautham/physics/ControlMapping.h"

#include <algorithm>
#include <stdexcept>

namespace kautham::physics {

ControlMapping::ControlMapping(const core::ControlSet& controls,
                               const std::vector<JointInfo>& joints)
    : matrix_(controls.matrix), maxVelocity_(static_cast<Eigen::Index>(joints.size())) {
  if (static_cast<std::size_t>(matrix_.rows()) != joints.size())
    throw std::logic_error("control set rows do not match the robot's joints");
  for (std::size_t j = 0; j < joints.size(); ++j)
    maxVelocity_[static_cast<Eigen::Index>(j)] = joints[j].maxVelocity;
}

void ControlMapping::jointVelocities(const double* controls, double* velocities) const {
  for (Eigen::Index j = 0; j < matrix_.rows(); ++j) {
    double combined = 0.0;
    for (Eigen::Index i = 0; i < matrix_.cols(); ++i) combined += matrix_(j, i) * controls[i];
    velocities[j] = maxVelocity_[j] * std::clamp(combined, -1.0, 1.0);
  }
}

std::vector<double> ControlMapping::controlsFor(const std::vector<double>& velocities) const {
  Eigen::VectorXd fractions(matrix_.rows());
  for (Eigen::Index j = 0; j < matrix_.rows(); ++j)
    fractions[j] = velocities.at(static_cast<std::size_t>(j)) / maxVelocity_[j];
  const Eigen::VectorXd u = matrix_.completeOrthogonalDecomposition().solve(fractions);
  return {u.data(), u.data() + u.size()};
}

}  // namespace kautham::physics
