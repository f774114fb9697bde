#include "kautham/planners/geometric/GeometricQuery.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/terminationconditions/IterationTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>

#include "kautham/planners/geometric/JointSpaceGoals.h"

namespace kautham::planners::geometric {

namespace {

/// How often the path simplifier may ask whether to stop: its rounds (at most 5 + 5) ask about
/// 15 times, so this bounds a pathological run and never a normal one.
constexpr unsigned kSimplifierChecks = 100;

const double* coordinates(const ompl::base::State* state) {
  return state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
}

}  // namespace

GeometricQuery::GeometricQuery(physics::PlanningContext& context) : context_(&context) {
  const core::Problem& problem = context.problem();
  joints_ = std::make_shared<physics::JointSpace>(problem, context.query(), context.layout());
  const auto dimension = static_cast<unsigned>(joints_->dimension());
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(dimension);
  space->setBounds(0.0, 1.0);
  si_ = std::make_shared<ompl::base::SpaceInformation>(space);
  const std::optional<int> link = problem.robot.model.findLink(context.query().goal.link);
  if (!link) throw std::logic_error("no goal link " + context.query().goal.link);
  gripperLink_ = *link;
  checker_ = std::make_shared<physics::SceneChecker>(si_, context.world(), *joints_, gripperLink_,
                                                     context.startState().data(),
                                                     &context.validityChecker());
  si_->setStateValidityChecker(checker_);
  si_->setup();
  ik_ = std::make_shared<physics::InverseKinematics>(*joints_, gripperLink_);
  setClearance(0.0);
}

void GeometricQuery::setClearance(double metres) {
  checker_->setClearance(metres, joints_->start().data());
  constexpr double kWorkspaceMargin = 0.01;  // m: about what the tracking deviates by
  const Eigen::AlignedBox3d& workspace = context_->problem().workspace;
  const Eigen::Vector3d inset = Eigen::Vector3d::Constant(std::max(metres, kWorkspaceMargin));
  checker_->setWorkspace(Eigen::AlignedBox3d(workspace.min() + inset, workspace.max() - inset));
  constexpr double kFinestMotion = 0.002;  // m: finer checks cost more than they find
  const double step = std::max(metres, kFinestMotion) / joints_->stretch();
  // Bounded below: a long arm on a mobile base would otherwise check thousands of states per
  // motion (its bound on point motion is loose), and its trees would not grow.
  constexpr double kFinestFraction = 0.001;
  si_->setStateValidityCheckingResolution(
      std::clamp(step / si_->getStateSpace()->getMaximumExtent(), kFinestFraction, 0.01));
  si_->setup();
}

ompl::base::GoalPtr GeometricQuery::problemGoal(bool freeSpaceClear, std::vector<double> near) {
  const physics::GoalSpec& spec = context_->goal().spec();
  if (!spec.joints.empty()) return std::make_shared<ConfigurationGoal>(si_, *joints_, spec);
  physics::PoseTarget target;
  target.position = spec.position;
  target.approach = spec.approach;
  target.levelAxis = spec.levelAxis;
  target.tolerance = 0.5 * spec.tolerance;
  target.angleTolerance = 0.5 * spec.approachTolerance;
  std::shared_ptr<PoseGoal> pose;
  if (freeSpaceClear) {
    // The free space between the fingers must be clear in the scene, not only the pose reached.
    const physics::WorkspaceGoal& goal = context_->goal();
    physics::SceneChecker& checker = *checker_;
    pose = std::make_shared<PoseGoal>(si_, *ik_, target, [&goal, &checker](const double* c) {
      return goal.reached(checker.stateAt(c).data());
    });
  } else {
    pose = std::make_shared<PoseGoal>(si_, *ik_, target);
  }
  pose->seedNear(near.empty() ? joints_->start() : std::move(near));
  return pose;
}

std::optional<CoordinatePath> GeometricQuery::plan(
    const std::vector<double>& start, const ompl::base::GoalPtr& goal, ompl::base::Planner& planner,
    const ompl::base::PlannerTerminationCondition& ptc, bool simplify) {
  auto pdef = std::make_shared<ompl::base::ProblemDefinition>(si_);
  ompl::base::ScopedState<> from(si_->getStateSpace());
  std::copy(start.begin(), start.end(),
            from->as<ompl::base::RealVectorStateSpace::StateType>()->values);
  pdef->addStartState(from);
  pdef->setGoal(goal);
  // Any path will do: optimising planners (RRT*, BIT*) stop at their first solution too.
  auto objective = std::make_shared<ompl::base::PathLengthOptimizationObjective>(si_);
  objective->setCostThreshold(ompl::base::Cost(std::numeric_limits<double>::infinity()));
  pdef->setOptimizationObjective(objective);

  planner.clear();
  planner.setProblemDefinition(pdef);
  if (!planner.isSetup()) planner.setup();  // once: the task planner reuses its planner
  // OMPL warns of every goal sample it skips, and a goal that IK cannot reach in the scene
  // (the task planner asks such questions on purpose) would print hundreds of lines; the
  // outcome says what matters. Debug output (KAUTHAM_OMPL_DEBUG) keeps everything.
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  if (level != ompl::msg::LOG_DEBUG) ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const ompl::base::PlannerStatus status = planner.solve(ptc);
  ompl::msg::setLogLevel(level);
  if (status != ompl::base::PlannerStatus::EXACT_SOLUTION) return std::nullopt;

  auto& path = static_cast<ompl::geometric::PathGeometric&>(*pdef->getSolutionPath());
  if (simplify && !ptc()) {
    // Without the goal: the simplifier would take any goal sample for a goal state.
    // Bounded by a count, not a clock, so a fixed seed gives the same path on a busy machine.
    ompl::geometric::PathSimplifier simplifier(si_);
    ompl::base::IterationTerminationCondition rounds(kSimplifierChecks);
    simplifier.simplify(path, ompl::base::plannerOrTerminationCondition(ptc, rounds));
  }
  // A configuration goal is reached within a tolerance; end on the configuration itself when
  // the last motion there is free, so the plan ends in the middle of the goal region.
  if (const auto* configuration = dynamic_cast<const ConfigurationGoal*>(goal.get())) {
    ompl::base::ScopedState<> exact(si_->getStateSpace());
    configuration->sampleGoal(exact.get());
    if (si_->checkMotion(path.getState(path.getStateCount() - 1), exact.get()))
      path.append(exact.get());
  }
  CoordinatePath result;
  for (const ompl::base::State* state : path.getStates()) {
    const double* c = coordinates(state);
    result.emplace_back(c, c + si_->getStateDimension());
  }
  return result;
}

std::vector<std::vector<double>> GeometricQuery::jointValues(const CoordinatePath& path) const {
  std::vector<std::vector<double>> values;
  for (const std::vector<double>& c : path) values.push_back(joints_->jointValues(c.data()));
  return values;
}

}  // namespace kautham::planners::geometric
