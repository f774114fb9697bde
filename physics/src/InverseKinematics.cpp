#include "kautham/physics/InverseKinematics.h"

#include <algorithm>
#include <cmath>

#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

namespace kautham::physics {

namespace {

/// Metres of position error that one radian of axis error weighs as: a 0.1 rad tilt counts as
/// much as 2 cm, so neither error wins the optimisation alone.
constexpr double kAxisWeight = 0.2;
/// Weight of the pull towards the seed: Eigen's Levenberg-Marquardt needs at least as many
/// residuals as unknowns, which a 7-joint arm reaching a 6-number pose does not have; a faint
/// pull to the seed adds one per coordinate and picks, among the arm's many solutions, one
/// near the seed.
constexpr double kSeedWeight = 1e-3;

/// The residuals of a pose target as Eigen's optimisers want a functor: position (3), approach
/// axis (3, when given), level axis (1, when given), at coordinates clamped into [0, 1].
struct PoseResiduals {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

  const JointSpace* joints;
  int link;
  const PoseTarget* target;
  Eigen::VectorXd seed;

  int inputs() const { return static_cast<int>(joints->dimension()); }
  int values() const {
    return 3 + (target->approach ? 3 : 0) + (target->levelAxis ? 1 : 0) + inputs();
  }

  Eigen::Isometry3d pose(const Eigen::VectorXd& c) const {
    const Eigen::VectorXd clamped = c.cwiseMax(0.0).cwiseMin(1.0);
    return joints->linkPose(joints->jointValues(clamped.data()), link);
  }

  int operator()(const Eigen::VectorXd& c, Eigen::VectorXd& residual) const {
    const Eigen::Isometry3d p = pose(c);
    residual.head<3>() = p.translation() - target->position;
    int next = 3;
    if (target->approach) {
      residual.segment<3>(next) = kAxisWeight * (p.linear().col(2) - *target->approach);
      next += 3;
    }
    if (target->levelAxis) residual[next++] = kAxisWeight * (p.linear() * *target->levelAxis).z();
    residual.tail(inputs()) = kSeedWeight * (c - seed);
    return 0;
  }
};

}  // namespace

std::pair<double, double> InverseKinematics::errors(const PoseTarget& target,
                                                    const std::vector<double>& c) const {
  const Eigen::Isometry3d pose = joints_->linkPose(joints_->jointValues(c.data()), link_);
  const double position = (pose.translation() - target.position).norm();
  double angle = 0.0;
  if (target.approach)
    angle = std::acos(std::clamp(pose.linear().col(2).dot(*target.approach), -1.0, 1.0));
  if (target.levelAxis)
    angle = std::max(
        angle, std::asin(std::clamp(std::abs((pose.linear() * *target.levelAxis).z()), 0.0, 1.0)));
  return {position, angle};
}

std::optional<std::vector<double>> InverseKinematics::solve(const PoseTarget& target,
                                                            const std::vector<double>& seed) const {
  ++solves_;
  PoseResiduals residuals{joints_, link_, &target,
                          Eigen::Map<const Eigen::VectorXd>(seed.data(), seed.size())};
  Eigen::NumericalDiff<PoseResiduals> differentiated(residuals);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<PoseResiduals>> optimiser(differentiated);
  optimiser.parameters.maxfev = 400;
  Eigen::VectorXd c = Eigen::Map<const Eigen::VectorXd>(seed.data(), residuals.inputs());
  optimiser.minimize(c);
  c = c.cwiseMax(0.0).cwiseMin(1.0);
  std::vector<double> result(c.data(), c.data() + c.size());
  const auto [position, angle] = errors(target, result);
  if (position > target.tolerance || angle > target.angleTolerance) return std::nullopt;
  return result;
}

}  // namespace kautham::physics
