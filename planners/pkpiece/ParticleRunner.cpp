#include "kautham/planners/pkpiece/ParticleRunner.h"

#include <algorithm>
#include <random>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/core/Pose.h"
#include "kautham/physics/Replay.h"
#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners {

ParticleRunner::ParticleRunner(physics::PlanningContext& context)
    : context_(context),
      from_(context.spaceInformation()->allocState()),
      to_(context.spaceInformation()->allocState()),
      control_(context.spaceInformation()->allocControl()),
      stateSize_(context.layout().stateSize()),
      controlSize_(context.spaceInformation()->getControlSpace()->getDimension()) {
  const auto& bodies = context.layout().bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].role == physics::BodyRole::Movable) movableBodies_.push_back(b);
}

ParticleRunner::~ParticleRunner() {
  const auto& si = context_.spaceInformation();
  si->freeState(from_);
  si->freeState(to_);
  si->freeControl(control_);
}

bool ParticleRunner::step(const double* from, const double* control, double* to,
                          const Eigen::Vector3d& targetReference) {
  std::copy(from, from + stateSize_, physics::WorldStateSpace::values(from_));
  std::copy(control, control + controlSize_,
            control_->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
  const auto& si = context_.spaceInformation();
  context_.propagator().propagate(from_, control_, si->getPropagationStepSize(), to_);
  const double* result = physics::WorldStateSpace::values(to_);
  std::copy(result, result + stateSize_, to);
  return context_.validityChecker().check(to, targetReference) == physics::Violation::None;
}

std::optional<std::size_t> ParticleRunner::tiltedBeyond(const double* state, double limit) const {
  if (limit <= 0.0) return std::nullopt;
  for (std::size_t b : movableBodies_)
    if (core::tiltAngle(physics::WorldLayout::orientation(state, b)) > limit) return b;
  return std::nullopt;
}

bool ParticleRunner::targetDriftedBeyond(const double* state, const Eigen::Vector3d& reference,
                                         double limit) const {
  if (limit <= 0.0) return false;  // every step of every particle asks: the usual answer first
  const std::optional<std::size_t> target = context_.validityChecker().targetBody();
  if (!target) return false;
  return (physics::WorldLayout::position(state, *target) - reference).norm() > limit;
}

ParticleResult ParticleRunner::run(const ParticleJob& job) {
  context_.world().setContactParameters(job.contact);
  ParticleResult result;
  result.end = job.start;
  std::vector<double> next(stateSize_);
  auto record = job.recordAfter.begin();
  unsigned stepsRun = 0;
  bool lastRecorded = false;
  for (unsigned i = 0; i < job.steps && result.valid; ++i) {
    result.valid = step(result.end.data(), job.control.data(), next.data(), job.targetReference) &&
                   !tiltedBeyond(next.data(), job.tiltLimit) &&
                   !targetDriftedBeyond(next.data(), job.targetReference, job.targetDriftLimit);
    bool stop = false;
    if (result.valid && job.goalStop != GoalStop::Ignore) {
      const bool inGoal = context_.goal().reached(next.data());
      // Left the goal: end at its last state inside, whose contacts this step judged.
      if (result.goalFrom > 0 && !inGoal) return result;
      if (inGoal && result.goalFrom == 0) {
        result.goalFrom = i + 1;
        stop = job.goalStop == GoalStop::Entering;
      }
    }
    result.end.swap(next);
    stepsRun = i + 1;
    lastRecorded = result.valid && record != job.recordAfter.end() && *record == stepsRun;
    if (lastRecorded) {
      result.recorded.push_back(result.end);
      ++record;
    }
    if (stop) break;
  }
  if (result.valid && stepsRun > 0) judgeLastState(job, stepsRun, lastRecorded, result);
  return result;
}

void ParticleRunner::judgeLastState(const ParticleJob& job, unsigned stepsRun, bool lastRecorded,
                                    ParticleResult& result) {
  // A step judges the contacts it starts from, so no step judged the state this run ends in;
  // physics::execute judges an execution's last state, and a run ends a plan (or a particle's
  // share of one) where an execution does. The world is in that state: the last step left it.
  physics::addFinalContacts(context_.world(), result.end.data());
  if (context_.validityChecker().check(result.end.data(), job.targetReference) ==
      physics::Violation::None)
    return;
  result.valid = false;
  if (lastRecorded) result.recorded.pop_back();  // only valid states are recorded
  if (result.goalFrom == stepsRun) result.goalFrom = 0;
}

physics::ExecutionResult ParticleRunner::execute(const std::vector<physics::ControlStep>& controls,
                                                 std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return physics::execute(context_, controls, rng, true);
}

ExecutionOutcome ParticleRunner::outcomeOf(const physics::ExecutionResult& run,
                                           std::size_t controls) {
  ExecutionOutcome outcome;
  outcome.reached = run.reachedGoal;
  if (run.brokenInControl)
    outcome.controlsPassed = static_cast<unsigned>(*run.brokenInControl);
  else if (run.firstViolation == physics::Violation::None)
    outcome.controlsPassed = static_cast<unsigned>(controls);
  return outcome;  // invalid before its first control: none passed
}

}  // namespace kautham::planners
