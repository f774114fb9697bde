#include "kautham/planners/geometric/JointSpaceGoals.h"

#include <algorithm>
#include <cmath>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

namespace kautham::planners::geometric {

namespace {

double* coordinates(ompl::base::State* state) {
  return state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
}
const double* coordinates(const ompl::base::State* state) {
  return state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
}

/// Metres that one radian of axis error counts as in the distance to a pose goal.
constexpr double kMetresPerRadian = 0.1;

}  // namespace

PoseGoal::PoseGoal(const ompl::base::SpaceInformationPtr& si, const physics::InverseKinematics& ik,
                   physics::PoseTarget target, ConfigurationTest accept)
    : GoalSampleableRegion(si), ik_(&ik), target_(std::move(target)), accept_(std::move(accept)) {
  setThreshold(0.0);
}

double PoseGoal::distanceGoal(const ompl::base::State* state) const {
  const double* c = coordinates(state);
  const auto [position, angle] =
      ik_->errors(target_, std::vector<double>(c, c + si_->getStateDimension()));
  return std::max(0.0, position - target_.tolerance) +
         kMetresPerRadian * std::max(0.0, angle - target_.angleTolerance);
}

bool PoseGoal::isSatisfied(const ompl::base::State* state, double* distance) const {
  const double d = distanceGoal(state);
  if (distance) *distance = d;
  return d <= 0.0 && (!accept_ || accept_(coordinates(state)));
}

void PoseGoal::sampleGoal(ompl::base::State* state) const {
  constexpr int kTries = 100;
  ompl::RNG& rng = rng_;  // seeded from OMPL's seed: runs repeat
  const std::size_t dimension = si_->getStateDimension();
  std::vector<double> seed(dimension);
  for (int attempt = 0; attempt < kTries; ++attempt) {
    // Near the arm first, ever wider (a tenth of the range, then up to half), then anywhere.
    const bool near = !near_.empty() && attempt < kTries / 2;
    const double spread = 0.02 + 0.5 * attempt / kTries;
    for (std::size_t i = 0; i < seed.size(); ++i)
      seed[i] = near ? std::clamp(near_[i] + rng.gaussian(0.0, spread), 0.0, 1.0) : rng.uniform01();
    const auto solution = ik_->solve(target_, seed);
    if (!solution) continue;
    std::copy(solution->begin(), solution->end(), coordinates(state));
    if (si_->isValid(state) && (!accept_ || accept_(coordinates(state)))) {
      found_.push_back(*solution);
      return;
    }
  }
  // Nothing new: one found before (a goal state all the same); else a state outside the
  // bounds, which planners skip (RRTConnect would take any valid sample for a goal state).
  if (!found_.empty()) {
    const std::vector<double>& again =
        found_[static_cast<std::size_t>(rng.uniformInt(0, static_cast<int>(found_.size()) - 1))];
    std::copy(again.begin(), again.end(), coordinates(state));
    return;
  }
  std::fill(coordinates(state), coordinates(state) + dimension, -1.0);
}

ConfigurationGoal::ConfigurationGoal(const ompl::base::SpaceInformationPtr& si,
                                     const physics::JointSpace& joints,
                                     const physics::GoalSpec& spec)
    : GoalSampleableRegion(si),
      joints_(&joints),
      spec_(spec),
      goal_(joints.coordinatesFor(spec.joints)) {
  setThreshold(spec.jointTolerance);
}

double ConfigurationGoal::distanceGoal(const ompl::base::State* state) const {
  const std::vector<double> q = joints_->jointValues(coordinates(state));
  double sum = 0.0;
  for (std::size_t j = 0; j < q.size(); ++j) {
    const double normalized = (q[j] - spec_.joints[j]) / spec_.jointRanges[j];
    sum += normalized * normalized;
  }
  return std::sqrt(sum);
}

void ConfigurationGoal::sampleGoal(ompl::base::State* state) const {
  std::copy(goal_.begin(), goal_.end(), coordinates(state));
}

}  // namespace kautham::planners::geometric
