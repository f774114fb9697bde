#include "kautham/planners/pkpiece/GoalSteering.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace kautham::planners {

namespace {
constexpr double kProbe = 0.5;     // control of a probe step (controls lie in [-1, 1])
constexpr double kDamping = 1e-3;  // m per step: keeps the least squares tame near singularities
}  // namespace

GoalSteering::GoalSteering(const physics::PlanningContext& context, MotionEvaluator& evaluator)
    : context_(context), evaluator_(evaluator) {}

std::optional<NominalMotion> GoalSteering::towardsGoal(const double* start) const {
  if (context_.goal().spec().joints.size() > 0) return std::nullopt;
  // While an object fills the goal's free space, the straight move at the goal point only
  // shoves it on towards the target: the expansion keeps its random candidates instead.
  if (context_.goal().freeSpaceBlocker(start)) return std::nullopt;
  const auto& si = context_.spaceInformation();
  const auto dimension = static_cast<Eigen::Index>(si->getControlSpace()->getDimension());
  std::vector<NominalMotion> probes(static_cast<std::size_t>(dimension) + 1);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    probes[i].control.assign(static_cast<std::size_t>(dimension), 0.0);
    if (i > 0) probes[i].control[i - 1] = kProbe;
    probes[i].steps = 1;
  }
  const std::vector<NominalRun> runs = evaluator_.runNominals(start, probes, false);
  for (const NominalRun& run : runs)
    if (run.steps == 0) return std::nullopt;
  const physics::WorldLayout& layout = context_.layout();
  const Eigen::Vector3d drift = layout.goalLinkPosition(runs[0].end.data());
  Eigen::MatrixXd jacobian(3, dimension);  // link displacement per step and unit of control
  for (Eigen::Index i = 0; i < dimension; ++i)
    jacobian.col(i) =
        (layout.goalLinkPosition(runs[static_cast<std::size_t>(i) + 1].end.data()) - drift) /
        kProbe;
  const Eigen::Vector3d toGo = context_.goal().position() - layout.goalLinkPosition(start);
  const Eigen::Matrix3d damped =
      jacobian * jacobian.transpose() + kDamping * kDamping * Eigen::Matrix3d::Identity();
  const Eigen::VectorXd perStep = jacobian.transpose() * damped.ldlt().solve(toGo);
  // The fewest steps whose control stays within the limits; the longest one, scaled down,
  // when none does.
  const unsigned minSteps = si->getMinControlDuration();
  const unsigned maxSteps = si->getMaxControlDuration();
  const double largest = perStep.cwiseAbs().maxCoeff();
  if (!std::isfinite(largest) || largest <= 0.0) return std::nullopt;
  const unsigned steps = std::clamp(static_cast<unsigned>(std::ceil(largest)), minSteps, maxSteps);
  const Eigen::VectorXd control = perStep / std::max(static_cast<double>(steps), largest);
  NominalMotion motion;
  motion.control.assign(control.data(), control.data() + control.size());
  motion.steps = steps;
  return motion;
}

}  // namespace kautham::planners
