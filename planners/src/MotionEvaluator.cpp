#include "kautham/planners/MotionEvaluator.h"

#include <algorithm>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners {

namespace {
double* controlValues(ompl::control::Control* control) {
  return control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
}
}  // namespace

MotionEvaluator::MotionEvaluator(physics::PlanningContext& context, double maxDisplacement)
    : context_(context),
      sampler_(context.problem(), context.layout()),
      maxDisplacement_(maxDisplacement),
      from_(context.spaceInformation()->allocState()),
      to_(context.spaceInformation()->allocState()),
      control_(context.spaceInformation()->allocControl()),
      stateSize_(context.layout().stateSize()),
      controlSize_(context.spaceInformation()->getControlSpace()->getDimension()) {
  const auto& bodies = context.layout().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].role != physics::BodyRole::Robot) objectBodies_.push_back(b);
}

MotionEvaluator::~MotionEvaluator() {
  const auto& si = context_.spaceInformation();
  si->freeState(from_);
  si->freeState(to_);
  si->freeControl(control_);
}

bool MotionEvaluator::step(const double* from, const double* control, double* to,
                           const Eigen::Vector3d& targetReference) {
  std::copy(from, from + stateSize_, physics::WorldStateSpace::values(from_));
  std::copy(control, control + controlSize_, controlValues(control_));
  const auto& si = context_.spaceInformation();
  context_.propagator().propagate(from_, control_, si->getPropagationStepSize(), to_);
  const double* result = physics::WorldStateSpace::values(to_);
  std::copy(result, result + stateSize_, to);
  return context_.validityChecker().check(to, targetReference) == physics::Violation::None;
}

NominalRun MotionEvaluator::runNominal(const double* start, const double* control, unsigned steps) {
  NominalRun run;
  run.end.assign(start, start + stateSize_);
  std::vector<double> next(stateSize_);
  for (unsigned i = 0; i < steps; ++i) {
    if (!step(run.end.data(), control, next.data(), context_.validityChecker().targetStart()))
      break;
    run.end.swap(next);
    run.states.push_back(run.end);
    run.steps = i + 1;
    if (context_.goal().reached(run.end.data())) {
      run.reachedGoal = true;
      break;
    }
  }
  return run;
}

Eigen::Vector3d MotionEvaluator::targetPosition(const double* state) const {
  // A particle's target stands where its start was sampled; without a target nothing drifts.
  const auto target = context_.validityChecker().targetBody();
  return target ? physics::WorldLayout::position(state, *target)
                : context_.validityChecker().targetStart();
}

bool MotionEvaluator::displacementWithinLimit(const double* start, const double* end) const {
  for (std::size_t b : objectBodies_) {
    const Eigen::Vector3d a = physics::WorldLayout::position(start, b);
    const Eigen::Vector3d c = physics::WorldLayout::position(end, b);
    if ((c - a).norm() > maxDisplacement_) return false;
  }
  return true;
}

ParticleVerdict MotionEvaluator::judgeNominal(const double* start, const double* end) const {
  ParticleVerdict verdict;
  verdict.interaction = displacementWithinLimit(start, end) ? 1.0 : 0.0;
  return verdict;
}

ParticleVerdict MotionEvaluator::runParticles(const double* start, const double* control,
                                              unsigned steps, const ObjectPoseBelief& belief,
                                              unsigned particles, std::uint64_t streamSeed) {
  ParticleVerdict verdict;
  if (particles == 0) return verdict;
  physics::World& world = context_.world();
  const physics::ContactParameters mean = world.contactParameters();
  unsigned validStates = 0;
  unsigned validInteractions = 0;
  unsigned inGoal = 0;
  std::vector<double> noisy(controlSize_);
  std::vector<double> sampledStart(start, start + stateSize_);
  std::vector<double> next(stateSize_);
  for (unsigned p = 0; p < particles; ++p) {
    std::mt19937_64 rng(streamSeed + p);
    std::copy(start, start + stateSize_, sampledStart.begin());
    belief.samplePoses(sampledStart.data(), rng);
    world.setContactParameters(sampler_.sampleContact(rng));
    sampler_.perturbControl(control, noisy.data(), controlSize_, rng);
    std::vector<double> state = sampledStart;
    const Eigen::Vector3d targetReference = targetPosition(sampledStart.data());
    bool valid = true;
    for (unsigned i = 0; i < steps && valid; ++i) {
      valid = step(state.data(), noisy.data(), next.data(), targetReference);
      state.swap(next);
    }
    validStates += valid ? 1 : 0;
    inGoal += valid && context_.goal().reached(state.data()) ? 1 : 0;
    validInteractions += displacementWithinLimit(sampledStart.data(), state.data()) ? 1 : 0;
    verdict.ends.push_back(std::move(state));
  }
  world.setContactParameters(mean);
  particleCount_ += particles;
  verdict.stateValidity = static_cast<double>(validStates) / particles;
  verdict.interaction = static_cast<double>(validInteractions) / particles;
  verdict.goal = static_cast<double>(inGoal) / particles;
  return verdict;
}

}  // namespace kautham::planners
