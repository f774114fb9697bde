#include "kautham/physics/Execution.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/UncertaintySampler.h"

namespace kautham::physics {

namespace {

constexpr int kMaxStartDraws = 100;
constexpr double kOverlapDepth = 0.002;  // m, as PlanningContext's start check

/// Puts the world's contact parameters back when the run ends, however it ends.
class ContactRestorer {
 public:
  explicit ContactRestorer(World& world) : world_(world), saved_(world.contactParameters()) {}
  ~ContactRestorer() { world_.setContactParameters(saved_); }
  ContactRestorer(const ContactRestorer&) = delete;
  ContactRestorer& operator=(const ContactRestorer&) = delete;

 private:
  World& world_;
  ContactParameters saved_;
};

/// The layout, shared without ownership: the context outlives everything made here.
std::shared_ptr<const WorldLayout> borrowedLayout(const PlanningContext& context) {
  return std::shared_ptr<const WorldLayout>(std::shared_ptr<const WorldLayout>(),
                                            &context.layout());
}

/// Why a sampled start cannot be: things interpenetrate, or it breaks a constraint.
bool startIsPossible(PlanningContext& context, const WorldValidityChecker& checker,
                     std::vector<double>& start) {
  World& world = context.world();
  world.writeState(start.data());
  const bool overlaps = !world.probeContacts(kOverlapDepth).empty();
  const std::size_t flags = context.layout().flagsIndex();
  start[flags] = world.takeEvents();
  world.takeTouchedBodies();
  const bool valid = checker.check(start.data()) == Violation::None;
  start[flags] = 0.0;
  return !overlaps && valid;
}

/// What the robot touches in `state`: the objects' names, and kFixedObstacle.
std::vector<std::string> touchedAt(PlanningContext& context, const std::vector<double>& state) {
  World& world = context.world();
  world.writeState(state.data());
  const RobotTouches touches = world.robotTouches();
  std::vector<std::string> names;
  for (const int body : touches.bodies)
    names.push_back(context.layout().bodies[static_cast<std::size_t>(body)].name);
  if (touches.fixed) names.emplace_back(kFixedObstacle);
  return names;
}

}  // namespace

ExecutionResult execute(PlanningContext& context, const std::vector<ControlStep>& controls,
                        std::mt19937_64& rng, bool sampleUncertainty) {
  const auto& si = context.spaceInformation();
  const WorldLayout& layout = context.layout();
  ContactRestorer restorer(context.world());
  ExecutionResult result;
  result.startState = context.startState();
  result.contact = context.world().contactParameters();

  const WorldValidityChecker* checker = &context.validityChecker();
  const WorkspaceGoal* goal = &context.goal();
  std::unique_ptr<WorldValidityChecker> sampledChecker;
  std::unique_ptr<WorkspaceGoal> sampledGoal;
  std::optional<UncertaintySampler> sampler;
  if (sampleUncertainty) {
    sampler.emplace(context.problem(), layout);
    for (int draw = 0; draw < kMaxStartDraws; ++draw) {
      result.startState = context.startState();
      sampler->sampleInitialPoses(result.startState.data(), rng);
      // The target's "has not moved" check measures from where it really starts.
      sampledChecker = std::make_unique<WorldValidityChecker>(
          si, borrowedLayout(context), context.problem(), result.startState.data());
      sampledChecker->allowRestingSink(context.validityChecker().restingSink());
      if (startIsPossible(context, *sampledChecker, result.startState)) break;
      ++result.rejectedStarts;
    }
    checker = sampledChecker.get();
    sampledGoal = context.goalForStart(result.startState.data());
    if (sampledGoal) goal = sampledGoal.get();
    result.contact = sampler->sampleContact(rng);
    context.world().setContactParameters(result.contact);
  }

  const double stepSize = si->getPropagationStepSize();
  ompl::base::State* current = si->allocState();
  ompl::base::State* next = si->allocState();
  ompl::control::Control* control = si->allocControl();
  double* values = WorldStateSpace::values(current);
  double* applied = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
  const std::size_t controlSize = context.propagator().mapping().size();
  std::copy(result.startState.begin(), result.startState.end(), values);

  World& world = context.world();
  world.release();
  for (std::size_t c = 0; c < controls.size(); ++c) {
    const ControlStep& step = controls[c];
    if (result.firstViolation != Violation::None) break;
    applyGripperAction(world, step, values);
    if (sampler)
      sampler->perturbControl(step.values.data(), applied,
                              std::min(controlSize, step.values.size()), rng);
    else
      std::copy(step.values.begin(), step.values.end(), applied);
    for (unsigned i = 0; i < step.steps && result.firstViolation == Violation::None; ++i) {
      context.propagator().propagate(current, control, stepSize, next);
      si->copyState(current, next);
      result.time += stepSize;
      result.firstViolation = checker->check(values, checker->targetStart(), world.held());
    }
    result.touchedInControl.push_back(world.takeTouchedBodies());
    if (result.firstViolation != Violation::None)
      result.brokenInControl = c;
    else
      result.linkAfterControl.push_back(context.layout().goalLinkPosition(values));
  }
  if (result.firstViolation == Violation::None && result.time > 0.0) {  // a step ran
    addFinalContacts(world, values);
    result.firstViolation = checker->check(values, checker->targetStart(), world.held());
    if (result.firstViolation != Violation::None) {
      result.brokenInControl = controls.size() - 1;
      result.linkAfterControl.pop_back();  // kept only for controls run in full and valid
    }
  }
  if (result.firstViolation != Violation::None)
    result.offendingObject = checker->offendingObject(values, checker->targetStart(), world.held());
  world.release();
  result.finalState.assign(values, values + si->getStateDimension());
  si->freeControl(control);
  si->freeState(current);
  si->freeState(next);
  result.finalGoalDistance = goal->distance(result.finalState.data());
  result.reachedGoal =
      result.firstViolation == Violation::None && goal->reached(result.finalState.data());
  if (!result.reachedGoal && result.firstViolation == Violation::None) {
    result.poseMissed = goal->poseMiss(result.finalState.data());
    if (result.poseMissed.any()) result.touchedOffThePose = touchedAt(context, result.finalState);
    if (goal->poseReached(result.finalState.data()))
      result.leftInFreeSpace = goal->freeSpaceOccupants(result.finalState.data());
  }
  return result;
}

}  // namespace kautham::physics
