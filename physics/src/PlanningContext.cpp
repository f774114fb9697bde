#include "kautham/physics/PlanningContext.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/RestingSink.h"

namespace kautham::physics {

namespace {

/// One dimension per control of the robot's control set, each in [-1, 1] (ControlMapping).
std::shared_ptr<ompl::control::RealVectorControlSpace> makeControlSpace(
    const ompl::base::StateSpacePtr& space, std::size_t size) {
  const auto dimension = static_cast<unsigned>(size);
  auto controls = std::make_shared<ompl::control::RealVectorControlSpace>(space, dimension);
  ompl::base::RealVectorBounds bounds(dimension);
  bounds.setLow(-1.0);
  bounds.setHigh(1.0);
  controls->setBounds(bounds);
  return controls;
}

GoalSpec makeGoalSpec(const core::Problem& problem, const core::GoalRegion& goal,
                      const WorldLayout& layout) {
  GoalSpec spec;
  spec.position = problem.goalPosition(goal);
  spec.tolerance = goal.tolerance;
  spec.approach = problem.goalApproach(goal);
  spec.approachTolerance = goal.approachTolerance;
  spec.levelAxis = goal.levelAxis;
  spec.freeSpace = goal.freeSpace;
  if (goal.isConfiguration()) {
    spec.joints = problem.jointValuesFromControls(goal.controls);
    for (const JointInfo& joint : layout.joints)
      spec.jointRanges.push_back(joint.limited ? joint.upper - joint.lower : 2.0 * M_PI);
    spec.jointTolerance = goal.jointTolerance;
  }
  return spec;
}

void checkSettings(const PropagationSettings& settings, double physicsStep) {
  const double ratio = settings.propagationStepSize / physicsStep;
  if (!(settings.propagationStepSize > 0.0) || std::abs(ratio - std::round(ratio)) > 1e-6 ||
      std::round(ratio) < 1.0)
    throw std::invalid_argument(
        "the propagation step size (" + std::to_string(settings.propagationStepSize) +
        " s) must be a whole multiple of the physics step (" + std::to_string(physicsStep) + " s)");
  if (settings.minControlSteps < 1 || settings.minControlSteps > settings.maxControlSteps)
    throw std::invalid_argument("control steps need 1 <= min_control_steps <= max_control_steps");
}

}  // namespace

PlanningContext::PlanningContext(const core::Problem& problem, std::size_t queryIndex,
                                 const PropagationSettings& settings)
    : problem_(problem), queryIndex_(queryIndex) {
  checkSettings(settings, problem_.physics.stepSize);
  world_ = std::make_shared<World>(problem_, query());
  layout_ = std::make_shared<WorldLayout>(world_->layout());
  start_.resize(layout_->stateSize());
  world_->readState(start_.data());

  space_ = std::make_shared<WorldStateSpace>(layout_, problem_.workspace);

  const ControlMapping mapping(problem_.robot.controls, layout_->joints);
  si_ = std::make_shared<ompl::control::SpaceInformation>(space_,
                                                          makeControlSpace(space_, mapping.size()));
  propagator_ = std::make_shared<PhysicsPropagator>(si_, world_, mapping);
  validity_ = std::make_shared<WorldValidityChecker>(si_, layout_, problem_, start_.data());
  knowledgeValidity_ = std::make_shared<WorldValidityChecker>(si_, layout_, problem_, start_.data(),
                                                              ValidityRules::KnowledgeOnly);
  // Objects on soft contacts (Kautham's CFM) settle centimetres into the ground: no drop. The
  // start is left to rest once, for this and for the restless objects below.
  const bool soft = hasSoftContacts(*world_);
  std::vector<double> settled;
  if (soft) {
    settled = settledStart(*world_, start_);
    const std::vector<double> sink = restingSink(*layout_, start_, settled);
    validity_->allowRestingSink(sink);
    knowledgeValidity_->allowRestingSink(sink);
  }
  si_->setStatePropagator(propagator_);
  si_->setStateValidityChecker(validity_);
  si_->setPropagationStepSize(settings.propagationStepSize);
  si_->setMinMaxControlDuration(settings.minControlSteps, settings.maxControlSteps);
  si_->setup();

  // A start state that already touches what it must not is reported, not planned from.
  constexpr double kOverlapDepth = 0.002;  // resting contacts sink about 0.5 mm
  startOverlaps_ = world_->probeContacts(kOverlapDepth);
  start_[layout_->flagsIndex()] = world_->takeEvents();
  startViolation_ = validity_->check(start_.data());
  start_[layout_->flagsIndex()] = 0.0;
  if (startOverlaps_.empty()) {
    if (settled.empty()) settled = settledStart(*world_, start_);
    restlessAtStart_ = restlessObjects(*layout_, start_, settled, soft);
  }

  goal_ =
      std::make_shared<WorkspaceGoal>(si_, layout_, makeGoalSpec(problem_, query().goal, *layout_));
  if (!goal_->spec().joints.empty()) space_->measureJoints();
  pdef_ = std::make_shared<ompl::base::ProblemDefinition>(si_);
  ompl::base::ScopedState<> start(space_);
  std::copy(start_.begin(), start_.end(), WorldStateSpace::values(start.get()));
  pdef_->addStartState(start);
  pdef_->setGoal(goal_);
}

EndEffectorProjection& PlanningContext::projection() {
  return static_cast<EndEffectorProjection&>(*space_->getDefaultProjection());
}

std::vector<std::pair<Violation, std::uint64_t>> PlanningContext::rejections() const {
  std::array<std::uint64_t, kViolationKinds> total{};
  for (const auto& checker : {validity_, knowledgeValidity_})
    if (checker) {
      const auto counts = checker->rejectionCounts();
      for (std::size_t v = 0; v < kViolationKinds; ++v) total[v] += counts[v];
    }
  std::vector<std::pair<Violation, std::uint64_t>> counts;
  for (std::size_t v = 1; v < kViolationKinds; ++v)
    if (total[v]) counts.emplace_back(static_cast<Violation>(v), total[v]);
  std::stable_sort(counts.begin(), counts.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return counts;
}

void PlanningContext::usePlanningRules(ValidityRules rules) {
  const auto& checker = rules == ValidityRules::Full ? validity_ : knowledgeValidity_;
  if (si_->getStateValidityChecker() == checker) return;
  si_->setStateValidityChecker(checker);
  // A new checker un-setups the space information; setting it up again re-registers the
  // projection, so a planner sets its cell size after choosing its rules.
  si_->setup();
}

std::unique_ptr<WorkspaceGoal> PlanningContext::goalForStart(const double* start) const {
  const core::GoalRegion& region = query().goal;
  if (region.isConfiguration() || region.relativeTo.empty()) return nullptr;
  const std::optional<int> object = problem_.findObject(region.relativeTo);
  const WorldLayout& layout = *layout_;
  for (std::size_t b = 0; object && b < layout.bodies.size(); ++b) {
    if (layout.bodies[b].objectIndex != *object) continue;
    const Eigen::Isometry3d move =
        layout.linkPose(start, b) * layout.linkPose(start_.data(), b).inverse();
    if (move.isApprox(Eigen::Isometry3d::Identity(), 1e-12)) return nullptr;
    GoalSpec spec = goal_->spec();
    spec.position = move * spec.position;
    if (spec.approach) spec.approach = (move.linear() * *spec.approach).normalized();
    return std::make_unique<WorkspaceGoal>(si_, layout_, spec);
  }
  return nullptr;
}

}  // namespace kautham::physics
